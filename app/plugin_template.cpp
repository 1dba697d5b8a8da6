#include "plugin_template.hpp"

#include <fstream>
#include <regex>
#include <set>

#include <fmt/format.h>

#include "commands.hpp"
#include "somasim/error.hpp"
#include "somasim/version.hpp"
#include "somasim/yaml_text.hpp"

namespace somasim::app {

namespace fs = std::filesystem;

namespace {

// "my_gain" -> "MyGain"
std::string class_name(const std::string& name) {
  std::string out;
  bool upper = true;
  for (char c : name) {
    if (c == '_') {
      upper = true;
      continue;
    }
    out += upper && c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c;
    upper = false;
  }
  return out;
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos;
       at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

constexpr const char* kCMakeLists =
    R"(# The somasim plugin @NAME@, built against somasim (installed, or its build tree):
#   cmake -S . -B build -DCMAKE_PREFIX_PATH=<somasim prefix or build folder>
#   cmake --build build && ctest --test-dir build
# The library lands in build/plugins/ with its index; load it with
# `somasim --plugin-path build/plugins ...` or `plugin_libraries: [path]` in an experiment.
cmake_minimum_required(VERSION 3.22)
project(somasim_plugin_@NAME@ LANGUAGES CXX)
set(CMAKE_CXX_STANDARD 20)
set(CMAKE_CXX_STANDARD_REQUIRED ON)
set(CMAKE_CXX_EXTENSIONS OFF)

find_package(somasim REQUIRED)
somasim_add_plugin(@NAME@ SOURCES @NAME@.cpp)

# The harness test: the plugin in a small graph, its inputs fed by the test.
find_package(GTest)
if(GTest_FOUND)
  enable_testing()
  add_executable(test_@NAME@ test_@NAME@.cpp)
  target_link_libraries(test_@NAME@ PRIVATE somasim::framework GTest::gtest_main)
  target_compile_definitions(test_@NAME@ PRIVATE PLUGIN_DIR="${SOMASIM_PLUGIN_BUILD_DIR}")
  add_dependencies(test_@NAME@ somasim_plugin_@NAME@)
  add_test(NAME test_@NAME@ COMMAND test_@NAME@)
endif()
)";

constexpr const char* kPlugin =
    R"(// @NAME@: a somasim plugin. It starts as a gain, out = gain * in, on scalar ports; make it
// yours: the parameters (Config), the ports (Ports), and configure / step / finish.
#include <somasim/config.hpp>
#include <somasim/plugin.hpp>
#include <somasim/plugin_ports.hpp>

namespace @NAME@ {

class @CLASS@ : public somasim::Plugin {
 public:
  // Parameters: each member has its default; visit() names it once, with unit, range and doc
  // (what `somasim plugins describe @NAME@` prints and `validate` checks).
  struct Config {
    double gain = 1.0;
    template <class V>
    void visit(V& v) {
      v.field("gain", gain).range(-1e6, 1e6).doc("output = gain * input");
    }
  };
  // Ports, named once the same way. double and Eigen::Vector3d come with somasim/plugin.hpp;
  // the robot's, skin's and PPS types with somasim/robot/ports.hpp, somasim/skin/ports.hpp, ...
  struct Ports {
    somasim::In<double> in;
    somasim::Out<double> out;
    template <class V>
    void visit(V& v) {
      v.port("in", in, "the input signal");
      v.port("out", out, "gain * input");
    }
  };

  static somasim::PluginSpec spec() {
    return somasim::make_plugin_spec<Config, Ports>("@NAME@", "Multiplies a scalar by a gain.");
  }

  void configure(somasim::NodeContext& ctx) override {
    config_ = somasim::read_config<Config>(ctx);
    somasim::bind_ports(ctx, ports_);
  }
  void step(somasim::NodeContext&) override {
    *ports_.out = config_.gain * *ports_.in;
    ++steps_;
  }
  void finish(somasim::NodeContext& ctx) override { ctx.report_metric("steps", steps_); }

 private:
  Config config_;
  Ports ports_;
  long steps_ = 0;
};

}  // namespace @NAME@

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<@NAME@::@CLASS@>();
}
)";

constexpr const char* kTest =
    R"(// The plugin @NAME@ in the test harness: a graph from inline YAML, inputs fed by the test.
#include <gtest/gtest.h>

#include <somasim/testing/harness.hpp>

TEST(@CLASS@, MultipliesItsInputByTheGain) {
  somasim::testing::Harness h(R"yaml(
    base_rate_hz: 100
    duration_s: 1
    nodes:
      g: {plugin: @NAME@, params: {gain: 2.5}, inputs: {in: harness.u}}
  )yaml",
                              {PLUGIN_DIR});
  h.input<double>("u") = 4.0;
  ASSERT_TRUE(h.step(3));
  EXPECT_DOUBLE_EQ(h.output<double>("g.out"), 10.0);
  EXPECT_EQ(h.finish(), "");
  EXPECT_EQ(h.metric("g", "steps"), 3);
}

TEST(@CLASS@, RefusesAGainOutOfRange) {
  EXPECT_THROW(somasim::testing::Harness(R"yaml(
    nodes:
      g: {plugin: @NAME@, params: {gain: 1e9}, inputs: {in: harness.u}}
  )yaml",
                                         {PLUGIN_DIR}),
               somasim::InputError);
}
)";

constexpr const char* kReadme = R"(# @NAME@

A somasim plugin (written from `somasim plugin new @NAME@`, somasim @VERSION@).

```sh
cmake -S . -B build -DCMAKE_PREFIX_PATH=<somasim install prefix, or somasim's build folder>
cmake --build build                 # build/plugins/libsomasim_@NAME@.so and its index
ctest --test-dir build              # the harness test (test_@NAME@.cpp; needs GoogleTest)
somasim --plugin-path build/plugins plugins describe @NAME@
```

In an experiment: `plugin: @NAME@` on a node, with `--plugin-path build/plugins` (or
`SOMASIM_PLUGIN_PATH`, or `plugin_libraries: [build/plugins/libsomasim_@NAME@.so]`).
)";

}  // namespace

std::map<std::string, std::string> plugin_template_files(const std::string& name) {
  static const std::regex valid("[a-z][a-z0-9_]{0,62}");
  // The name is also a C++ namespace and file name: keywords, predefined macros and reserved
  // identifiers ("__") would not compile.
  static const std::set<std::string> reserved = {"alignas",       "alignof",     "and",
                                                 "and_eq",        "asm",         "auto",
                                                 "bitand",        "bitor",       "bool",
                                                 "break",         "case",        "catch",
                                                 "char",          "char8_t",     "char16_t",
                                                 "char32_t",      "class",       "compl",
                                                 "concept",       "const",       "consteval",
                                                 "constexpr",     "constinit",   "const_cast",
                                                 "continue",      "co_await",    "co_return",
                                                 "co_yield",      "decltype",    "default",
                                                 "delete",        "do",          "double",
                                                 "dynamic_cast",  "else",        "enum",
                                                 "explicit",      "export",      "extern",
                                                 "false",         "float",       "for",
                                                 "friend",        "goto",        "if",
                                                 "inline",        "int",         "long",
                                                 "mutable",       "namespace",   "new",
                                                 "noexcept",      "not",         "not_eq",
                                                 "nullptr",       "operator",    "or",
                                                 "or_eq",         "private",     "protected",
                                                 "public",        "register",    "reinterpret_cast",
                                                 "requires",      "return",      "short",
                                                 "signed",        "sizeof",      "static",
                                                 "static_assert", "static_cast", "struct",
                                                 "switch",        "template",    "this",
                                                 "thread_local",  "throw",       "true",
                                                 "try",           "typedef",     "typeid",
                                                 "typename",      "union",       "unsigned",
                                                 "using",         "virtual",     "void",
                                                 "volatile",      "wchar_t",     "while",
                                                 "xor",           "xor_eq",      "linux",
                                                 "unix",          "errno",       "assert",
                                                 "std",           "somasim",     "main"};
  if (!std::regex_match(name, valid) || reserved.count(name) ||
      name.find("__") != std::string::npos)
    throw InputError(fmt::format(
        "plugin name '{}': expected lower-case letters, digits and '_', starting with a letter "
        "(at most 63 characters, no '__', not a C++ keyword), e.g. my_filter",
        escape_control_bytes(name)));
  auto fill = [&](const char* text) {
    std::string out = replace_all(text, "@NAME@", name);
    out = replace_all(out, "@CLASS@", class_name(name));
    return replace_all(out, "@VERSION@", kVersion);
  };
  return {{"CMakeLists.txt", fill(kCMakeLists)},
          {name + ".cpp", fill(kPlugin)},
          {"test_" + name + ".cpp", fill(kTest)},
          {"README.md", fill(kReadme)}};
}

int cmd_plugin_new(const std::string& name, const fs::path& dir_arg) {
  const auto files = plugin_template_files(name);
  const fs::path dir = dir_arg.empty() ? fs::path(name) : dir_arg;
  std::error_code ec;
  if (fs::is_symlink(dir, ec) || (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) ||
      (fs::is_directory(dir, ec) && !fs::is_empty(dir, ec)))
    throw InputError(fmt::format("plugin new: '{}' exists and is not an empty folder",
                                 escape_control_bytes(dir.string())));
  fs::create_directories(dir);
  for (const auto& [file, text] : files) {
    std::ofstream out(dir / file, std::ios::binary);
    out << text;
    if (!out) throw RunError("cannot write " + (dir / file).string());
  }
  fmt::print("{}: plugin '{}' (CMakeLists.txt, {}.cpp, test_{}.cpp, README.md)\n", dir.string(),
             name, name, name);
  return kExitOk;
}

}  // namespace somasim::app
