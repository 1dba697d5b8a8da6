// pps_learner: learning from contact events, activations, save/load, errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "somasim/port_types.hpp"
#include "somasim/pps/map_io.hpp"
#include "somasim/pps/ports.hpp"
#include "somasim/skin/ports.hpp"
#include "somasim/testing/harness.hpp"

using somasim::ContactEvents;
using somasim::SkinTaxels;
using somasim::TaxelValues;
using somasim::pps::Stimulus;
using somasim::testing::Harness;

namespace {

const char* kGraph = R"(
base_rate_hz: 20
nodes:
  pps:
    plugin: pps_learner
    params: {body_part: patch, save: learned.json, PARAMS}
    inputs: {stimulus: harness.stimulus, taxels: harness.taxels, contacts: harness.contacts}
)";

std::string graph(const std::string& params = "") {
  std::string g = kGraph;
  g.replace(g.find("PARAMS"), 6, params.empty() ? "learn: true" : params);
  return g;
}

// Two taxels 5 cm apart on a flat patch (root frame, normals +z).
void set_patch(Harness& h) {
  auto& skin = h.input<SkinTaxels>("taxels");
  somasim::SkinPart part;
  part.name = "patch";
  part.taxel_ids = {10, 11};
  part.positions = {{0, 0, 0}, {0.05, 0, 0}};
  part.normals = {{0, 0, 1}, {0, 0, 1}};
  skin.parts = {part};
}

// A straight approach along -z onto taxel 10 at 0.1 m/s from 0.2 m, then a contact on it.
void approach_and_touch(Harness& h, std::uint64_t event_id) {
  auto& s = h.input<Stimulus>("stimulus");
  s.present = true;
  s.velocity = {0, 0, -0.1};
  for (int k = 0; k <= 40; ++k) {
    s.position = {0, 0, 0.2 - 0.1 * 0.05 * k};
    h.step();
  }
  auto& contacts = h.input<ContactEvents>("contacts");
  somasim::ContactEvent e;
  e.id = event_id;
  e.time_s = h.time_s();
  e.body_part = "patch";
  e.touched_taxels = {10};
  contacts.recent.push_back(e);
  h.step();
  s.present = false;
  h.step();
}

// Learns from one approach-and-touch and keeps the saved map as `file_name` in the temp dir.
std::filesystem::path learn_one_contact(const std::string& file_name) {
  const std::filesystem::path saved = std::filesystem::temp_directory_path() / file_name;
  Harness h(graph());
  set_patch(h);
  approach_and_touch(h, 1);
  h.finish();
  std::filesystem::copy_file(h.out_dir() / "learned.json", saved,
                             std::filesystem::copy_options::overwrite_existing);
  return saved;
}

}  // namespace

TEST(PpsLearner, LearnsPositivesForTheTouchedTaxelAndNegativesForTheOthers) {
  Harness h(graph());
  set_patch(h);
  approach_and_touch(h, 1);
  h.finish();
  EXPECT_EQ(h.metric("pps", "events"), 1);
  EXPECT_GT(h.metric("pps", "positive_samples").get<int>(), 20);
  EXPECT_GT(h.metric("pps", "negative_samples").get<int>(), 0);
  const auto state = somasim::pps::load_learned_state((h.out_dir() / "learned.json").string());
  ASSERT_EQ(state.taxels.size(), 2u);
  EXPECT_EQ(state.taxels[0].id, 10);
  unsigned neg_on_touched = 0, pos_on_other = 0;
  for (auto c : state.taxels[0].neg) neg_on_touched += c;
  for (auto c : state.taxels[1].pos) pos_on_other += c;
  EXPECT_EQ(neg_on_touched, 0u);
  EXPECT_EQ(pos_on_other, 0u);
}

TEST(PpsLearner, ActivatesForAnApproachLikeTheLearnedOneAndNotForARecedingObject) {
  Harness h(graph());
  set_patch(h);
  approach_and_touch(h, 1);
  approach_and_touch(h, 2);
  auto& s = h.input<Stimulus>("stimulus");
  s.present = true;
  s.position = {0, 0, 0.08};
  s.velocity = {0, 0, -0.1};
  h.step();
  const auto& act = h.output<TaxelValues>("pps.activations");
  ASSERT_EQ(act.values.size(), 2u);
  EXPECT_EQ(act.labels[0], "patch/10");
  EXPECT_GT(act.values[0], 0.5);
  s.velocity = {0, 0, 0.1};  // receding: signed TTC undefined
  h.step();
  EXPECT_EQ(h.output<TaxelValues>("pps.activations").values[0], 0.0);
  EXPECT_EQ(h.output<double>("pps.max_activation"), 0.0);
}

TEST(PpsLearner, ReloadsItsSavedStateAndEvaluatesWithoutLearning) {
  const std::filesystem::path saved = learn_one_contact("somasim_test_pps_reload.json");
  Harness h(graph("learn: false, load: " + saved.string()));
  set_patch(h);
  approach_and_touch(h, 1);
  h.finish();
  EXPECT_EQ(h.metric("pps", "events"), 0);
  auto& s = h.input<Stimulus>("stimulus");
  (void)s;
  const auto state = somasim::pps::load_learned_state((h.out_dir() / "learned.json").string());
  const auto original = somasim::pps::load_learned_state(saved.string());
  EXPECT_EQ(state.taxels[0].pos, original.taxels[0].pos);
  std::filesystem::remove(saved);
}

TEST(PpsLearner, UnknownBodyPartIsABadInputNamingTheParts) {
  std::string g = graph();
  g.replace(g.find("body_part: patch"), 16, "body_part: pach");
  Harness h(g);
  set_patch(h);
  try {
    h.step();
    FAIL() << "expected an InputError";
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "<inline>:6:25: node 'pps', key 'params.body_part': no skin part 'pach' in the "
                 "'taxels' input (did you mean 'patch'?); parts: patch");
  }
}

TEST(PpsLearner, ALearnedFileForAnotherBodyPartIsRejected) {
  const std::filesystem::path saved = learn_one_contact("somasim_test_pps_other.json");
  std::string g = graph("load: " + saved.string());
  g.replace(g.find("body_part: patch"), 16, "body_part: palm");
  try {
    Harness h(g);
    FAIL() << "expected an InputError";
  } catch (const somasim::InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "<inline>:6:57: node 'pps', key 'params.load': " + saved.string() +
                  ": body part is \"patch\", expected \"palm\"");
  }
  std::filesystem::remove(saved);
}

// The single-taxel Monte Carlo (Fig 3 noise and speeds, unsigned TTC, the code's RF) with a
// -2 cm systematic offset, shortened: the ridge-end estimate is within 1 cm of the truth (the
// mean perceived D at contact, from the thrower) and of the injected offset; the floor within a
// D bin (3.75 cm here); the Fig 8 estimate is reported alongside under its old key.
TEST(PpsLearner, RidgeEndOffsetRecoversAnInjectedTwoCentimetreOffset) {
  Harness h(R"(
base_rate_hz: 20
nodes:
  thrower:
    plugin: taxel_thrower
    params: {throws: 150, landing_sigma: 0.018, speed_min: 0.02, speed_max: 0.12,
             position_noise: 0.001, velocity_noise: 0.01, offset: -0.02}
  pps:
    plugin: pps_learner
    params: {body_part: taxel, ttc: unsigned, buffer_horizon: 0,
             rf_shape: cone_mirrored_cylinder, save: ''}
    inputs: {stimulus: thrower.stimulus, taxels: thrower.taxels, contacts: thrower.contacts}
)");
  while (h.step()) {
  }
  h.finish();
  const double truth = h.metric("thrower", "contact_distance_m").get<double>();
  const double ridge = h.metric("pps", "offset_ridge_m").get<double>();
  EXPECT_NEAR(truth, -0.024, 0.003);
  EXPECT_NEAR(ridge, truth, 0.01);
  EXPECT_NEAR(ridge, -0.02, 0.01);
  const auto taxel = h.metric("pps", "taxels")["0"];
  EXPECT_DOUBLE_EQ(taxel["offset_ridge_m"].get<double>(), ridge);
  const double floor = h.metric("pps", "offset_floor_m").get<double>();
  EXPECT_DOUBLE_EQ(taxel["offset_floor_m"].get<double>(), floor);
  EXPECT_DOUBLE_EQ(h.metric("pps", "offset_mean_floor_m")["taxel"].get<double>(), floor);
  EXPECT_EQ(h.metric("pps", "offset_mean_m"), h.metric("pps", "offset_mean_contact_m"));
  // The contact estimator: the stimulus's D when it touched (the thrower's event time).
  EXPECT_NEAR(h.metric("pps", "offset_mean_contact_m")["taxel"].get<double>(), truth, 0.005);
  EXPECT_NEAR(floor, truth, 0.0375) << floor;
  EXPECT_TRUE(taxel["offset_estimate_m"].is_number());
  EXPECT_TRUE(h.metric("pps", "offset_estimate_m").is_number());
}

TEST(PpsLearner, DistanceOnlyModelActivatesForStaticAndRecedingObjects) {
  Harness with_ttc(graph());
  Harness distance_only(graph("model: distance_only"));
  for (Harness* h : {&with_ttc, &distance_only}) {
    set_patch(*h);
    approach_and_touch(*h, 1);
    approach_and_touch(*h, 2);
    auto& s = h->input<Stimulus>("stimulus");
    s.present = true;
    s.position = {0, 0, 0.08};
    s.velocity = {0, 0, -0.1};
    h->step();
    EXPECT_GT(h->output<TaxelValues>("pps.activations").values[0], 0.5);
  }
  for (const Eigen::Vector3d& v : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 0.1)}) {
    for (Harness* h : {&with_ttc, &distance_only}) {
      h->input<Stimulus>("stimulus").velocity = v;
      h->step();
    }
    EXPECT_EQ(with_ttc.output<TaxelValues>("pps.activations").values[0], 0.0);
    EXPECT_GT(distance_only.output<TaxelValues>("pps.activations").values[0], 0.5);
    EXPECT_GT(distance_only.output<double>("pps.max_activation"), 0.5);
  }
  distance_only.finish();
  EXPECT_TRUE(distance_only.metric("pps", "offset_estimate_m").is_null());  // no TTC axis
  const auto state =
      somasim::pps::load_learned_state((distance_only.out_dir() / "learned.json").string());
  EXPECT_EQ(state.model, somasim::pps::PpsModel::kDistanceOnly);
}

TEST(PpsLearner, ALearnedFileOfTheOtherModelIsRejected) {
  std::filesystem::path saved =
      std::filesystem::temp_directory_path() / "somasim_test_pps_distance_only.json";
  {
    Harness h(graph("model: distance_only"));
    set_patch(h);
    approach_and_touch(h, 1);
    h.finish();
    std::filesystem::copy_file(h.out_dir() / "learned.json", saved,
                               std::filesystem::copy_options::overwrite_existing);
  }
  try {
    Harness h(graph("load: " + saved.string()));
    FAIL() << "expected an InputError";
  } catch (const somasim::InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "<inline>:6:58: node 'pps', key 'params.load': " + saved.string() +
                  ": model is \"distance_only\", expected \"d_ttc\"");
  }
  Harness h(graph("model: distance_only, learn: false, load: " + saved.string()));
  set_patch(h);
  auto& s = h.input<Stimulus>("stimulus");
  s.present = true;
  s.position = {0, 0, 0.05};
  s.velocity = {0, 0, 0};
  h.step();
  EXPECT_GT(h.output<TaxelValues>("pps.activations").values[0], 0.5);
  std::filesystem::remove(saved);
}
