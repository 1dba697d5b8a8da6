// joint_command_mux: merging, later inputs win, conflicts as errors, unwired/empty inputs,
// size mismatches.
#include <gtest/gtest.h>

#include "somasim/robot/ports.hpp"
#include "somasim/testing/harness.hpp"

using somasim::JointCommand;
using somasim::JointCommandMode;
using somasim::testing::Harness;

namespace {

std::string graph(const std::string& conflict, const std::string& inputs) {
  return "base_rate_hz: 10\nnodes:\n  mux: {plugin: joint_command_mux, params: {conflict: " +
         conflict + "}, inputs: {" + inputs + "}}\n";
}

// A command on `dofs` of a 5-dof robot in `mode`, with positions/velocities = value.
JointCommand command(std::vector<int> dofs, JointCommandMode mode, double value, int n = 5) {
  JointCommand c;
  c.mode.assign(n, JointCommandMode::kNone);
  c.position.setZero(n);
  c.velocity.setZero(n);
  for (int d : dofs) {
    c.mode[d] = mode;
    c.position[d] = value;
    c.velocity[d] = value;
  }
  return c;
}

const std::string kThree = "in0: harness.a, in1: harness.b, in3: harness.c";

}  // namespace

TEST(JointCommandMux, MergesDisjointCommandsAndLeavesTheRestFree) {
  Harness h(graph("last_wins", kThree));
  h.input<JointCommand>("a") = command({0, 1}, JointCommandMode::kPosition, 1.0);
  h.input<JointCommand>("b") = command({3}, JointCommandMode::kVelocity, 2.0);
  // c not produced yet (empty): ignored
  ASSERT_TRUE(h.step());
  const auto& out = h.output<JointCommand>("mux.command");
  ASSERT_EQ(out.mode.size(), 5u);
  EXPECT_EQ(out.mode[0], JointCommandMode::kPosition);
  EXPECT_EQ(out.mode[1], JointCommandMode::kPosition);
  EXPECT_EQ(out.mode[2], JointCommandMode::kNone);
  EXPECT_EQ(out.mode[3], JointCommandMode::kVelocity);
  EXPECT_EQ(out.mode[4], JointCommandMode::kNone);
  EXPECT_EQ(out.position[1], 1.0);
  EXPECT_EQ(out.velocity[3], 2.0);
}

TEST(JointCommandMux, LaterInputsWinOnSharedDofs) {
  Harness h(graph("last_wins", kThree));
  h.input<JointCommand>("a") = command({0, 1, 2}, JointCommandMode::kPosition, 1.0);
  h.input<JointCommand>("b") = command({1}, JointCommandMode::kVelocity, 2.0);
  h.input<JointCommand>("c") = command({2}, JointCommandMode::kPosition, 3.0);
  ASSERT_TRUE(h.step());
  const auto& out = h.output<JointCommand>("mux.command");
  EXPECT_EQ(out.mode[0], JointCommandMode::kPosition);
  EXPECT_EQ(out.position[0], 1.0);
  EXPECT_EQ(out.mode[1], JointCommandMode::kVelocity);
  EXPECT_EQ(out.velocity[1], 2.0);
  EXPECT_EQ(out.position[2], 3.0);
  // A controller releasing a dof (kNone) hands it back to the earlier input.
  h.input<JointCommand>("c") = command({}, JointCommandMode::kNone, 0.0);
  ASSERT_TRUE(h.step());
  EXPECT_EQ(h.output<JointCommand>("mux.command").position[2], 1.0);
}

TEST(JointCommandMux, ConflictsStopTheRunWhenAskedTo) {
  Harness h(graph("error", kThree));
  h.input<JointCommand>("a") = command({0, 1}, JointCommandMode::kPosition, 1.0);
  h.input<JointCommand>("c") = command({4}, JointCommandMode::kPosition, 1.0);
  ASSERT_TRUE(h.step());  // disjoint: fine
  h.input<JointCommand>("c") = command({1}, JointCommandMode::kVelocity, 1.0);
  try {
    h.step();
    FAIL() << "expected a RunError";
  } catch (const somasim::RunError& e) {
    EXPECT_STREQ(e.what(), "mux: 'in0' and 'in3' both command dof 1");
  }
}

TEST(JointCommandMux, InputsOfDifferentSizesAreAnError) {
  Harness h(graph("last_wins", kThree));
  h.input<JointCommand>("a") = command({0}, JointCommandMode::kPosition, 1.0);
  h.input<JointCommand>("b") = command({0}, JointCommandMode::kPosition, 1.0, 7);
  try {
    h.step();
    FAIL() << "expected a RunError";
  } catch (const somasim::RunError& e) {
    EXPECT_STREQ(e.what(), "mux: 'in1' has 7 dofs, expected 5 (as 'in0')");
  }
}

TEST(JointCommandMux, UnknownConflictPolicyIsABadInput) {
  try {
    Harness h(graph("first_wins", "in0: harness.a"));
    FAIL() << "expected an InputError";
  } catch (const somasim::InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("params.conflict"), std::string::npos) << m;
  }
}
