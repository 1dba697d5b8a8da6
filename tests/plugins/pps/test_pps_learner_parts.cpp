// pps_learner with several body parts: independent learning, output layout, the multi-part
// learned file and its errors, and the offset metrics against known true offsets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>

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

// The unsigned TTC and the released code's RF keep the samples behind the skin, and every
// sample of an approach is kept: the ridge-end estimate is then exact for straight approaches
// along the normal (see below).
std::string graph(const std::string& parts, const std::string& params = "learn: true",
                  bool with_truth = true) {
  return R"(
base_rate_hz: 20
nodes:
  pps:
    plugin: pps_learner
    params: {body_part: ")" +
         parts + R"(", save: learned.json, ttc: unsigned, rf_shape: cone_mirrored_cylinder,
             buffer_horizon: 0, min_samples: 10, )" +
         params + R"(}
    inputs: {stimulus: harness.stimulus, taxels: harness.taxels, contacts: harness.contacts)" +
         (with_truth ? ", true_offsets: harness.truth" : "") + R"(}
)";
}

somasim::SkinPart flat_part(const std::string& name, const std::vector<int>& ids,
                            const std::vector<double>& xs) {
  somasim::SkinPart p;
  p.name = name;
  p.taxel_ids = ids;
  for (double x : xs) {
    p.positions.emplace_back(x, 0, 0);
    p.normals.emplace_back(0, 0, 1);
  }
  return p;
}

// The input lists "patch" (ids 10, 11; 5 cm apart) before "palm" (ids 0, 1, 2; taxel 2 out of
// every approach's reach), all in the plane z = 0 with normals +z. `palm_taxels` < 3 drops the
// last palm taxels.
void set_skin(Harness& h, std::size_t palm_taxels = 3) {
  std::vector<int> ids{0, 1, 2};
  std::vector<double> xs{1.0, 1.05, 1.5};
  ids.resize(palm_taxels);
  xs.resize(palm_taxels);
  h.input<SkinTaxels>("taxels").parts = {flat_part("patch", {10, 11}, {0.0, 0.05}),
                                         flat_part("palm", ids, xs)};
}

// A straight approach along -z onto (x, 0, 0) at 5 cm/s (2.5 mm per tick), from z = 0.19875 m
// down to the last sample not below `end_z`, then a contact on taxel `id` of `part`.
void approach(Harness& h, double x, double end_z, const std::string& part, int id,
              std::uint64_t event_id) {
  auto& s = h.input<Stimulus>("stimulus");
  s.present = true;
  s.velocity = {0, 0, -0.05};
  double last_sample_s = 0.0;
  for (int k = 0; 0.19875 - 0.0025 * k >= end_z - 1e-9; ++k) {
    s.position = {x, 0, 0.19875 - 0.0025 * k};
    last_sample_s = h.time_s();  // the time of the step about to run
    h.step();
  }
  somasim::ContactEvent e;
  e.id = event_id;
  e.time_s = h.time_s();
  e.first_touch_s = last_sample_s;  // the skin's contact time: that of the last sample
  e.body_part = part;
  e.touched_taxels = {id};
  h.input<ContactEvents>("contacts").recent.push_back(e);
  s.present = false;
  h.step();
}

// Two approaches each: onto patch/10 ending at D = -0.02 m (behind the skin), onto palm/1
// ending at D = +0.01 m (short of it). Sample D values are 0.19875 - 0.0025 k: the plateau bin
// [0.05, 0.0875) m gets 15 per approach, D < 0.05 gets 28 (patch) or 16 (palm), so the
// ridge-end estimate, 0.05 - 0.0375 * below / plateau, is exactly -0.02 and +0.01 m.
void learn_both(Harness& h) {
  approach(h, 0.0, -0.02, "patch", 10, 1);
  approach(h, 1.05, 0.01, "palm", 1, 2);
  approach(h, 0.0, -0.02, "patch", 10, 3);
  approach(h, 1.05, 0.01, "palm", 1, 4);
}

// The truth as a thrower would give it, in another order than the activations, with a label
// no learner has, NaN for untouched taxels, and a huge value on palm/2 (no samples: ignored).
void set_truth(Harness& h, double patch10, double palm1) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto& t = h.input<TaxelValues>("truth");
  t.labels = {"other/10", "palm/0", "palm/2", "patch/11", "palm/1", "patch/10"};
  t.values = {1.0, nan, 0.5, nan, palm1, patch10};
}

std::filesystem::path keep(const Harness& h, const std::string& name) {
  const auto saved = std::filesystem::temp_directory_path() / name;
  std::filesystem::copy_file(h.out_dir() / "learned.json", saved,
                             std::filesystem::copy_options::overwrite_existing);
  return saved;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const somasim::InputError& e) {
    return e.what();
  }
  return "no InputError";
}

}  // namespace

TEST(PpsLearnerParts, ActivationsFollowTheOrderOfBodyPartWithPartLabels) {
  Harness h(graph("palm patch"));
  set_skin(h);
  h.step();
  const auto& act = h.output<TaxelValues>("pps.activations");
  EXPECT_EQ(act.labels,
            (std::vector<std::string>{"palm/0", "palm/1", "palm/2", "patch/10", "patch/11"}));
  EXPECT_EQ(act.values.size(), 5u);
}

// Each part learns only from its own contacts: the multi-part learner's maps and activations
// equal those of one learner per part fed the same stream.
TEST(PpsLearnerParts, PartsLearnIndependentlyLikeOneLearnerPerPart) {
  Harness both(graph("palm patch"));
  Harness palm(graph("palm"));
  Harness patch(graph("patch"));
  for (Harness* h : {&both, &palm, &patch}) {
    set_skin(*h);
    set_truth(*h, -0.02, 0.013);
    learn_both(*h);
    auto& s = h->input<Stimulus>("stimulus");
    s.present = true;
    s.position = {1.05, 0, 0.06};
    s.velocity = {0, 0, -0.05};
    h->step();
  }
  const auto& a = both.output<TaxelValues>("pps.activations").values;
  const auto& a_palm = palm.output<TaxelValues>("pps.activations").values;
  const auto& a_patch = patch.output<TaxelValues>("pps.activations").values;
  ASSERT_EQ(a.size(), 5u);
  EXPECT_GT(a[1], 0.5);  // palm/1, approached as it learned
  for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(a[k], a_palm[k]) << k;
  for (std::size_t k = 0; k < 2; ++k) EXPECT_EQ(a[3 + k], a_patch[k]) << k;
  EXPECT_EQ(both.output<double>("pps.max_activation"),
            std::max(palm.output<double>("pps.max_activation"),
                     patch.output<double>("pps.max_activation")));
  for (Harness* h : {&both, &palm, &patch}) h->finish();
  EXPECT_EQ(both.metric("pps", "events"), 4);
  EXPECT_EQ(both.metric("pps", "per_part")["palm"]["events"], 2);
  EXPECT_EQ(both.metric("pps", "per_part")["patch"]["events"], 2);
  EXPECT_EQ(both.metric("pps", "per_part")["palm"]["samples"], palm.metric("pps", "samples"));
  EXPECT_EQ(both.metric("pps", "samples").get<int>(),
            palm.metric("pps", "samples").get<int>() + patch.metric("pps", "samples").get<int>());
  // One file, both parts; each equals the single learner's.
  const auto parts = somasim::pps::load_learned_parts((both.out_dir() / "learned.json").string());
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].body_part, "palm");
  const auto one_palm =
      somasim::pps::load_learned_state((palm.out_dir() / "learned.json").string());
  const auto one_patch =
      somasim::pps::load_learned_state((patch.out_dir() / "learned.json").string());
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(parts[0].taxels[k].pos, one_palm.taxels[k].pos);
    EXPECT_EQ(parts[0].taxels[k].neg, one_palm.taxels[k].neg);
  }
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(parts[1].taxels[k].pos, one_patch.taxels[k].pos);
    EXPECT_EQ(parts[1].taxels[k].neg, one_patch.taxels[k].neg);
  }
}

// Known answer: the ridge-end estimates are -0.02 (patch/10) and +0.01 m (palm/1); with true
// offsets -0.02 and +0.013 the largest ridge error is 0.003 m on palm/1. The floor reads the
// same ends to a fraction of the paper's 3.75 cm bins.
// Untouched taxels (NaN), taxels with too few samples (palm/2, no estimate at all) and labels
// of no part are left out. The unsuffixed keys are the contact estimator's.
TEST(PpsLearnerParts, OffsetErrorsAgainstTrueOffsetsMatchedByLabel) {
  Harness h(graph("palm patch"));
  set_skin(h);
  set_truth(h, -0.02, 0.013);
  learn_both(h);
  h.finish();
  const auto taxels = h.metric("pps", "taxels");
  const double ridge_patch = taxels["patch/10"]["offset_ridge_m"].get<double>();
  const double ridge_palm = taxels["palm/1"]["offset_ridge_m"].get<double>();
  EXPECT_NEAR(ridge_patch, -0.02, 1e-12);
  EXPECT_NEAR(ridge_palm, 0.01, 1e-12);
  EXPECT_EQ(taxels["palm/1"]["true_offset_m"], 0.013);
  EXPECT_TRUE(taxels["palm/0"]["true_offset_m"].is_null());
  EXPECT_EQ(taxels["palm/2"]["samples"], 0);
  for (const char* key : {"offset_floor_m", "offset_ridge_m", "offset_estimate_m"})
    EXPECT_TRUE(taxels["palm/2"][key].is_null()) << key;
  EXPECT_NEAR(h.metric("pps", "offset_error_max_ridge_m").get<double>(), 0.003, 1e-12);
  EXPECT_NEAR(h.metric("pps", "offset_error_mean_ridge_m").get<double>(), 0.0015, 1e-12);
  EXPECT_EQ(h.metric("pps", "offset_taxels_evaluated"), 2);
  EXPECT_EQ(h.metric("pps", "offset_taxels_without_estimate"),
            (nlohmann::json{{"contact", 0}, {"floor", 0}, {"ridge", 0}, {"paper", 0}}));
  // The contact estimator: the stimulus's D at the skin's contact time, the last sample of each
  // approach (-0.01875 m behind the patch, +0.01125 m short of the palm).
  EXPECT_NEAR(taxels["patch/10"]["offset_contact_m"].get<double>(), -0.01875, 1e-12);
  EXPECT_NEAR(taxels["palm/1"]["offset_contact_m"].get<double>(), 0.01125, 1e-12);
  EXPECT_EQ(taxels["patch/10"]["contacts"], 2);
  EXPECT_NEAR(h.metric("pps", "offset_error_max_contact_m").get<double>(), 0.00175, 1e-12);
  EXPECT_NEAR(h.metric("pps", "offset_error_mean_contact_m").get<double>(), 0.0015, 1e-12);
  EXPECT_NEAR(h.metric("pps", "offset_mean_contact_m")["patch"].get<double>(), -0.01875, 1e-12);
  EXPECT_NEAR(h.metric("pps", "offset_contact_m").get<double>(), -0.00375, 1e-12);
  // The floor and Fig 8: the same statistics from their per-taxel estimates.
  const double floor_patch = taxels["patch/10"]["offset_floor_m"].get<double>();
  const double floor_palm = taxels["palm/1"]["offset_floor_m"].get<double>();
  EXPECT_NEAR(floor_patch, -0.02, 0.001);
  EXPECT_NEAR(floor_palm, 0.01, 0.001);
  const double floor_err[] = {std::abs(floor_patch + 0.02), std::abs(floor_palm - 0.013)};
  EXPECT_DOUBLE_EQ(h.metric("pps", "offset_error_max_floor_m").get<double>(),
                   std::max(floor_err[0], floor_err[1]));
  EXPECT_DOUBLE_EQ(h.metric("pps", "offset_error_mean_floor_m").get<double>(),
                   (floor_err[0] + floor_err[1]) / 2);
  EXPECT_EQ(h.metric("pps", "offset_error_max_m"), h.metric("pps", "offset_error_max_contact_m"));
  EXPECT_EQ(h.metric("pps", "offset_error_mean_m"), h.metric("pps", "offset_error_mean_contact_m"));
  const double paper_patch = taxels["patch/10"]["offset_estimate_m"].get<double>();
  const double paper_palm = taxels["palm/1"]["offset_estimate_m"].get<double>();
  EXPECT_DOUBLE_EQ(h.metric("pps", "offset_error_max_paper_m").get<double>(),
                   std::max(std::abs(paper_patch + 0.02), std::abs(paper_palm - 0.013)));
  // Per part: means over the taxels with enough samples. Patch/11 and palm/0 have negatives
  // only (no floor or ridge estimate, and a Fig 8 line through their activations).
  EXPECT_EQ(taxels["patch/11"]["offset_ridge_m"], nullptr);
  EXPECT_EQ(taxels["patch/11"]["offset_floor_m"], nullptr);
  EXPECT_DOUBLE_EQ(h.metric("pps", "offset_mean_floor_m")["patch"].get<double>(), floor_patch);
  EXPECT_DOUBLE_EQ(h.metric("pps", "offset_mean_floor_m")["palm"].get<double>(), floor_palm);
  EXPECT_EQ(h.metric("pps", "offset_mean_m"), h.metric("pps", "offset_mean_contact_m"));
  EXPECT_NEAR(h.metric("pps", "offset_mean_ridge_m")["patch"].get<double>(), -0.02, 1e-12);
  EXPECT_NEAR(h.metric("pps", "offset_mean_ridge_m")["palm"].get<double>(), 0.01, 1e-12);
  EXPECT_NEAR(h.metric("pps", "true_offset_mean_m")["patch"].get<double>(), -0.02, 1e-12);
  EXPECT_NEAR(h.metric("pps", "true_offset_mean_m")["palm"].get<double>(), 0.013, 1e-12);
  EXPECT_TRUE(h.metric("pps", "offset_mean_paper_m")["palm"].is_number());
  const auto per_part = h.metric("pps", "per_part");
  EXPECT_DOUBLE_EQ(per_part["palm"]["offset_error_max_floor_m"].get<double>(), floor_err[1]);
  EXPECT_DOUBLE_EQ(per_part["patch"]["offset_error_mean_floor_m"].get<double>(), floor_err[0]);
  EXPECT_EQ(per_part["palm"]["offset_error_max_m"], per_part["palm"]["offset_error_max_contact_m"]);
  EXPECT_NEAR(per_part["palm"]["offset_error_max_contact_m"].get<double>(), 0.00175, 1e-12);
  EXPECT_NEAR(per_part["palm"]["offset_error_max_ridge_m"].get<double>(), 0.003, 1e-12);
  EXPECT_NEAR(per_part["patch"]["offset_error_max_ridge_m"].get<double>(), 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(per_part["palm"]["offset_error_max_paper_m"].get<double>(),
                   std::abs(paper_palm - 0.013));
  // The all-taxel means under the original keys.
  EXPECT_NEAR(h.metric("pps", "offset_ridge_m").get<double>(), -0.005, 1e-12);
  EXPECT_DOUBLE_EQ(h.metric("pps", "offset_floor_m").get<double>(), (floor_patch + floor_palm) / 2);
}

TEST(PpsLearnerParts, WithoutTrueOffsetsThereAreNoErrorMetrics) {
  Harness h(graph("palm patch", "learn: true", false));
  set_skin(h);
  learn_both(h);
  h.finish();
  EXPECT_TRUE(h.metric("pps", "offset_error_max_m").is_null());
  EXPECT_TRUE(h.metric("pps", "true_offset_mean_m").is_null());
  EXPECT_TRUE(h.metric("pps", "offset_error_max_ridge_m").is_null());
  EXPECT_NEAR(h.metric("pps", "offset_mean_contact_m")["palm"].get<double>(), 0.01125, 1e-12);
  EXPECT_NEAR(h.metric("pps", "offset_mean_floor_m")["palm"].get<double>(), 0.01, 0.001);
  EXPECT_EQ(h.metric("pps", "offset_mean_m"), h.metric("pps", "offset_mean_contact_m"));
  EXPECT_NEAR(h.metric("pps", "offset_mean_ridge_m")["palm"].get<double>(), 0.01, 1e-12);
}

TEST(PpsLearnerParts, ReloadsAMultiPartFile) {
  Harness learnt(graph("palm patch"));
  set_skin(learnt);
  set_truth(learnt, -0.02, 0.013);
  learn_both(learnt);
  learnt.finish();
  const auto saved = keep(learnt, "somasim_test_pps_parts_reload.json");
  // Another order of the parts; only evaluation.
  Harness h(graph("patch palm", "learn: false, load: " + saved.string()));
  set_skin(h);
  set_truth(h, -0.02, 0.013);
  learn_both(h);
  h.finish();
  EXPECT_EQ(h.metric("pps", "events"), 0);
  EXPECT_EQ(h.metric("pps", "offset_error_max_m"), learnt.metric("pps", "offset_error_max_m"));
  const auto parts = somasim::pps::load_learned_parts((h.out_dir() / "learned.json").string());
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].body_part, "patch");
  EXPECT_EQ(parts[1].taxels[1].pos,
            somasim::pps::load_learned_parts(saved.string())[0].taxels[1].pos);
  std::filesystem::remove(saved);
}

// The iCub's .ini format: saved and loaded back (taxel geometry from the 'taxels' input, parts in
// another order), the maps and the metrics are the same as from the JSON file.
TEST(PpsLearnerParts, RoundTripThroughTheIcubIniFormat) {
  auto with_ini = [](std::string g) {
    g.replace(g.find("save: learned.json"), 18, "save: learned.ini");
    return g;
  };
  Harness learnt(with_ini(graph("palm patch")));
  set_skin(learnt);
  set_truth(learnt, -0.02, 0.013);
  learn_both(learnt);
  learnt.finish();
  const auto saved = std::filesystem::temp_directory_path() / "somasim_test_pps_parts.ini";
  std::filesystem::copy_file(learnt.out_dir() / "learned.ini", saved,
                             std::filesystem::copy_options::overwrite_existing);
  Harness h(graph("patch palm", "learn: false, load: " + saved.string()));
  set_skin(h);
  set_truth(h, -0.02, 0.013);
  learn_both(h);
  h.finish();
  EXPECT_EQ(h.metric("pps", "events"), 0);
  // The maps' estimators agree; the .ini format has no contact evidence (nothing to compare).
  EXPECT_EQ(h.metric("pps", "offset_error_max_floor_m"),
            learnt.metric("pps", "offset_error_max_floor_m"));
  EXPECT_TRUE(h.metric("pps", "offset_error_max_contact_m").is_null());
  EXPECT_TRUE(h.metric("pps", "offset_error_max_m").is_null());
  const auto parts = somasim::pps::load_learned_parts((h.out_dir() / "learned.json").string());
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].body_part, "patch");
  EXPECT_EQ(parts[0].taxels[1].pose_link.position.x(), 0.05);  // from the input, not the file
  ASSERT_EQ(parts[1].taxels.size(), 3u);
  // The .ini holds the learnt counts exactly.
  Harness json(graph("palm patch"));
  set_skin(json);
  set_truth(json, -0.02, 0.013);
  learn_both(json);
  json.finish();
  const auto direct = somasim::pps::load_learned_parts((json.out_dir() / "learned.json").string());
  EXPECT_EQ(parts[1].taxels[1].pos, direct[0].taxels[1].pos);
  EXPECT_EQ(parts[0].taxels[0].neg, direct[1].taxels[0].neg);
  // A distance-only learner cannot save an .ini; a missing part names what the file has.
  EXPECT_EQ(error_of([&] { Harness d(with_ini(graph("palm", "model: distance_only"))); }),
            "<inline>:6:39: node 'pps', key 'params.save': an .ini file holds (D, TTC) maps; "
            "this learner's model is distance_only (save as .json)");
  EXPECT_EQ(error_of([&] { Harness m(graph("hand", "load: " + saved.string())); }),
            "<inline>:7:56: node 'pps', key 'params.load': " + saved.string() +
                ": has no body part \"hand\" (it has: palm patch), expected every body part of "
                "\"hand\"");
  std::filesystem::remove(saved);
}

TEST(PpsLearnerParts, AFileLackingAPartIsRejectedNamingFileAndParts) {
  Harness learnt(graph("patch"));
  set_skin(learnt);
  set_truth(learnt, -0.02, 0.013);
  learn_both(learnt);
  learnt.finish();
  const auto one = keep(learnt, "somasim_test_pps_parts_one.json");
  const std::string where = "<inline>:7:56: node 'pps', key 'params.load': ";
  EXPECT_EQ(error_of([&] { Harness h(graph("palm patch", "load: " + one.string())); }),
            where + one.string() +
                ": has no body part \"palm\" (it has: patch), expected every body part of "
                "\"palm patch\"");
  Harness learnt2(graph("palm patch"));
  set_skin(learnt2);
  set_truth(learnt2, -0.02, 0.013);
  learn_both(learnt2);
  learnt2.finish();
  const auto two = keep(learnt2, "somasim_test_pps_parts_two.json");
  EXPECT_EQ(error_of([&] { Harness h(graph("palm hand patch", "load: " + two.string())); }),
            where + two.string() +
                ": has no body part \"hand\" (it has: palm patch), expected every body part of "
                "\"palm hand patch\"");
  std::filesystem::remove(one);
  std::filesystem::remove(two);
}

TEST(PpsLearnerParts, AFileWithAnotherTaxelCountForAPartIsRejected) {
  Harness learnt(graph("palm patch"));
  set_skin(learnt);
  set_truth(learnt, -0.02, 0.013);
  learn_both(learnt);
  learnt.finish();
  const auto saved = keep(learnt, "somasim_test_pps_parts_count.json");
  Harness h(graph("palm patch", "load: " + saved.string()));
  set_skin(h, 2);
  EXPECT_EQ(error_of([&] { h.step(); }),
            saved.string() +
                ": body part \"palm\" has 3 taxels, expected 2 (the 'taxels' input's count)");
  // Same count, other ids: the maps would land on the wrong taxels.
  Harness other_ids(graph("palm patch", "load: " + saved.string()));
  set_skin(other_ids);
  other_ids.input<SkinTaxels>("taxels").parts[1].taxel_ids = {0, 2, 1};
  EXPECT_EQ(error_of([&] { other_ids.step(); }),
            saved.string() +
                ": body part \"palm\": taxel 1 has id 1, expected 2 (the 'taxels' input's order)");
  std::filesystem::remove(saved);
}

TEST(PpsLearnerParts, BadBodyPartLists) {
  EXPECT_EQ(error_of([] { Harness h(graph("patch palm patch")); }),
            "<inline>:6:25: node 'pps', key 'params.body_part': lists 'patch' twice");
  EXPECT_EQ(error_of([] { Harness h(graph("  ")); }),
            "<inline>:6:25: node 'pps', key 'params.body_part': is empty, expected one or more "
            "skin parts");
  Harness h(graph("palm hand"));
  set_skin(h);
  EXPECT_EQ(error_of([&] { h.step(); }),
            "<inline>:6:25: node 'pps', key 'params.body_part': no skin part 'hand' in the "
            "'taxels' input; parts: patch, palm");
  Harness f(graph("palm patch", "figure_taxels: [1, 7]"));
  set_skin(f);
  EXPECT_EQ(error_of([&] { f.step(); }),
            "<inline>:7:65: node 'pps', key 'params.figure_taxels': taxel id 7 is on none of "
            "the parts (palm patch)");
}

// Snapshots and final landscapes per part: file names carry the part, so they do not collide.
TEST(PpsLearnerParts, FiguresPerPart) {
  Harness h(graph("palm patch", "snapshot_events: [1], figure_taxels: [1, 10]"));
  set_skin(h);
  set_truth(h, -0.02, 0.013);
  learn_both(h);
  h.finish();
  for (const char* f :
       {"landscape_palm_1_after_1_events.png", "landscape_patch_10_after_1_events.png",
        "landscape_palm_1.png", "landscape_patch_10.png"})
    EXPECT_TRUE(std::filesystem::exists(h.out_dir() / "figures" / f)) << f;
  EXPECT_FALSE(std::filesystem::exists(h.out_dir() / "figures" / "landscape_palm_10.png"));
}

// offset_groups: taxels of a part selected by the side their normal faces (all normals are +z).
TEST(PpsLearnerParts, OffsetGroupsReportTheirTaxelsTogether) {
  Harness h(
      graph("palm patch", "offset_groups: \"up: patch +z, down: patch -z, whole_palm: palm\""));
  set_skin(h);
  set_truth(h, -0.02, 0.013);
  learn_both(h);
  h.finish();
  const auto groups = h.metric("pps", "offset_groups");
  const auto means = h.metric("pps", "offset_mean_contact_m");
  EXPECT_EQ(groups["up"]["taxels"], h.metric("pps", "per_part")["patch"]["taxels"]);
  EXPECT_EQ(groups["up"]["offset_mean_m"], means["patch"]);
  EXPECT_EQ(groups["whole_palm"]["offset_mean_m"], means["palm"]);
  EXPECT_EQ(groups["down"]["taxels"], 0);
  EXPECT_TRUE(groups["down"]["offset_mean_m"].is_null());
  EXPECT_NEAR(groups["up"]["offset_error_max_m"].get<double>(), 0.00125, 1e-12);
  EXPECT_EQ(groups["whole_palm"]["offset_error_max_m"],
            h.metric("pps", "per_part")["palm"]["offset_error_max_m"]);
  EXPECT_EQ(groups["up"]["offset_taxels_evaluated"], 1);
  EXPECT_NEAR(groups["up"]["true_offset_mean_m"].get<double>(), -0.02, 1e-12);
  // The group's offset against the true one: signed, the estimate minus the truth.
  EXPECT_NEAR(groups["up"]["group_offset_error_m"].get<double>(),
              groups["up"]["offset_mean_m"].get<double>() + 0.02, 1e-12);
  EXPECT_NEAR(std::abs(groups["up"]["group_offset_error_m"].get<double>()), 0.00125, 1e-12);
  EXPECT_TRUE(groups["down"]["group_offset_error_m"].is_null());
}

TEST(PpsLearnerParts, BadOffsetGroups) {
  EXPECT_EQ(error_of([] { Harness h(graph("palm patch", "offset_groups: \"a: hand\"")); }),
            "<inline>:7:65: node 'pps', key 'params.offset_groups': offset_groups entry 'a: "
            "hand': 'hand' is not a body_part of this learner (its parts: palm, patch)");
  EXPECT_EQ(error_of([] { Harness h(graph("palm patch", "offset_groups: \"a: palm up\"")); }),
            "<inline>:7:65: node 'pps', key 'params.offset_groups': offset_groups entry 'a: palm "
            "up': side 'up' is not one of +x -x +y -y +z -z (the taxel normal's direction in the "
            "part's link frame)");
  EXPECT_EQ(error_of([] { Harness h(graph("palm patch", "offset_groups: \"palm +z\"")); }),
            "<inline>:7:65: node 'pps', key 'params.offset_groups': offset_groups entry 'palm "
            "+z': expected 'name: part [side]', e.g. 'inner_forearm: left_forearm +z'");
}
