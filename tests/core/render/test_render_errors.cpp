// Every error a user of somasim::render can meet, with its full message: no GL context, unknown
// camera or link names, image sizes of 0 or above the context's maximum, mesh files that do not
// load, and a frame in which an item in view draws nothing. (Bad intrinsics: test_camera.cpp;
// bad draw items and the bare "drew no pixel" check: test_scene_renderer.cpp; shader and GL
// errors: test_gl_objects.cpp; hypothesis batches: test_hypothesis_batch.cpp.)
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include <unistd.h>

#include "somasim/error.hpp"
#include "somasim/render/context.hpp"
#include "somasim/render/gl_objects.hpp"
#include "somasim/render/robot_scene.hpp"
#include "somasim/render/scene_renderer.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_loader.hpp"

namespace render = somasim::render;
namespace robot = somasim::robot;
namespace fs = std::filesystem;
using somasim::InputError;
using somasim::RunError;

namespace {

std::shared_ptr<const robot::RobotModel> icub() {
  static const auto m =
      robot::load_robot_model_shared(SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml");
  return m;
}

std::vector<Eigen::Isometry3d> rest_poses(const robot::RobotModel& m) {
  robot::RobotData data(m);
  robot::forward_kinematics(m, data, Eigen::VectorXd::Zero(m.num_dofs()));
  return data.link_poses;
}

// The message of the E that `f` throws ("" and a failure when it throws none).
template <typename E, typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  ADD_FAILURE() << "nothing thrown";
  return "";
}

bool starts_with(const std::string& s, const std::string& prefix) {
  return s.rfind(prefix, 0) == 0;
}

// A folder of its own under the system's temporary folder, removed at the end.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("somasim_render_errors_" + std::string(info->name()) +
                                         "_" + std::to_string(::getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(path_ / name, std::ios::binary) << text;
    return path_ / name;
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// A one-link robot "r" whose root link is drawn with the mesh `file` (0.5 m ahead of its camera
// "eye", which looks along the root z axis).
robot::RobotModel one_mesh_robot(const TempDir& dir, const std::string& file) {
  return robot::parse_robot_model(
      "robot: r\n"
      "links:\n"
      "  root:\n"
      "    mass: 1\n"
      "    collision: [{type: sphere, radius: 0.01}]\n"
      "    visual: [{type: mesh, file: " +
          file +
          ", origin: {xyz: [0, 0, 0.5]}}]\n"
          "cameras:\n"
          "  eye: {link: root, fx: 100, fy: 100, cx: 32, cy: 24, width: 64, height: 48, "
          "near: 0.05, far: 10}\n",
      "robot.yaml", dir.path());
}

class RenderErrors : public ::testing::Test {
 protected:
  render::OsmesaContext context;
  render::SceneRenderer renderer{context.gl()};
};

}  // namespace

// --- no context ----------------------------------------------------------------------------

TEST(RenderContextErrors, ImpossibleGlVersionIsNamedAndTheThreadStaysUsable) {
  EXPECT_EQ(error_of<RunError>([] { render::OsmesaContext impossible(9, 9); }),
            "render: OSMesaCreateContextAttribs failed for an OpenGL 9.9 core-profile context "
            "(is Mesa's libOSMesa installed: Debian package libosmesa6?)");
  // The failed attempt does not hold the thread's one context.
  EXPECT_NO_THROW(render::OsmesaContext usable);
}

// --- unknown names ---------------------------------------------------------------------------

TEST(RenderNameErrors, UnknownCameraListsTheRobotsCameras) {
  EXPECT_EQ(
      error_of<InputError>([] { render::camera_for(*icub(), "left_eyes", rest_poses(*icub())); }),
      "camera 'left_eyes' is not in robot 'icub_v1' (cameras: left_eye, right_eye)");
}

TEST(RenderNameErrors, UnknownLinkSuggestsTheNearestName) {
  EXPECT_EQ(error_of<InputError>([] { render::link_mesh(*icub(), "r_forarm", 8); }),
            "robot 'icub_v1': unknown link 'r_forarm' (did you mean 'r_forearm'?)");
}

TEST(RenderNameErrors, LinkWithoutGeometryIsNamed) {
  TempDir dir;
  const robot::RobotModel r = robot::parse_robot_model(
      "robot: r\nlinks:\n  root: {mass: 1, collision: [{type: sphere, radius: 0.01}]}\n"
      "  tip: {mass: 0.1, inertia: [0.001, 0.001, 0.001, 0, 0, 0]}\n"
      "joints:\n  j: {type: fixed, parent: root, child: tip}\n",
      "robot.yaml", dir.path());
  EXPECT_EQ(error_of<InputError>([&] { render::link_mesh(r, "tip", 8); }),
            "robot 'r', link 'tip': no visual or collision geometry");
  EXPECT_EQ(
      error_of<InputError>([&] { render::link_mesh(r, "tip", 8, render::LinkShapes::kCollision); }),
      "robot 'r', link 'tip': no collision geometry");
  // The collision proxy of a link with both: its primitives only.
  const render::TriangleMesh proxy =
      render::link_mesh(*icub(), "r_forearm", 6, render::LinkShapes::kCollision);
  const render::TriangleMesh drawn = render::link_mesh(*icub(), "r_forearm", 6);
  EXPECT_GT(proxy.triangle_count(), 0u);
  EXPECT_LT(proxy.triangle_count(), drawn.triangle_count());  // the cover mesh is finer
}

// --- image size ------------------------------------------------------------------------------

TEST_F(RenderErrors, ImageSizeZeroIsNamedWithTheCamera) {
  const render::MeshHandle ball = renderer.upload(render::tessellate_sphere(0.05, 16));
  render::Camera cam = render::camera_for(*icub(), "left_eye", rest_poses(*icub()));
  cam.intrinsics.width = 0;
  EXPECT_EQ(error_of<InputError>([&] {
              renderer.render({{ball, {}, {1, 1, 1}, 1}}, cam);
            }),
            "camera 'left_eye': image size must be positive, got 0 x 240");
  // The framebuffer itself refuses it before any GL call.
  EXPECT_EQ(error_of<RunError>([&] { render::Framebuffer fb(context.gl(), 320, 0, "camera 'x'"); }),
            "camera 'x': image size 320 x 0 px: both sides must be at least 1 px");
}

TEST_F(RenderErrors, ImageSizeAboveTheMaximumIsNamedWithTheCameraAndTheMaximum) {
  const int max_side = render::max_framebuffer_side(context.gl());
  ASSERT_GE(max_side, 4096);  // what llvmpipe and every GL 3.3 GPU offer
  std::cout << "largest framebuffer side of this context: " << max_side << " px\n";
  EXPECT_EQ(
      error_of<RunError>(
          [&] { render::Framebuffer fb(context.gl(), max_side + 1, 240, "camera 'left_eye'"); }),
      "camera 'left_eye': image size " + std::to_string(max_side + 1) +
          " x 240 px is above the maximum of this OpenGL context: at most " +
          std::to_string(max_side) +
          " px per side (GL_MAX_TEXTURE_SIZE, GL_MAX_RENDERBUFFER_SIZE, GL_MAX_VIEWPORT_DIMS)");
  // Through the renderer: a camera of the robot with a huge image. The message names the
  // camera, the size asked and the maximum the context allows.
  const render::MeshHandle ball = renderer.upload(render::tessellate_sphere(0.05, 16));
  render::Camera cam = render::camera_for(*icub(), "right_eye", rest_poses(*icub()));
  cam.intrinsics.width = 2 * max_side;
  cam.intrinsics.cx = max_side;
  const std::string m = error_of<RunError>([&] {
    renderer.render({{ball, {}, {1, 1, 1}, 1}}, cam);
  });
  std::cout << m << "\n";
  EXPECT_TRUE(starts_with(m, "camera 'right_eye': ")) << m;
  EXPECT_NE(m.find(std::to_string(2 * max_side) + " x 240"), std::string::npos) << m;
  EXPECT_NE(m.find("at most "), std::string::npos) << m;
  EXPECT_NO_THROW(render::check_gl(context.gl(), "after the refused size"));
  // The renderer still works at a normal size.
  cam.intrinsics.width = 320;
  cam.intrinsics.cx = 160;
  EXPECT_NO_THROW(renderer.render({}, cam));
}

// --- mesh files ------------------------------------------------------------------------------

TEST_F(RenderErrors, GarbageMeshFileNamesTheRobotLinkFileAndAssimpsReason) {
  TempDir dir;
  const fs::path file = dir.write("hand.stl", std::string("\x7f\x01garbage, not a mesh\n", 21));
  const auto model = std::make_shared<const robot::RobotModel>(one_mesh_robot(dir, "hand.stl"));
  const std::string m = error_of<InputError>([&] { render::RobotScene scene(renderer, model); });
  std::cout << m << "\n";
  const std::string prefix =
      "robot 'r', link 'root', visual shape 0: mesh file '" + file.string() + "': ";
  EXPECT_TRUE(starts_with(m, prefix)) << m;
  // assimp's own reason follows, in brackets (or the loader's "holds no triangles").
  const std::string reason = m.substr(std::min(m.size(), prefix.size()));
  EXPECT_TRUE(reason == "holds no triangles" || (starts_with(reason, "cannot be read (") &&
                                                 reason.size() > 20 && reason.back() == ')'))
      << m;
  // The same through link_mesh().
  EXPECT_EQ(error_of<InputError>([&] { render::link_mesh(*model, "root", 8); }), m);
}

TEST_F(RenderErrors, EmptyMeshFileHoldsNoTriangles) {
  TempDir dir;
  const fs::path file = dir.write("empty.stl", "solid empty\nendsolid empty\n");
  const auto model = std::make_shared<const robot::RobotModel>(one_mesh_robot(dir, "empty.stl"));
  const std::string m = error_of<InputError>([&] { render::RobotScene scene(renderer, model); });
  std::cout << m << "\n";
  EXPECT_TRUE(
      starts_with(m, "robot 'r', link 'root', visual shape 0: mesh file '" + file.string() + "': "))
      << m;
}

TEST_F(RenderErrors, MeshFileRemovedAfterLoadingIsNamed) {
  TempDir dir;
  const fs::path file = dir.write("tri.obj", "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nf 1 2 3\n");
  const auto model = std::make_shared<const robot::RobotModel>(one_mesh_robot(dir, "tri.obj"));
  EXPECT_NO_THROW(render::RobotScene(renderer, model));
  fs::remove(file);
  const std::string m = error_of<InputError>([&] { render::RobotScene scene(renderer, model); });
  std::cout << m << "\n";
  const std::string prefix =
      "robot 'r', link 'root', visual shape 0: mesh file '" + file.string() + "': cannot be read (";
  EXPECT_TRUE(starts_with(m, prefix)) << m;
  EXPECT_NE(m.find(file.string(), prefix.size()), std::string::npos)
      << "assimp's reason names the file: " << m;
  EXPECT_EQ(m.back(), ')') << m;
}

// --- a frame that renders nothing ------------------------------------------------------------

TEST_F(RenderErrors, DegenerateLinkMeshInViewIsAnErrorNamingTheCamera) {
  TempDir dir;
  // One triangle whose corners lie on a line: it loads, projects into the image and covers
  // no pixel.
  dir.write("line.obj", "v -0.1 0 0\nv 0 0 0\nv 0.1 0 0\nf 1 2 3\n");
  const auto model = std::make_shared<const robot::RobotModel>(one_mesh_robot(dir, "line.obj"));
  render::RobotScene scene(renderer, model);
  const auto poses = rest_poses(*model);
  const render::Camera cam = render::camera_for(*model, "eye", poses);
  std::vector<render::DrawItem> items;
  scene.add_robot(poses, items);
  ASSERT_EQ(items.size(), 1u);
  EXPECT_EQ(error_of<RunError>([&] { renderer.render(items, cam); }),
            "camera 'eye': item 0 (id 1) projects into the image but drew no pixel");
}
