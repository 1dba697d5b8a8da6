// Robot-description loading: structure, masses, variants, and every error message in full.
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "robot_test_support.hpp"
#include "somasim/error.hpp"
#include "somasim/robot/kinematic_chain.hpp"

namespace somasim::robot {
namespace {
namespace fs = std::filesystem;

class RobotLoader : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("somasim-robot-test-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string error(const std::string& text) {
    try {
      parse_robot_model(text, "robot.yaml", dir_);
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no error)";
  }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
  }
  fs::path dir_;
};

TEST_F(RobotLoader, MissingParentLink) {
  EXPECT_EQ(error(R"(robot: r
links:
  torso: {}
  a: {}
joints:
  base: {type: fixed, parent: root, child: torso}
  j: {type: fixed, parent: torsoo, child: a}
)"),
            "robot.yaml:7:28: joint 'j', key 'parent': unknown link 'torsoo'; expected the root, a "
            "link under 'links', a chain link or another joint's child (did you mean 'torso'?)");
}

TEST_F(RobotLoader, JointCycle) {
  EXPECT_EQ(error(R"(robot: r
links:
  l1: {}
  l2: {}
joints:
  a: {type: revolute, parent: l1, child: l2, limits_deg: [-10, 10]}
  b: {type: revolute, parent: l2, child: l1, limits_deg: [-10, 10]}
)"),
            "robot.yaml:6:3: joint 'a': joints form a cycle: 'a' (l1 -> l2), 'b' (l2 -> l1); "
            "expected every link to lead back to the root link 'root'");
}

TEST_F(RobotLoader, ZeroAndNegativeMass) {
  EXPECT_EQ(
      error("robot: r\nlinks:\n  root: {mass: 0, collision: [{type: sphere, radius: 0.1}]}\n"),
      "robot.yaml:3:16: link 'root', key 'mass': expected a mass > 0 [kg], got 0");
  EXPECT_EQ(error("robot: r\nlinks:\n  root: {mass: -1.5}\n"),
            "robot.yaml:3:16: link 'root', key 'mass': expected a mass > 0 [kg], got -1.5");
}

TEST_F(RobotLoader, UnknownGeometryType) {
  EXPECT_EQ(error(R"(robot: r
links:
  root:
    collision: [{type: cilinder, radius: 0.1, length: 0.2}]
)"),
            "robot.yaml:4:24: link 'root', key 'collision[0].type': unknown geometry type "
            "'cilinder' (did you mean 'cylinder'?); expected one of: sphere, box, cylinder, "
            "capsule, mesh");
}

TEST_F(RobotLoader, HugeFilesAreRefusedBeforeTheyAreRead) {
  write("huge.yaml", "robot: r\n");
  fs::resize_file(dir_ / "huge.yaml", 3u << 20);
  try {
    load_robot_model(dir_ / "huge.yaml");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "robot description '" + (dir_ / "huge.yaml").string() +
                                         "' is 3145728 bytes; at most 2097152 (2 MiB) are read");
  }
}

TEST_F(RobotLoader, MeshFileMissingOrUnreadable) {
  EXPECT_EQ(error("robot: r\nlinks:\n  root:\n    visual: [{type: mesh, file: meshes/hand.stl}]\n"),
            "robot.yaml:4:33: link 'root', key 'visual[0].file': mesh file 'meshes/hand.stl' "
            "does not exist (resolved to '" +
                (dir_ / "meshes/hand.stl").string() + "')");
  fs::create_directories(dir_ / "folder.stl");
  EXPECT_EQ(error("robot: r\nlinks:\n  root:\n    visual: [{type: mesh, file: folder.stl}]\n"),
            "robot.yaml:4:33: link 'root', key 'visual[0].file': mesh file 'folder.stl' cannot "
            "be read (resolved to '" +
                (dir_ / "folder.stl").string() + "'); expected a readable regular file");
  // A FIFO is not opened (that would block until a writer came).
  ASSERT_EQ(mkfifo((dir_ / "fifo.stl").c_str(), 0600), 0);
  EXPECT_NE(error("robot: r\nlinks:\n  root:\n    visual: [{type: mesh, file: fifo.stl}]\n")
                .find("mesh file 'fifo.stl' cannot be read"),
            std::string::npos);
  write("hand.stl", "solid hand\nendsolid hand\n");
  const RobotModel m = parse_robot_model(
      "robot: r\nlinks:\n  root:\n    visual: [{type: mesh, file: hand.stl, scale: 0.001}]\n",
      "robot.yaml", dir_);
  EXPECT_EQ(m.link(0).visual.at(0).mesh_file, (dir_ / "hand.stl").string());
  EXPECT_DOUBLE_EQ(m.link(0).visual.at(0).mesh_scale.x(), 0.001);
  EXPECT_EQ(error("robot: r\nlinks:\n  root:\n    collision: [{type: mesh, file: hand.stl}]\n"),
            "robot.yaml:4:16: link 'root', key 'mass': cannot compute the mass of mesh geometry; "
            "expected 'mass' [kg]");
}

TEST_F(RobotLoader, VisualColour) {
  const RobotModel m = parse_robot_model(
      "robot: r\nlinks:\n  root:\n    collision: [{type: sphere, radius: 0.1}]\n"
      "    visual: [{type: sphere, radius: 0.1}, {type: sphere, radius: 0.01, colour: [0, 1, "
      "0.25]}]\n",
      "robot.yaml", dir_);
  ASSERT_EQ(m.link(0).visual.size(), 2u);
  EXPECT_FALSE(m.link(0).visual[0].colour.has_value());
  ASSERT_TRUE(m.link(0).visual[1].colour.has_value());
  EXPECT_EQ(*m.link(0).visual[1].colour, Eigen::Vector3d(0, 1, 0.25));
  EXPECT_EQ(error("robot: r\nlinks:\n  root:\n    visual: [{type: sphere, radius: 0.1, "
                  "colour: [0, 1.5, 0]}]\n"),
            "robot.yaml:4:50: link 'root', key 'visual[0].colour': expected [r, g, b] with each "
            "value in [0, 1]");
  EXPECT_EQ(error("robot: r\nlinks:\n  root:\n    visual: [{type: sphere, radius: 0.1, "
                  "colour: [0, 1]}]\n"),
            "robot.yaml:4:50: link 'root', key 'visual[0].colour': expected a list of 3 "
            "numbers, got 2 items");
  // A colour is drawn: collision shapes have none.
  EXPECT_EQ(error("robot: r\nlinks:\n  root:\n    collision: [{type: sphere, radius: 0.1, "
                  "colour: [0, 1, 0]}]\n"),
            "robot.yaml:4:53: link 'root', key 'collision[0].colour': only visual shapes are "
            "drawn with a colour; expected it under 'visual'");
}

// The iCub's right index fingertip carries the green marker the eyes track; the hand's other
// visuals are its collision shapes.
TEST_F(RobotLoader, IcubFingertipMarker) {
  for (const char* v : {"icub_v1", "icub_v1_7", "icub_v2"}) {
    const RobotModel m = test::load_icub(v);
    const Link& hand = m.link(m.link_index("r_hand"));
    ASSERT_EQ(hand.visual.size(), hand.collision.size() + 1) << v;
    for (std::size_t i = 0; i < hand.collision.size(); ++i) {
      EXPECT_EQ(hand.visual[i].type, hand.collision[i].type) << v << " shape " << i;
      EXPECT_TRUE(hand.visual[i].origin.isApprox(hand.collision[i].origin)) << v << " " << i;
      EXPECT_EQ(hand.visual[i].radius, hand.collision[i].radius) << v << " shape " << i;
      EXPECT_EQ(hand.visual[i].length, hand.collision[i].length) << v << " shape " << i;
      EXPECT_EQ(hand.visual[i].size, hand.collision[i].size) << v << " shape " << i;
      EXPECT_FALSE(hand.visual[i].colour.has_value());
    }
    const Geometry& marker = hand.visual.back();
    EXPECT_EQ(marker.type, GeometryType::Sphere);
    EXPECT_NEAR(marker.radius, 0.007, 1e-12);
    ASSERT_TRUE(marker.colour.has_value());
    EXPECT_GT((*marker.colour)[1], 0.8);
    EXPECT_LT((*marker.colour)[0], 0.2);
    EXPECT_LT((*marker.colour)[2], 0.2);
    const Frame& tip = m.frames()[static_cast<std::size_t>(m.find_frame("r_index_tip"))];
    EXPECT_EQ(tip.link, m.link_index("r_hand"));
    EXPECT_LT((marker.origin.translation() - tip.pose.translation()).norm(), 1e-12) << v;
  }
}

TEST_F(RobotLoader, LimitsMinAboveMax) {
  EXPECT_EQ(error(R"(robot: r
links:
  a: {}
joints:
  j: {type: revolute, parent: root, child: a, limits_deg: [30, 10]}
)"),
            "robot.yaml:5:59: joint 'j', key 'limits_deg': min 30 > max 10; expected [min, max] "
            "with min <= max");
  EXPECT_EQ(error("robot: r\nchains:\n  c:\n    links:\n      - {joint: j, limits_deg: [5, -5]}\n"),
            "robot.yaml:5:32: chain 'c', key 'links[0].limits_deg': min 5 > max -5; expected "
            "[min, max] with min <= max");
}

TEST_F(RobotLoader, CameraFocalLength) {
  EXPECT_EQ(error(R"(robot: r
cameras:
  eye: {link: root, fx: 0, fy: 257.34, width: 320, height: 240}
)"),
            "robot.yaml:3:25: camera 'eye', key 'fx': expected a focal length > 0 [px], got 0");
  EXPECT_EQ(error(R"(robot: r
cameras:
  eye: {link: root, fx: 100, fy: -1, width: 320, height: 240, near: 1, far: 0.5}
)"),
            "robot.yaml:3:34: camera 'eye', key 'fy': expected a focal length > 0 [px], got -1");
}

// Intrinsics that render nothing useful and sizes no integer of the renderer holds: refused,
// never narrowed (a width of 4294967616 once rendered at 320 px).
TEST_F(RobotLoader, CameraIntrinsicsOutOfAnyUsefulRangeAreRefused) {
  const auto camera = [&](const std::string& fields) {
    return error("robot: r\ncameras:\n  eye: {link: root, " + fields + "}\n");
  };
  EXPECT_EQ(camera("fx: 1e-300, fy: 257, width: 320, height: 240"),
            "robot.yaml:3:25: camera 'eye', key 'fx': 1e-300 px for an image 320 px wide; "
            "expected a focal length in [0.32, 320000] px (1e-3 to 1e3 times the width)");
  EXPECT_NE(camera("fx: 257, fy: 1e308, width: 320, height: 240").find("key 'fy': 1e+308 px"),
            std::string::npos);
  EXPECT_EQ(camera("fx: 257, fy: 257, width: 4294967616, height: 240"),
            "robot.yaml:3:46: camera 'eye', key 'width': expected an integer in [1, 16384], got "
            "'4294967616'");
  EXPECT_NE(camera("fx: 257, fy: 257, width: 320, height: 240, cx: 1e9").find("key 'cx'"),
            std::string::npos);
  EXPECT_EQ(camera("fx: 257, fy: 257, width: 320, height: 240, cx: -40, cy: 300"), "(no error)");
}

TEST_F(RobotLoader, SkinPatchOnUnknownLink) {
  EXPECT_EQ(error(R"(robot: r
links:
  l_forearm: {}
joints:
  f: {type: fixed, parent: root, child: l_forearm}
skin:
  left_forearm: {link: l_forarm, surface: cylinder, radius: 0.02, z_min: 0, z_max: 0.1, spacing: 0.02}
)"),
            "robot.yaml:7:24: skin patch 'left_forearm', key 'link': unknown link 'l_forarm' "
            "(did you mean 'l_forearm'?)");
}

TEST_F(RobotLoader, SkinPatchNumbers) {
  EXPECT_EQ(
      error(R"(robot: r
skin:
  palm: {link: root, surface: box_face, size_x: 0.05, size_y: -0.04, spacing: 0.02, group_size: 0}
  arm: {link: root, surface: cylindre}
  fore: {link: root, surface: cylinder, radius: 0.02, z_min: 0.1, z_max: 0.05, spacing: 0.01}
)"),
      "4 errors:\n"
      "  robot.yaml:3:63: skin patch 'palm', key 'size_y': expected a size > 0 [m], got -0.04\n"
      "  robot.yaml:3:97: skin patch 'palm', key 'group_size': expected an integer >= 1, got '0'\n"
      "  robot.yaml:4:30: skin patch 'arm', key 'surface': unknown surface 'cylindre' (did you "
      "mean 'cylinder'?); expected one of: cylinder, box_face\n"
      "  robot.yaml:5:74: skin patch 'fore', key 'z_max': z_max 0.05 <= z_min 0.1; expected "
      "z_min < z_max [m]");
}

TEST_F(RobotLoader, UnknownKeysWithSuggestions) {
  EXPECT_EQ(error("robot: r\ndesnity: 3\nlinks:\n  root: {colision: []}\n"),
            "2 errors:\n"
            "  robot.yaml:2:1: key 'desnity': unknown key (did you mean 'density'?); expected one "
            "of: robot, extends, set, root, density, links, joints, chains, frames, cameras, skin\n"
            "  robot.yaml:4:10: link 'root', key 'colision': unknown key (did you mean "
            "'collision'?); expected one of: collision, visual, mass, density, com, inertia");
  EXPECT_EQ(error("robot: r\nchains:\n  c:\n    links:\n      - {joint: j, alpah_deg: 90, "
                  "limits_deg: [0, 1]}\n"),
            "robot.yaml:5:20: chain 'c', key 'links[0].alpah_deg': unknown key (did you mean "
            "'alpha_deg'?); expected one of: joint, a, d, alpha_deg, offset_deg, limits_deg, link");
}

TEST_F(RobotLoader, SharedJointNeedsTheSameFrameBefore) {
  EXPECT_EQ(error(R"(robot: r
chains:
  a:
    links:
      - {joint: j0, a: 0.1, limits_deg: [-90, 90]}
  b:
    H0: {xyz: [0, 0, 0.01]}
    links:
      - {joint: j0, a: 0.1, limits_deg: [-90, 90]}
)"),
            "robot.yaml:9:17: chain 'b', key 'links[0].joint': joint 'j0' is shared with chain "
            "'a' but the frame before it differs (by 0.01 m and 0 deg); expected a chain whose "
            "links before a shared joint are the same");
  EXPECT_EQ(error(R"(robot: r
chains:
  a:
    links:
      - {joint: j0, a: 0.1, limits_deg: [-90, 90]}
  b:
    links:
      - {joint: j0, a: 0.2, limits_deg: [-90, 80]}
)"),
            "robot.yaml:8:41: chain 'b', key 'links[0].limits_deg': joint 'j0' is shared with "
            "chain 'a' but its limits differ; expected [-90, 90] as there");
}

TEST_F(RobotLoader, SecondParentAndDuplicateKey) {
  EXPECT_EQ(error(R"(robot: r
links:
  a: {}
joints:
  j1: {type: fixed, parent: root, child: a}
  j2: {type: fixed, parent: root, child: a}
robot: s
)"),
            "2 errors:\n"
            "  robot.yaml:6:42: joint 'j2', key 'child': link 'a' already has a parent joint "
            "('j1' of joint 'j1'); expected each link to have exactly one parent joint\n"
            "  robot.yaml:7:1: key 'robot': duplicate key (first defined at robot.yaml:1:1)");
}

TEST_F(RobotLoader, MassFromGeometryOrGiven) {
  const RobotModel m = parse_robot_model(R"(robot: r
density: 500
links:
  root: {collision: [{type: sphere, radius: 0.1, origin: {xyz: [0, 0, 0.2]}}]}
  a:
    mass: 2
    collision: [{type: box, size: [0.1, 0.2, 0.3]}]
  b:
    mass: 1
    com: [0, 0, 0.1]
    inertia: [0.01, 0.02, 0.03, 0, 0, 0]
joints:
  ja: {type: fixed, parent: root, child: a}
  jb: {type: fixed, parent: a, child: b}
)",
                                         "robot.yaml", dir_);
  const Inertial& root = m.link(0).inertial;
  EXPECT_NEAR(root.mass, 500 * 4.0 / 3.0 * M_PI * 1e-3, 1e-12);
  EXPECT_NEAR(root.com.z(), 0.2, 1e-15);
  EXPECT_NEAR(root.inertia(0, 0), 0.4 * root.mass * 0.01, 1e-15);
  const Inertial& a = m.link(m.link_index("a")).inertial;
  EXPECT_DOUBLE_EQ(a.mass, 2.0);
  EXPECT_NEAR(a.inertia(2, 2), 2.0 / 12.0 * (0.01 + 0.04), 1e-15);
  const Inertial& b = m.link(m.link_index("b")).inertial;
  EXPECT_DOUBLE_EQ(b.inertia(1, 1), 0.02);
  EXPECT_DOUBLE_EQ(b.com.z(), 0.1);
}

TEST_F(RobotLoader, ExtendsAndSet) {
  write("base.yaml", R"(robot: base
chains:
  c:
    tip: tool
    links:
      - {joint: j0, a: 0.1, limits_deg: [-90, 90]}
      - {joint: j1, d: 0.2, limits_deg: [-90, 90]}
)");
  write("derived.yaml", R"(extends: base.yaml
robot: derived
set:
  chains.c.links.1.d: 0.3
)");
  const RobotModel m = load_robot_model(dir_ / "derived.yaml");
  EXPECT_EQ(m.name(), "derived");
  const KinematicChain c = KinematicChain::named(m, "c");
  EXPECT_NEAR(c.forward(Eigen::Vector2d::Zero()).translation().z(), 0.3, 1e-15);
  write("bad.yaml", R"(extends: base.yaml
set:
  chains.c.links.5.d: 0.3
  chains.c.lnks.1.d: 0.3
  chains.c.links.1.alpha: 90
)");
  const std::string bad = (dir_ / "bad.yaml").string();
  const std::string base = (dir_ / "base.yaml").string();
  try {
    load_robot_model(dir_ / "bad.yaml");
    FAIL();
  } catch (const InputError& e) {
    // The unknown key is reported where it was written, in the derived file.
    EXPECT_EQ(std::string(e.what()),
              "3 errors:\n  " + bad +
                  ":3:3: key 'set.chains.c.links.5.d': 'chains.c.links' is a list of 2 items in " +
                  base + "; expected an index 0..1\n  " + bad +
                  ":4:3: key 'set.chains.c.lnks.1.d': no key 'chains.c.lnks' in " + base +
                  " (did you mean 'links'?)\n  " + bad +
                  ":5:27: chain 'c', key 'links[1].alpha': unknown key (did you mean "
                  "'alpha_deg'?); expected one of: joint, a, d, alpha_deg, offset_deg, "
                  "limits_deg, link");
  }
  write("loop.yaml", "extends: loop.yaml\n");
  try {
    load_robot_model(dir_ / "loop.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), (dir_ / "loop.yaml").string() +
                                         ":1:10: key 'extends': 'loop.yaml' extends itself "
                                         "(directly or through other files)");
  }
}

TEST_F(RobotLoader, IcubVariantsLoad) {
  for (const char* v : {"icub_v1", "icub_v1_7", "icub_v2"}) {
    const RobotModel m = test::load_icub(v);
    EXPECT_EQ(m.name(), v);
    EXPECT_EQ(m.num_dofs(), 23);
    EXPECT_EQ(m.chains().size(), 4u);
    EXPECT_EQ(m.cameras().size(), 2u);
    EXPECT_GT(m.total_mass(), 1.0);
  }
}

}  // namespace
}  // namespace somasim::robot
