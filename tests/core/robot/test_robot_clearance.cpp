// point_clear_of_robot: points inside or next to the robot are not clear; far points are.
// distance_to_shape against sampled surfaces; segment_clear_of_robot with an ignored link;
// object_path_clear_of_shapes against closed forms and a dense search.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "robot_test_support.hpp"
#include "somasim/robot/clearance.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/shape_distance.hpp"

using namespace somasim::robot;
using somasim::ObjectShape;
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

// object_geometry turns an ObjectSpawn's size into the primitive's own dimensions.
TEST(RobotClearance, ObjectGeometryHasTheSpawnsDimensions) {
  const auto sphere = object_geometry(ObjectShape::kSphere, Eigen::Vector3d(0.03, 0, 0));
  ASSERT_TRUE(sphere);
  EXPECT_EQ(sphere->type, GeometryType::Sphere);
  EXPECT_DOUBLE_EQ(sphere->radius, 0.03);
  const auto box = object_geometry(ObjectShape::kBox, Eigen::Vector3d(0.01, 0.02, 0.03));
  ASSERT_TRUE(box);
  EXPECT_TRUE(box->size.isApprox(Eigen::Vector3d(0.02, 0.04, 0.06)));
  const auto cylinder = object_geometry(ObjectShape::kCylinder, Eigen::Vector3d(0.06, 0.05, 0));
  ASSERT_TRUE(cylinder);
  EXPECT_DOUBLE_EQ(cylinder->radius, 0.06);
  EXPECT_DOUBLE_EQ(cylinder->length, 0.10);
  EXPECT_FALSE(object_geometry(ObjectShape::kMesh, Eigen::Vector3d::Ones()));
}

namespace {

Eigen::Isometry3d random_pose(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  std::normal_distribution<double> gauss;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translate(Eigen::Vector3d(u(rng), u(rng), u(rng)));
  pose.rotate(Eigen::Quaterniond(gauss(rng), gauss(rng), gauss(rng), gauss(rng)).normalized());
  return pose;
}

// A point `distance` [m] from a uniformly drawn point of the segment from -> to, in a uniformly
// drawn direction.
Eigen::Vector3d beside_segment(std::mt19937_64& rng, const Eigen::Vector3d& from,
                               const Eigen::Vector3d& to, double distance) {
  std::normal_distribution<double> gauss;
  const double along = std::uniform_real_distribution<double>(0, 1)(rng);
  Eigen::Vector3d direction;
  for (int k = 0; k < 3; ++k) direction[k] = gauss(rng);
  return from + along * (to - from) + distance * direction.normalized();
}

}  // namespace

// A ball moved past a ball fixed to a link: clear exactly when the closed-form least distance
// between the two surfaces exceeds the clearance (generated paths on both sides of it).
TEST(RobotClearance, AnObjectPathPastABallIsClearExactlyWhenItsLeastDistanceIs) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-0.15, 0.15), radius(0.005, 0.05);
  std::normal_distribution<double> gauss;
  int clear = 0, blocked = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Isometry3d link = random_pose(rng);
    Geometry ball;
    ball.type = GeometryType::Sphere;
    ball.radius = radius(rng);
    const Geometry object =
        *object_geometry(ObjectShape::kSphere, Eigen::Vector3d(radius(rng), 0, 0));
    const Eigen::Vector3d from(u(rng), u(rng), u(rng)), to(u(rng), u(rng), u(rng));
    // The ball beside a point of the path, about as far from it as the two radii.
    const double distance = ball.radius + object.radius + 0.01 * gauss(rng);
    ball.origin.translation() = link.inverse() * beside_segment(rng, from, to, distance);
    const double clearance = 0.003;
    const Eigen::Vector3d c = link * ball.origin.translation();
    const double t = std::clamp((c - from).dot(to - from) / (to - from).squaredNorm(), 0.0, 1.0);
    const double least = (from + t * (to - from) - c).norm() - ball.radius - object.radius;
    if (std::abs(least - clearance) < 2e-4) continue;  // within the sampling's reach
    const std::vector<Geometry> shapes{ball};
    const bool is_clear = object_path_clear_of_shapes(object, Eigen::Matrix3d::Identity(), from, to,
                                                      shapes, link, clearance);
    EXPECT_EQ(is_clear, least > clearance) << "trial " << trial << ": least " << least;
    (is_clear ? clear : blocked) += 1;
  }
  EXPECT_GT(clear, 50);
  EXPECT_GT(blocked, 50);
}

// A turned cylinder moved past boxes and cylinders: the same decision as evaluating every
// 0.5 mm of the path (the skipped samples and the bounding test change nothing).
TEST(RobotClearance, AnObjectPathPastShapesDecidesAsADenseSearchWould) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> u(-0.06, 0.06), extent(0.01, 0.04);
  std::normal_distribution<double> gauss;
  int clear = 0, blocked = 0;
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::Isometry3d link = random_pose(rng);
    Geometry shape;
    shape.origin = random_pose(rng);
    if (trial % 2) {
      shape.type = GeometryType::Box;
      shape.size = Eigen::Vector3d(extent(rng), extent(rng), extent(rng));
    } else {
      shape.type = GeometryType::Cylinder;
      shape.radius = 0.5 * extent(rng);
      shape.length = 2.0 * extent(rng);
    }
    const Geometry object =
        *object_geometry(ObjectShape::kCylinder, Eigen::Vector3d(extent(rng), extent(rng), 0));
    const Eigen::Matrix3d rotation =
        Eigen::Quaterniond(gauss(rng), gauss(rng), gauss(rng), gauss(rng))
            .normalized()
            .toRotationMatrix();
    const Eigen::Vector3d from(u(rng), u(rng), u(rng)), to(u(rng), u(rng), u(rng));
    // The shape beside a point of the path, about as far from it as the two sizes.
    const double distance = 0.05 + 0.02 * gauss(rng);
    shape.origin.translation() = link.inverse() * beside_segment(rng, from, to, distance);
    const double clearance = 0.004;
    double least = std::numeric_limits<double>::infinity();
    const int samples = static_cast<int>(std::ceil((to - from).norm() / 0.0005));
    for (int i = 0; i <= samples; ++i) {
      Geometry placed = object;
      placed.origin = Eigen::Isometry3d::Identity();
      placed.origin.translate(from + (to - from) * (double(i) / samples));
      placed.origin.rotate(rotation);
      least = std::min(least, shape_distance(placed, Eigen::Isometry3d::Identity(), shape, link));
    }
    if (std::abs(least - clearance) < 5e-4) continue;
    const std::vector<Geometry> shapes{shape};
    const bool is_clear =
        object_path_clear_of_shapes(object, rotation, from, to, shapes, link, clearance);
    EXPECT_EQ(is_clear, least > clearance) << "trial " << trial << ": least " << least;
    (is_clear ? clear : blocked) += 1;
  }
  EXPECT_GT(clear, 10);
  EXPECT_GT(blocked, 10);
}
