// point_clear_of_robot: points inside or next to the robot are not clear; far points are.
// distance_to_shape against sampled surfaces; segment_clear_of_robot with an ignored link.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "robot_test_support.hpp"
#include "somasim/robot/clearance.hpp"
#include "somasim/robot/kinematics.hpp"

using namespace somasim::robot;
using somasim::robot::test::load_icub;

namespace {
std::vector<Eigen::Isometry3d> rest_poses(const RobotModel& model) {
  RobotData data(model);
  forward_kinematics(model, data, Eigen::VectorXd::Zero(model.num_dofs()));
  return data.link_poses;
}
}  // namespace

TEST(RobotClearance, InsideTheHeadOrNextToTheForearmIsNotClear) {
  const RobotModel model = load_icub();
  const auto poses = rest_poses(model);
  const auto head = static_cast<std::size_t>(model.link_index("head"));
  // The head is a sphere of radius 0.055 m centred at (0.0628, 0.0108, 0) in its link frame.
  EXPECT_FALSE(
      point_clear_of_robot(model, poses, poses[head] * Eigen::Vector3d(0.06, 0.01, 0.0), 0.0));
  const auto forearm = static_cast<std::size_t>(model.link_index("l_forearm"));
  const Eigen::Vector3d beside = poses[forearm] * Eigen::Vector3d(0.0, -0.07, 0.03);
  EXPECT_FALSE(point_clear_of_robot(model, poses, beside, 0.01));
}

TEST(RobotClearance, FarAwayIsClearAndMarginsCount) {
  const RobotModel model = load_icub();
  const auto poses = rest_poses(model);
  EXPECT_TRUE(point_clear_of_robot(model, poses, Eigen::Vector3d(-1.0, 0.0, 0.3), 0.05));
  EXPECT_FALSE(point_clear_of_robot(model, poses, Eigen::Vector3d(-1.0, 0.0, 0.3), 1.5));
}

TEST(RobotClearance, WithoutPosesNothingIsTested) {
  const RobotModel model = load_icub();
  EXPECT_TRUE(point_clear_of_robot(model, {}, Eigen::Vector3d::Zero(), 0.1));
}

namespace {

// The primitive's surface sampled densely (in the shape's own frame).
std::vector<Eigen::Vector3d> surface_samples(const Geometry& g) {
  std::vector<Eigen::Vector3d> out;
  const int n = 120;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double u = static_cast<double>(i) / n, v = static_cast<double>(j) / n;
      const double phi = 2 * M_PI * u, theta = M_PI * v;
      switch (g.type) {
        case GeometryType::Sphere:
          out.push_back(g.radius * Eigen::Vector3d(std::sin(theta) * std::cos(phi),
                                                   std::sin(theta) * std::sin(phi),
                                                   std::cos(theta)));
          break;
        case GeometryType::Box:
          for (int axis = 0; axis < 3; ++axis)
            for (const double side : {-0.5, 0.5}) {
              Eigen::Vector3d p;
              p[axis] = side * g.size[axis];
              p[(axis + 1) % 3] = (u - 0.5) * g.size[(axis + 1) % 3];
              p[(axis + 2) % 3] = (v - 0.5) * g.size[(axis + 2) % 3];
              out.push_back(p);
            }
          break;
        case GeometryType::Cylinder:
          out.emplace_back(g.radius * std::cos(phi), g.radius * std::sin(phi),
                           (v - 0.5) * g.length);
          for (const double side : {-0.5, 0.5})
            out.emplace_back(v * g.radius * std::cos(phi), v * g.radius * std::sin(phi),
                             side * g.length);
          break;
        case GeometryType::Capsule:
          out.emplace_back(g.radius * std::cos(phi), g.radius * std::sin(phi),
                           (v - 0.5) * g.length);
          for (const double side : {-1.0, 1.0})
            out.emplace_back(g.radius * std::sin(0.5 * theta) * std::cos(phi),
                             g.radius * std::sin(0.5 * theta) * std::sin(phi),
                             side * (0.5 * g.length + g.radius * std::cos(0.5 * theta)));
          break;
        case GeometryType::Mesh:
          break;
      }
    }
  return out;
}

}  // namespace

// Generated cases: random primitives and points; outside, the distance is the nearest surface
// sample's (within the sampling's resolution); inside, it is negative.
TEST(RobotClearance, DistanceToEveryPrimitiveMatchesItsSampledSurface) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    Geometry g;
    g.type = static_cast<GeometryType>(trial % 4);
    g.radius = 0.01 + 0.04 * u(rng);
    g.length = 0.02 + 0.1 * u(rng);
    g.size = Eigen::Vector3d(0.02 + 0.1 * u(rng), 0.02 + 0.1 * u(rng), 0.02 + 0.1 * u(rng));
    g.origin = Eigen::Translation3d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5) *
               Eigen::AngleAxisd(M_PI * u(rng), Eigen::Vector3d(u(rng), u(rng), 1).normalized());
    const auto surface = surface_samples(g);
    for (int k = 0; k < 20; ++k) {
      const Eigen::Vector3d local(0.3 * (u(rng) - 0.5), 0.3 * (u(rng) - 0.5), 0.3 * (u(rng) - 0.5));
      double nearest = 1e9;
      for (const auto& s : surface) nearest = std::min(nearest, (s - local).norm());
      const double d = distance_to_shape(g, g.origin * local);
      EXPECT_NEAR(std::abs(d), nearest, 0.003)
          << geometry_type_name(g.type) << " at " << local.transpose();
    }
    EXPECT_LT(distance_to_shape(g, g.origin.translation()), 0.0) << "the centre is inside";
  }
  Geometry mesh;
  mesh.type = GeometryType::Mesh;
  EXPECT_TRUE(std::isinf(distance_to_shape(mesh, Eigen::Vector3d::Zero())));
}

TEST(RobotClearance, APathBesideTheForearmIsBlockedUnlessItsLinkIsIgnored) {
  const RobotModel model = load_icub();
  const auto poses = rest_poses(model);
  const auto forearm = model.link_index("l_forearm");
  const auto& pose = poses[static_cast<std::size_t>(forearm)];
  // Through the forearm's middle (its cylinder: r = 0.02 along -y from the wrist to -0.14).
  const Eigen::Vector3d from = pose * Eigen::Vector3d(0.0, -0.07, 0.3);
  const Eigen::Vector3d to = pose * Eigen::Vector3d(0.0, -0.07, -0.3);
  EXPECT_FALSE(segment_clear_of_robot(model, poses, from, to, 0.0));
  const int ignored[] = {forearm};
  // A path that ends 2 mm above the forearm's collision surface: within a 5 mm margin of the
  // forearm, clear of every other link.
  const Eigen::Vector3d above = pose * Eigen::Vector3d(0.0, -0.07, 0.022);
  EXPECT_TRUE(segment_clear_of_robot(model, poses, from, above, 0.005, ignored));
  EXPECT_FALSE(segment_clear_of_robot(model, poses, from, above, 0.005));
  EXPECT_TRUE(segment_clear_of_robot(model, {}, from, to, 0.1)) << "no poses: nothing tested";
}

namespace {
// Every sample of the path evaluated, 2 mm apart as segment_clear_of_robot samples it.
bool every_sample_clear(const RobotModel& model, const std::vector<Eigen::Isometry3d>& poses,
                        const Eigen::Vector3d& from, const Eigen::Vector3d& to, double margin) {
  const int samples = 1 + static_cast<int>(std::ceil((to - from).norm() / 0.002));
  for (int l = 0; l < model.num_links(); ++l) {
    const Eigen::Isometry3d world_to_link = poses[static_cast<std::size_t>(l)].inverse();
    for (const auto& g : model.link(l).collision)
      for (int i = 0; i <= samples; ++i) {
        const Eigen::Vector3d p = from + (to - from) * (static_cast<double>(i) / samples);
        if (distance_to_shape(g, world_to_link * p) <= margin) return false;
      }
  }
  return true;
}
}  // namespace

TEST(RobotClearance, SkippingSamplesByTheirDistanceDecidesAsEverySampleWould) {
  const RobotModel model = load_icub();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), margin(0.0, 0.05);
  // Sized to stay cheap under the sanitizers: the reference evaluates every sample.
  constexpr int kPostures = 5, kPathsPerPosture = 60, kGrazingPaths = 40;
  int blocked = 0, cases = 0, grazing = 0;
  for (int posture = 0; posture < kPostures; ++posture) {
    RobotData data(model);
    Eigen::VectorXd q(model.num_dofs());
    for (int j = 0; j < model.num_dofs(); ++j) {
      const double lower = model.lower_limits()[j], upper = model.upper_limits()[j];
      q[j] = lower + 0.5 * (1.0 + unit(rng)) * (upper - lower);
    }
    forward_kinematics(model, data, q);
    const auto forearm = static_cast<std::size_t>(model.link_index("l_forearm"));
    for (int k = 0; k < kPathsPerPosture; ++k) {
      // Paths around the left forearm, some through it, some beside it, some far.
      const Eigen::Vector3d centre = data.link_poses[forearm].translation();
      const Eigen::Vector3d from = centre + 0.4 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
      const Eigen::Vector3d to = centre + 0.15 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
      const double m = margin(rng);
      const bool expected = every_sample_clear(model, data.link_poses, from, to, m);
      ASSERT_EQ(segment_clear_of_robot(model, data.link_poses, from, to, m), expected)
          << "posture " << posture << " path " << k;
      ++cases;
      blocked += expected ? 0 : 1;
      // Paths that just miss: the margin at which this path becomes blocked, less 0.1 mm.
      if (expected && grazing < kGrazingPaths) {
        double lo = m, hi = m + 0.5;
        if (every_sample_clear(model, data.link_poses, from, to, hi)) continue;
        for (int it = 0; it < 14; ++it) {  // 0.5 m / 2^14 = 0.03 mm
          const double mid = 0.5 * (lo + hi);
          (every_sample_clear(model, data.link_poses, from, to, mid) ? lo : hi) = mid;
        }
        EXPECT_TRUE(segment_clear_of_robot(model, data.link_poses, from, to, lo - 1e-4));
        EXPECT_FALSE(segment_clear_of_robot(model, data.link_poses, from, to, hi + 1e-4));
        ++grazing;
      }
    }
  }
  // Both outcomes were exercised, and paths that graze the robot by a tenth of a millimetre.
  EXPECT_GT(blocked, cases / 5);
  EXPECT_LT(blocked, cases * 4 / 5);
  EXPECT_EQ(grazing, kGrazingPaths);
}
