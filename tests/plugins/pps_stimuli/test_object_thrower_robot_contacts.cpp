// object_thrower with the world's contacts: guided objects by default, touches of robot links
// with and without skin counted per presentation, and withdraw_after_robot_contact ending a
// presentation that meets the robot anywhere.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "object_thrower_test_support.hpp"

using namespace object_thrower_test;
using somasim::Contact;
using somasim::Contacts;
using somasim::ObjectMotion;

namespace {

std::shared_ptr<const somasim::robot::RobotModel> icub() {
  return somasim::robot::load_robot_model_shared(kRobot);
}

// A contact at `time_s` between `link` and object 0.
Contact touching(const std::string& link, double time_s) {
  Contact c;
  c.link_a = icub()->link_index(link);
  c.object_b = 0;
  c.normal_force = 1.0;
  c.time_s = time_s;
  return c;
}

const std::string kContactsWire = "world_contacts: harness.world_contacts";

}  // namespace

TEST(ObjectThrowerRobotContacts, ObjectsAreGuidedWithTheirMassUnlessKinematicIsAsked) {
  Harness guided(thrower("approaches: 2, mass: 0.25"));
  for (const auto& s : all_spawns(guided)) {
    EXPECT_EQ(s.motion, ObjectMotion::kGuided);
    EXPECT_EQ(s.mass, 0.25);
  }
  Harness kinematic(thrower("approaches: 2, object_motion: kinematic"));
  for (const auto& s : all_spawns(kinematic)) EXPECT_EQ(s.motion, ObjectMotion::kKinematic);
}

TEST(ObjectThrowerRobotContacts, TouchesAreCountedPerPresentationWithTheLinksWithoutSkin) {
  Harness h(thrower("approaches: 3, pause: 0.2", kContactsWire));
  feed_world(h);
  auto& contacts = h.input<Contacts>("world_contacts");
  std::uint64_t presentation = 0;
  double started = 0.0;
  while (h.step()) {
    const auto& spawn = h.output<ObjectSpawns>("t.spawns").recent.back();
    if (spawn.id != presentation) presentation = spawn.id, started = h.time_s();
    feed_object(h, spawn, h.time_s() - started);
    const double t = h.time_s();
    contacts.recent.clear();
    if (presentation == 1 && std::abs(t - started - 0.5) < 1e-9)  // skin only
      contacts.recent = {touching("l_forearm", t)};
    if (presentation == 2 && std::abs(t - started - 0.5) < 1e-9)  // the head, then skin
      contacts.recent = {touching("head", t), touching("l_forearm", t)};
    if (presentation == 2 && std::abs(t - started - 0.6) < 1e-9)  // the same head again
      contacts.recent = {touching("head", t)};
  }
  h.finish();
  EXPECT_EQ(h.metric("t", "robot_contact_presentations"), 2);
  EXPECT_EQ(h.metric("t", "robot_contact_unskinned_presentations"), 1);
  EXPECT_EQ(h.metric("t", "robot_contact_unskinned_links"), nlohmann::json({{"head", 1}}));
}

TEST(ObjectThrowerRobotContacts, ATouchAnywhereEndsThePresentationWhenAsked) {
  Harness h(thrower("approaches: 2, pause: 0.5, withdraw_after_robot_contact: 0.1", kContactsWire));
  feed_world(h);
  ASSERT_TRUE(h.step());
  const auto spawn = h.output<ObjectSpawns>("t.spawns").recent.back();
  const auto& withdraw = h.output<ObjectSpawns>("t.spawns").withdraw;
  const double touched = 0.5;
  ASSERT_LT(touched + 0.2, spawn.remove_after_s);
  while (h.time_s() < touched - 1e-9) {
    feed_object(h, spawn, h.time_s());
    ASSERT_TRUE(h.step());
  }
  h.input<Contacts>("world_contacts").recent = {touching("r_upper_arm", touched)};
  while (h.time_s() < touched + 0.1 - 1e-9) {
    feed_object(h, spawn, h.time_s());
    ASSERT_TRUE(h.step());
    EXPECT_TRUE(withdraw.empty()) << h.time_s();
  }
  ASSERT_TRUE(h.step());
  EXPECT_EQ(withdraw, std::vector<std::string>{spawn.name});
  while (h.step()) {
  }
  h.finish();
  EXPECT_EQ(h.metric("t", "objects_withdrawn"), 1);
}

TEST(ObjectThrowerRobotContacts, WithdrawingOnRobotContactNeedsTheWorldsContacts) {
  const std::string msg = error_of(thrower("withdraw_after_robot_contact: 0.1"));
  EXPECT_NE(msg.find("node 't', key 'params.withdraw_after_robot_contact': needs the world's "
                     "contacts: wire input 'world_contacts' (e.g. world.contacts)"),
            std::string::npos)
      << msg;
}
