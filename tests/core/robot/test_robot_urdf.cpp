// URDF robots: generated trees against their own forward kinematics, a YAML overlay that extends
// a URDF, package:// meshes through the resource path, and the bad inputs with their messages.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <random>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "somasim/error.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/robot/urdf_export.hpp"

namespace fs = std::filesystem;
using namespace somasim::robot;

namespace {

class TempDir {
 public:
  TempDir() {
    path_ = fs::temp_directory_path() / fmt::format("somasim_urdf_{}_{}", ::getpid(), counter_++);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path p = path_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p;
  }

 private:
  static inline int counter_ = 0;
  fs::path path_;
};

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const somasim::InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

const char* kInertial =
    R"(<inertial><origin xyz="0 0 0.05"/><mass value="0.5"/>)"
    R"(<inertia ixx="0.001" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0.003"/></inertial>)";

/// A random chain of `n` joints (revolute, continuous or prismatic), with random origins and
/// axes; `expected` gets the tip's pose for joint values `q` computed here, independently.
struct RandomChain {
  std::string urdf;
  std::vector<Eigen::Isometry3d> origins;
  std::vector<Eigen::Vector3d> axes;
  std::vector<bool> prismatic;

  Eigen::Isometry3d tip(const Eigen::VectorXd& q) const {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    for (std::size_t i = 0; i < origins.size(); ++i) {
      t = t * origins[i];
      const double v = q[static_cast<Eigen::Index>(i)];
      if (prismatic[i])
        t.translate(axes[i] * v);
      else
        t.rotate(Eigen::AngleAxisd(v, axes[i]));
    }
    return t;
  }
};

RandomChain random_chain(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  RandomChain c;
  std::string links = "<link name=\"base\"/>", joints;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d xyz(0.2 * u(rng), 0.2 * u(rng), 0.2 * u(rng));
    const Eigen::Vector3d rpy(3 * u(rng), 1.5 * u(rng), 3 * u(rng));
    Eigen::Vector3d axis(u(rng), u(rng), u(rng));
    axis.normalize();
    Eigen::Isometry3d o = Eigen::Isometry3d::Identity();
    o.translation() = xyz;
    o.linear() = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    const int kind = static_cast<int>(rng() % 3);
    const std::string type = kind == 0 ? "revolute" : kind == 1 ? "continuous" : "prismatic";
    c.origins.push_back(o);
    c.axes.push_back(axis);
    c.prismatic.push_back(kind == 2);
    links += fmt::format(R"(<link name="l{}">{}<collision><geometry><sphere radius="0.02"/>)"
                         R"(</geometry></collision></link>)",
                         i, kInertial);
    joints +=
        fmt::format(R"(<joint name="j{}" type="{}"><parent link="{}"/><child link="l{}"/>)"
                    R"(<origin xyz="{:.17g} {:.17g} {:.17g}" rpy="{:.17g} {:.17g} {:.17g}"/>)"
                    R"(<axis xyz="{:.17g} {:.17g} {:.17g}"/>{}</joint>)",
                    i, type, i == 0 ? "base" : fmt::format("l{}", i - 1), i, xyz.x(), xyz.y(),
                    xyz.z(), rpy.x(), rpy.y(), rpy.z(), axis.x(), axis.y(), axis.z(),
                    kind == 1 ? "" : R"(<limit lower="-2" upper="2" effort="1" velocity="1"/>)");
  }
  c.urdf = "<robot name=\"chain\">" + links + joints + "</robot>";
  return c;
}

std::string two_links(const std::string& extra_link, const std::string& joint_extra = "") {
  return fmt::format(
      R"(<?xml version="1.0"?>
<robot name="r">
  <link name="base"/>
  <link name="arm">{}</link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/>
    <child link="arm"/>
    {}
  </joint>
</robot>
)",
      extra_link, joint_extra);
}

}  // namespace

TEST(UrdfImport, GeneratedChainsHaveTheirOwnForwardKinematics) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  TempDir dir;
  for (int trial = 0; trial < 20; ++trial) {
    const RandomChain chain = random_chain(rng, 1 + trial % 7);
    const RobotModel model =
        load_robot_model(dir.write(fmt::format("chain{}.urdf", trial), chain.urdf));
    ASSERT_EQ(model.num_dofs(), static_cast<int>(chain.origins.size()));
    RobotData data(model);
    for (int k = 0; k < 5; ++k) {
      Eigen::VectorXd q(model.num_dofs());
      for (Eigen::Index i = 0; i < q.size(); ++i) q[i] = u(rng);
      forward_kinematics(model, data, q);
      const Eigen::Isometry3d got =
          link_pose(data, model.link_index(fmt::format("l{}", model.num_dofs() - 1)));
      const Eigen::Isometry3d want = chain.tip(q);
      EXPECT_LT((got.matrix() - want.matrix()).cwiseAbs().maxCoeff(), 1e-12)
          << "trial " << trial << ", q = " << q.transpose();
    }
  }
}

TEST(UrdfImport, JointsKeepTheFilesOrderTypesAndLimits) {
  TempDir dir;
  const auto file = dir.write("order.urdf", R"(<robot name="ordered">
  <link name="base"/><link name="a"/><link name="b"/><link name="c"/><link name="d"/>
  <joint name="zeta" type="revolute"><parent link="base"/><child link="a"/>
    <axis xyz="0 1 0"/><limit lower="-0.5" upper="1.25" effort="1" velocity="1"/></joint>
  <joint name="alpha" type="prismatic"><parent link="a"/><child link="b"/>
    <axis xyz="0 0 1"/><limit lower="0" upper="0.1" effort="1" velocity="1"/></joint>
  <joint name="mid" type="continuous"><parent link="b"/><child link="c"/></joint>
  <joint name="tool" type="fixed"><parent link="c"/><child link="d"/>
    <origin xyz="0.1 0 0"/></joint>
</robot>)");
  const RobotModel model = load_robot_model(file);
  EXPECT_EQ(model.name(), "ordered");
  ASSERT_EQ(model.num_dofs(), 3);
  EXPECT_EQ(model.joint(model.dof_joint(0)).name, "zeta");  // file order, not alphabetical
  EXPECT_EQ(model.joint(model.dof_joint(1)).name, "alpha");
  EXPECT_EQ(model.joint(model.dof_joint(2)).name, "mid");
  const Joint& zeta = model.joint(model.joint_index("zeta"));
  EXPECT_EQ(zeta.type, JointType::Revolute);
  EXPECT_NEAR(zeta.lower, -0.5, 1e-15);
  EXPECT_NEAR(zeta.upper, 1.25, 1e-15);
  EXPECT_TRUE(zeta.axis.isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_EQ(model.joint(model.joint_index("alpha")).type, JointType::Prismatic);
  EXPECT_DOUBLE_EQ(model.joint(model.joint_index("alpha")).upper, 0.1);
  EXPECT_LT(model.joint(model.joint_index("mid")).lower, -1e3);  // continuous: unlimited
  EXPECT_EQ(model.joint(model.joint_index("tool")).type, JointType::Fixed);
  // URDF's default axis is x.
  EXPECT_TRUE(model.joint(model.joint_index("mid")).axis.isApprox(Eigen::Vector3d::UnitX()));
}

TEST(UrdfImport, InertiaIsTurnedIntoLinkAxesAndShapesAndColoursKept) {
  TempDir dir;
  const auto file = dir.write("shapes.urdf", R"(<robot name="shapes">
  <material name="red"><color rgba="1 0 0 1"/></material>
  <link name="base">
    <inertial><origin xyz="0.1 0.2 0.3" rpy="0 0 1.5707963267948966"/><mass value="2"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="3"/></inertial>
    <collision><origin xyz="0 0 0.5"/><geometry><box size="0.1 0.2 0.3"/></geometry></collision>
    <collision><geometry><cylinder radius="0.05" length="0.4"/></geometry></collision>
    <visual><geometry><sphere radius="0.07"/></geometry><material name="red"/></visual>
  </link>
</robot>)");
  const RobotModel model = load_robot_model(file);
  const Link& base = model.link(0);
  EXPECT_DOUBLE_EQ(base.inertial.mass, 2.0);
  EXPECT_TRUE(base.inertial.com.isApprox(Eigen::Vector3d(0.1, 0.2, 0.3)));
  // Turned by 90 degrees about z: the x and y moments swap.
  EXPECT_NEAR(base.inertial.inertia(0, 0), 2.0, 1e-12);
  EXPECT_NEAR(base.inertial.inertia(1, 1), 1.0, 1e-12);
  EXPECT_NEAR(base.inertial.inertia(2, 2), 3.0, 1e-12);
  ASSERT_EQ(base.collision.size(), 2u);
  EXPECT_EQ(base.collision[0].type, GeometryType::Box);
  EXPECT_TRUE(base.collision[0].size.isApprox(Eigen::Vector3d(0.1, 0.2, 0.3)));
  EXPECT_DOUBLE_EQ(base.collision[0].origin.translation().z(), 0.5);
  EXPECT_EQ(base.collision[1].type, GeometryType::Cylinder);
  EXPECT_DOUBLE_EQ(base.collision[1].length, 0.4);
  ASSERT_EQ(base.visual.size(), 1u);
  EXPECT_EQ(base.visual[0].type, GeometryType::Sphere);
  ASSERT_TRUE(base.visual[0].colour.has_value());
  EXPECT_TRUE(base.visual[0].colour->isApprox(Eigen::Vector3d(1, 0, 0)));
}

TEST(UrdfImport, AYamlOverlayAddsWhatUrdfCannotSay) {
  TempDir dir;
  dir.write("arm.urdf",
            two_links(kInertial, R"(<limit lower="-1" upper="1" effort="1" velocity="1"/>)"));
  const auto overlay = dir.write("arm_with_eye.yaml", R"(extends: arm.urdf
robot: arm_with_eye
set:
  frames.palm: {link: arm, origin: {xyz: [0, 0, 0.1]}}
  cameras.eye: {link: base, fx: 100, fy: 100, width: 64, height: 48}
)");
  const RobotModel model = load_robot_model(overlay);
  EXPECT_EQ(model.name(), "arm_with_eye");
  EXPECT_GE(model.find_frame("palm"), 0);
  EXPECT_GE(model.find_camera("eye"), 0);
  EXPECT_EQ(model.num_dofs(), 1);
}

TEST(UrdfImport, RelativeMeshesOfAUrdfGivenByARelativePathAreFound) {
  TempDir dir;
  dir.write("robots/arm/meshes/part.obj",
            "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n");
  dir.write(
      "robots/arm/arm.urdf",
      two_links(std::string(kInertial) +
                    R"(<visual><geometry><mesh filename="meshes/part.obj"/></geometry></visual>)",
                R"(<limit lower="-1" upper="1" effort="1" velocity="1"/>)"));
  const fs::path cwd = fs::current_path();
  fs::current_path(dir.path());
  const RobotModel model = load_robot_model("robots/arm/arm.urdf");
  fs::current_path(cwd);
  const Link& arm = model.link(model.link_index("arm"));
  ASSERT_EQ(arm.visual.size(), 1u);
  EXPECT_EQ(fs::path(arm.visual[0].mesh_file),
            (dir.path() / "robots/arm/meshes/part.obj").lexically_normal());
}

TEST(UrdfImport, PackageMeshesAreFoundThroughTheResourcePath) {
  TempDir dir;
  dir.write("share/my_robot/meshes/part.obj",
            "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n");
  const auto file = dir.write(
      "mesh.urdf",
      two_links(std::string(kInertial) +
                    R"(<visual><geometry><mesh filename="package://my_robot/meshes/part.obj" )"
                    R"(scale="2 2 2"/></geometry></visual>)",
                R"(<limit lower="-1" upper="1" effort="1" velocity="1"/>)"));
  ::setenv("SOMASIM_RESOURCE_PATH", (dir.path() / "share").c_str(), 1);
  const RobotModel model = load_robot_model(file);
  ::unsetenv("SOMASIM_RESOURCE_PATH");
  const Link& arm = model.link(model.link_index("arm"));
  ASSERT_EQ(arm.visual.size(), 1u);
  EXPECT_EQ(arm.visual[0].type, GeometryType::Mesh);
  EXPECT_EQ(fs::path(arm.visual[0].mesh_file),
            (dir.path() / "share/my_robot/meshes/part.obj").lexically_normal());
  EXPECT_TRUE(arm.visual[0].mesh_scale.isApprox(Eigen::Vector3d(2, 2, 2)));
}

TEST(UrdfImportBadInput, EveryMessageNamesTheFileTheLineAndWhatWasExpected) {
  TempDir dir;
  const std::string limit = R"(<limit lower="-1" upper="1" effort="1" velocity="1"/>)";
  auto fails = [&](const std::string& name, const std::string& urdf) {
    const fs::path file = dir.write(name, urdf);
    return message_of([&] { load_robot_model(file); });
  };
  const std::string d = dir.path().string();
  EXPECT_EQ(fails("xml.urdf", "<robot name=\"r\">\n  <link name=\"a\">\n</robot>\n"),
            d + "/xml.urdf:3: malformed XML (Error reading end tag); expected a well-formed URDF "
                "document");
  EXPECT_EQ(fails("missing.urdf", R"(<robot name="r">
<link name="base"/>
<joint name="j" type="fixed"><parent link="base"/><child link="hand"/></joint>
</robot>)"),
            d + "/missing.urdf:3: joint 'j': its child link 'hand' is not defined in the file");
  EXPECT_EQ(fails("roots.urdf", R"(<robot name="r">
<link name="a"/>
<link name="b"/>
</robot>)"),
            d + "/roots.urdf:1: 2 links have no parent joint ('a', 'b'); expected one root link");
  EXPECT_EQ(fails("cycle.urdf", R"(<robot name="r">
<link name="root"/><link name="a"/><link name="b"/>
<joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>
<joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint>
</robot>)"),
            d + "/cycle.urdf:4: joint cycle through link 'a'; expected a tree");
  EXPECT_EQ(fails("mass.urdf", two_links(R"(<inertial>
<mass value="-1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>)",
                                         limit)),
            d + "/mass.urdf:5: link 'arm': mass -1 is negative; expected a mass >= 0 [kg]");
  EXPECT_EQ(fails("inertia.urdf", two_links(R"(<inertial>
<mass value="1"/><inertia ixx="1" ixy="2" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>)",
                                            limit)),
            d + "/inertia.urdf:5: link 'arm': the inertia is not positive semi-definite "
                "(smallest principal moment -1 kg m^2); expected a physical inertia");
  EXPECT_EQ(fails("limits.urdf",
                  two_links("", R"(<limit lower="1" upper="-1" effort="1" velocity="1"/>)")),
            d + "/limits.urdf:8: joint 'shoulder': limit lower 1 > upper -1; expected lower <= "
                "upper (an omitted bound is 0)");
  EXPECT_EQ(fails("lower.urdf", two_links("", R"(<limit upper="-0.5" effort="1" velocity="1"/>)")),
            d + "/lower.urdf:8: joint 'shoulder': limit lower 0 > upper -0.5; expected lower <= "
                "upper (an omitted bound is 0)");
  EXPECT_EQ(fails("floating.urdf", R"(<robot name="r">
<link name="world"/><link name="body"/>
<joint name="free" type="floating"><parent link="world"/><child link="body"/></joint>
</robot>)"),
            d + "/floating.urdf:3: joint 'free' is floating: somasim robots have a fixed root and "
                "1-dof joints; expected revolute, continuous, prismatic or fixed");
  // Every missing mesh, in one message.
  EXPECT_EQ(fails("meshes.urdf", two_links(R"(
<visual><geometry><mesh filename="meshes/a.stl"/></geometry></visual>
<collision><geometry><mesh filename="meshes/b.stl"/></geometry></collision>)",
                                           limit)),
            fmt::format("{0}/meshes.urdf:5: link 'arm': mesh 'meshes/a.stl': no such file "
                        "({0}/meshes/a.stl)\n{0}/meshes.urdf:6: link 'arm': mesh 'meshes/b.stl': "
                        "no such file ({0}/meshes/b.stl)",
                        d));
  ::setenv("SOMASIM_RESOURCE_PATH", "/nonexistent/one:/nonexistent/two", 1);
  ::unsetenv("ROS_PACKAGE_PATH");
  EXPECT_EQ(fails("package.urdf", two_links(R"(
<visual><geometry><mesh filename="package://icub_meshes/hand.dae"/></geometry></visual>)",
                                            limit)),
            d + "/package.urdf:5: link 'arm': mesh 'package://icub_meshes/hand.dae': no package "
                "'icub_meshes' in the resource path (/nonexistent/one:/nonexistent/two); add the "
                "directory that holds 'icub_meshes' to SOMASIM_RESOURCE_PATH or pass "
                "--resource-path");
  ::unsetenv("SOMASIM_RESOURCE_PATH");
}

TEST(UrdfImport, AnOverlayChoosesWhatMissingMeshesDo) {
  TempDir dir;
  dir.write("arm.urdf", two_links(std::string(kInertial) + R"(
<visual><geometry><mesh filename="meshes/gone.dae"/></geometry></visual>
<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>)",
                                  R"(<limit lower="-1" upper="1" effort="1" velocity="1"/>)"));
  auto arm_of = [&](const std::string& policy) {
    const auto file =
        dir.write(policy + ".yaml", "extends: arm.urdf\nmissing_meshes: " + policy + "\n");
    const RobotModel model = load_robot_model(file);
    return model.link(model.link_index("arm"));
  };
  const Link skipped = arm_of("skip");
  EXPECT_TRUE(skipped.visual.empty());
  EXPECT_EQ(skipped.collision.size(), 1u);
  const Link drawn = arm_of("collision");  // the collision box is drawn instead
  ASSERT_EQ(drawn.visual.size(), 1u);
  EXPECT_EQ(drawn.visual[0].type, GeometryType::Box);
  EXPECT_NE(message_of([&] { arm_of("error"); }).find("mesh 'meshes/gone.dae': no such file"),
            std::string::npos);
  const auto bad = dir.write("bad.yaml", "extends: arm.urdf\nmissing_meshes: maybe\n");
  EXPECT_EQ(message_of([&] { load_robot_model(bad); }),
            bad.string() +
                ":2:17: key 'missing_meshes': expected error, skip or collision, got "
                "'maybe'");
}

namespace {

/// The iCub's published model (robotology/icub-models, as in ../shared), with the meshes the
/// shared copy has and the others left out; nullopt when ../shared is absent.
std::optional<RobotModel> published_icub() {
  const fs::path models =
      fs::path(SOMASIM_SOURCE_DIR) / "../shared/body-schema-data/robotology-icub-models";
  const fs::path urdf = models / "iCub/robots/iCubLisboa01/model.urdf";
  if (!fs::exists(urdf)) return std::nullopt;
  TempDir dir;
  const auto overlay =
      dir.write("icub.yaml", "extends: " + fs::absolute(urdf).lexically_normal().string() +
                                 "\nmissing_meshes: skip\n");
  ::setenv("SOMASIM_RESOURCE_PATH", models.c_str(), 1);
  RobotModel model = load_robot_model(overlay);
  ::unsetenv("SOMASIM_RESOURCE_PATH");
  return model;
}

}  // namespace

TEST(UrdfImportValidation, TheICubsPublishedModelLoads) {
  const auto published = published_icub();
  if (!published) GTEST_SKIP() << "../shared is absent";
  const RobotModel& model = *published;
  EXPECT_GT(model.num_dofs(), 30);
  EXPECT_GE(model.find_joint("r_elbow"), 0);
  EXPECT_GE(model.find_link("r_hand"), 0);
  EXPECT_GT(model.total_mass(), 20.0);
}

// The published model's arm chains against icub_v1.yaml (iKin's DH tables): the pose of each
// hand's DH frame for random joint vectors of the torso and arm, after aligning the two root
// frames (the transform that maps one onto the other at the zero posture).
TEST(UrdfImportValidation, TheICubsPublishedArmsAgreeWithTheDhTables) {
  const auto loaded = published_icub();
  if (!loaded) GTEST_SKIP() << "../shared is absent";
  const RobotModel& published = *loaded;
  const RobotModel dh =
      load_robot_model(fs::path(SOMASIM_SOURCE_DIR) / "assets/robots/icub_v1.yaml");
  std::mt19937 rng(11);
  for (const std::string side : {"r", "l"}) {
    std::vector<std::string> joints = {"torso_pitch", "torso_roll", "torso_yaw"};
    for (const char* j : {"shoulder_pitch", "shoulder_roll", "shoulder_yaw", "elbow",
                          "wrist_prosup", "wrist_pitch", "wrist_yaw"})
      joints.push_back(side + "_" + j);
    RobotData dp(published), dd(dh);
    auto pose = [&](const Eigen::VectorXd& values, bool of_published) {
      const RobotModel& m = of_published ? published : dh;
      RobotData& d = of_published ? dp : dd;
      Eigen::VectorXd q = Eigen::VectorXd::Zero(m.num_dofs());
      for (std::size_t k = 0; k < joints.size(); ++k)
        q[m.dof_index(joints[k])] = values[static_cast<Eigen::Index>(k)];
      forward_kinematics(m, d, q);
      return link_pose(d, m.link_index(of_published ? side + "_hand_dh_frame" : side + "_hand"));
    };
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(joints.size()));
    const Eigen::Isometry3d align = pose(zero, true) * pose(zero, false).inverse();
    double worst_mm = 0, worst_deg = 0;
    for (int trial = 0; trial < 20; ++trial) {
      Eigen::VectorXd values(static_cast<Eigen::Index>(joints.size()));
      for (std::size_t k = 0; k < joints.size(); ++k) {
        const int dof = dh.dof_index(joints[k]);
        const double lo = std::max(dh.lower_limits()[dof],
                                   published.lower_limits()[published.dof_index(joints[k])]);
        const double hi = std::min(dh.upper_limits()[dof],
                                   published.upper_limits()[published.dof_index(joints[k])]);
        values[static_cast<Eigen::Index>(k)] = std::uniform_real_distribution<double>(lo, hi)(rng);
      }
      const Eigen::Isometry3d a = pose(values, true), b = align * pose(values, false);
      worst_mm = std::max(worst_mm, 1000 * (a.translation() - b.translation()).norm());
      worst_deg = std::max(
          worst_deg, Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180 / M_PI);
    }
    std::printf("%s arm: largest difference over 20 postures %.4f mm, %.4f deg\n", side.c_str(),
                worst_mm, worst_deg);
    EXPECT_LT(worst_mm, 1.0) << side;
    EXPECT_LT(worst_deg, 0.5) << side;
  }
}

namespace {

/// Every link pose of `a` and `b` (by link name) for random joint vectors, and their masses.
void expect_same_robot(const RobotModel& a, const RobotModel& b, std::mt19937& rng) {
  ASSERT_EQ(a.num_dofs(), b.num_dofs());
  for (int d = 0; d < a.num_dofs(); ++d)
    EXPECT_EQ(a.joint(a.dof_joint(d)).name, b.joint(b.dof_joint(d)).name) << d;
  RobotData da(a), db(b);
  for (int trial = 0; trial < 10; ++trial) {
    Eigen::VectorXd q(a.num_dofs());
    for (int d = 0; d < a.num_dofs(); ++d) {
      const double lo = std::max(a.lower_limits()[d], -3.0),
                   hi = std::min(a.upper_limits()[d], 3.0);
      q[d] = std::uniform_real_distribution<double>(lo, hi)(rng);
    }
    forward_kinematics(a, da, q);
    forward_kinematics(b, db, q);
    for (int l = 0; l < a.num_links(); ++l) {
      const int lb = b.link_index(a.link(l).name);
      EXPECT_LT((link_pose(da, l).matrix() - link_pose(db, lb).matrix()).cwiseAbs().maxCoeff(),
                1e-12)
          << a.link(l).name;
    }
  }
  for (int l = 0; l < a.num_links(); ++l) {
    const Link& la = a.link(l);
    const Link& lb = b.link(b.link_index(la.name));
    EXPECT_NEAR(la.inertial.mass, lb.inertial.mass, 1e-12) << la.name;
    EXPECT_LT((la.inertial.com - lb.inertial.com).norm(), 1e-12) << la.name;
    EXPECT_LT((la.inertial.inertia - lb.inertial.inertia).cwiseAbs().maxCoeff(), 1e-12) << la.name;
    auto count = [](const std::vector<Geometry>& shapes) {
      std::size_t n = 0;
      for (const auto& g : shapes) n += g.type == GeometryType::Capsule ? 3 : 1;
      return n;
    };
    EXPECT_EQ(count(la.collision), lb.collision.size()) << la.name;
  }
  for (const Frame& f : a.frames()) {
    const int k = b.find_frame(f.name);
    ASSERT_GE(k, 0) << f.name;
    EXPECT_EQ(b.link(b.frames()[static_cast<std::size_t>(k)].link).name, a.link(f.link).name);
    EXPECT_TRUE(b.frames()[static_cast<std::size_t>(k)].pose.isApprox(f.pose, 1e-12)) << f.name;
  }
  for (const ChainInfo& c : a.chains()) {
    const ChainInfo* other = b.find_chain(c.name);
    ASSERT_NE(other, nullptr) << c.name;
    EXPECT_EQ(b.link(other->base_link).name, a.link(c.base_link).name) << c.name;
    EXPECT_EQ(other->tip_frame, c.tip_frame) << c.name;
    EXPECT_EQ(other->joints, c.joints) << c.name;
  }
  EXPECT_EQ(a.cameras().size(), b.cameras().size());
  EXPECT_EQ(a.skin_patches().size(), b.skin_patches().size());
}

}  // namespace

TEST(UrdfExport, ImportOfTheExportIsTheSameRobot) {
  std::mt19937 rng(3);
  TempDir dir;
  for (const char* variant : {"icub_v1", "icub_v2", "icub_v1_full_skin"}) {
    const RobotModel original = load_robot_model(fs::path(SOMASIM_SOURCE_DIR) / "assets/robots" /
                                                 (std::string(variant) + ".yaml"));
    const fs::path urdf = dir.write(std::string(variant) + ".urdf", to_urdf(original));
    const fs::path overlay =
        dir.write(std::string(variant) + ".yaml", urdf_overlay(original, urdf.filename().string()));
    const RobotModel back = load_robot_model(overlay);
    SCOPED_TRACE(variant);
    expect_same_robot(original, back, rng);
  }
  // Generated URDF chains survive export and import too.
  for (int trial = 0; trial < 10; ++trial) {
    const RandomChain chain = random_chain(rng, 1 + trial % 6);
    const RobotModel original = load_robot_model(dir.write("c.urdf", chain.urdf));
    const RobotModel back = load_robot_model(dir.write("c2.urdf", to_urdf(original)));
    expect_same_robot(original, back, rng);
  }
}

TEST(UrdfImport, ChainsAlongTheTreeNameTheJointsBetweenBaseAndTip) {
  TempDir dir;
  dir.write("order.urdf", R"(<robot name="r">
  <link name="base"/><link name="a"/><link name="b"/><link name="c"/><link name="side"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="a"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="fix" type="fixed"><parent link="a"/><child link="b"/></joint>
  <joint name="j2" type="revolute"><parent link="b"/><child link="c"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j3" type="revolute"><parent link="base"/><child link="side"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>)");
  const auto ok = dir.write("ok.yaml", R"(extends: order.urdf
set:
  frames.tool: {link: c, origin: {xyz: [0, 0, 0.1]}}
  chains.arm: {tip: tool}
  chains.forearm: {base: a, tip: c}
)");
  const RobotModel model = load_robot_model(ok);
  ASSERT_NE(model.find_chain("arm"), nullptr);
  EXPECT_EQ(model.find_chain("arm")->joints, (std::vector<std::string>{"j1", "j2"}));
  EXPECT_EQ(model.find_chain("arm")->tip_frame, "tool");
  EXPECT_EQ(model.find_chain("forearm")->joints, (std::vector<std::string>{"j2"}));
  const auto bad = dir.write("bad.yaml", R"(extends: order.urdf
set:
  chains.crossed: {base: side, tip: c}
  chains.nowhere: {tip: hand}
)");
  const std::string m = message_of([&] { load_robot_model(bad); });
  EXPECT_NE(m.find("chain 'crossed', key 'tip': 'c' is not below the base link 'side'; expected a "
                   "tip on the tree below the base"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("chain 'nowhere', key 'tip': unknown frame or link 'hand'; expected a frame "
                   "or a link"),
            std::string::npos)
      << m;
}
