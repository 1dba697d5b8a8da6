// object_thrower's presented geometry: how a cylinder's axis lies relative to the skin part
// (cylinder_axis), and how far the object's path keeps from the links it is not aimed at
// (path_clearance), checked against the spawn requests on generated parts and on the real
// left forearm.
#include <cmath>
#include <limits>
#include <random>

#include "object_thrower_test_support.hpp"
#include "somasim/robot/clearance.hpp"

using namespace object_thrower_test;
using somasim::LinkPoses;

namespace {

// A strip of taxels along `long_axis` (9 taxels 1.5 cm apart, two rows 1 cm apart across it),
// all facing `normal` (perpendicular to long_axis).
SkinPart strip(const Eigen::Vector3d& long_axis, const Eigen::Vector3d& normal) {
  SkinPart p = forearm();
  p.taxel_ids.clear();
  p.positions.clear();
  p.normals.clear();
  const Eigen::Vector3d across = normal.cross(long_axis);
  for (int k = 0; k < 18; ++k) {
    p.taxel_ids.push_back(k);
    p.positions.push_back(Eigen::Vector3d(0.1, -0.2, 0.3) + 0.015 * (k / 2) * long_axis +
                          0.01 * (k % 2) * across);
    p.normals.push_back(normal);
  }
  p.positions_link = p.positions;
  p.normals_link = p.normals;
  return p;
}

// The local z axes (cylinder axes) of the cylinders a run of `axis_mode` presents to `part`.
std::vector<Eigen::Vector3d> cylinder_axes(const SkinPart& part, const std::string& axis_mode) {
  Harness h(
      thrower("shapes: cylinder, size: 0.02, cylinder_half_height: 0.05, approaches: 6, "
              "pause: 0, speed_min: 1, speed_max: 1, cylinder_axis: " +
              axis_mode));
  feed_world(h);
  h.input<SkinTaxels>("taxels").parts = {part};
  std::vector<Eigen::Vector3d> axes;
  for (const auto& s : all_spawns(h, false)) axes.push_back(s.pose.linear().col(2));
  return axes;
}

}  // namespace

TEST(ObjectThrowerGeometry, CylinderAxisLiesAcrossOrAlongThePart) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> gauss;
  for (int trial = 0; trial < 8; ++trial) {
    const Eigen::Vector3d normal = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const Eigen::Vector3d long_axis =
        normal.cross(Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng))).normalized();
    const SkinPart part = strip(long_axis, normal);
    const auto across = cylinder_axes(part, "across_part");
    const auto along = cylinder_axes(part, "along_part");
    const auto any = cylinder_axes(part, "any");
    ASSERT_EQ(across.size(), 6u);
    ASSERT_EQ(along.size(), 6u);
    ASSERT_EQ(any.size(), 6u);
    for (std::size_t i = 0; i < across.size(); ++i) {
      SCOPED_TRACE(::testing::Message() << "trial " << trial << ", object " << i);
      EXPECT_NEAR(across[i].norm(), 1.0, 1e-9);
      EXPECT_NEAR(across[i].dot(long_axis), 0.0, 1e-6);  // spans the part's width
      EXPECT_NEAR(across[i].dot(normal), 0.0, 1e-9);     // its round side faces the taxel
      EXPECT_NEAR(std::abs(along[i].dot(long_axis)), 1.0, 1e-6);
      EXPECT_NEAR(any[i].dot(normal), 0.0, 1e-9);
      // `any` keeps the direction fixed by the normal alone.
      EXPECT_LT((any[i] - normal.unitOrthogonal()).norm(), 1e-9);
    }
  }
}

TEST(ObjectThrowerGeometry, CylinderAxisNeedsAKnownChoice) {
  const std::string msg = error_of(thrower("shapes: cylinder, cylinder_axis: sideways"));
  EXPECT_NE(msg.find("cylinder_axis"), std::string::npos) << msg;
  EXPECT_NE(msg.find("across_part"), std::string::npos) << msg;
}

namespace {

// The real left forearm, the arms raised in front (the visual configs' posture): three taxels
// round it, 7 cm from the elbow.
struct ArmScene {
  std::shared_ptr<const somasim::robot::RobotModel> model =
      somasim::robot::load_robot_model_shared(kRobot);
  somasim::robot::RobotData data{*model};
  SkinPart part = forearm();
  int forearm_link = model->link_index("l_forearm");

  ArmScene() {
    Eigen::VectorXd q = Eigen::VectorXd::Zero(model->num_dofs());
    const std::pair<const char*, double> posture[] = {{"l_shoulder_pitch", -60},
                                                      {"l_shoulder_roll", 40},
                                                      {"l_shoulder_yaw", 45},
                                                      {"l_elbow", 55},
                                                      {"l_wrist_prosup", -45}};
    for (const auto& [joint, deg] : posture) q[model->dof_index(joint)] = deg * M_PI / 180;
    somasim::robot::forward_kinematics(*model, data, q);
    part = forearm_ring(data.link_poses[std::size_t(forearm_link)], {0.0, 120.0, 240.0});
  }

  // The least distance [m] between a sphere of `radius` moved from `start` to `end` and the
  // collision shapes of every link but the forearm (sampled every 1 mm).
  double path_clearance(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                        double radius) const {
    double least = std::numeric_limits<double>::infinity();
    const int samples = std::max(1, int(std::ceil((end - start).norm() / 0.001)));
    for (int i = 0; i <= samples; ++i) {
      const Eigen::Vector3d p = start + (end - start) * (double(i) / samples);
      for (int l = 0; l < model->num_links(); ++l) {
        if (l == forearm_link) continue;
        const Eigen::Vector3d local = data.link_poses[std::size_t(l)].inverse() * p;
        for (const auto& shape : model->links()[std::size_t(l)].collision)
          least = std::min(least, somasim::robot::distance_to_shape(shape, local) - radius);
      }
    }
    return least;
  }

  // The least clearance over every approach of a run of `clearance` [m], and how many
  // presentations fell back to the least clearance.
  std::pair<double, int> least_clearance(double clearance) const {
    constexpr double kRadius = 0.02;
    Harness h(
        thrower("shapes: sphere, size: 0.02, cone_deg: 45, distance_min: 0.15, "
                "distance_max: 0.2, approaches: 30, pause: 0, speed_min: 1, speed_max: 1, "
                "path_clearance: " +
                    std::to_string(clearance),
                "link_poses: harness.poses"));
    feed_world(h);
    h.input<SkinTaxels>("taxels").parts = {part};
    h.input<LinkPoses>("poses").poses = data.link_poses;
    double least = std::numeric_limits<double>::infinity();
    const auto spawns = all_spawns(h, false);
    EXPECT_EQ(spawns.size(), 30u);
    for (const auto& s : spawns) {
      // The path ends at the aimed taxel's target (one radius above it): the taxel whose
      // target lies on the line of flight.
      const Eigen::Vector3d start = s.pose.translation();
      const Eigen::Vector3d dir = s.linear_velocity.normalized();
      double best = std::numeric_limits<double>::infinity();
      Eigen::Vector3d end = start;
      for (std::size_t k = 0; k < part.positions.size(); ++k) {
        const Eigen::Vector3d target = part.positions[k] + kRadius * part.normals[k];
        const double off = ((target - start) - (target - start).dot(dir) * dir).norm();
        if (off < best) best = off, end = target;
      }
      EXPECT_LT(best, 1e-6);
      least = std::min(least, path_clearance(start, end, kRadius));
    }
    const auto reduced = h.metric("t", "presentations_reduced_clearance");
    return {least, reduced.is_null() ? 0 : reduced.get<int>()};
  }
};

}  // namespace

TEST(ObjectThrowerGeometry, PathsKeepTheirClearanceFromTheOtherLinks) {
  const ArmScene scene;
  // A wide clearance is kept over every path; the default one lets paths come closer than it,
  // so the check below can tell the two apart.
  EXPECT_LT(scene.least_clearance(0.005).first, 0.04);
  const auto [least, reduced] = scene.least_clearance(0.04);
  EXPECT_GE(least, 0.04 - 0.002);
  EXPECT_EQ(reduced, 0);
}

// A clearance no path can keep (15 cm beside the hand and the upper arm): every presentation
// is drawn again with the least one (5 mm) and counted, rather than stopping the run.
TEST(ObjectThrowerGeometry, AClearanceNoPathKeepsFallsBackToTheLeastOne) {
  const ArmScene scene;
  const auto [least, reduced] = scene.least_clearance(0.15);
  EXPECT_EQ(reduced, 30);
  EXPECT_GE(least, 0.005 - 0.002);
}
