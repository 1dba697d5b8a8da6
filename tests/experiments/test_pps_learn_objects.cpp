#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "experiment_runner.hpp"

using somasim::testing::read_file;
using somasim::testing::run_config;

namespace {

// configs/pps_learn_objects.yaml, shortened to three objects per part (balls and cubes); each
// touched taxel is touched once, so the learner's estimates accept one event here.
const std::vector<somasim::Override> kShort = {{"nodes.thrower.params.approaches", "6"},
                                               {"nodes.pps.params.contact_min_events", "1"}};

nlohmann::json without_wall_clock(nlohmann::json m) {
  for (const char* key : {"wall_time_s", "real_time_factor"}) m.erase(key);
  return m;
}

}  // namespace

// Objects reach the skin, the skin reports the contacts, one learner teaches both parts from
// the taxels posed by the believed kinematics, and compares its offset estimates with the
// offsets the thrower knows each touched taxel should show.
TEST(PpsLearnObjects, ApproachingObjectsTeachBothPartsAndTheirOffsetsAreEvaluated) {
  const auto run = run_config("pps_learn_objects", kShort, "a");
  ASSERT_EQ(run.metrics["status"], "completed") << run.metrics["error"];
  EXPECT_EQ(run.metric("objects_presented"), 6);
  const auto& pps = run.metrics["nodes"]["pps"];
  EXPECT_EQ(pps["events"], 6);
  for (const char* part : {"left_forearm", "right_palm"}) {
    EXPECT_EQ(pps["per_part"][part]["events"], 3) << part;
    EXPECT_GT(pps["per_part"][part]["positive_samples"].get<int>(), 0) << part;
    EXPECT_TRUE(run.metric("offset_mean_m")[part].is_number()) << part;
    // The injected error is 2 cm-class and positive (the believed skin lies inside) but for
    // forearm taxels near the elbow, which the shoulder and elbow errors move little (over 40
    // objects the forearm's taxels show -0.3 to 21 mm).
    const double truth = run.metric("true_offset_mean_m")[part].get<double>();
    EXPECT_GT(truth, std::string(part) == "right_palm" ? 0.005 : -0.005) << part;
    EXPECT_LT(truth, 0.04) << part;
    EXPECT_EQ(run.metric("presented_per_part")[part]["contact_events"], 3) << part;
  }
  EXPECT_GT(run.metric("offset_taxels_evaluated").get<int>(), 0);
  // The contact estimator under the unsuffixed keys, floor and Fig 8 alongside; the ridge end too
  // (null here: 1 cm bins hold too few samples of 2 approaches for its plateau of 5 counts).
  EXPECT_TRUE(run.metric("offset_error_max_m").is_number());
  EXPECT_EQ(run.metric("offset_error_max_m"), run.metric("offset_error_max_contact_m"));
  EXPECT_TRUE(run.metric("offset_error_max_floor_m").is_number());
  EXPECT_TRUE(run.metric("offset_error_max_paper_m").is_number());
  EXPECT_TRUE(run.flat.contains("offset_error_max_ridge_m"));
  EXPECT_TRUE(std::filesystem::exists(run.dir / "pps_objects.json"));
  // Fig 9-style snapshot after the first event, of the taxel that event touched (the only one
  // with a positive sample), and the final landscapes.
  int snapshots = 0;
  for (const auto& f : std::filesystem::directory_iterator(run.dir / "figures")) {
    const std::string name = f.path().filename().string();
    if (name.rfind("landscape_left_forearm_", 0) != 0 || name.find("_after_1_events") == name.npos)
      continue;
    ++snapshots;
    const std::string id = name.substr(23, name.find('_', 23) - 23);
    EXPECT_GT(run.metrics["nodes"]["pps"]["taxels"]["left_forearm/" + id]["contacts"].get<int>(), 0)
        << name;
  }
  EXPECT_GE(snapshots, 1);
  EXPECT_TRUE(std::filesystem::exists(run.dir / "figures/landscape_right_palm_0.png"));

  // Same seed: the same metrics (but for wall-clock figures) and the same learned maps.
  const auto again = run_config("pps_learn_objects", kShort, "b");
  ASSERT_EQ(again.metrics["status"], "completed") << again.metrics["error"];
  EXPECT_EQ(without_wall_clock(again.metrics), without_wall_clock(run.metrics));
  EXPECT_EQ(read_file(again.dir / "pps_objects.json"), read_file(run.dir / "pps_objects.json"));
}

// Injected kinematic errors of either sign and mixed signs across joints (2-3 cm perceived
// offsets): every evaluated taxel's contact estimate within 1 cm of the truth (issue 10; the
// README's offset table reports the full runs and the map-based estimators beside it).
class PpsLearnObjectsErrorSets : public ::testing::TestWithParam<const char*> {};

TEST_P(PpsLearnObjectsErrorSets, EveryTaxelEstimateWithinOneCentimetre) {
  const std::vector<somasim::Override> overrides = {
      {"nodes.thrower.params.approaches", "120"},
      {"nodes.believed.params.joint_offsets_deg", std::string("{") + GetParam() + "}"}};
  const auto run = run_config("pps_learn_objects", overrides, "set");
  ASSERT_EQ(run.metrics["status"], "completed") << run.metrics["error"];
  EXPECT_GE(run.metric("offset_taxels_evaluated").get<int>(), 30);
  EXPECT_LE(run.metric("offset_error_max_m").get<double>(), 0.01) << GetParam();
  // The error is real: perceived offsets of centimetres, which the estimate follows.
  double largest_truth = 0.0;
  for (const auto& [label, taxel] : run.metrics["nodes"]["pps"]["taxels"].items())
    if (taxel["true_offset_m"].is_number())
      largest_truth = std::max(largest_truth, std::abs(taxel["true_offset_m"].get<double>()));
  EXPECT_GT(largest_truth, 0.01) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(
    Sets, PpsLearnObjectsErrorSets,
    ::testing::Values("l_shoulder_roll: 4, l_elbow: 3, r_shoulder_roll: 3, r_elbow: 2",
                      "l_shoulder_roll: -4, l_elbow: 3, r_shoulder_roll: -3, r_elbow: 2",
                      "l_shoulder_roll: 3, l_elbow: -3, r_shoulder_roll: -2, r_elbow: 3"));
