// assets/robots/icub_v1_full_skin.yaml: the whole-arm and torso skin of the PPS scale
// experiment has at least 4,000 taxels, and every taxel lies on its link's collision surface
// with its normal pointing out of the link.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/skin/skin_layout.hpp"

namespace {

using somasim::robot::Geometry;
using somasim::robot::GeometryType;

const std::string kFullSkin = SOMASIM_SOURCE_DIR "/assets/robots/icub_v1_full_skin.yaml";

// Distance [m] from `p` (link frame) to the boundary of a box or capped cylinder (inside or
// outside); +inf for other shapes (the skin links have none).
double distance_to_boundary(const Geometry& g, const Eigen::Vector3d& p_link) {
  const Eigen::Vector3d p = g.origin.inverse() * p_link;
  Eigen::Vector3d q, half;  // |coordinates| and half extents of the shape's box-like profile
  if (g.type == GeometryType::Box) {
    q = p.cwiseAbs();
    half = 0.5 * g.size;
  } else if (g.type == GeometryType::Cylinder) {
    q = Eigen::Vector3d(std::hypot(p.x(), p.y()), std::abs(p.z()), 0.0);
    half = Eigen::Vector3d(g.radius, 0.5 * g.length, 0.0);
  } else {
    return std::numeric_limits<double>::infinity();
  }
  const Eigen::Vector3d out = (q - half).cwiseMax(0.0);
  if (out.squaredNorm() > 0) return out.norm();
  const Eigen::Vector3d in = half - q;
  return g.type == GeometryType::Box ? in.minCoeff() : std::min(in.x(), in.y());
}

// Is `p` (link frame) inside any collision shape of the link?
bool inside_any(const std::vector<Geometry>& shapes, const Eigen::Vector3d& p_link) {
  for (const Geometry& g : shapes) {
    const Eigen::Vector3d p = g.origin.inverse() * p_link;
    if (g.type == GeometryType::Box && ((p.cwiseAbs() - 0.5 * g.size).array() < 0).all())
      return true;
    if (g.type == GeometryType::Cylinder && std::hypot(p.x(), p.y()) < g.radius &&
        std::abs(p.z()) < 0.5 * g.length)
      return true;
  }
  return false;
}

TEST(FullSkin, BothArmsAndTheTorsoCarryAtLeast4000Taxels) {
  const auto model = somasim::robot::load_robot_model(kFullSkin);
  EXPECT_EQ(model.name(), "icub_v1_full_skin");
  const std::map<std::string, std::string> expected = {{"left_upper_arm", "l_upper_arm"},
                                                       {"right_upper_arm", "r_upper_arm"},
                                                       {"left_forearm", "l_forearm"},
                                                       {"right_forearm", "r_forearm"},
                                                       {"left_palm", "l_hand"},
                                                       {"right_palm", "r_hand"},
                                                       {"torso", "chest"}};
  std::map<std::string, std::string> found;
  std::size_t physical = 0, virtual_taxels = 0;
  for (const auto& patch : model.skin_patches()) {
    found[patch.body_part] = model.link(patch.link).name;
    const auto layout = somasim::skin::generate_layout(patch);
    EXPECT_GT(layout.size(), 100u) << patch.body_part;
    physical += layout.size();
    virtual_taxels += layout.virtual_taxels.size();
  }
  EXPECT_EQ(found, expected);
  EXPECT_GE(physical, 4000u);
  // Modules of about 10 taxels, like the iCub's triangles.
  EXPECT_NEAR(static_cast<double>(physical) / static_cast<double>(virtual_taxels), 10.0, 1.0);
  // With one module per taxel (as configs/pps_scale.yaml learns) every taxel is a virtual one.
  std::size_t single = 0;
  for (const auto& patch : model.skin_patches())
    single += somasim::skin::generate_layout(patch, {0.0, 1}).virtual_taxels.size();
  EXPECT_EQ(single, physical);
}

TEST(FullSkin, EveryTaxelLiesOnItsLinksCollisionSurfaceFacingOut) {
  const auto model = somasim::robot::load_robot_model(kFullSkin);
  for (const auto& patch : model.skin_patches()) {
    const auto& shapes = model.link(patch.link).collision;
    ASSERT_FALSE(shapes.empty()) << patch.body_part;
    const auto layout = somasim::skin::generate_layout(patch);
    double worst = 0.0;
    int facing_in = 0;
    for (std::size_t i = 0; i < layout.size(); ++i) {
      const Eigen::Vector3d& p = layout.positions[i];
      double d = std::numeric_limits<double>::infinity();
      for (const Geometry& g : shapes) d = std::min(d, distance_to_boundary(g, p));
      worst = std::max(worst, d);
      // 3 mm along the normal leaves the link; 3 mm against it is inside.
      if (inside_any(shapes, p + 0.003 * layout.normals[i]) ||
          !inside_any(shapes, p - 0.003 * layout.normals[i]))
        ++facing_in;
      EXPECT_NEAR(layout.normals[i].norm(), 1.0, 1e-9);
    }
    EXPECT_LE(worst, 0.0015) << patch.body_part;  // cylinders are 1 mm outside the link
    EXPECT_EQ(facing_in, 0) << patch.body_part;
  }
}

TEST(FullSkin, TheTorsoSkinFacesForwardAndLeftAndRightPartsAreMirrorImages) {
  const auto model = somasim::robot::load_robot_model(kFullSkin);
  somasim::robot::RobotData data(model);
  somasim::robot::forward_kinematics(model, data, Eigen::VectorXd::Zero(model.num_dofs()));
  std::map<std::string, Eigen::Vector3d> mean_normal, mean_position;
  for (const auto& patch : model.skin_patches()) {
    const auto layout = somasim::skin::generate_layout(patch);
    const Eigen::Isometry3d& pose = data.link_poses[static_cast<std::size_t>(patch.link)];
    Eigen::Vector3d n = Eigen::Vector3d::Zero(), p = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < layout.size(); ++i) {
      n += pose.linear() * layout.normals[i];
      p += pose * layout.positions[i];
    }
    mean_normal[patch.body_part] = n / static_cast<double>(layout.size());
    mean_position[patch.body_part] = p / static_cast<double>(layout.size());
  }
  // Root frame: x backward, y to the robot's right, z up. The chest front faces -x.
  EXPECT_NEAR(mean_normal["torso"].x(), -1.0, 1e-9);
  // Left parts are mirror images of the right ones (y -> -y) at q = 0.
  for (const std::string part : {"upper_arm", "forearm", "palm"}) {
    const Eigen::Vector3d l = mean_position["left_" + part], r = mean_position["right_" + part];
    EXPECT_NEAR(l.y(), -r.y(), 2e-3) << part;
    EXPECT_NEAR(l.x(), r.x(), 2e-3) << part;
    EXPECT_NEAR(l.z(), r.z(), 2e-3) << part;
    const Eigen::Vector3d nl = mean_normal["left_" + part], nr = mean_normal["right_" + part];
    EXPECT_NEAR(nl.y(), -nr.y(), 1e-6) << part;
    EXPECT_NEAR(nl.x(), nr.x(), 1e-6) << part;
  }
}

}  // namespace
