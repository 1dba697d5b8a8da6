// ball_thrower: parameter checks (the full behaviour runs in tests/experiments, with physics).
#include <gtest/gtest.h>

#include "somasim/testing/harness.hpp"

using somasim::testing::Harness;

namespace {
std::string thrower(const std::string& parts) {
  return std::string("robots: {icub: ") + SOMASIM_SOURCE_DIR +
         "/assets/robots/icub_v1.yaml}\nnodes:\n  t: {plugin: ball_thrower, params: {parts: '" +
         parts +
         "'}, inputs: {taxels: harness.taxels, link_poses: harness.poses, objects: "
         "harness.objects, contacts: harness.contacts, skin_events: harness.events}}\n";
}
}  // namespace

TEST(BallThrower, AcceptsTheRobotsSkinParts) {
  EXPECT_NO_THROW(Harness(thrower("left_forearm right_palm")));
}

TEST(BallThrower, UnknownPartNamesTheRobotsParts) {
  try {
    Harness h(thrower("left_forarm"));
    FAIL() << "expected an InputError";
  } catch (const somasim::InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("node 't', key 'params.parts': unknown skin part 'left_forarm' (did you "
                       "mean 'left_forearm'?); the robot's skin parts: left_forearm, right_palm"),
              std::string::npos)
        << msg;
  }
}

TEST(BallThrower, NeedsAtLeastOnePart) {
  try {
    Harness h(thrower(" "));
    FAIL() << "expected an InputError";
  } catch (const somasim::InputError& e) {
    EXPECT_NE(
        std::string(e.what()).find("key 'params.parts': expected at least one skin part name"),
        std::string::npos)
        << e.what();
  }
}
