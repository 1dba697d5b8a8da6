// One 320 x 240 view of the iCub upper body (assets/robots/icub_v1.yaml, the robot of
// configs/camera_demo.yaml: its arm posture, the right hand raised in front of the eyes) from the
// left eye posed by camera_for, through SceneRenderer + RobotScene at the camera plugin's
// resolution (24 segments), plain background.
//
// BM_RenderView: render + RGB read-back (the "drew no pixel" check off), then variants that add
// the check (as the camera plugin runs it), the depth read-back, the id read-back, and all of
// them (camera_demo's outputs). Counter fps = frames per second of wall time.
// Baseline in the same run, BM_TrivialShaderBaseline: the same triangles (the same meshes,
// uploaded in RobotScene's order, drawn with the same poses) into the same kind of framebuffer,
// with clear + depth test + draw + RGB read-back, by a position-only, constant-colour shader.
// BM_RenderViewOverBaseline alternates the two in one loop and reports their ratio.
#include <benchmark/benchmark.h>

#include <array>
#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "somasim/render/context.hpp"
#include "somasim/render/gl_objects.hpp"
#include "somasim/render/robot_scene.hpp"
#include "somasim/render/scene_renderer.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/units.hpp"

namespace render = somasim::render;
namespace robot = somasim::robot;

namespace {

constexpr int kSegments = 24;  // the camera plugin's `resolution` in configs/camera_demo.yaml

std::shared_ptr<const robot::RobotModel> icub() {
  static const auto model =
      robot::load_robot_model_shared(SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml");
  return model;
}

// configs/camera_demo.yaml's initial posture with the right hand at its first target (in front
// of the eyes); other joints at 0.
std::vector<Eigen::Isometry3d> link_poses() {
  const std::map<std::string, double> posture_deg = {
      {"l_shoulder_pitch", -40}, {"l_shoulder_roll", 40}, {"l_shoulder_yaw", 10}, {"l_elbow", 60},
      {"r_shoulder_pitch", -90}, {"r_shoulder_roll", 5},  {"r_shoulder_yaw", 25}, {"r_elbow", 40}};
  const robot::RobotModel& model = *icub();
  robot::RobotData data(model);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.num_dofs());
  for (const auto& [joint, deg] : posture_deg) q[model.dof_index(joint)] = somasim::deg_to_rad(deg);
  robot::forward_kinematics(model, data, q);
  return data.link_poses;
}

// The scene of the left eye: renderer, robot scene, camera and draw items.
struct View {
  std::unique_ptr<render::RenderContext> context;
  render::SceneRenderer renderer;
  render::RobotScene scene{renderer, icub(), {kSegments}};
  render::Camera camera;
  std::vector<render::DrawItem> items;

  explicit View(render::RenderBackend backend = render::RenderBackend::kOsmesa)
      : context(render::make_render_context(backend)), renderer(context->gl()) {
    const std::vector<Eigen::Isometry3d> poses = link_poses();
    camera = render::camera_for(*icub(), "left_eye", poses);
    const Eigen::Vector3d viewpoint = camera.pose_root.translation();
    scene.add_robot(poses, items, &viewpoint);
  }
};

void report(benchmark::State& state, const View& view) {
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["triangles"] = static_cast<double>(view.scene.triangle_count());
  state.counters["items"] = static_cast<double>(view.items.size());
}

void BM_RenderView(benchmark::State& state) {
  // egl = 1: through EGL (a hardware EGL device where the machine has one, else llvmpipe).
  View view(state.range(3) != 0 ? render::RenderBackend::kEgl : render::RenderBackend::kOsmesa);
  render::RenderOptions options;
  options.read_rgb = true;
  options.check_drawn = state.range(0) != 0;
  options.read_depth = state.range(1) != 0;
  options.read_ids = state.range(2) != 0;
  // Robot pixels in the view (a sanity figure: the robot fills part of the image).
  render::RenderOptions ids_only;
  ids_only.read_rgb = ids_only.read_depth = false;
  const cv::Mat ids = view.renderer.render(view.items, view.camera, ids_only).ids;
  state.counters["robot_px"] = cv::countNonZero(ids);
  for (auto _ : state)
    benchmark::DoNotOptimize(view.renderer.render(view.items, view.camera, options));
  report(state, view);
}
BENCHMARK(BM_RenderView)
    ->ArgNames({"check", "depth", "ids", "egl"})
    ->Args({0, 0, 0, 0})
    ->Args({1, 0, 0, 0})
    ->Args({0, 1, 0, 0})
    ->Args({0, 0, 1, 0})
    ->Args({1, 1, 1, 0})
    ->Args({0, 0, 0, 1})
    ->Args({1, 1, 1, 1})
    ->UseRealTime();

constexpr const char* kTrivialVertex = R"(#version 330 core
uniform mat4 mvp;
in vec3 position;
void main() {
  gl_Position = mvp * vec4(position, 1.0);
}
)";

constexpr const char* kTrivialFragment = R"(#version 330 core
out vec4 out_colour;
void main() {
  out_colour = vec4(0.8, 0.8, 0.8, 1.0);
}
)";

// The meshes of RobotScene, in its upload order (so that item.mesh.index picks the same mesh).
std::vector<render::TriangleMesh> scene_meshes(const robot::RobotModel& model) {
  std::vector<render::TriangleMesh> meshes;
  for (int i = 0; i < model.num_links(); ++i) {
    const robot::Link& link = model.link(i);
    for (const robot::Geometry& g : link.visual.empty() ? link.collision : link.visual)
      meshes.push_back(render::geometry_mesh(g, kSegments));
  }
  return meshes;
}

// Clear + draw + RGB read-back of a View's items with the trivial shader, in its own
// framebuffer of the same kind as SceneRenderer's, on the View's context.
class TrivialFrame {
 public:
  explicit TrivialFrame(const View& view)
      : gl_(view.context->gl()),
        program_(gl_, "bench: trivial shader", kTrivialVertex, kTrivialFragment),
        framebuffer_(gl_, view.camera.intrinsics.width, view.camera.intrinsics.height,
                     "bench: baseline"),
        rgb_(view.camera.intrinsics.height, view.camera.intrinsics.width, CV_8UC3) {
    for (const render::TriangleMesh& mesh : scene_meshes(*icub()))
      buffers_.emplace_back(gl_, mesh, "bench: baseline mesh");
    u_mvp_ = program_.uniform("mvp");
    const Eigen::Matrix4d view_projection = view.camera.view_projection();
    for (const render::DrawItem& item : view.items) {
      mvp_.push_back((view_projection * item.pose_root.matrix()).cast<float>());
      mesh_.push_back(item.mesh.index);
    }
  }
  /// The same meshes as the View's RobotScene uploaded (same count).
  std::size_t mesh_count() const { return buffers_.size(); }

  const cv::Mat& draw() {
    const std::array<GLfloat, 4> background = {0.0f, 0.0f, 0.0f, 1.0f};
    const GLfloat far_depth = 1.0f;
    framebuffer_.bind();
    gl_.Enable(GL_DEPTH_TEST);
    gl_.DepthFunc(GL_LESS);
    gl_.ClearBufferfv(GL_COLOR, 0, background.data());
    gl_.ClearBufferfv(GL_DEPTH, 0, &far_depth);
    program_.use();
    for (std::size_t i = 0; i < mvp_.size(); ++i) {
      gl_.UniformMatrix4fv(u_mvp_, 1, GL_FALSE, mvp_[i].data());
      buffers_[mesh_[i]].draw();
    }
    gl_.BindVertexArray(0);
    gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl_.ReadPixels(0, 0, rgb_.cols, rgb_.rows, GL_RGB, GL_UNSIGNED_BYTE, rgb_.data);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
    render::check_gl(gl_, "bench: baseline frame");
    return rgb_;
  }

 private:
  const render::GlApi& gl_;
  render::ShaderProgram program_;
  GLint u_mvp_ = -1;
  render::Framebuffer framebuffer_;
  std::vector<render::MeshBuffer> buffers_;
  std::vector<Eigen::Matrix4f> mvp_;
  std::vector<std::size_t> mesh_;
  cv::Mat rgb_;
};

void BM_TrivialShaderBaseline(benchmark::State& state) {
  View view;
  TrivialFrame baseline(view);
  if (baseline.mesh_count() != view.renderer.mesh_count()) {
    state.SkipWithError("the baseline's meshes do not match RobotScene's");
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(baseline.draw().data);
  report(state, view);
}
BENCHMARK(BM_TrivialShaderBaseline)->UseRealTime();

// Render + RGB read-back and the baseline in alternation on the same context, so that the
// machine's load falls on both alike: the time is the render's; counters fps and baseline_fps
// (from the sums over all iterations) and ratio = render time / baseline time.
void BM_RenderViewOverBaseline(benchmark::State& state) {
  View view;
  TrivialFrame baseline(view);
  render::RenderOptions options;
  options.read_depth = options.read_ids = options.check_drawn = false;
  using Clock = std::chrono::steady_clock;
  double render_s = 0.0, baseline_s = 0.0;
  for (auto _ : state) {
    const Clock::time_point t0 = Clock::now();
    benchmark::DoNotOptimize(baseline.draw().data);
    const Clock::time_point t1 = Clock::now();
    benchmark::DoNotOptimize(view.renderer.render(view.items, view.camera, options));
    const Clock::time_point t2 = Clock::now();
    baseline_s += std::chrono::duration<double>(t1 - t0).count();
    const double s = std::chrono::duration<double>(t2 - t1).count();
    render_s += s;
    state.SetIterationTime(s);
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["fps"] = render_s > 0.0 ? n / render_s : 0.0;
  state.counters["baseline_fps"] = baseline_s > 0.0 ? n / baseline_s : 0.0;
  state.counters["ratio"] = baseline_s > 0.0 ? render_s / baseline_s : 0.0;
}
BENCHMARK(BM_RenderViewOverBaseline)->UseManualTime();

}  // namespace
