#pragma once
// Helpers shared by the robot tests: the shipped iCub descriptions and a standalone DH chain.
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <Eigen/Geometry>

#include "somasim/robot/robot_loader.hpp"

namespace somasim::robot::test {

inline RobotModel load_icub(const std::string& variant = "icub_v1") {
  return load_robot_model(std::string(SOMASIM_SOURCE_DIR) + "/assets/robots/" + variant + ".yaml");
}

inline constexpr double kDeg = M_PI / 180.0;

/// One iKin DH row [m, deg].
struct DhRow {
  double a, d, alpha_deg, offset_deg;
};

/// Standalone iKin FK: H0 · Π Rz(q_i + offset_i)·Tz(d_i)·Tx(a_i)·Rx(alpha_i), q in rad.
inline Eigen::Matrix4d dh_forward(const std::vector<DhRow>& rows, const Eigen::VectorXd& q) {
  Eigen::Matrix4d t;
  t << 0, -1, 0, 0, 0, 0, -1, 0, 1, 0, 0, 0, 0, 0, 0, 1;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const double th = q[static_cast<Eigen::Index>(i)] + rows[i].offset_deg * kDeg;
    const double al = rows[i].alpha_deg * kDeg;
    Eigen::Matrix4d m;
    m << std::cos(th), -std::sin(th) * std::cos(al), std::sin(th) * std::sin(al),
        rows[i].a * std::cos(th), std::sin(th), std::cos(th) * std::cos(al),
        -std::cos(th) * std::sin(al), rows[i].a * std::sin(th), 0, std::sin(al), std::cos(al),
        rows[i].d, 0, 0, 0, 1;
    t = t * m;
  }
  return t;
}

inline const std::vector<DhRow> kLeftArmV1 = {
    {0.032, 0, 90, 0},     {0, -0.0055, 90, -90}, {0.0233647, -0.1433, -90, 105},
    {0, 0.10774, -90, 90}, {0, 0, 90, -90},       {0.015, 0.15228, -90, 75},
    {-0.015, 0, 90, 0},    {0, 0.1373, 90, -90},  {0, 0, 90, 90},
    {0.0625, -0.016, 0, 0}};
inline const std::vector<DhRow> kRightArmV1 = {
    {0.032, 0, 90, 0},      {0, -0.0055, 90, -90}, {-0.0233647, -0.1433, 90, -105},
    {0, -0.10774, 90, -90}, {0, 0, -90, -90},      {-0.015, -0.15228, -90, -105},
    {0.015, 0, 90, 0},      {0, -0.1373, 90, -90}, {0, 0, 90, 90},
    {0.0625, 0.016, 0, 180}};
inline const std::vector<DhRow> kLeftEyeV1 = {
    {0.032, 0, 90, 0},   {0, -0.0055, 90, -90}, {0.00231, -0.1933, -90, -90},
    {0.033, 0, 90, 90},  {0, 0.001, -90, -90},  {-0.054, 0.0825, -90, 90},
    {0, -0.034, -90, 0}, {0, 0, 90, -90}};
inline const std::vector<DhRow> kRightEyeV1 = {
    {0.032, 0, 90, 0},  {0, -0.0055, 90, -90}, {0.00231, -0.1933, -90, -90},
    {0.033, 0, 90, 90}, {0, 0.001, -90, -90},  {-0.054, 0.0825, -90, 90},
    {0, 0.034, -90, 0}, {0, 0, 90, -90}};

inline Eigen::Isometry3d random_pose(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(0.1 * u(rng), 0.1 * u(rng), 0.1 * u(rng));
  t.linear() = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
  return t;
}

/// A random tree of `n` links: revolute, prismatic and fixed joints with random pre, post,
/// offset and axis; some links massless, some with shapes; every child after its parent.
inline RobotModel random_tree(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Link> links(static_cast<std::size_t>(n));
  std::vector<Joint> joints;
  int dofs = 0;
  for (int i = 0; i < n; ++i) {
    Link& link = links[static_cast<std::size_t>(i)];
    link.name = fmt::format("link{}", i);
    if (u(rng) > -0.5) {
      link.inertial.mass = 0.1 + u(rng) * 0.05;
      link.inertial.com = Eigen::Vector3d(0.05 * u(rng), 0.05 * u(rng), 0.05 * u(rng));
      const Eigen::Matrix3d r = random_pose(rng).linear();
      link.inertial.inertia = r * Eigen::Vector3d(2e-4, 3e-4, 4e-4).asDiagonal() * r.transpose();
      Geometry g;
      g.type = i % 3 == 0 ? GeometryType::Capsule : GeometryType::Box;
      g.radius = 0.02;
      g.length = 0.05;
      g.size = Eigen::Vector3d(0.03, 0.04, 0.05);
      g.origin = random_pose(rng);
      link.collision.push_back(g);
    }
    if (i == 0) continue;
    Joint j;
    j.name = fmt::format("joint{}", i);
    j.parent_link = std::uniform_int_distribution<int>(0, i - 1)(rng);
    j.child_link = i;
    const int kind = std::uniform_int_distribution<int>(0, 5)(rng);
    j.type = kind == 0 ? JointType::Fixed : kind == 1 ? JointType::Prismatic : JointType::Revolute;
    j.pre = random_pose(rng);
    j.post = u(rng) > 0 ? random_pose(rng) : Eigen::Isometry3d::Identity();
    j.axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    if (j.type != JointType::Fixed) {
      j.offset = u(rng);
      j.lower = -1.0 + 0.5 * u(rng);
      j.upper = 1.0 + 0.5 * u(rng);
      j.dof = dofs++;
    }
    link.parent_joint = static_cast<int>(joints.size());
    link.parent_link = j.parent_link;
    joints.push_back(j);
  }
  return RobotModel("random_tree", std::move(links), std::move(joints), {}, {}, {}, {});
}

inline Eigen::VectorXd random_posture(const RobotModel& model, std::mt19937& rng) {
  Eigen::VectorXd q(model.num_dofs());
  for (int d = 0; d < model.num_dofs(); ++d)
    q[d] = std::uniform_real_distribution<double>(std::max(model.lower_limits()[d], -3.0),
                                                  std::min(model.upper_limits()[d], 3.0))(rng);
  return q;
}

}  // namespace somasim::robot::test
