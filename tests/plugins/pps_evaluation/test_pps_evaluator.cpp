// pps_evaluator: triggers (aimed part only, while the object is present), true distances at the
// trigger and at the closest (sphere, box, cylinder), skin and object contacts attributed by
// time, rates split by motion (static and receding triggers are false ones), the per-
// presentation CSV, the figures, and bad wiring.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "somasim/port_types.hpp"
#include "somasim/pps/ports.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/skin/ports.hpp"
#include "somasim/testing/harness.hpp"

using somasim::ContactEvent;
using somasim::ContactEvents;
using somasim::ObjectShape;
using somasim::ObjectSpawn;
using somasim::ObjectSpawns;
using somasim::ObjectStates;
using somasim::Presentation;
using somasim::PresentationMotion;
using somasim::SkinPart;
using somasim::SkinTaxels;
using somasim::TaxelValues;
using somasim::testing::Harness;

namespace {

constexpr double kDt = 0.01;  // 100 Hz

std::string graph(const std::string& params = "", const std::string& extra_inputs = "") {
  return "base_rate_hz: 100\nnodes:\n  ev: {plugin: pps_evaluator, params: {" + params +
         "}, inputs: {presentation: harness.presentation, objects: harness.objects, taxels: "
         "harness.taxels, contacts: harness.contacts, activations: harness.act, spawns: "
         "harness.spawns" +
         (extra_inputs.empty() ? "" : ", " + extra_inputs) + "}}\n";
}

// Forearm: taxels 10 and 11 on the plane z = 0 facing +z; palm: taxel 5 far away.
SkinTaxels skin() {
  SkinPart forearm;
  forearm.name = "left_forearm";
  forearm.link = "l_forearm";
  forearm.taxel_ids = {10, 11};
  forearm.positions = {{0, 0, 0}, {0.05, 0, 0}};
  forearm.normals = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()};
  SkinPart palm;
  palm.name = "right_palm";
  palm.link = "r_hand";
  palm.taxel_ids = {5};
  palm.positions = {{1.0, 0, 0}};
  palm.normals = {Eigen::Vector3d::UnitZ()};
  return SkinTaxels{{forearm, palm}};
}

// Drives the evaluator: presentations of one object each, moved by hand.
struct Bench {
  explicit Bench(const std::string& yaml = graph()) : h(yaml) {
    h.input<SkinTaxels>("taxels") = skin();
    auto& act = h.input<TaxelValues>("act");
    act.labels = {"left_forearm/10", "left_forearm/11", "right_palm/5"};
    act.values = {0, 0, 0};
  }
  // A new presentation of object `name` (spawned with `shape`, `size`) aimed at `part`.
  void present(std::uint64_t id, PresentationMotion motion, ObjectShape shape,
               const Eigen::Vector3d& size, const std::string& part = "left_forearm") {
    auto& p = h.input<Presentation>("presentation");
    p.id = id;
    p.active = true;
    p.motion = motion;
    p.object = "obj" + std::to_string(id);
    p.body_part = part;
    p.taxel_id = 10;
    p.start_time_s = h.time_s();
    p.speed = motion == PresentationMotion::kStatic ? 0.0 : 0.1;
    ObjectSpawn s;
    s.id = id;
    s.name = p.object;
    s.shape = shape;
    s.size = size;
    h.input<ObjectSpawns>("spawns").recent = {s};
    auto& o = h.input<ObjectStates>("objects");
    o.names.push_back(p.object);
    o.present.push_back(true);
    o.poses.push_back(Eigen::Isometry3d::Identity());
    o.linear_velocity.emplace_back(0, 0, 0);
    o.angular_velocity.emplace_back(0, 0, 0);
    o.radius.push_back(size.norm());
  }
  void place(const Eigen::Vector3d& centre) {
    h.input<ObjectStates>("objects").poses.back().translation() = centre;
  }
  void remove() {
    h.input<ObjectStates>("objects").present.back() = false;
    h.input<Presentation>("presentation").active = false;
  }
  void activations(double forearm10, double forearm11, double palm) {
    h.input<TaxelValues>("act").values = {forearm10, forearm11, palm};
  }
  void skin_contact(std::uint64_t id, const std::string& part) {
    ContactEvent e;
    e.id = id;
    e.time_s = h.time_s();
    e.body_part = part;
    h.input<ContactEvents>("contacts").recent.push_back(e);
  }
  void step(int n = 1) { ASSERT_TRUE(h.step(n)); }
  nlohmann::json metric(const std::string& name) const { return h.metric("ev", name); }

  Harness h;
};

// A 2 cm sphere moves down the z axis onto taxel 10 at 0.1 m/s, from z = 0.22 (surface 0.20 m
// away) to z = 0.02 (touching).
void approach_taxel_10(Bench& b, std::uint64_t id, double trigger_below_m, bool touch) {
  b.present(id, PresentationMotion::kApproach, ObjectShape::kSphere, {0.02, 0, 0});
  for (int k = 0; k <= 200; ++k) {
    const double gap = 0.20 - 0.001 * k;
    b.place({0, 0, 0.02 + gap});
    const double a = gap < trigger_below_m ? 0.8 : 0.1;
    b.activations(a, a / 2, 0.0);
    if (touch && k == 200) b.skin_contact(id, "left_forearm");
    b.step();
  }
  b.remove();
  b.activations(0, 0, 0);
  b.step(10);
}

// Field k of a CSV row.
std::string field(const std::string& row, int k) {
  std::stringstream in(row);
  std::string f;
  for (int i = 0; i <= k; ++i) std::getline(in, f, ',');
  return f;
}

}  // namespace

TEST(PpsEvaluator, AnApproachIsTriggeredAtTheTrueDistanceAndTouchesTheSkin) {
  Bench b;
  approach_taxel_10(b, 1, 0.1, /*touch=*/true);
  EXPECT_EQ(b.h.finish(), "");
  EXPECT_EQ(b.metric("approaches"), 1);
  EXPECT_EQ(b.metric("triggered_rate"), 1.0);
  EXPECT_EQ(b.metric("skin_contact_rate"), 1.0);
  EXPECT_EQ(b.metric("contact_rate"), 1.0);
  // The first sample with gap < 0.1 m: gap 0.099 m (steps of 1 mm).
  EXPECT_NEAR(b.metric("trigger_distance_m")["median"].get<double>(), 0.099, 1e-9);
  EXPECT_EQ(b.metric("trigger_distance_m")["n"], 1);
  EXPECT_NEAR(b.metric("min_distance_m")["min"].get<double>(), 0.0, 1e-9);
  EXPECT_NEAR(b.metric("contact_time_s")["median"].get<double>(), 2.0, 1e-9);
  EXPECT_TRUE(b.metric("false_trigger_rate").is_null());  // no static or receding object
  EXPECT_EQ(b.metric("per_part")["left_forearm"]["approaches"], 1);
  std::ifstream csv(b.h.out_dir() / "presentations.csv");
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_EQ(field(header, 11), "trigger_taxel_id");
  EXPECT_EQ(field(row, 11), "10");  // the most activated taxel then
}

TEST(PpsEvaluator, AnAvoidedApproachKeepsItsMinimumDistance) {
  Bench b;
  b.present(1, PresentationMotion::kApproach, ObjectShape::kSphere, {0.02, 0, 0});
  for (int k = 0; k <= 150; ++k) {  // stops 5 cm above the skin (the arm moved away)
    b.place({0, 0, 0.02 + 0.20 - 0.001 * k});
    b.activations(k > 50 ? 0.9 : 0.0, 0.0, 0.0);
    b.step();
  }
  b.remove();
  b.step(5);
  approach_taxel_10(b, 2, 0.0, /*touch=*/true);  // never triggered, touched
  EXPECT_EQ(b.h.finish(), "");
  EXPECT_EQ(b.metric("approaches"), 2);
  EXPECT_EQ(b.metric("triggered_rate"), 0.5);
  EXPECT_EQ(b.metric("skin_contact_rate"), 0.5);
  const auto d = b.metric("min_distance_m");
  EXPECT_NEAR(d["min"].get<double>(), 0.0, 1e-9);
  EXPECT_NEAR(d["max"].get<double>(), 0.05, 1e-9);
  EXPECT_NEAR(d["mean"].get<double>(), 0.025, 1e-9);
  EXPECT_NEAR(d["p95"].get<double>(), 0.0475, 1e-9);  // interpolated between 0 and 0.05
  EXPECT_NEAR(b.metric("trigger_distance_m")["min"].get<double>(), 0.149, 1e-9);
}

TEST(PpsEvaluator, StaticAndRecedingTriggersAreFalseOnesOtherPartsDoNotCount) {
  Bench b;
  // Static box 3 cm above taxel 11: only the palm (not aimed) goes above the threshold.
  b.present(1, PresentationMotion::kStatic, ObjectShape::kBox, {0.01, 0.01, 0.01});
  b.place({0.05, 0, 0.04});
  b.activations(0.2, 0.3, 0.95);
  b.step(100);
  b.remove();
  b.step(10);
  // Receding cylinder: the forearm goes above the threshold.
  b.present(2, PresentationMotion::kReceding, ObjectShape::kCylinder, {0.02, 0.05, 0});
  for (int k = 0; k < 100; ++k) {
    b.place({0, 0, 0.10 + 0.001 * k});
    b.activations(k == 40 ? 0.5 : 0.0, 0.0, 0.0);
    b.step();
  }
  b.remove();
  b.step(10);
  EXPECT_EQ(b.h.finish(), "");
  EXPECT_EQ(b.metric("approaches"), 0);
  EXPECT_TRUE(b.metric("triggered_rate").is_null());
  EXPECT_EQ(b.metric("static_trigger_rate"), 0.0);
  EXPECT_EQ(b.metric("receding_trigger_rate"), 1.0);
  EXPECT_EQ(b.metric("false_trigger_rate"), 0.5);
  const auto per_motion = b.metric("per_motion");
  // Box: its face is 3 cm above taxel 11 (exact distance); cylinder (axis z, half height 5 cm):
  // its end face starts 5 cm above taxel 10.
  EXPECT_NEAR(per_motion["static"]["min_distance_m"]["min"].get<double>(), 0.03, 1e-9);
  EXPECT_NEAR(per_motion["receding"]["min_distance_m"]["min"].get<double>(), 0.05, 1e-9);
  EXPECT_EQ(per_motion["static"]["presentations"], 1);
}

// With the controllers' hold (0.05 s) and at-once level (0.6): a static object whose activation
// is 0.5 for 3 ticks is no trigger, one at 0.9 for a single tick is; an approach triggers where
// its 0.5 crossing has held 5 ticks.
TEST(PpsEvaluator, CountsTriggersAsTheHeldControllersDo) {
  Bench b(graph("threshold: 0.3, trigger_hold_s: 0.05, trigger_at_once_above: 0.6"));
  const auto flash_static = [&](std::uint64_t id, double a, int ticks) {
    b.present(id, PresentationMotion::kStatic, ObjectShape::kSphere, {0.02, 0, 0});
    b.place({0, 0, 0.2});
    for (int k = 0; k < 50; ++k) {
      b.activations(k >= 10 && k < 10 + ticks ? a : 0.0, 0.0, 0.0);
      b.step();
    }
    b.remove();
    b.activations(0, 0, 0);
    b.step(10);
  };
  flash_static(1, 0.5, 3);
  flash_static(2, 0.9, 1);
  b.present(3, PresentationMotion::kApproach, ObjectShape::kSphere, {0.02, 0, 0});
  for (int k = 0; k <= 100; ++k) {
    b.place({0, 0, 0.02 + 0.20 - 0.001 * k});
    b.activations(k >= 50 ? 0.5 : 0.0, 0.0, 0.0);
    b.step();
  }
  b.remove();
  b.step(10);
  EXPECT_EQ(b.h.finish(), "");
  EXPECT_EQ(b.metric("static_trigger_rate"), 0.5);
  EXPECT_EQ(b.metric("triggered_rate"), 1.0);
  // Above from k = 50 (gap 0.150 m); held at k = 55 (gap 0.145 m).
  EXPECT_NEAR(b.metric("trigger_distance_m")["median"].get<double>(), 0.145, 1e-9);
}

TEST(PpsEvaluator, BoxAndCylinderDistancesAreExactSideways) {
  Bench b;
  // A box rotated 90 deg about z, half extents (0.01, 0.03, 0.01): its long side along x now.
  b.present(1, PresentationMotion::kStatic, ObjectShape::kBox, {0.01, 0.03, 0.01});
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.translation() =
      Eigen::Vector3d(0.10, 0.0, 0.03);  // corner region beyond taxel 11 (x = 0.05)
  b.h.input<ObjectStates>("objects").poses.back() = pose;
  b.step(3);
  b.remove();
  b.step(2);
  // A cylinder lying on its side (axis along x): radius 1 cm, its axis 4 cm above taxel 10.
  b.present(2, PresentationMotion::kStatic, ObjectShape::kCylinder, {0.01, 0.2, 0});
  pose.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(0.0, 0.0, 0.04);
  b.h.input<ObjectStates>("objects").poses.back() = pose;
  b.step(3);
  b.remove();
  b.step(2);
  EXPECT_EQ(b.h.finish(), "");
  std::ifstream csv(b.h.out_dir() / "presentations.csv");
  std::string header, row1, row2;
  std::getline(csv, header);
  std::getline(csv, row1);
  std::getline(csv, row2);
  // Box: nearest point (0.07, 0, 0.02) to taxel 11 at (0.05, 0, 0): hypot(0.02, 0.02).
  EXPECT_EQ(field(header, 13), "min_distance [m]");
  EXPECT_NEAR(std::stod(field(row1, 13)), std::hypot(0.02, 0.02), 1e-6);
  EXPECT_EQ(field(row1, 5), "box");
  EXPECT_NEAR(std::stod(field(row2, 13)), 0.03, 1e-6);
  EXPECT_EQ(field(row2, 5), "cylinder");
  EXPECT_EQ(field(row2, 1), "static");
}

TEST(PpsEvaluator, ContactsAreAttributedToThePresentationOfTheirTime) {
  Bench b(graph("", "world_contacts: harness.world"));
  b.present(1, PresentationMotion::kApproach, ObjectShape::kSphere, {0.02, 0, 0});
  b.place({0, 0, 0.3});
  b.step(5);
  // The object touches the robot's hand link (no skin there), then the palm's skin.
  somasim::Contact c;
  c.object_a = 0;
  c.link_b = 7;
  c.time_s = b.h.time_s();
  b.h.input<somasim::Contacts>("world").recent = {c};
  b.skin_contact(3, "right_palm");
  b.step(5);
  b.remove();
  b.step(5);
  // Between presentations: a skin contact belongs to nobody.
  b.skin_contact(4, "left_forearm");
  b.step(5);
  b.present(2, PresentationMotion::kApproach, ObjectShape::kSphere, {0.02, 0, 0});
  b.place({0, 0, 0.3});
  b.step(5);
  b.remove();
  b.step(5);
  EXPECT_EQ(b.h.finish(), "");
  EXPECT_EQ(b.metric("approaches"), 2);
  EXPECT_EQ(b.metric("skin_contact_rate"), 0.5);  // presentation 1: the palm, not aimed
  EXPECT_EQ(b.metric("contact_rate"), 0.0);
  EXPECT_EQ(b.metric("object_contact_rate"), 0.5);
}

TEST(PpsEvaluator, DrawsTheChosenPresentations) {
  Bench b(
      graph("figure_presentations: [2], velocity_parts: left_forearm", "velocity_1: harness.v"));
  approach_taxel_10(b, 1, 0.1, false);
  b.h.input<Eigen::Vector3d>("v") = {0, 0, -0.1};
  approach_taxel_10(b, 2, 0.1, true);
  EXPECT_EQ(b.h.finish(), "");
  EXPECT_FALSE(
      std::filesystem::exists(b.h.out_dir() / "figures/presentation_1_approach_left_forearm.png"));
  EXPECT_TRUE(
      std::filesystem::exists(b.h.out_dir() / "figures/presentation_2_approach_left_forearm.png"));
}

TEST(PpsEvaluator, SameInputsGiveTheSameMetrics) {
  const auto run = [] {
    Bench b;
    approach_taxel_10(b, 1, 0.07, true);
    approach_taxel_10(b, 2, 0.12, false);
    EXPECT_EQ(b.h.finish(), "");
    return b.h.metric("ev", "trigger_distance_m").dump() + b.h.metric("ev", "per_part").dump();
  };
  EXPECT_EQ(run(), run());
}

TEST(PpsEvaluator, BadWiringAndUnknownPartsAreReported) {
  const auto load_error = [](const std::string& yaml) {
    try {
      Harness h(yaml);
      return std::string("no error");
    } catch (const somasim::InputError& e) {
      const std::string m = e.what();
      return m.substr(m.find("node"));
    }
  };
  EXPECT_EQ(load_error(graph("velocity_parts: left_forearm")),
            "node 'ev', key 'params.velocity_parts': part 'left_forearm' is named for input "
            "'velocity_1', which is not wired");
  EXPECT_EQ(load_error(graph("", "velocity_2: harness.v")),
            "node 'ev', key 'params.velocity_parts': input 'velocity_2' is wired, but no part "
            "is named for it");
  EXPECT_EQ(load_error(graph("threshold: 1.2")),
            "node 'ev', key 'params.threshold': value 1.2 is out of range; expected a number in "
            "[0, 1]");
  Bench b;
  b.present(1, PresentationMotion::kApproach, ObjectShape::kSphere, {0.02, 0, 0}, "left_forarm");
  try {
    b.h.step();
    FAIL() << "expected a RunError";
  } catch (const somasim::RunError& e) {
    EXPECT_STREQ(e.what(),
                 "ev: presentation 1 aims at skin part 'left_forarm', which is not in the "
                 "'taxels' input (did you mean 'left_forearm'?); parts: left_forearm, right_palm");
  }
}

TEST(PpsEvaluator, ApproachesOutOfTheCamerasViewAreReportedApart) {
  Bench b;
  // Seen coming and triggered; not seen, untriggered and touched; seen, untriggered.
  const std::pair<somasim::PresentationSight, double> shown[] = {
      {somasim::PresentationSight::kInView, 0.1},
      {somasim::PresentationSight::kOutOfView, 0.0},
      {somasim::PresentationSight::kInView, 0.0}};
  std::uint64_t id = 0;
  for (const auto& [sight, trigger_below] : shown) {
    ++id;
    b.h.input<Presentation>("presentation").sight = sight;
    approach_taxel_10(b, id, trigger_below, /*touch=*/sight != somasim::PresentationSight::kInView);
  }
  EXPECT_EQ(b.h.finish(), "");
  EXPECT_NEAR(b.metric("triggered_rate").get<double>(), 1.0 / 3.0, 1e-12);  // all: not hidden
  EXPECT_EQ(b.metric("presentations_out_of_view"), 1);
  EXPECT_EQ(b.metric("in_view")["approaches"], 2);
  EXPECT_EQ(b.metric("in_view")["triggered_rate"], 0.5);
  EXPECT_EQ(b.metric("in_view")["skin_contact_rate"], 0.0);
  EXPECT_EQ(b.metric("out_of_view")["approaches"], 1);
  EXPECT_EQ(b.metric("out_of_view")["triggered_rate"], 0.0);
  EXPECT_EQ(b.metric("out_of_view")["skin_contact_rate"], 1.0);
  std::ifstream csv(b.h.out_dir() / "presentations.csv");
  std::string header, row;
  std::getline(csv, header);
  EXPECT_EQ(field(header, 23), "sight");
  std::getline(csv, row);
  EXPECT_EQ(field(row, 23), "in_view");
  std::getline(csv, row);
  EXPECT_EQ(field(row, 23), "out_of_view");
}

TEST(PpsEvaluator, UncheckedSightAddsNoViewMetrics) {
  Bench b;
  approach_taxel_10(b, 1, 0.1, /*touch=*/false);
  EXPECT_EQ(b.h.finish(), "");
  EXPECT_TRUE(b.metric("in_view").is_null());
  EXPECT_TRUE(b.metric("presentations_out_of_view").is_null());
}
