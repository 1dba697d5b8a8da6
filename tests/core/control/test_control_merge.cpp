// merge_joint_commands: order, skipping, conflicts, sizes.
#include <gtest/gtest.h>

#include "somasim/control/joint_command_merge.hpp"

using somasim::JointCommand;
using somasim::JointCommandMode;
using somasim::control::merge_joint_commands;
using somasim::control::MergeConflict;

namespace {
JointCommand on(int dof, double value, int n = 3) {
  JointCommand c;
  c.mode.assign(n, JointCommandMode::kNone);
  c.position.setZero(n);
  c.velocity.setZero(n);
  c.mode[dof] = JointCommandMode::kPosition;
  c.position[dof] = value;
  return c;
}
}  // namespace

TEST(ControlMerge, LaterWinsAndEmptyOrNullAreSkipped) {
  const JointCommand a = on(0, 1.0), b = on(0, 2.0), empty;
  JointCommand out;
  EXPECT_EQ(merge_joint_commands({&a, nullptr, &empty, &b}, MergeConflict::kLastWins, out), "");
  ASSERT_EQ(out.mode.size(), 3u);
  EXPECT_EQ(out.position[0], 2.0);
  EXPECT_EQ(out.mode[1], JointCommandMode::kNone);
}

TEST(ControlMerge, ConflictsAndSizesAreReported) {
  const JointCommand a = on(1, 1.0), b = on(1, 2.0), c = on(0, 1.0, 4);
  JointCommand out;
  EXPECT_EQ(merge_joint_commands({&a, &b}, MergeConflict::kError, out),
            "input 0 and input 1 both command dof 1");
  EXPECT_EQ(merge_joint_commands({&a, &c}, MergeConflict::kLastWins, out, {"arm", "head"}),
            "'head' has 4 dofs, expected 3 (as 'arm')");
  JointCommand bad = on(0, 1.0);
  bad.velocity.resize(1);
  EXPECT_EQ(merge_joint_commands({&bad}, MergeConflict::kLastWins, out),
            "input 0 is malformed: 3 modes, 3 positions and 1 velocities");
  EXPECT_EQ(merge_joint_commands({}, MergeConflict::kLastWins, out), "");
  EXPECT_TRUE(out.mode.empty());
}
