// configs/body_schema_reaching.yaml, shortened to two short movements: the filter must beat the
// nominal model, the closed loop must beat the open loop, the outputs must not depend on the
// render thread count, and every user error is reported in full.
#include <gtest/gtest.h>

#include <algorithm>

#include "experiment_runner.hpp"
#include "somasim/error.hpp"

using somasim::Override;
using somasim::testing::read_file;
using somasim::testing::run_config;

namespace {

// One target, two start poses, 40 + 15 frames, M = 100.
std::vector<Override> short_run(std::vector<Override> extra = {}) {
  std::vector<Override> o = {
      {"nodes.reach.params.targets", "[-0.006, 0.007, 0.258, 44.2, -78.7, -66.4]"},
      {"nodes.reach.params.starts_per_target", "2"},
      {"nodes.reach.params.repetitions", "1"},
      {"nodes.reach.params.open_loop_frames", "40"},
      {"nodes.reach.params.closed_loop_frames", "15"},
      {"nodes.filter.params.particles", "100"}};
  for (const Override& e : extra) {  // an extra value replaces the default one
    auto same =
        std::find_if(o.begin(), o.end(), [&](const Override& d) { return d.path == e.path; });
    if (same != o.end())
      same->value = e.value;
    else
      o.push_back(e);
  }
  return o;
}

double num(const nlohmann::json& m, const char* key) {
  EXPECT_TRUE(m.contains(key) && m[key].is_number()) << key;
  return m.value(key, 1e9);
}

}  // namespace

TEST(BodySchemaReaching, AdaptationBeatsTheNominalModelAndTheClosedLoopTheOpenLoop) {
  const auto run = run_config("body_schema_reaching",
                              short_run({{"nodes.filter.params.evaluate_frame", "39"}}), "short");
  const auto& m = run.flat;
  ASSERT_EQ(m["status"], "completed") << m["error"];
  EXPECT_EQ(m["reach_movements"], 2);
  EXPECT_EQ(m["stop_reason"], "node 'reach': 2 movements done");
  // The nominal model is off by the injected offsets: several centimetres.
  EXPECT_GT(num(m, "estimation_error_nominal_mm"), 20.0);
  EXPECT_LT(num(m, "estimation_error_mm"), 0.5 * num(m, "estimation_error_nominal_mm"));
  EXPECT_LT(num(m, "estimation_error_deg"), num(m, "estimation_error_nominal_deg"));
  EXPECT_LT(num(m, "reaching_error_closed_loop_mm"), 0.5 * num(m, "reaching_error_open_loop_mm"));
  EXPECT_GT(num(m, "filter_step_ms"), 0.0);
  EXPECT_EQ(m["filter_frames"], 2 * 56);  // frames 0 ... 55 of each movement
  // At the evaluated frame the true offsets and the estimate are scored on the same images.
  EXPECT_GT(num(m, "truth_likelihood"), 0.0);
  EXPECT_LE(num(m, "truth_likelihood"), 1.0);
  EXPECT_GT(num(m, "estimate_likelihood"), 0.0);
  EXPECT_LE(num(m, "estimate_likelihood"), 1.0);
  EXPECT_GE(num(m, "truth_outscored_movements"), 0);
  EXPECT_LE(num(m, "truth_outscored_movements"), 2);
  for (const char* f :
       {"figures/body_schema_estimation.png", "figures/body_schema_reaching.png",
        "figures/body_schema_closed_loop.png", "reach_frames.csv", "body_schema_filter.csv"})
    EXPECT_TRUE(std::filesystem::exists(run.dir / f)) << f;
}

TEST(BodySchemaReaching, StillAdaptsWithImageNoise) {
  const auto run = run_config("body_schema_reaching",
                              short_run({{"nodes.reach.params.starts_per_target", "1"},
                                         {"nodes.filter.params.image_noise", "12"}}),
                              "noise");
  const auto& m = run.flat;
  ASSERT_EQ(m["status"], "completed") << m["error"];
  EXPECT_EQ(m["filter_frames_without_match"], 0);
  EXPECT_LT(num(m, "estimation_error_mm"), 0.5 * num(m, "estimation_error_nominal_mm"));
}

TEST(BodySchemaReaching, SameSeedSameOutputsWhateverTheRenderThreads) {
  const auto a = run_config("body_schema_reaching",
                            short_run({{"nodes.reach.params.starts_per_target", "1"},
                                       {"nodes.filter.params.render_threads", "1"}}),
                            "threads1");
  const auto b = run_config("body_schema_reaching",
                            short_run({{"nodes.reach.params.starts_per_target", "1"},
                                       {"nodes.filter.params.render_threads", "3"}}),
                            "threads3");
  ASSERT_EQ(a.metrics["status"], "completed") << a.metrics["error"];
  ASSERT_EQ(b.metrics["status"], "completed") << b.metrics["error"];
  for (const char* f : {"body_schema_filter.csv", "reach_frames.csv"}) {
    const std::string text = read_file(a.dir / f);
    EXPECT_GT(text.size(), 1000u) << f;
    EXPECT_EQ(text, read_file(b.dir / f)) << f;
  }
}

// An ensemble's first member is the single filter (its stream is drawn first) and the estimate
// published is the member's that explains the frame best: at the evaluated frame of the one
// movement (in the open loop, so the images are the same) it explains the images at least as
// well as the single filter's estimate. The outputs do not depend on the render thread count.
TEST(BodySchemaReaching, AnEnsemblePublishesTheMemberThatExplainsTheFrameBest) {
  const auto with = [](const char* members, const char* threads) {
    return short_run({{"nodes.reach.params.starts_per_target", "1"},
                      {"nodes.filter.params.evaluate_frame", "39"},
                      {"nodes.filter.params.particles", "60"},
                      {"nodes.filter.params.ensemble", members},
                      {"nodes.filter.params.render_threads", threads}});
  };
  const auto single = run_config("body_schema_reaching", with("1", "2"), "single");
  const auto three = run_config("body_schema_reaching", with("3", "1"), "ensemble");
  const auto three_again = run_config("body_schema_reaching", with("3", "3"), "ensemble3");
  for (const auto* run : {&single, &three, &three_again})
    ASSERT_EQ(run->metrics["status"], "completed") << run->metrics["error"];
  EXPECT_GE(num(three.flat, "estimate_likelihood"), num(single.flat, "estimate_likelihood"));
  EXPECT_FALSE(single.flat.contains("ensemble_switches"));
  EXPECT_GE(num(three.flat, "ensemble_switches"), 0.0);
  EXPECT_EQ(three.flat["filter_frames"], single.flat["filter_frames"]);
  EXPECT_LT(num(three.flat, "estimation_error_mm"), num(three.flat, "estimation_error_nominal_mm"));
  EXPECT_EQ(read_file(three.dir / "body_schema_filter.csv"),
            read_file(three_again.dir / "body_schema_filter.csv"));
}

// A configuration error ends the run before it starts: status bad_input, the located message.
TEST(BodySchemaReaching, AJointOutsideTheArmChainIsALocatedError) {
  const auto run = run_config(
      "body_schema_reaching",
      short_run({{"nodes.filter.params.joints", "[r_shoulder_pitch, l_elbow]"}}), "joint");
  EXPECT_EQ(run.metrics["status"], "bad_input");
  EXPECT_EQ(run.metrics["error"],
            "--set nodes.filter.params.joints=[r_shoulder_pitch, l_elbow]: node 'filter', key "
            "'params.joints': joint 'l_elbow' is not in the arm chain 'right_arm' (joints: "
            "torso_pitch, torso_roll, torso_yaw, r_shoulder_pitch, r_shoulder_roll, "
            "r_shoulder_yaw, r_elbow, r_wrist_prosup, r_wrist_pitch, r_wrist_yaw)");
}

TEST(BodySchemaReaching, FewerThanOneParticleIsALocatedError) {
  try {
    run_config("body_schema_reaching", short_run({{"nodes.filter.params.particles", "0"}}));
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "--set nodes.filter.params.particles=0: node 'filter', key 'params.particles': "
                 "value 0 is out of range; expected an integer in [1, 20000]");
  }
}

TEST(BodySchemaReaching, HypothesisLinksOutOfViewFailTheRunWithTheReason) {
  const auto run =
      run_config("body_schema_reaching",
                 short_run({{"nodes.filter.params.links", "[l_upper_arm]"}}), "unseen");
  EXPECT_EQ(run.metrics["status"], "failed");
  EXPECT_EQ(run.metrics["error"],
            "node 'filter' at t = 1.9 s: body_schema_filter: movement 0: the hypothesis links "
            "(l_upper_arm) are not visible: camera 'left_eye': hypothesis batch: the region of "
            "interest is empty (no mesh of any of the 100 hypotheses projects into the image)");
}

TEST(BodySchemaReaching, ATargetOutOfReachIsReportedWithTheClosestPose) {
  const auto run =
      run_config("body_schema_reaching",
                 short_run({{"nodes.reach.params.targets", "[0.0, 0.0, 0.9, 0, 0, 0]"}}), "far");
  EXPECT_EQ(run.metrics["status"], "bad_input");
  EXPECT_NE(run.metrics["error"].get<std::string>().find(
                "node 'reach', key 'params.targets': target 0 (0.000, 0.000, 0.900) m in the "
                "left_eye frame is outside the arm's reach: the closest palm pose found is 596.3 "
                "mm and 29.1 deg away"),
            std::string::npos)
      << run.metrics["error"];
}

TEST(BodySchemaReaching, NoMatchingParticleStopsCleanlyOrReinflates) {
  // A hand colour no pixel has: every likelihood is 0.
  const std::vector<Override> blind = {{"nodes.filter.params.hand_hsv_low", "[100, 250, 250]"},
                                       {"nodes.filter.params.hand_hsv_high", "[101, 255, 255]"}};
  auto stop = blind;
  stop.push_back({"nodes.filter.params.on_no_match", "stop"});
  const auto stopped = run_config("body_schema_reaching", short_run(stop), "stop");
  EXPECT_EQ(stopped.metrics["status"], "completed");
  EXPECT_EQ(stopped.metrics["stop_reason"],
            "node 'filter': body_schema_filter: no particle explains the images at t = 1.900 s "
            "(movement 0): every likelihood is 0 (is the hand in view and segmented? "
            "hand_hsv_low/high)");
  EXPECT_EQ(stopped.metric("filter_frames_without_match"), 1);
  const auto kept = run_config("body_schema_reaching", short_run(blind), "reinflate");
  EXPECT_EQ(kept.metrics["status"], "completed");
  EXPECT_EQ(kept.metric("filter_frames_without_match"), 2 * 56);
}

TEST(BodySchemaParticles, FiltersOfOtherSizesRunOnTheSameImages) {
  const auto run =
      run_config("body_schema_particles",
                 {{"nodes.reach.params.targets", "[-0.006, 0.007, 0.258, 44.2, -78.7, -66.4]"},
                  {"nodes.reach.params.starts_per_target", "1"},
                  {"nodes.reach.params.open_loop_frames", "30"},
                  {"nodes.filter.params.particles", "60"},
                  {"nodes.filter.params.compare_particles", "[20, 120]"},
                  {"nodes.filter.params.evaluate_frame", "30"}},
                 "particles");
  const auto& m = run.metrics;
  ASSERT_EQ(m["status"], "completed") << m["error"];
  for (const char* key : {"particles_20_estimation_error_mm", "particles_60_estimation_error_mm",
                          "particles_120_estimation_error_deg", "particles_120_step_ms"})
    EXPECT_TRUE(m["nodes"]["filter"][key].is_number()) << key;
  // More particles cost more time per step.
  EXPECT_GT(m["nodes"]["filter"]["particles_120_step_ms"].get<double>(),
            m["nodes"]["filter"]["particles_20_step_ms"].get<double>());
  EXPECT_TRUE(std::filesystem::exists(run.dir / "figures/body_schema_particles.png"));
}

TEST(BodySchemaEdges, BothArmsAdaptFromEdgesAndTheBimanualErrorIsReported) {
  const auto run = run_config("body_schema_edges",
                              {{"nodes.reach_right.params.starts_per_target", "1"},
                               {"nodes.reach_left.params.starts_per_target", "1"},
                               {"nodes.filter_right.params.particles", "100"},
                               {"nodes.filter_left.params.particles", "100"}},
                              "edges");
  const auto& m = run.metrics;
  ASSERT_EQ(m["status"], "completed") << m["error"];
  for (const char* arm : {"reach_right", "reach_left"}) {
    const auto& r = m["nodes"][arm];
    EXPECT_LT(r["estimation_error_mm"].get<double>(),
              r["estimation_error_nominal_mm"].get<double>())
        << arm;
  }
  const auto& b = m["nodes"]["bimanual"];
  for (const char* key :
       {"bimanual_tip_gap_open_loop_mm", "bimanual_tip_gap_closed_loop_mm",
        "bimanual_tip_surface_gap_open_loop_mm", "bimanual_tip_surface_gap_closed_loop_mm",
        "bimanual_palm_distance_error_open_loop_mm", "bimanual_palm_distance_error_closed_loop_mm"})
    EXPECT_TRUE(b[key].is_number()) << key;
  EXPECT_LT(b["bimanual_tip_gap_closed_loop_mm"].get<double>(),
            b["bimanual_tip_gap_open_loop_mm"].get<double>());
  // The fingertip frames lie on the fingers' surfaces: the surfaces are never farther apart.
  for (const std::string loop : {"open", "closed"})
    EXPECT_LE(b["bimanual_tip_surface_gap_" + loop + "_loop_mm"].get<double>(),
              b["bimanual_tip_gap_" + loop + "_loop_mm"].get<double>())
        << loop;
}
