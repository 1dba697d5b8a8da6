// configs/ball_on_forearm.yaml, shortened: every ball that touches a part's skin (physics
// ground truth) yields a skin contact event on that part, and on no other part.
#include <gtest/gtest.h>

#include "experiment_runner.hpp"

using somasim::testing::run_config;

TEST(BallOnForearm, EveryBallTouchingASkinPartYieldsAnEventOnThatPart) {
  const auto run = run_config("ball_on_forearm", {{"nodes.thrower.params.throws", "8"}});
  ASSERT_EQ(run.metrics["status"], "completed") << run.metrics["error"];
  EXPECT_EQ(run.metric("balls_thrown"), 8);
  const int touched = run.metric("balls_touched_expected_part").get<int>();
  EXPECT_GE(touched, 2);  // most throws reach the aimed skin (some are blocked by the thumb)
  EXPECT_EQ(run.metric("hits_on_expected_part").get<int>(), touched);
  EXPECT_EQ(run.metric("events_on_other_parts"), 0);
  EXPECT_TRUE(std::filesystem::exists(run.dir / "figures/skin_layout.png"));
  EXPECT_GT(run.metrics["real_time_factor"].get<double>(), 0.0);
}

TEST(BallOnForearm, SameSeedSameMetrics) {
  const std::vector<somasim::Override> shorter = {{"nodes.thrower.params.throws", "3"}};
  auto a = run_config("ball_on_forearm", shorter, "a").metrics;
  auto b = run_config("ball_on_forearm", shorter, "b").metrics;
  for (auto* m : {&a, &b}) {
    m->erase("wall_time_s");
    m->erase("real_time_factor");
  }
  EXPECT_EQ(a, b);
}

// configs/urdf_ball_on_forearm.yaml: the same experiment on the iCub loaded from its URDF
// (assets/robots/icub_v1.urdf, written by `somasim robot export-urdf`) and the YAML overlay that
// adds its skin. The skin sees the same balls as on the YAML robot.
TEST(BallOnForearm, TheRobotLoadedFromAUrdfFeelsTheSameBalls) {
  const std::vector<somasim::Override> shorter = {{"nodes.thrower.params.throws", "8"}};
  const auto yaml = run_config("ball_on_forearm", shorter, "yaml");
  const auto urdf = run_config("urdf_ball_on_forearm", shorter, "urdf");
  ASSERT_EQ(urdf.metrics["status"], "completed") << urdf.metrics["error"];
  for (const char* m : {"balls_thrown", "balls_touched_expected_part", "hits_on_expected_part",
                        "events_on_other_parts"})
    EXPECT_EQ(urdf.metric(m), yaml.metric(m)) << m;
}
