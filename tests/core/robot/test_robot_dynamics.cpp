// Inverse dynamics (recursive Newton–Euler) against the Jacobians on shipped and generated
// robots: gravity torques are −Σ Jᵀ m g, the accelerations' torques are M q̈ with M built from the
// links' Jacobians, and the velocity torques are Lagrange's Ṁ q̇ − ½ ∂(q̇ᵀ M q̇)/∂q.
#include <gtest/gtest.h>

#include <random>

#include "robot_test_support.hpp"
#include "somasim/robot/dynamics.hpp"
#include "somasim/robot/kinematics.hpp"

namespace somasim::robot {
namespace {

constexpr double kFrameMass = 0.02, kFrameInertia = 1e-5;

/// M(q) from the links' Jacobians: Σ J_vᵀ m J_v + J_ωᵀ R I Rᵀ J_ω (at each centre of mass).
Eigen::MatrixXd mass_matrix(const RobotModel& model, const std::vector<Inertial>& inertials,
                            const Eigen::VectorXd& q) {
  RobotData data(model);
  forward_kinematics(model, data, q);
  const int n = model.num_dofs();
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
  Matrix6Xd j(6, n);
  for (int l = 0; l < model.num_links(); ++l) {
    const Inertial& in = inertials[static_cast<std::size_t>(l)];
    if (in.mass <= 0.0) continue;
    point_jacobian(model, data, l, in.com, j);
    const Eigen::Matrix3d r = data.link_poses[l].linear();
    m += in.mass * j.topRows<3>().transpose() * j.topRows<3>() +
         j.bottomRows<3>().transpose() * (r * in.inertia * r.transpose()) * j.bottomRows<3>();
  }
  return m;
}

std::vector<RobotModel> robots(std::mt19937& rng) {
  std::vector<RobotModel> out;
  out.push_back(test::load_icub("icub_v1"));
  out.push_back(test::load_icub("icub_v2"));
  while (out.size() < 22) {  // 20 generated trees that move
    RobotModel tree = test::random_tree(rng, 2 + static_cast<int>(out.size()) % 9);
    if (tree.num_dofs() > 0) out.push_back(std::move(tree));
  }
  return out;
}

TEST(InverseDynamics, GravityTorquesAreTheJacobiansTransposedTimesTheWeights) {
  std::mt19937 rng(1);
  const Eigen::Vector3d g(0.3, -0.2, -9.81);
  for (const RobotModel& model : robots(rng)) {
    SCOPED_TRACE(model.name());
    const auto inertials = physical_inertials(model, kFrameMass, kFrameInertia);
    InverseDynamics dynamics(model, inertials);
    RobotData data(model);
    const int n = model.num_dofs();
    Matrix6Xd j(6, n);
    for (int trial = 0; trial < 5; ++trial) {
      forward_kinematics(model, data, test::random_posture(model, rng));
      Eigen::VectorXd expected = Eigen::VectorXd::Zero(n);
      for (int l = 0; l < model.num_links(); ++l) {
        const Inertial& in = inertials[static_cast<std::size_t>(l)];
        if (in.mass <= 0.0) continue;
        point_jacobian(model, data, l, in.com, j);
        expected -= j.topRows<3>().transpose() * (in.mass * g);
      }
      const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
      EXPECT_LT((dynamics.torques(data, zero, zero, g) - expected).cwiseAbs().maxCoeff(), 1e-10);
    }
  }
}

TEST(InverseDynamics, AccelerationTorquesAreTheMassMatrixTimesTheAccelerations) {
  std::mt19937 rng(2);
  for (const RobotModel& model : robots(rng)) {
    SCOPED_TRACE(model.name());
    const auto inertials = physical_inertials(model, kFrameMass, kFrameInertia);
    InverseDynamics dynamics(model, inertials);
    RobotData data(model);
    const int n = model.num_dofs();
    const Eigen::VectorXd q = test::random_posture(model, rng);
    forward_kinematics(model, data, q);
    const Eigen::VectorXd qdd = Eigen::VectorXd::Random(n);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
    const Eigen::VectorXd expected = mass_matrix(model, inertials, q) * qdd;
    EXPECT_LT((dynamics.torques(data, zero, qdd, Eigen::Vector3d::Zero()) - expected)
                  .cwiseAbs()
                  .maxCoeff(),
              1e-10 * std::max(1.0, expected.cwiseAbs().maxCoeff()));
  }
}

TEST(InverseDynamics, VelocityTorquesAreLagrangesCoriolisAndCentrifugalTerms) {
  std::mt19937 rng(3);
  for (const RobotModel& model : robots(rng)) {
    SCOPED_TRACE(model.name());
    const auto inertials = physical_inertials(model, kFrameMass, kFrameInertia);
    InverseDynamics dynamics(model, inertials);
    RobotData data(model);
    const int n = model.num_dofs();
    const Eigen::VectorXd q = test::random_posture(model, rng);
    const Eigen::VectorXd qd = 2.0 * Eigen::VectorXd::Random(n);
    const double h = 1e-6;
    // Ṁ q̇ by central differences along q̇; ∂(q̇ᵀ M q̇)/∂q_i along each coordinate.
    const Eigen::MatrixXd m_dot =
        (mass_matrix(model, inertials, q + h * qd) - mass_matrix(model, inertials, q - h * qd)) /
        (2.0 * h);
    Eigen::VectorXd expected = m_dot * qd;
    for (int i = 0; i < n; ++i) {
      Eigen::VectorXd step = Eigen::VectorXd::Zero(n);
      step[i] = h;
      const double plus = qd.dot(mass_matrix(model, inertials, q + step) * qd);
      const double minus = qd.dot(mass_matrix(model, inertials, q - step) * qd);
      expected[i] -= 0.5 * (plus - minus) / (2.0 * h);
    }
    forward_kinematics(model, data, q);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
    EXPECT_LT((dynamics.torques(data, qd, zero, Eigen::Vector3d::Zero()) - expected)
                  .cwiseAbs()
                  .maxCoeff(),
              1e-6 * std::max(1.0, expected.cwiseAbs().maxCoeff()));
  }
}

TEST(PhysicalInertials, OnlyMovingGroupsWithoutMassGetAFrameLinksMass) {
  const RobotModel model = test::load_icub();
  const auto plain = physical_inertials(model, 0.02, 1e-5);
  const std::vector<bool> all_locked(static_cast<std::size_t>(model.num_dofs()), true);
  const auto locked = physical_inertials(model, 0.02, 1e-5, all_locked);
  for (int l = 0; l < model.num_links(); ++l) {
    const double own = model.link(l).inertial.mass;
    EXPECT_EQ(locked[static_cast<std::size_t>(l)].mass, own) << model.link(l).name;
    EXPECT_TRUE(plain[static_cast<std::size_t>(l)].mass == own ||
                (own == 0.0 && plain[static_cast<std::size_t>(l)].mass == 0.02))
        << model.link(l).name;
  }
  // The shoulder's DH frame links carry nothing of their own: they get a frame link's mass.
  EXPECT_EQ(plain[static_cast<std::size_t>(model.link_index("l_shoulder_1"))].mass, 0.02);
}

}  // namespace
}  // namespace somasim::robot
