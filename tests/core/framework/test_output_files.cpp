// Output files named by parameters: every name that would overwrite one of the run's own files
// or another node's output is a located error at configure time (`validate`), for every
// output-file parameter of a shipped config.
#include <gtest/gtest.h>

#include "cli_support.hpp"

namespace somasim::test {
namespace {

const std::string kConfigs = std::string(SOMASIM_SOURCE_DIR) + "/configs/";

CliResult validate_with(const std::string& config, const std::string& set, const TempDir& dir) {
  return cli({"validate", kConfigs + config, "--set", set}, dir, /*with_plugin_path=*/false);
}

TEST(OutputFiles, TheRunsOwnFilesCannotBeNamed) {
  TempDir dir;
  // pps_single_taxel records pps.activations and thrower.stimulus.
  for (const std::string name :
       {"metrics.json", "log.txt", "experiment.resolved.yaml", "manifest.json", "./metrics.json",
        "sub/../log.txt", "pps.activations.csv", "thrower.stimulus.csv", "figures",
        "figures/map.png", "frames", "frames/cam.left_eye_rgb/000001.png", "pps.activations",
        "pps.activations/index.csv"}) {
    const CliResult r =
        validate_with("pps_single_taxel.yaml", "nodes.pps.params.save=" + name, dir);
    EXPECT_EQ(r.code, 2) << name;
    EXPECT_NE(r.err.find("node 'pps', key 'params.save': output file '" + name + "'"),
              std::string::npos)
        << r.err;
  }
  const CliResult ok =
      validate_with("pps_single_taxel.yaml", "nodes.pps.params.save=maps/learned.json", dir);
  EXPECT_EQ(ok.code, 0) << ok.err;
}

TEST(OutputFiles, TwoParametersCannotNameOneFile) {
  TempDir dir;
  // pps_avoidance: the evaluator writes presentations.csv; the learner's save may not take it.
  for (const std::string name : {"presentations.csv", "./presentations.csv"}) {
    const CliResult r = validate_with("pps_avoidance.yaml", "nodes.pps.params.save=" + name, dir);
    EXPECT_EQ(r.code, 2) << name;
    EXPECT_NE(r.err.find("node 'eval', key 'params.csv': output file 'presentations.csv' is "
                         "written by node 'pps', key 'params.save' already"),
              std::string::npos)
        << r.err;
  }
}

}  // namespace
}  // namespace somasim::test
