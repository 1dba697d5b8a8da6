// Config structs visited once: the schema, the filled struct, located cross-field errors, the
// integer widths, enumerations' name tables and the file field types.
#include <sys/stat.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <span>

#include <gtest/gtest.h>

#include "somasim/config.hpp"

namespace somasim {
namespace {

namespace fs = std::filesystem;

enum class Shape { kBall, kCube, kCylinder };
constexpr NamedValue<Shape> kShapeNames[] = {
    {Shape::kBall, "ball"}, {Shape::kCube, "cube"}, {Shape::kCylinder, "cylinder"}};
constexpr std::span<const NamedValue<Shape>> name_table(Shape) {
  return kShapeNames;
}

struct NoiseBlock {
  double sigma_m = 0.003;
  int warmup = 2;
  template <class V>
  void visit(V& v) {
    v.field("sigma_m", sigma_m).unit("m").at_least(0).doc("noise");
    v.field("warmup", warmup).range(0, 100).doc("frames");
  }
  void validate(ConfigChecks& checks) const {
    checks.require(warmup != 13, warmup, "13 frames are unlucky");
  }
};

struct TestConfig {
  bool enabled = true;
  std::int64_t count = 7;
  std::uint32_t particles = 200;
  double speed = 0.25;
  std::string label = "x";
  std::vector<double> gains{1.0, 2.0};
  std::vector<std::string> parts;
  Shape shape = Shape::kCube;
  NoiseBlock noise;
  OutputFile csv;
  template <class V>
  void visit(V& v) {
    v.field("enabled", enabled).doc("on");
    v.field("count", count).at_least(1).doc("how many");
    v.field("particles", particles).doc("M");
    v.field("speed", speed).unit("m/s").range(0, 10).doc("speed");
    v.field("label", label).doc("a label");
    v.field("gains", gains).size(2).doc("two gains");
    v.field("parts", parts).max_size(3).doc("parts");
    v.field("shape", shape).doc("shape");
    v.block(noise);
    v.field("csv", csv).doc("table");
  }
  void validate(ConfigChecks& checks) const {
    checks.require(!(shape == Shape::kBall && speed > 5), speed, "balls fly at most 5 m/s");
  }
};

std::map<std::string, ParamValue> defaults_of(const std::vector<ParamSpec>& specs) {
  std::map<std::string, ParamValue> values;
  for (const ParamSpec& s : specs)
    if (s.default_value) values[s.name] = *s.default_value;
  return values;
}

TEST(Config, TheSchemaComesFromTheVisitInOrderWithTheMembersDefaults) {
  const auto specs = config_schema<TestConfig>();
  std::vector<std::string> names;
  for (const auto& s : specs) names.push_back(s.name);
  EXPECT_EQ(names,
            (std::vector<std::string>{"enabled", "count", "particles", "speed", "label", "gains",
                                      "parts", "shape", "sigma_m", "warmup", "csv"}));
  EXPECT_EQ(specs[1].type, ParamType::Int);
  EXPECT_EQ(std::get<std::int64_t>(*specs[1].default_value), 7);
  EXPECT_EQ(specs[1].min, 1.0);
  EXPECT_EQ(specs[2].int_min, 0);
  EXPECT_EQ(specs[2].int_max, std::numeric_limits<std::uint32_t>::max());
  EXPECT_EQ(specs[3].unit, "m/s");
  EXPECT_EQ(specs[3].max, 10.0);
  EXPECT_EQ(specs[5].list_size, 2u);
  EXPECT_EQ(specs[6].max_list_size, 3u);
  EXPECT_EQ(specs[7].type, ParamType::String);
  EXPECT_EQ(specs[7].choices, (std::vector<std::string>{"ball", "cube", "cylinder"}));
  EXPECT_EQ(std::get<std::string>(*specs[7].default_value), "cube");
  EXPECT_EQ(specs[8].doc, "noise");
  EXPECT_EQ(std::get<std::string>(*specs[10].default_value), "");
}

TEST(Config, ReadingFillsEveryMemberIncludingEmbeddedBlocks) {
  auto values = defaults_of(config_schema<TestConfig>());
  values["count"] = std::int64_t{42};
  values["particles"] = std::int64_t{4000000000};
  values["shape"] = std::string("cylinder");
  values["sigma_m"] = 0.01;
  values["parts"] = std::vector<std::string>{"a", "b"};
  values["csv"] = std::string("sub/table.csv");
  ParamsSource source(Params(values), "/run");
  const auto c = read_config<TestConfig>(source);
  EXPECT_EQ(c.count, 42);
  EXPECT_EQ(c.particles, 4000000000u);
  EXPECT_EQ(c.shape, Shape::kCylinder);
  EXPECT_EQ(c.noise.sigma_m, 0.01);
  EXPECT_EQ(c.parts.size(), 2u);
  EXPECT_EQ(c.csv.path, fs::path("/run/sub/table.csv"));
  EXPECT_TRUE(c.csv.enabled());
}

TEST(Config, CrossFieldChecksNameTheMembersParameter) {
  auto values = defaults_of(config_schema<TestConfig>());
  values["shape"] = std::string("ball");
  values["speed"] = 6.0;
  ParamsSource source{Params(values)};
  try {
    read_config<TestConfig>(source);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "key 'params.speed': balls fly at most 5 m/s");
  }
  values["speed"] = 1.0;
  values["warmup"] = std::int64_t{13};
  ParamsSource block_source{Params(values)};
  EXPECT_THROW(
      {
        try {
          read_config<TestConfig>(block_source);
        } catch (const InputError& e) {
          EXPECT_STREQ(e.what(), "key 'params.warmup': 13 frames are unlucky");
          throw;
        }
      },
      InputError);
}

TEST(Config, ConfigKeyFindsTheNameOfAMember) {
  TestConfig c;
  EXPECT_EQ(config_key(c, c.speed), "speed");
  EXPECT_EQ(config_key(c, c.noise.warmup), "warmup");
  EXPECT_EQ(config_key(c, c.csv), "csv");
}

// Every integer member refuses exactly the values its type cannot hold, at random values around
// each bound of several widths.
template <class T>
struct OneInt {
  T value{};
  template <class V>
  void visit(V& v) {
    v.field("n", value).doc("n");
  }
};

struct Particles {
  int particles = 1;
  template <class V>
  void visit(V& v) {
    v.field("particles", particles).doc("M");
  }
};

struct TwoOutputs {
  OutputFile a, b;
  template <class V>
  void visit(V& v) {
    v.field("a", a).doc("a");
    v.field("b", b).doc("b");
  }
};

struct OneInput {
  InputFile file;
  template <class V>
  void visit(V& v) {
    v.field("file", file).doc("f");
  }
};

template <class T>
void check_integer_width(std::mt19937_64& rng) {
  const auto lo = static_cast<long double>(std::numeric_limits<T>::min());
  const auto hi = static_cast<long double>(std::numeric_limits<T>::max());
  std::uniform_int_distribution<int> step(-3, 3);
  for (int trial = 0; trial < 200; ++trial) {
    const long double base = (trial % 2 == 0) ? lo : hi;
    const long double candidate = base + step(rng);
    if (candidate < static_cast<long double>(INT64_MIN) ||
        candidate > static_cast<long double>(INT64_MAX))
      continue;
    const auto i = static_cast<std::int64_t>(candidate);
    const auto spec = config_schema<OneInt<T>>().front();
    const bool fits_schema = i >= *spec.int_min && i <= *spec.int_max;
    EXPECT_EQ(fits_schema, std::in_range<T>(i)) << i;
    ParamsSource source{Params({{"n", i}})};
    if (std::in_range<T>(i)) {
      EXPECT_EQ(static_cast<std::int64_t>(read_config<OneInt<T>>(source).value), i);
    } else {
      EXPECT_THROW(read_config<OneInt<T>>(source), InputError) << i;
    }
  }
}

TEST(Config, IntegersAreRefusedWhereTheyDoNotFitTheMembersType) {
  std::mt19937_64 rng(5);
  check_integer_width<int>(rng);
  check_integer_width<std::uint32_t>(rng);
  check_integer_width<std::int16_t>(rng);
  check_integer_width<std::uint8_t>(rng);
  check_integer_width<std::size_t>(rng);
  check_integer_width<std::int64_t>(rng);
  ParamsSource source{Params({{"particles", std::int64_t{4294967297}}})};
  try {
    read_config<Particles>(source);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "key 'params.particles': value 4294967297 does not fit the parameter's 32-bit "
                 "integer");
  }
}

TEST(Config, EnumerationsParseAndWriteThroughTheirOneTable) {
  for (const auto& entry : kShapeNames) {
    EXPECT_EQ(enum_name(entry.value), entry.name);
    EXPECT_EQ(parse_enum<Shape>(entry.name), entry.value);
  }
  EXPECT_FALSE(parse_enum<Shape>("sphere"));
  EXPECT_EQ(enum_names_joined<Shape>(), "ball, cube, cylinder");
}

TEST(Config, OutputFilesStayInsideAndAreClaimedOnce) {
  const auto read = [](const std::string& a, const std::string& b) {
    ParamsSource source(Params({{"a", a}, {"b", b}}), "/run");
    return read_config<TwoOutputs>(source);
  };
  EXPECT_EQ(read("x.csv", "y.csv").b.path, fs::path("/run/y.csv"));
  EXPECT_FALSE(read("", "").a.enabled());
  EXPECT_THROW(read("x.csv", "./x.csv"), InputError);
  EXPECT_THROW(read("../x.csv", "y.csv"), InputError);
  EXPECT_THROW(read("/tmp/x.csv", "y.csv"), InputError);
}

TEST(Config, InputFilesMustBeRegularFilesOfBoundedSize) {
  const fs::path dir = fs::temp_directory_path() / ("somasim_config_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "ok.txt") << "data\n";
  ASSERT_EQ(mkfifo((dir / "fifo").c_str(), 0600), 0);
  const auto read = [&](const std::string& name) {
    ParamsSource source(Params({{"file", name}}), {}, dir);
    return read_config<OneInput>(source);
  };
  EXPECT_EQ(read("ok.txt").file.path, dir / "ok.txt");
  EXPECT_FALSE(read("").file.given());
  for (const std::string bad : {"missing.txt", "fifo", ".", "/dev/zero", "/dev/null"}) {
    try {
      read(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("key 'params.file': input file '" + bad + "'"),
                std::string::npos)
          << e.what();
    }
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace somasim
