// object_thrower's presented geometry: how a cylinder's axis lies relative to the skin part
// (cylinder_axis), and how far the object's path keeps from the links it is not aimed at
// (path_clearance) and from the aimed link's shapes beside the skin, checked against the spawn
// requests on generated parts, the real left forearm and the real right palm.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "object_thrower_test_support.hpp"
#include "skin_link_shapes.hpp"
#include "somasim/robot/clearance.hpp"
#include "somasim/robot/shape_distance.hpp"

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

// Where a presented object's path ends: one `radius` above the taxel of `part` whose target
// lies on its line of flight (within 1 µm).
Eigen::Vector3d aimed_path_end(const somasim::ObjectSpawn& spawn, const SkinPart& part,
                               double radius) {
  const Eigen::Vector3d start = spawn.pose.translation();
  const Eigen::Vector3d dir = spawn.linear_velocity.normalized();
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector3d end = start;
  for (std::size_t k = 0; k < part.positions.size(); ++k) {
    const Eigen::Vector3d target = part.positions[k] + radius * part.normals[k];
    const double off = ((target - start) - (target - start).dot(dir) * dir).norm();
    if (off < best) best = off, end = target;
  }
  EXPECT_LT(best, 1e-6);
  return end;
}

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
      least = std::min(
          least, path_clearance(s.pose.translation(), aimed_path_end(s, part, kRadius), kRadius));
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

namespace {

// The real right palm, the arm raised in front: a grid of taxels over the palm's face of the
// hand's box (its link frame: z = 0, normal +z), the thumb standing 3.5 cm above it at one side.
struct PalmScene {
  std::shared_ptr<const somasim::robot::RobotModel> model =
      somasim::robot::load_robot_model_shared(kRobot);
  somasim::robot::RobotData data{*model};
  int hand_link = model->link_index("r_hand");
  SkinPart part;

  PalmScene() {
    Eigen::VectorXd q = Eigen::VectorXd::Zero(model->num_dofs());
    const std::pair<const char*, double> posture[] = {{"r_shoulder_pitch", -60},
                                                      {"r_shoulder_roll", 40},
                                                      {"r_shoulder_yaw", 45},
                                                      {"r_elbow", 55},
                                                      {"r_wrist_prosup", -45}};
    for (const auto& [joint, deg] : posture) q[model->dof_index(joint)] = deg * M_PI / 180;
    somasim::robot::forward_kinematics(*model, data, q);
    const Eigen::Isometry3d& hand = data.link_poses[std::size_t(hand_link)];
    part.name = "right_palm";
    part.link = "r_hand";
    for (int i = 0; i < 7; ++i)
      for (int j = 0; j < 7; ++j) {
        part.taxel_ids.push_back(7 * i + j);
        part.positions_link.push_back(Eigen::Vector3d(-0.058 + 0.01 * i, -0.027 + 0.009 * j, 0));
        part.normals_link.push_back(Eigen::Vector3d::UnitZ());
        part.positions.push_back(hand * part.positions_link.back());
        part.normals.push_back(hand.linear() * Eigen::Vector3d::UnitZ());
      }
  }

  // The least surface distance [m] between `object` moved from `start` to `end` (turned by
  // `rotation`) and the hand's thumb and fingers (every shape of the hand but its box), every
  // 1 mm.
  double beside_skin_distance(const somasim::robot::Geometry& object,
                              const Eigen::Matrix3d& rotation, const Eigen::Vector3d& start,
                              const Eigen::Vector3d& end) const {
    const auto& shapes = model->links()[std::size_t(hand_link)].collision;
    double least = std::numeric_limits<double>::infinity();
    const int samples = std::max(1, int(std::ceil((end - start).norm() / 0.001)));
    for (int i = 0; i <= samples; ++i) {
      somasim::robot::Geometry placed = object;
      placed.origin = Eigen::Isometry3d::Identity();
      placed.origin.translate(start + (end - start) * (double(i) / samples));
      placed.origin.rotate(rotation);
      const Eigen::Isometry3d& hand = data.link_poses[std::size_t(hand_link)];
      for (std::size_t s = 1; s < shapes.size(); ++s) {  // shape 0: the palm's box
        // Far from the shape (by its distance from the object's centre less the object's
        // half diagonal) the exact distance is not needed.
        const double far = somasim::robot::distance_to_shape(
                               shapes[s], hand.inverse() * placed.origin.translation()) -
                           std::hypot(object.radius, 0.5 * object.length);
        least = std::min(least, far > 0.01
                                    ? far
                                    : somasim::robot::shape_distance(
                                          placed, Eigen::Isometry3d::Identity(), shapes[s], hand));
      }
    }
    return least;
  }

  // Every object the thrower of `h` presents to this palm (the arm held still).
  std::vector<somasim::ObjectSpawn> present(Harness& h) const {
    feed_world(h);
    h.input<SkinTaxels>("taxels").parts = {part};
    h.input<LinkPoses>("poses").poses = data.link_poses;
    return all_spawns(h, false);
  }

  // The least surface distance [m] between a presented cylinder (`spawn`, of `radius` and
  // `half_height`) and the thumb and fingers along its path.
  double spawn_beside_skin_distance(const somasim::ObjectSpawn& spawn, double radius,
                                    double half_height) const {
    const auto object = somasim::robot::object_geometry(somasim::ObjectShape::kCylinder,
                                                        Eigen::Vector3d(radius, half_height, 0));
    EXPECT_TRUE(object);
    return object ? beside_skin_distance(*object, spawn.pose.linear(), spawn.pose.translation(),
                                         aimed_path_end(spawn, part, radius))
                  : 0.0;
  }
};

}  // namespace

// A cylinder wider than the palm aimed near the thumb would meet the thumb (the palm's own link,
// beside its skin) before the skin: such paths are given up, every presented one reaches the
// skin first, and the paths given up are counted.
TEST(ObjectThrowerGeometry, ObjectsWiderThanThePalmReachItsSkinBeforeTheThumb) {
  const PalmScene scene;
  constexpr double kRadius = 0.06, kHalfHeight = 0.05;
  Harness h(
      thrower("parts: right_palm, shapes: cylinder, size: 0.06, cylinder_half_height: 0.05, "
              "cylinder_axis: across_part, cone_deg: 45, distance_min: 0.15, distance_max: 0.2, "
              "approaches: 24, pause: 0, speed_min: 1, speed_max: 1",
              "link_poses: harness.poses"));
  const auto spawns = scene.present(h);
  ASSERT_EQ(spawns.size(), 24u);
  for (const auto& s : spawns)
    EXPECT_GE(scene.spawn_beside_skin_distance(s, kRadius, kHalfHeight), 0.002 - 1e-4);
  EXPECT_GT(h.metric("t", "paths_met_beside_skin").get<int>(), 0);
}

// A cylinder wider than the palm, its axis fixed by the normal (cylinder_axis any), lies across
// the thumb at some taxels: where no taxel drawn can be reached first as it is presented, the
// taxels are drawn again with the cylinder turned about the aimed normal. Every presentation is
// placed (none stops the run), each reaches the skin before the thumb, and exactly the turned
// ones are counted.
TEST(ObjectThrowerGeometry, AnObjectNoPathBringsToTheSkinAsPresentedIsTurnedAboutTheNormal) {
  const PalmScene scene;
  constexpr double kRadius = 0.06, kHalfHeight = 0.05;
  Harness h(thrower(
      "parts: right_palm, shapes: cylinder, size: 0.06, cylinder_half_height: 0.05, "
      "cylinder_axis: any, cone_deg: 30, distance_min: 0.2, distance_max: 0.3, approaches: 24, "
      "pause: 0, speed_min: 1, speed_max: 1",
      "link_poses: harness.poses"));
  const auto spawns = scene.present(h);
  ASSERT_EQ(spawns.size(), 24u);
  const Eigen::Vector3d normal = scene.part.normals.front();  // one normal over the flat palm
  const Eigen::Vector3d as_presented = normal.unitOrthogonal();
  int turned = 0;
  for (const auto& s : spawns) {
    const Eigen::Matrix3d r = s.pose.linear();
    EXPECT_LT((r.col(0) - normal).norm(), 1e-9);  // its round side still faces the skin
    if (std::abs(r.col(2).dot(as_presented)) < 1.0 - 1e-9) ++turned;
    EXPECT_GE(scene.spawn_beside_skin_distance(s, kRadius, kHalfHeight), 0.002 - 1e-4);
  }
  EXPECT_GT(turned, 0);
  EXPECT_EQ(h.metric("t", "presentations_turned").get<int>(), turned);
}

// Links of 2-5 generated primitives apart from one another, taxels on the surface of one of
// them: that one is the skin's own shape and every other is beside the skin.
TEST(ObjectThrowerGeometry, TheSkinsOwnShapeIsTheOneItsTaxelsLieOn) {
  using somasim::robot::Geometry;
  using somasim::robot::GeometryType;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> extent(0.01, 0.04), unit(-1.0, 1.0);
  std::normal_distribution<double> gauss;
  for (int trial = 0; trial < 40; ++trial) {
    const int count = 2 + trial % 4;
    std::vector<Geometry> shapes(static_cast<std::size_t>(count));
    for (int s = 0; s < count; ++s) {
      Geometry& g = shapes[std::size_t(s)];
      g.origin.translation() = Eigen::Vector3d(0.15 * s, 0.0, 0.0);
      if ((s + trial) % 2) {
        g.type = GeometryType::Sphere;
        g.radius = extent(rng);
      } else {
        g.type = GeometryType::Box;
        g.size = Eigen::Vector3d(extent(rng), extent(rng), extent(rng)) * 2.0;
      }
    }
    const int own = trial % count;
    const Geometry& g = shapes[std::size_t(own)];
    std::vector<Eigen::Vector3d> taxels;
    for (int k = 0; k < 12; ++k) {
      Eigen::Vector3d local;
      if (g.type == GeometryType::Sphere) {
        local = g.radius * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
      } else {  // a point on one of the box's faces
        local = 0.5 * g.size.cwiseProduct(Eigen::Vector3d(unit(rng), unit(rng), unit(rng)));
        const int axis = k % 3;
        local[axis] = (k % 2 ? 0.5 : -0.5) * g.size[axis];
      }
      taxels.push_back(g.origin * local);
    }
    const auto beside = somasim::plugins::shapes_beside_skin(shapes, taxels);
    ASSERT_EQ(beside.size(), std::size_t(count - 1)) << "trial " << trial;
    for (const Geometry& b : beside)
      EXPECT_FALSE(b.origin.translation().isApprox(g.origin.translation())) << "trial " << trial;
  }
  // One shape, or no taxel: nothing beside the skin.
  EXPECT_TRUE(
      somasim::plugins::shapes_beside_skin({Geometry{}}, {Eigen::Vector3d::Zero()}).empty());
  EXPECT_TRUE(somasim::plugins::shapes_beside_skin({Geometry{}, Geometry{}}, {}).empty());
}
