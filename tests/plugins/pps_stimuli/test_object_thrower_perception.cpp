// object_thrower: vision through the believed head/eye kinematics, and the offset each taxel
// should show (true_offsets: perceived D − true D at its contact events).
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "object_thrower_test_support.hpp"
#include "somasim/pps/stimulus.hpp"

using namespace object_thrower_test;
using somasim::ContactEvent;
using somasim::ContactEvents;
using somasim::Presentation;
using somasim::TaxelValues;
namespace robot = somasim::robot;

namespace {

// Believed joint values: all zero but `joint` at `deg`.
Eigen::VectorXd believed_q(const std::string& joint, double deg) {
  const auto model = robot::load_robot_model_shared(kRobot);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model->num_dofs());
  q[model->dof_index(joint)] = deg * M_PI / 180.0;
  return q;
}

// p' = T_b · T_t⁻¹ for `link` (true joint values all zero).
Eigen::Isometry3d vision_map(const std::string& link, const Eigen::VectorXd& qb) {
  const auto model = robot::load_robot_model_shared(kRobot);
  robot::RobotData t(*model), b(*model);
  robot::forward_kinematics(*model, t, Eigen::VectorXd::Zero(model->num_dofs()));
  robot::forward_kinematics(*model, b, qb);
  const int l = model->link_index(link);
  return robot::link_pose(b, l) * robot::link_pose(t, l).inverse();
}

double d_of(const Eigen::Vector3d& taxel, const Eigen::Vector3d& normal,
            const Eigen::Vector3d& centre, double radius) {
  const auto local = somasim::pps::to_taxel_frame({taxel, normal}, {centre, {}, radius});
  return somasim::pps::compute_d_ttc(local.p, local.v, somasim::pps::TtcDefinition::kUnsigned).d;
}

ContactEvent touch(std::uint64_t id, double t, std::vector<int> taxels,
                   std::string part = "left_forearm") {
  ContactEvent e;
  e.id = id;
  e.time_s = t;
  e.body_part = std::move(part);
  e.touched_taxels = std::move(taxels);
  return e;
}

// forearm() with its taxels believed `shift` [m] out along their normals.
SkinPart forearm_believed_out(double shift) {
  SkinPart part = forearm();
  for (std::size_t k = 0; k < part.positions.size(); ++k)
    part.positions[k] += shift * part.normals[k];
  return part;
}

// Index in forearm() of the taxel the current presentation aims at.
std::size_t aimed(Harness& h) {
  const int id = h.output<Presentation>("t.presentation").taxel_id;
  return static_cast<std::size_t>(id);  // forearm() ids are 0, 1, 2
}

}  // namespace

TEST(ObjectThrowerPerception, TheBelievedEyePosePlacesTheObject) {
  const Eigen::VectorXd qb = believed_q("eyes_tilt", 4.0);
  for (const std::string link : {"", "head"}) {
    Harness h(thrower("approaches: 2" + (link.empty() ? "" : ", vision_link: " + link),
                      "believed_state: harness.believed"));
    h.input<JointState>("believed").position = qb;
    const auto [seen, truth] = first_perception(h);
    ASSERT_TRUE(seen.present);
    // Default: the left eye camera's link. The eye tilt does not move the head.
    const Eigen::Isometry3d m = vision_map(link.empty() ? "l_eye" : "head", qb);
    EXPECT_LT((seen.position - m * truth.position).norm(), 1e-12);
    EXPECT_LT((seen.velocity - m.linear() * truth.velocity).norm(), 1e-12);
    if (link.empty())
      EXPECT_GT((seen.position - truth.position).norm(), 0.01);  // 4° at ~0.5 m
    else
      EXPECT_LT((seen.position - truth.position).norm(), 1e-12);
  }
}

TEST(ObjectThrowerPerception, UnknownVisionLinkSuggestsTheNearest) {
  EXPECT_EQ(error_of(thrower("vision_link: l_ey", "believed_state: harness.believed")),
            "<inline>:4:" + std::to_string(87) +
                ": node 't', key 'params.vision_link': robot 'icub_v1': unknown link 'l_ey' "
                "(did you mean 'l_eye'?)");
}

// Believed taxels 2 cm out along their normals, an object moving along the aimed taxel's
// normal: at any instant the perceived D is the true D − 2 cm, so the true offset is −0.02.
TEST(ObjectThrowerPerception, TaxelsBelievedOutAlongTheirNormalsShowThatShift) {
  Harness h(thrower("approaches: 1, cone_deg: 0",
                    "contacts: harness.contacts, believed_taxels: harness.believed_taxels"));
  feed_world(h);
  h.input<SkinTaxels>("believed_taxels").parts = {forearm_believed_out(0.02)};
  ASSERT_TRUE(h.step());
  const std::size_t k = aimed(h);
  feed_object(h, h.output<ObjectSpawns>("t.spawns").recent.back(), 0.05);
  // The contact came 20 ms before this tick; the object is placed back along its path.
  h.input<ContactEvents>("contacts").recent = {touch(1, 0.03, {int(k)})};
  ASSERT_TRUE(h.step());
  const auto& offsets = h.output<TaxelValues>("t.true_offsets");
  EXPECT_EQ(offsets.labels,
            std::vector<std::string>({"left_forearm/0", "left_forearm/1", "left_forearm/2"}));
  ASSERT_EQ(offsets.values.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i)
    if (i == k)
      EXPECT_NEAR(offsets.values[i], -0.02, 1e-12);
    else
      EXPECT_TRUE(std::isnan(offsets.values[i])) << i;
  // A second event on the same taxel: the mean stays; an event seen before is not counted
  // again; events on parts the thrower does not follow are ignored.
  h.input<ContactEvents>("contacts").recent = {touch(1, 0.03, {int(k)}), touch(2, 0.05, {int(k)}),
                                               touch(3, 0.05, {1}, "right_palm")};
  ASSERT_TRUE(h.step());
  EXPECT_NEAR(offsets.values[k], -0.02, 1e-12);
  h.finish();
  EXPECT_EQ(h.metric("t", "presented_per_part"),
            nlohmann::json({{"left_forearm",
                             {{"presentations", 1},
                              {"contact_events", 2},
                              {"true_offset_mean_m", offsets.values[k]},
                              {"taxels_touched", 1}}}}));
}

// A learner fed by a tracker subtracts the radius the tracker perceives (here 1.2 cm below the
// contact distance, as for a cube meeting the skin with a corner): the true offset it should
// show is then the kinematic shift plus that difference, the median radius over the
// presentation (one wild radius does not move it).
TEST(ObjectThrowerPerception, TheLearnersPerceivedRadiusEntersItsTrueOffset) {
  for (const bool wired : {false, true}) {
    SCOPED_TRACE(wired ? "learner_stimulus wired" : "unwired");
    Harness h(thrower("approaches: 1, cone_deg: 0, size: 0.025",
                      std::string("contacts: harness.contacts, believed_taxels: "
                                  "harness.believed_taxels") +
                          (wired ? ", learner_stimulus: harness.learner" : "")));
    feed_world(h);
    h.input<SkinTaxels>("believed_taxels").parts = {forearm_believed_out(0.02)};
    ASSERT_TRUE(h.step());
    const std::size_t k = aimed(h);
    const auto spawn = h.output<ObjectSpawns>("t.spawns").recent.back();
    double t = 0.0;
    for (const double radius : {0.013, 0.5, 0.013}) {
      t += 0.05;
      feed_object(h, spawn, t);
      if (wired) {
        auto& seen = h.input<Stimulus>("learner");
        seen.present = true;
        seen.radius = radius;
      }
      ASSERT_TRUE(h.step());
    }
    h.input<ContactEvents>("contacts").recent = {touch(1, 0.12, {int(k)})};
    ASSERT_TRUE(h.step());
    const double expected = -0.02 + (wired ? 0.025 - 0.013 : 0.0);
    EXPECT_NEAR(h.output<TaxelValues>("t.true_offsets").values[k], expected, 1e-12);
  }
}

// Contacts with objects the learner never perceived teach it nothing: they are not counted in
// its true offsets either, but reported.
TEST(ObjectThrowerPerception, ObjectsTheLearnerNeverSawAddNoTrueOffset) {
  Harness h(thrower("approaches: 1, cone_deg: 0",
                    "contacts: harness.contacts, learner_stimulus: harness.learner"));
  feed_world(h);
  ASSERT_TRUE(h.step());
  feed_object(h, h.output<ObjectSpawns>("t.spawns").recent.back(), 0.05);
  h.input<ContactEvents>("contacts").recent = {touch(1, 0.03, {0, 1, 2})};
  ASSERT_TRUE(h.step());
  for (double v : h.output<TaxelValues>("t.true_offsets").values) EXPECT_TRUE(std::isnan(v));
  h.finish();
  EXPECT_EQ(h.metric("t", "true_offset_events_unseen_by_learner"), 1);
}

TEST(ObjectThrowerPerception, ALearnerStimulusNeedsTheContacts) {
  const std::string msg = error_of(thrower("approaches: 1", "learner_stimulus: harness.learner"));
  EXPECT_NE(msg.find("learner_stimulus"), std::string::npos) << msg;
  EXPECT_NE(msg.find("contacts"), std::string::npos) << msg;
}

// Vision through a believed neck error and the true taxels: the offset is the D of the
// object seen through the believed head minus its true D, at the event.
TEST(ObjectThrowerPerception, AVisionErrorGivesTheDifferenceOfDistancesAtTheEvent) {
  const Eigen::VectorXd qb = believed_q("neck_pitch", -3.0);
  Harness h(thrower("approaches: 1, size: 0.03",
                    "believed_state: harness.believed, contacts: harness.contacts"));
  h.input<JointState>("believed").position = qb;
  feed_world(h);
  ASSERT_TRUE(h.step());
  const auto spawn = h.output<ObjectSpawns>("t.spawns").recent.back();
  feed_object(h, spawn, 0.05);
  h.input<ContactEvents>("contacts").recent = {touch(7, 0.04, {0, 1, 2})};
  ASSERT_TRUE(h.step());
  const Eigen::Vector3d centre = spawn.pose.translation() + 0.04 * spawn.linear_velocity;
  const Eigen::Isometry3d m = vision_map("l_eye", qb);
  const SkinPart part = forearm();
  const auto& offsets = h.output<TaxelValues>("t.true_offsets");
  for (std::size_t k = 0; k < 3; ++k) {
    const double expected = d_of(part.positions[k], part.normals[k], m * centre, 0.03) -
                            d_of(part.positions[k], part.normals[k], centre, 0.03);
    EXPECT_NEAR(offsets.values[k], expected, 1e-12) << k;
    EXPECT_GT(std::abs(expected), 1e-3) << k;
  }
}

TEST(ObjectThrowerPerception, ContactsOutsideTheObjectsLifetimeTeachNothing) {
  Harness h(thrower("approaches: 2, pause: 1", "contacts: harness.contacts"));
  feed_world(h);
  ASSERT_TRUE(h.step());
  // Before anything was seen, and after the first object was removed.
  h.input<ContactEvents>("contacts").recent = {touch(1, 0.0, {0, 1, 2})};
  ASSERT_TRUE(h.step());
  const auto spawn = h.output<ObjectSpawns>("t.spawns").recent.back();
  feed_object(h, spawn, 0.1);
  ASSERT_TRUE(h.step());
  h.input<ContactEvents>("contacts").recent = {touch(2, spawn.remove_after_s + 0.2, {0, 1, 2})};
  while (h.time_s() < spawn.remove_after_s + 0.3) ASSERT_TRUE(h.step());
  for (double v : h.output<TaxelValues>("t.true_offsets").values) EXPECT_TRUE(std::isnan(v));
}

// A flat patch of two taxels 1.5 cm apart, believed 1 cm inside the skin; the skin reports the
// contact late, after the ball pressed 3 mm into it. The true D of the taxel beside the contact
// point would then be −|p| (p_z < 0) and the perceived +|p'|; the offsets are taken where the
// ball was kOffsetClearance (5 cm) above the skin on its way in instead.
TEST(ObjectThrowerPerception, ALateContactIsTakenWhereTheObjectApproachedTheSkin) {
  Harness h(thrower("approaches: 1, cone_deg: 0, size: 0.025",
                    "contacts: harness.contacts, believed_taxels: harness.believed_taxels"));
  feed_world(h);
  SkinPart flat = forearm();
  flat.taxel_ids = {0, 1};
  flat.positions = {{0.1, -0.2, 0.3}, {0.115, -0.2, 0.3}};
  flat.normals = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()};
  flat.positions_link = flat.positions;
  flat.normals_link = flat.normals;
  h.input<SkinTaxels>("taxels").parts = {flat};
  SkinPart believed = flat;
  for (auto& p : believed.positions) p.z() -= 0.01;
  h.input<SkinTaxels>("believed_taxels").parts = {believed};
  ASSERT_TRUE(h.step());
  const auto spawn = h.output<ObjectSpawns>("t.spawns").recent.back();
  const double speed = spawn.linear_velocity.norm();
  const double travel = spawn.remove_after_s - 0.1;
  const double late = travel + 0.003 / speed;  // 3 mm into the skin
  h.input<ContactEvents>("contacts").recent = {touch(1, late, {0, 1})};
  while (h.time_s() < late) {  // the object where the world has it at the next tick
    feed_object(h, spawn, h.time_s());
    ASSERT_TRUE(h.step());
  }
  const std::size_t k = aimed(h), beside = 1 - k;
  // Where the ball was 5 cm above both taxels' plane.
  const Eigen::Vector3d reached =
      flat.positions[k] + (0.025 + somasim::pps::kOffsetClearance) * Eigen::Vector3d::UnitZ();
  const auto& offsets = h.output<TaxelValues>("t.true_offsets");
  for (std::size_t i : {k, beside}) {
    const double expected = d_of(believed.positions[i], believed.normals[i], reached, 0.025) -
                            d_of(flat.positions[i], flat.normals[i], reached, 0.025);
    EXPECT_NEAR(offsets.values[i], expected, 1e-9) << i;
  }
  EXPECT_NEAR(offsets.values[k], 0.01, 1e-9);
  // Beside the contact: sqrt(1.5² + 6²) − sqrt(1.5² + 5²) cm, not ≈ 2 × 1.5 cm.
  EXPECT_NEAR(offsets.values[beside], std::hypot(0.015, 0.06) - std::hypot(0.015, 0.05), 1e-9);
}

// Labels for every taxel of every part of the true taxels input, parts in input order; an
// event on the second part fills only its taxel.
TEST(ObjectThrowerPerception, TrueOffsetsCoverEveryPartInInputOrder) {
  Harness h(thrower("parts: right_palm, approaches: 1, cone_deg: 0", "contacts: harness.contacts"));
  feed_world(h);
  SkinPart palm = forearm();
  palm.name = "right_palm";
  palm.link = "r_hand";
  palm.taxel_ids = {5, 9, 4};
  h.input<SkinTaxels>("taxels").parts.push_back(palm);
  ASSERT_TRUE(h.step());
  const int id = h.output<Presentation>("t.presentation").taxel_id;
  feed_object(h, h.output<ObjectSpawns>("t.spawns").recent.back(), 0.05);
  h.input<ContactEvents>("contacts").recent = {touch(1, 0.05, {id}, "right_palm")};
  ASSERT_TRUE(h.step());
  const auto& offsets = h.output<TaxelValues>("t.true_offsets");
  EXPECT_EQ(offsets.labels,
            std::vector<std::string>({"left_forearm/0", "left_forearm/1", "left_forearm/2",
                                      "right_palm/5", "right_palm/9", "right_palm/4"}));
  for (std::size_t i = 0; i < 6; ++i)
    if (offsets.labels[i] == "right_palm/" + std::to_string(id))
      EXPECT_NEAR(offsets.values[i], 0.0, 1e-12);  // believed = true taxels, no vision error
    else
      EXPECT_TRUE(std::isnan(offsets.values[i])) << offsets.labels[i];
}

// withdraw_after_skin_contact: the object is named for withdrawal 0.1 s after the skin first
// felt it, not at the end of its planned path; the next presentation clears the request.
TEST(ObjectThrowerPerception, AnObjectTheSkinFeltIsWithdrawn) {
  Harness h(thrower("approaches: 2, pause: 0.5, withdraw_after_skin_contact: 0.1",
                    "contacts: harness.contacts"));
  feed_world(h);
  ASSERT_TRUE(h.step());
  const auto spawn = h.output<ObjectSpawns>("t.spawns").recent.back();
  const auto& withdraw = h.output<ObjectSpawns>("t.spawns").withdraw;
  const double felt = 0.5;
  ASSERT_LT(felt + 0.2, spawn.remove_after_s);
  while (h.time_s() < felt - 1e-9) {
    feed_object(h, spawn, h.time_s());
    ASSERT_TRUE(h.step());
    EXPECT_TRUE(withdraw.empty());
  }
  h.input<ContactEvents>("contacts").recent = {touch(1, felt, {0})};
  while (h.time_s() < felt + 0.1 - 1e-9) {
    feed_object(h, spawn, h.time_s());
    ASSERT_TRUE(h.step());
    EXPECT_TRUE(withdraw.empty()) << h.time_s();
  }
  ASSERT_TRUE(h.step());
  EXPECT_EQ(withdraw, std::vector<std::string>{spawn.name});
  while (h.output<ObjectSpawns>("t.spawns").recent.back().id == spawn.id) ASSERT_TRUE(h.step());
  EXPECT_TRUE(withdraw.empty()) << "cleared for the next object";
  while (h.step()) {
  }
  h.finish();
  EXPECT_EQ(h.metric("t", "objects_withdrawn"), 1);
}

TEST(ObjectThrowerPerception, WithdrawingNeedsTheSkinContacts) {
  const std::string msg = error_of(thrower("withdraw_after_skin_contact: 0.1"));
  EXPECT_NE(msg.find("key 'params.withdraw_after_skin_contact': needs the skin's contact "
                     "events: wire input 'contacts'"),
            std::string::npos)
      << msg;
}
