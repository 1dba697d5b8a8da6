// CartesianVelocityController and ChainSelection on the iCub model: exact task velocity away
// from singularities, joint-limit clamping with re-solve, damping at a singularity, chain links.
#include <cmath>

#include <gtest/gtest.h>

#include "somasim/control/cartesian_velocity.hpp"
#include "somasim/error.hpp"
#include "somasim/robot/robot_loader.hpp"

using namespace somasim;
using control::CartesianVelocityController;

namespace {
std::shared_ptr<const robot::RobotModel> icub() {
  return robot::load_robot_model_shared(std::string(SOMASIM_SOURCE_DIR) +
                                        "/assets/robots/icub_v1.yaml");
}
Eigen::VectorXd mid(const robot::RobotModel& m) {
  return 0.5 * (m.lower_limits() + m.upper_limits());
}
}  // namespace

TEST(ControlChainSelection, NamedAndBaseTipChains) {
  const auto m = icub();
  const auto arm = control::select_chain(*m, "right_arm");
  EXPECT_EQ(arm.dofs.size(), 10u);
  EXPECT_EQ(m->link(arm.tip_link).name, "r_hand");
  EXPECT_TRUE(arm.contains_link(m->link_index("r_forearm")));
  EXPECT_FALSE(arm.contains_link(m->link_index("l_forearm")));
  EXPECT_FALSE(arm.contains_link(0));  // the base does not move with the chain
  const auto no_torso = control::select_chain(*m, "r_palm", "chest");
  EXPECT_EQ(no_torso.name, "chest->r_palm");
  EXPECT_EQ(no_torso.dofs.size(), 7u);
  try {
    no_torso.require_link(*m, "chest");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "link 'chest' is not in chain 'chest->r_palm' (links: r_shoulder_1, "
                 "r_shoulder_2, r_upper_arm, r_elbow_1, r_forearm, r_wrist_1, r_hand)");
  }
}

TEST(ControlCartesianVelocity, ReproducesTheTaskAndMatchesFiniteDifferences) {
  const auto m = icub();
  CartesianVelocityController c(m, control::select_chain(*m, "right_arm"));
  c.set_point("r_forearm", {0, 0.07, 0.02});
  Eigen::VectorXd q = mid(*m), qd(10);
  const Eigen::Vector3d v(0.01, -0.02, 0.03);
  c.compute(q, v, 0.01, qd);
  EXPECT_NEAR((c.predicted_velocity() - v).norm(), 0.0, 1e-12);
  EXPECT_FALSE(c.limited());
  // A tiny step along q̇ moves the point by v·h (to first order).
  const Eigen::Vector3d p0 = c.point_position();
  const double h = 1e-6;
  const auto& dofs = c.chain().dofs;
  for (int k = 0; k < 10; ++k) q[dofs[k]] += qd[k] * h;
  Eigen::VectorXd unused(10);
  c.compute(q, v, 0.01, unused);
  EXPECT_NEAR(((c.point_position() - p0) / h - v).norm(), 0.0, 1e-5);
}

TEST(ControlCartesianVelocity, NeverPushesAJointPastItsLimitAndSolvesWithTheOthers) {
  const auto m = icub();
  CartesianVelocityController c(m, control::select_chain(*m, "right_arm"));
  const auto dofs = c.chain().dofs;
  Eigen::VectorXd qd(10);
  int clamped = 0;
  for (const Eigen::Vector3d& v :
       {Eigen::Vector3d(0, 0, 0.05), Eigen::Vector3d(0.05, 0, 0), Eigen::Vector3d(0, -0.05, 0)})
    for (int k = 0; k < 10; ++k)
      for (bool upper : {false, true}) {
        Eigen::VectorXd q = mid(*m);
        const int d = dofs[k];
        q[d] = upper ? m->upper_limits()[d] : m->lower_limits()[d];
        c.compute(q, v, 0.01, qd);
        if (upper) {
          EXPECT_LE(qd[k], 0.0);
        } else {
          EXPECT_GE(qd[k], 0.0);
        }
        if (qd[k] == 0.0 && c.limited()) {
          ++clamped;
          // The other nine joints still produce the task exactly.
          EXPECT_NEAR((c.predicted_velocity() - v).norm(), 0.0, 1e-9) << k;
        }
      }
  EXPECT_GT(clamped, 5);
}

TEST(ControlCartesianVelocity, DampedAtASingularity) {
  const auto m = icub();
  // Elbow and pronosupination: rank <= 2 of 3, the task cannot be met exactly.
  CartesianVelocityController c(m, control::select_chain(*m, "r_forearm", "r_upper_arm"));
  ASSERT_EQ(c.chain().dofs.size(), 2u);  // r_elbow, r_wrist_prosup
  Eigen::VectorXd qd(2);
  c.compute(mid(*m), {0.0, 0.0, 0.1}, 0.01, qd);
  EXPECT_TRUE(qd.allFinite());
  EXPECT_LT(c.predicted_velocity().norm(), 0.1 + 1e-12);
}

TEST(ControlCartesianVelocity, BadSizesAreErrors) {
  const auto m = icub();
  control::CartesianVelocityOptions o;
  o.max_joint_velocity = Eigen::VectorXd::Ones(3);
  try {
    CartesianVelocityController c(m, control::select_chain(*m, "right_arm"), o);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "max joint velocity: expected 1 or 10 values (one per joint of chain "
                 "'right_arm'), got 3");
  }
  CartesianVelocityController c(m, control::select_chain(*m, "right_arm"));
  Eigen::VectorXd qd(10);
  try {
    c.compute(Eigen::VectorXd::Zero(3), {0, 0, 0}, 0.01, qd);
    FAIL();
  } catch (const RunError& e) {
    EXPECT_EQ(std::string(e.what()), "cartesian velocity: expected " +
                                         std::to_string(m->num_dofs()) + " joint values, got 3");
  }
}
