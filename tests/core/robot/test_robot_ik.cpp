// Damped-least-squares IK: reaches poses produced by random joint values, respects the limits.
#include <random>

#include <gtest/gtest.h>

#include "robot_test_support.hpp"
#include "somasim/robot/inverse_kinematics.hpp"

namespace somasim::robot {
namespace {

Eigen::VectorXd random_q(const KinematicChain& chain, std::mt19937_64& rng) {
  Eigen::VectorXd q(chain.num_dofs());
  for (int k = 0; k < chain.num_dofs(); ++k)
    q[k] = std::uniform_real_distribution<double>(chain.lower_limits()[k],
                                                  chain.upper_limits()[k])(rng);
  return q;
}

bool within_limits(const KinematicChain& chain, const Eigen::VectorXd& q) {
  return (q.array() >= chain.lower_limits().array()).all() &&
         (q.array() <= chain.upper_limits().array()).all();
}

class RobotIk : public ::testing::Test {
 protected:
  const RobotModel model = test::load_icub();
  const KinematicChain arm = KinematicChain::named(model, "right_arm");
};

TEST_F(RobotIk, ReachesRandomReachablePositions) {
  std::mt19937_64 rng(11);
  IkSolver solver(arm);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Vector3d target = arm.forward(random_q(arm, rng)).translation();
    Eigen::VectorXd q = Eigen::VectorXd::Zero(10);
    const IkResult r = solver.solve_position(target, q);
    EXPECT_TRUE(r.success) << "trial " << trial << " error " << r.position_error;
    EXPECT_LE(r.position_error, 1e-4);
    EXPECT_LT((arm.forward(q).translation() - target).norm(), 1e-4);
    EXPECT_TRUE(within_limits(arm, q));
  }
}

TEST_F(RobotIk, ReachesRandomReachablePoses) {
  std::mt19937_64 rng(12);
  IkSolver solver(arm);
  int successes = 0;
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Isometry3d target = arm.forward(random_q(arm, rng));
    Eigen::VectorXd q = 0.5 * (arm.lower_limits() + arm.upper_limits());
    const IkResult r = solver.solve_pose(target, q);
    EXPECT_TRUE(within_limits(arm, q));
    if (!r.success) continue;
    ++successes;
    const Eigen::Isometry3d got = arm.forward(q);
    EXPECT_LT((got.translation() - target.translation()).norm(), 1e-4);
    EXPECT_LT(Eigen::AngleAxisd(got.linear() * target.linear().transpose()).angle(), 1e-3);
  }
  EXPECT_EQ(successes, 50);
}

TEST_F(RobotIk, UnreachableTargetKeepsLimitsAndReportsResidual) {
  IkOptions options;
  options.restarts = 2;
  IkSolver solver(arm, options);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(10);
  const IkResult r = solver.solve_position(Eigen::Vector3d(-1.0, 0.5, 0.2), q);
  EXPECT_FALSE(r.success);
  EXPECT_GT(r.position_error, 0.3);
  EXPECT_TRUE(within_limits(arm, q));
  EXPECT_NEAR((arm.forward(q).translation() - Eigen::Vector3d(-1.0, 0.5, 0.2)).norm(),
              r.position_error, 1e-12);
}

TEST_F(RobotIk, ArmOnlyChainWithTorsoAsBase) {
  // A 7-DoF chain from the chest frame of the right arm (the body-schema study's arm).
  const KinematicChain arm7(model, "r_palm", "chest");
  ASSERT_EQ(arm7.num_dofs(), 7);
  std::mt19937_64 rng(13);
  IkSolver solver(arm7);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d target = arm7.forward(random_q(arm7, rng)).translation();
    Eigen::VectorXd q = Eigen::VectorXd::Zero(7);
    EXPECT_TRUE(solver.solve_position(target, q).success);
    EXPECT_TRUE(within_limits(arm7, q));
  }
}

}  // namespace
}  // namespace somasim::robot
