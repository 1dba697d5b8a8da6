// Sweep files: keys, values, ranges and seeds, and every message a bad file gets.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "somasim/error.hpp"
#include "somasim/sweep/jobs.hpp"
#include "somasim/sweep/sweep_file.hpp"
#include "test_support.hpp"

namespace somasim::sweep {
namespace {
namespace fs = std::filesystem;

class SweepFile : public ::testing::Test {
 protected:
  void SetUp() override { test::write_file(dir / "exp.yaml", "experiment: e\n"); }
  SweepSpec load(const std::string& text) { return load_sweep_text(text, "s.yaml", dir.path()); }
  std::string error_of(const std::string& text) {
    try {
      expand_jobs(load(text));
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  }
  test::TempDir dir;
};

std::vector<std::string> texts(const Axis& a) {
  std::vector<std::string> out;
  for (const auto& v : a.values) out.push_back(v.text);
  return out;
}

TEST_F(SweepFile, ReadsEveryKey) {
  const SweepSpec s = load(R"(sweep: demo
experiment: exp.yaml
output: out/here
seeds: {from: 3, to: 5}
mode: grid
set: {duration_s: 2}
axes:
  nodes.a.params.x: [0.5, "text", [1, 2], {l_elbow: -4}]
  nodes.a.params.n: {from: 100, to: 500, step: 200}
  nodes.a.params.y: {from: 0, to: 1, count: 3}
  nodes.a.params.z: {from: 1, to: 0, step: 0.5}
  nodes.a.params.w: {from: -0.15, to: 0.05, step: 0.05}
summary: {metric: m, against: nodes.a.params.n}
)");
  EXPECT_EQ(s.name, "demo");
  EXPECT_EQ(s.experiment, (dir / "exp.yaml").lexically_normal());
  EXPECT_EQ(output_root(s, ""), fs::path("out/here"));
  EXPECT_EQ(output_root(s, "cli"), fs::path("cli"));
  EXPECT_EQ(s.seeds, (std::vector<std::uint64_t>{3, 4, 5}));
  ASSERT_EQ(s.fixed.size(), 1u);
  EXPECT_EQ(s.fixed[0].values[0].text, "2");
  ASSERT_EQ(s.axes.size(), 5u);
  EXPECT_EQ(texts(s.axes[0]),
            (std::vector<std::string>{"0.5", "\"text\"", "[1, 2]", "{l_elbow: -4}"}));
  EXPECT_EQ(s.axes[0].values[1].where.str(), "s.yaml:8:27");
  EXPECT_EQ(texts(s.axes[1]), (std::vector<std::string>{"100", "300", "500"}));
  EXPECT_EQ(texts(s.axes[2]), (std::vector<std::string>{"0", "0.5", "1"}));
  EXPECT_EQ(texts(s.axes[3]), (std::vector<std::string>{"1", "0.5", "0"}));
  // Not -0.09999999999999999 and 2.7755575615628914e-17 (binary rounding of from + i step).
  EXPECT_EQ(texts(s.axes[4]), (std::vector<std::string>{"-0.15", "-0.1", "-0.05", "0", "0.05"}));
  EXPECT_EQ(s.summary_against, "nodes.a.params.n");
  const SweepSpec defaults = load("sweep: d\nexperiment: exp.yaml\naxes: {a.b: [1]}\n");
  EXPECT_EQ(output_root(defaults, ""), fs::path("runs/sweeps/d"));
  EXPECT_TRUE(defaults.seeds.empty());
}

TEST_F(SweepFile, GridRunsEveryCombinationWithSeedsInnermost) {
  const auto jobs =
      expand_jobs(load("sweep: g\nexperiment: exp.yaml\nseeds: [7, 8]\nset: {duration_s: 1}\n"
                       "axes: {a.x: [1, 2], a.y: [u, v, w]}\n"));
  ASSERT_EQ(jobs.size(), 12u);
  EXPECT_EQ(jobs[0].axis_values, (std::vector<std::string>{"1", "u"}));
  EXPECT_EQ(jobs[1].axis_values, (std::vector<std::string>{"1", "u"}));
  EXPECT_EQ(*jobs[1].seed, 8u);
  EXPECT_EQ(jobs[2].axis_values, (std::vector<std::string>{"1", "v"}));
  EXPECT_EQ(jobs[11].axis_values, (std::vector<std::string>{"2", "w"}));
  EXPECT_EQ(jobs[11].folder, "runs/0011");
  ASSERT_EQ(jobs[11].overrides.size(), 3u);
  EXPECT_EQ(jobs[11].overrides[0].path, "duration_s");
  EXPECT_EQ(jobs[11].overrides[2].value, "w");
}

TEST_F(SweepFile, ASeedSoakNeedsNoAxes) {
  for (const std::string mode : {"grid", "zip"}) {
    const auto jobs = expand_jobs(load("sweep: soak\nexperiment: exp.yaml\nmode: " + mode +
                                       "\nseeds: {from: 3, to: 6}\nset: {duration_s: 2}\n"));
    ASSERT_EQ(jobs.size(), 4u) << mode;
    for (std::size_t i = 0; i < jobs.size(); ++i) {
      EXPECT_EQ(*jobs[i].seed, 3u + i);
      EXPECT_TRUE(jobs[i].axis_values.empty());
      ASSERT_EQ(jobs[i].overrides.size(), 1u);
      EXPECT_EQ(jobs[i].overrides[0].path, "duration_s");
    }
  }
  // A soak of a base experiment that does not exist is refused, located, before any run.
  EXPECT_EQ(error_of("sweep: soak\nexperiment: gone.yaml\nseeds: [1, 2]\n"),
            "s.yaml:2:13: key 'experiment': expected an experiment file (relative to the sweep "
            "file), but '" +
                (dir / "gone.yaml").string() + "' does not exist");
}

TEST_F(SweepFile, ZipPairsTheValues) {
  const auto jobs = expand_jobs(
      load("sweep: z\nexperiment: exp.yaml\nmode: zip\naxes: {a.x: [1, 2, 3], a.y: [u, v, w]}\n"));
  ASSERT_EQ(jobs.size(), 3u);
  EXPECT_FALSE(jobs[0].seed.has_value());
  EXPECT_EQ(jobs[2].axis_values, (std::vector<std::string>{"3", "w"}));
}

TEST_F(SweepFile, BadInputsAreLocated) {
  const std::string head = "sweep: b\nexperiment: exp.yaml\n";
  EXPECT_EQ(error_of(head + "axes: {a.x: [1]}\nseed: [1]\n"),
            "s.yaml:4:1: key 'seed': unknown key (did you mean 'seeds'?); expected one of: sweep, "
            "description, experiment, output, seeds, mode, set, axes, summary");
  EXPECT_EQ(error_of(head + "axes:\n  a.x: []\n"),
            "s.yaml:4:8: key 'axes.a.x': expected at least one value, got an empty list");
  EXPECT_EQ(error_of(head + "mode: zip\naxes:\n  a.x: [1, 2]\n  a.y: [1, 2, 3]\n"),
            "s.yaml:6:3: key 'axes.a.y': zipped axes need the same number of values: 'a.x' has 2 "
            "(at s.yaml:5:3), this one has 3");
  EXPECT_EQ(error_of(head + "axes:\n  a.x: {from: 0, to: 1}\n"),
            "s.yaml:4:8: key 'axes.a.x': a range needs finite numbers 'from' and 'to' and one of "
            "'step' (> 0) or 'count' (an integer >= 1)");
  EXPECT_EQ(error_of(head + "axes:\n  a.x: {from: 0, to: 1, step: 0}\n"),
            "s.yaml:4:31: key 'axes.a.x': expected 'step' > 0, got '0'");
  EXPECT_EQ(error_of(head + "axes:\n  a.x: {from: 0, to: 1, stp: 1}\n"),
            "s.yaml:4:25: key 'axes.a.x.stp': unknown key (did you mean 'step'?); expected one "
            "of: from, to, step, count");
  EXPECT_EQ(error_of(head + "axes: {a.x: [1], a.y: [2]}\nsummary: {metric: m, against: a.z}\n"),
            "s.yaml:4:31: key 'summary.against': 'a.z' is not an axis (did you mean 'a.x'?); "
            "expected one of: a.x, a.y");
  EXPECT_EQ(error_of(head + "seeds: [1, 1]\naxes: {a.x: [1]}\n"),
            "s.yaml:3:12: key 'seeds': seed 1 is listed twice (first at s.yaml:3:9); two runs "
            "would be identical");
  EXPECT_EQ(error_of(head + "axes: {a..x: [1]}\n"),
            "s.yaml:3:8: key 'axes.a..x': expected a dotted --set path such as "
            "nodes.NODE.params.NAME");
  EXPECT_EQ(error_of("sweep: b\nexperiment: none.yaml\naxes: {a.x: [1]}\n"),
            "s.yaml:2:13: key 'experiment': expected an experiment file (relative to the sweep "
            "file), but '" +
                (dir / "none.yaml").string() + "' does not exist");
  EXPECT_EQ(error_of("sweep: b c\nexperiment: exp.yaml\n"),
            "2 errors:\n  s.yaml:1:1: key 'axes': missing required key (expected a map of PATH: "
            "values; a sweep without axes needs 'seeds')\n  s.yaml:1:8: key 'sweep': expected a "
            "name of letters, digits, '_' and '-', "
            "got 'b c'");
}

// Values that make identical runs: the same value twice on a grid axis (numbers compared by
// value: 0.0 and -0.0, 1 and 1.0), a zip position repeated on every axis, a `seed` axis that
// `seeds` overrides; and a file of two YAML documents.
TEST_F(SweepFile, ValuesThatMakeIdenticalRunsAreRefused) {
  const std::string head = "sweep: b\nexperiment: exp.yaml\n";
  EXPECT_EQ(error_of(head + "axes: {a.x: [0.0, -0.0]}\n"),
            "s.yaml:3:19: key 'axes.a.x': value -0.0 is the same as 0.0 (at s.yaml:3:14); two "
            "runs would be identical");
  EXPECT_NE(error_of(head + "axes: {a.x: [1, 2, 1.0]}\n").find("value 1.0 is the same as 1"),
            std::string::npos);
  EXPECT_NE(error_of(head + "axes: {a.x: [abc, abc]}\n").find("value abc is the same as abc"),
            std::string::npos);
  EXPECT_NE(error_of(head + "axes: {a.x: {from: 1, to: 1, count: 3}}\n").find("is the same as"),
            std::string::npos);
  EXPECT_EQ(error_of(head + "mode: zip\naxes: {a.x: [1, 2, 1], a.y: [5, 6, 5.0]}\n"),
            "s.yaml:4:20: key 'axes': zip position 3 has the same values as position 1 on every "
            "axis; two runs would be identical");
  EXPECT_EQ(error_of(head + "mode: zip\naxes: {a.x: [1, 2, 1], a.y: [5, 6, 7]}\n"), "no error");
  EXPECT_EQ(error_of(head + "seeds: [1, 2]\naxes: {seed: [3, 4]}\n"),
            "s.yaml:4:8: key 'axes.seed': is also swept by 'seeds' (at s.yaml:3:8), which would "
            "override it in every run; keep one");
  // Integers beyond 2^53 are told apart exactly (neighbours are one apart, and equal as doubles).
  for (const char* big : {"9007199254740993", "18446744073709551615", "-9223372036854775807"}) {
    const std::string v(big);
    const std::string less = v.substr(0, v.size() - 1) + static_cast<char>(v.back() - 1);
    EXPECT_EQ(error_of(head + "axes: {a.x: [" + v + ", " + less + "]}\n"), "no error") << v;
    EXPECT_NE(error_of(head + "axes: {a.x: [" + v + ", " + v + "]}\n").find("is the same as"),
              std::string::npos)
        << v;
  }
  EXPECT_EQ(error_of(head + "axes: {a.x: [1]}\n---\naxes: {a.x: [2]}\n"),
            "s.yaml: holds 2 YAML documents (separated by '---'); expected one");
}

// Generated grid axes of up to 100000 values (the limit) are checked in linear time: a large
// sweep expands in well under the test's timeout.
TEST_F(SweepFile, LargeAxesAreCheckedForRepeatsQuickly) {
  const std::string head = "sweep: b\nexperiment: exp.yaml\n";
  const SweepSpec spec = load(head + "axes: {a.x: {from: 0, to: 99999, step: 1}}\n");
  EXPECT_EQ(spec.axes.front().values.size(), 100000u);
}

// The sweep's size is bounded before anything is allocated for it: values over all axes, runs,
// and overrides over all runs.
TEST_F(SweepFile, SweepSizesAreBounded) {
  const std::string head = "sweep: b\nexperiment: exp.yaml\n";
  std::string axes = "axes:\n";
  for (int k = 0; k < 11; ++k) axes += fmt::format("  a.x{}: {{from: 0, to: 99999, step: 1}}\n", k);
  EXPECT_NE(error_of(head + axes).find("the axes hold more than 1000000 values in all"),
            std::string::npos);
  EXPECT_NE(error_of(head + "axes: {a.x: {from: 1, to: 400, step: 1}, a.y: {from: 1, to: 400, "
                            "step: 1}}\n")
                .find("the grid has more than 100000 runs"),
            std::string::npos);
  std::string zip2 = "mode: zip\naxes:\n";
  for (int k = 0; k < 12; ++k) zip2 += fmt::format("  a.x{}: {{from: 1, to: 90000, step: 1}}\n", k);
  EXPECT_NE(error_of(head + zip2).find("the axes hold more than 1000000 values"),
            std::string::npos);
  std::string zip3 = "mode: zip\nset: {";
  for (int k = 0; k < 30; ++k) zip3 += fmt::format("{}s.f{}: 1", k ? ", " : "", k);
  zip3 += "}\naxes: {a.x: {from: 1, to: 90000, step: 1}}\n";
  EXPECT_NE(error_of(head + zip3).find("overrides in all; split the sweep"), std::string::npos);
}

}  // namespace
}  // namespace somasim::sweep
