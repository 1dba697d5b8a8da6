// FK + Jacobian of the iCub's 10-DoF right arm (torso + arm → palm): the compiled
// KinematicChain against a naive baseline (Isometry3d built from the DH parameters per link,
// a full 4×4 product per link, frames kept in a std::vector), plus tree FK and IK for scale.
#include <cmath>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "somasim/robot/inverse_kinematics.hpp"
#include "somasim/robot/kinematic_chain.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_loader.hpp"

namespace {
using namespace somasim::robot;

const RobotModel& icub() {
  static const RobotModel model =
      load_robot_model(std::string(SOMASIM_SOURCE_DIR) + "/assets/robots/icub_v1.yaml");
  return model;
}

std::vector<Eigen::VectorXd> random_qs(int n, int dofs) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::VectorXd> out(n, Eigen::VectorXd(dofs));
  for (auto& q : out)
    for (int k = 0; k < dofs; ++k) q[k] = u(rng);
  return out;
}

// Right arm v1, iKin DH: a, d, alpha, offset [m, rad].
struct Dh {
  double a, d, alpha, offset;
};
const double kD = M_PI / 180.0;
const std::vector<Dh> kArm = {{0.032, 0, 90 * kD, 0},
                              {0, -0.0055, 90 * kD, -90 * kD},
                              {-0.0233647, -0.1433, 90 * kD, -105 * kD},
                              {0, -0.10774, 90 * kD, -90 * kD},
                              {0, 0, -90 * kD, -90 * kD},
                              {-0.015, -0.15228, -90 * kD, -105 * kD},
                              {0.015, 0, 90 * kD, 0},
                              {0, -0.1373, 90 * kD, -90 * kD},
                              {0, 0, 90 * kD, 90 * kD},
                              {0.0625, 0.016, 0, 180 * kD}};

// The naive way: one Isometry3d per link from AngleAxis/Translation, 4×4 products, and the
// Jacobian from the stored frames.
void naive_fk_jacobian(const Eigen::VectorXd& q, Eigen::Matrix4d& tip, Matrix6Xd& jac) {
  Eigen::Matrix4d h0;
  h0 << 0, -1, 0, 0, 0, 0, -1, 0, 1, 0, 0, 0, 0, 0, 0, 1;
  std::vector<Eigen::Matrix4d> frames;
  frames.push_back(h0);
  for (std::size_t i = 0; i < kArm.size(); ++i) {
    const Dh& dh = kArm[i];
    const Eigen::Isometry3d link =
        Eigen::Isometry3d(Eigen::AngleAxisd(q[static_cast<Eigen::Index>(i)] + dh.offset,
                                            Eigen::Vector3d::UnitZ())) *
        Eigen::Translation3d(0, 0, dh.d) * Eigen::Translation3d(dh.a, 0, 0) *
        Eigen::AngleAxisd(dh.alpha, Eigen::Vector3d::UnitX());
    frames.push_back(frames.back() * link.matrix());
  }
  tip = frames.back();
  const Eigen::Vector3d p = tip.block<3, 1>(0, 3);
  for (std::size_t i = 0; i < kArm.size(); ++i) {
    const Eigen::Vector3d z = frames[i].block<3, 1>(0, 2);
    const Eigen::Vector3d o = frames[i].block<3, 1>(0, 3);
    jac.col(static_cast<Eigen::Index>(i)) << z.cross(p - o), z;
  }
}

void BM_NaiveDhFkJacobian(benchmark::State& state) {
  const auto qs = random_qs(1024, 10);
  Eigen::Matrix4d tip;
  Matrix6Xd jac(6, 10);
  std::size_t i = 0;
  for (auto _ : state) {
    naive_fk_jacobian(qs[i++ & 1023], tip, jac);
    benchmark::DoNotOptimize(tip.data());
    benchmark::DoNotOptimize(jac.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_NaiveDhFkJacobian);

void BM_ChainFkJacobian(benchmark::State& state) {
  const KinematicChain arm = KinematicChain::named(icub(), "right_arm");
  const auto qs = random_qs(1024, 10);
  Eigen::Isometry3d tip;
  Matrix6Xd jac(6, 10);
  std::size_t i = 0;
  for (auto _ : state) {
    arm.forward_jacobian(qs[i++ & 1023], tip, jac);
    benchmark::DoNotOptimize(tip.data());
    benchmark::DoNotOptimize(jac.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ChainFkJacobian);

void BM_ChainFkWithOffsets(benchmark::State& state) {
  const KinematicChain arm = KinematicChain::named(icub(), "right_arm");
  const auto qs = random_qs(1024, 10);
  const Eigen::VectorXd beta = Eigen::VectorXd::Constant(10, 0.05);
  std::size_t i = 0;
  for (auto _ : state) {
    Eigen::Isometry3d tip = arm.forward(qs[i++ & 1023], beta);
    benchmark::DoNotOptimize(tip.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ChainFkWithOffsets);

void BM_TreeFkAllLinks(benchmark::State& state) {
  const RobotModel& model = icub();
  RobotData data(model);
  const auto qs = random_qs(1024, model.num_dofs());
  std::size_t i = 0;
  for (auto _ : state) {
    forward_kinematics(model, data, qs[i++ & 1023]);
    benchmark::DoNotOptimize(data.link_poses.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_TreeFkAllLinks);

void BM_IkPosition(benchmark::State& state) {
  const KinematicChain arm = KinematicChain::named(icub(), "right_arm");
  IkSolver solver(arm);
  std::mt19937_64 rng(2);
  std::vector<Eigen::Vector3d> targets;
  for (int n = 0; n < 64; ++n) {
    Eigen::VectorXd q(10);
    for (int k = 0; k < 10; ++k)
      q[k] =
          std::uniform_real_distribution<double>(arm.lower_limits()[k], arm.upper_limits()[k])(rng);
    targets.push_back(arm.forward(q).translation());
  }
  Eigen::VectorXd q(10);
  std::size_t i = 0;
  for (auto _ : state) {
    q.setZero();
    benchmark::DoNotOptimize(solver.solve_position(targets[i++ & 63], q));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_IkPosition);

}  // namespace
