// configs/replay_recording.yaml: a yarpdatadumper recording (the synthetic demo in
// assets/recordings) replayed into the graph. Every message arrives, the dropout is reported as
// a gap at its line, the skin's touches become one event per episode on the mapped parts, and
// the simulated arm follows the recorded encoders.
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <gtest/gtest.h>

#include "experiment_runner.hpp"

using somasim::testing::run_config;

namespace {

// The rows of a recorder CSV: time [s] -> values.
std::map<long, std::vector<double>> read_csv(const std::filesystem::path& file) {
  std::map<long, std::vector<double>> rows;
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::vector<double> v;
    for (std::string cell; std::getline(s, cell, ',');) v.push_back(std::stod(cell));
    rows[std::lround(v.at(0) * 1000.0)] = v;  // by millisecond
  }
  return rows;
}

}  // namespace

TEST(ReplayRecording, EveryMessageArrivesAndTheArmFollowsTheEncoders) {
  const auto run = run_config("replay_recording");
  ASSERT_EQ(run.metrics["status"], "completed") << run.metrics["error"];
  EXPECT_EQ(run.metric("arm.messages"), 750);
  EXPECT_EQ(run.metric("arm.delivered"), 750);
  ASSERT_EQ(run.metric("arm.gaps").size(), 1u);
  EXPECT_EQ(run.metric("arm.gaps")[0]["line"], 501);
  EXPECT_EQ(run.metric("samples_outside_limits"), 0);
  EXPECT_EQ(run.metric("skin_log.delivered"), 400);
  EXPECT_EQ(run.metric("parts.left_forearm.events"), 2);
  EXPECT_EQ(run.metric("parts.left_forearm.contacts"), 35);
  EXPECT_EQ(run.metric("parts.right_palm.events"), 1);

  // The world's joints against the replayed ones, at the replay's 100 Hz, after the first
  // second: every driven joint within 1 degree.
  const auto replayed = read_csv(run.dir / "arm.state.csv");
  const auto world = read_csv(run.dir / "world.joint_state.csv");
  ASSERT_GT(replayed.size(), 800u);
  double worst_deg = 0.0;
  int compared = 0;
  for (const auto& [ms, q] : replayed) {
    if (ms < 1000) continue;
    const auto w = world.find(ms);
    ASSERT_NE(w, world.end()) << ms;
    const std::size_t dofs = (q.size() - 1) / 2;
    for (std::size_t d = 1; d <= dofs; ++d) {
      if (q[d] == 0.0 && q[d + dofs] == 0.0) continue;  // not driven by the recording
      worst_deg = std::max(worst_deg, std::abs(q[d] - w->second[d]) * 180.0 / M_PI);
      ++compared;
    }
  }
  EXPECT_GT(compared, 5000);
  EXPECT_LT(worst_deg, 1.0);
}
