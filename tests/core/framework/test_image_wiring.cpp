// Image ports have one type per encoding: wiring a depth or id-mask output into an input that
// takes colour is refused when the experiment is checked, for every such pair in the shipped
// visual configs, with the wiring check's located message.
#include <gtest/gtest.h>

#include "cli_support.hpp"

namespace somasim::test {
namespace {

const std::string kConfigs = std::string(SOMASIM_SOURCE_DIR) + "/configs/";

TEST(ImageWiring, DepthAndMasksCannotFeedAColourInput) {
  TempDir dir;
  struct Input {
    std::string config, node;
  };
  // Nodes with colour inputs: the object tracker, the marker tracker, the body-schema filter.
  for (const Input& in : {Input{"pps_avoidance_visual.yaml", "track"},
                          Input{"pps_learn_visual_double_touch.yaml", "track"},
                          Input{"body_schema_edges.yaml", "filter_right"}}) {
    for (const std::string eye : {"left_eye", "right_eye"})
      for (const std::string kind : {"depth", "mask"}) {
        const std::string set =
            "nodes." + in.node + ".inputs." + eye + "_rgb=cam." + eye + "_" + kind;
        const CliResult r =
            cli({"validate", kConfigs + in.config, "--set", set}, dir, /*with_plugin_path=*/false);
        EXPECT_EQ(r.code, 2) << in.config << " " << set << "\n" << r.err;
        const std::string type = kind == "depth" ? "depth32f_image" : "id32s_image";
        EXPECT_NE(r.err.find("node '" + in.node + "', key 'inputs." + eye +
                             "_rgb': type mismatch: input '" + eye +
                             "_rgb' takes 'rgb8_image' but 'cam." + eye + "_" + kind + "' gives '" +
                             type + "'"),
                  std::string::npos)
            << r.err;
      }
  }
}

}  // namespace
}  // namespace somasim::test
