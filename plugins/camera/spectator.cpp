#include "spectator.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <unordered_map>

#include <fmt/format.h>

#include "render_thread.hpp"
#include "somasim/render/tessellate.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/units.hpp"

namespace somasim::plugins {

template <class V>
void Spectator::Config::visit(V& v) {
  v.block(robot);
  v.field("position", position).unit("m").size(3).range(-100, 100).doc("the viewpoint, root frame");
  v.field("look_at", look_at)
      .unit("m")
      .size(3)
      .range(-100, 100)
      .doc("the point at the image centre, root frame (the image's up is the root's +z)");
  v.field("fov_deg", fov_deg).unit("deg").range(5, 150).doc("horizontal field of view");
  v.field("width", width).range(16, 4096).doc("image width [px]");
  v.field("height", height).range(16, 4096).doc("image height [px]");
  v.field("taxel_radius", taxel_radius)
      .unit("m")
      .range(0.0005, 0.05)
      .doc("radius of the sphere drawn at each taxel");
  v.field("taxel_segments", taxel_segments)
      .range(4, 64)
      .doc(
          "segments around each taxel's sphere (segments² / 2 triangles; 4, an octahedron, is "
          "enough for taxels a few pixels across and draws a quarter of the triangles of 8)");
  v.field("resolution", resolution)
      .range(3, 256)
      .doc("segments around the robot's curved primitives (spheres, cylinders, capsules)");
  v.field("backend", backend).doc("OpenGL back end (as the camera's)");
  v.field("asynchronous", asynchronous)
      .doc(
          "render on a thread of its own, overlapping the simulation: the image published at a "
          "step is the frame of the spectator's previous step (its time_s is that frame's), so "
          "a recorded video holds the same frames except the run's last");
}

template <class V>
void Spectator::Ports::visit(V& v) {
  v.port("link_poses", link_poses, "link poses of the robot (root frame)");
  v.port("objects", objects, "the world's objects (drawn with their shapes)");
  v.port("taxels", taxels, "skin taxels (root frame), drawn as small spheres");
  v.port("taxel_values", taxel_values,
         "a value in [0, 1] per taxel by label \"part/id\" (e.g. pps_learner's activations), "
         "as the taxels' colour: grey at 0 through red to yellow at 1");
  v.port("rgb", rgb, "rgb8 view (somasim/render/ports.hpp)");
}

PluginSpec Spectator::spec() {
  return make_plugin_spec<Config, Ports>(
      "spectator",
      "A third-person view of the run: the robot, the objects and the skin's taxels coloured by "
      "a per-taxel value (e.g. PPS activation), from a fixed viewpoint; record it as a video.");
}

Eigen::Vector3f Spectator::taxel_colour(double value) {
  if (!std::isfinite(value)) return {0.5f, 0.5f, 0.5f};
  const float t = static_cast<float>(std::clamp(value, 0.0, 1.0));
  const Eigen::Vector3f low(0.25f, 0.25f, 0.3f), mid(0.95f, 0.15f, 0.05f), high(1.0f, 0.9f, 0.1f);
  return t < 0.5f ? Eigen::Vector3f(low + (mid - low) * (2 * t))
                  : Eigen::Vector3f(mid + (high - mid) * (2 * t - 1));
}

void Spectator::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  bind_ports(ctx, ports_);
  model_ = robot::experiment_robot(ctx, config_.robot);
  const Eigen::Vector3d eye(config_.position[0], config_.position[1], config_.position[2]);
  const Eigen::Vector3d target(config_.look_at[0], config_.look_at[1], config_.look_at[2]);
  const Eigen::Vector3d forward = target - eye;
  if (forward.norm() < 1e-6)
    config_error(ctx, config_, config_.look_at, "is the viewpoint itself; look elsewhere");
  const Eigen::Vector3d z = forward.normalized();
  const Eigen::Vector3d right = z.cross(Eigen::Vector3d::UnitZ());
  if (right.norm() < 1e-6)
    config_error(ctx, config_, config_.look_at,
                 "is straight above or below the viewpoint (the image's up is +z); tilt the view");
  Eigen::Matrix3d axes;
  axes.col(0) = right.normalized();    // x: right in the image
  axes.col(2) = z;                     // z: forward
  axes.col(1) = z.cross(axes.col(0));  // y: down in the image
  camera_.name = ctx.node_name();
  camera_.pose_root.linear() = axes;
  camera_.pose_root.translation() = eye;
  auto& in = camera_.intrinsics;
  in.width = config_.width;
  in.height = config_.height;
  in.fx = in.fy = 0.5 * config_.width / std::tan(0.5 * deg_to_rad(config_.fov_deg));
  in.cx = 0.5 * (config_.width - 1);
  in.cy = 0.5 * (config_.height - 1);
  in.near = 0.02;
  in.far = 50.0;

  options_.background = {0.93f, 0.94f, 0.96f};
  options_.read_depth = false;
  options_.read_ids = false;
  options_.check_drawn = false;  // taxels far away may cover no pixel
  options_.light_direction_root = (eye - target).normalized() + Eigen::Vector3d(0, 0, 1.0);
  robot::RobotData rest(*model_);
  robot::forward_kinematics(*model_, rest, Eigen::VectorXd::Zero(model_->num_dofs()));
  rest_poses_ = rest.link_poses;
  if (config_.asynchronous) {
    worker_ = std::make_unique<RenderWorker>(config_.backend);
    worker_->submit([this](render::RenderContext& context) { make_gl_objects(context); });
    worker_->wait();
    return;
  }
  bool created = false;
  context_ = thread_render_context(config_.backend, created);
  if (context_->backend() != config_.backend)
    config_error(ctx, config_, config_.backend,
                 fmt::format("'{}', but another rendering node on this thread already uses "
                             "'{}' (one OpenGL context per thread)",
                             render::render_backend_name(config_.backend),
                             render::render_backend_name(context_->backend())));
  make_gl_objects(*context_);
}

void Spectator::make_gl_objects(render::RenderContext& context) {
  renderer_ = std::make_unique<render::SceneRenderer>(context.gl());
  render::RobotSceneOptions scene_options;
  scene_options.segments = config_.resolution;
  scene_ = std::make_unique<render::RobotScene>(*renderer_, model_, scene_options);
  taxel_mesh_ =
      renderer_->upload(render::tessellate_sphere(config_.taxel_radius, config_.taxel_segments));
}

Spectator::~Spectator() {
  if (!worker_) return;
  try {
    end_worker();
  } catch (...) {  // NOLINT(bugprone-empty-catch): a destructor cannot report; finish() does
  }
}

void Spectator::end_worker() {
  std::exception_ptr frame_error;
  try {
    worker_->wait();
  } catch (...) {
    frame_error = std::current_exception();
  }
  // The GL objects end on the thread of their context.
  worker_->submit([this](render::RenderContext&) {
    scene_.reset();
    renderer_.reset();
  });
  worker_->wait();
  worker_.reset();
  if (frame_error) std::rethrow_exception(frame_error);
}

void Spectator::add_taxels(const SkinTaxels* taxels, const TaxelValues* taxel_values,
                           std::vector<render::DrawItem>& items) const {
  if (!taxels) return;
  std::unordered_map<std::string, double> values;
  if (const TaxelValues* v = taxel_values)
    for (std::size_t i = 0; i < v->labels.size() && i < v->values.size(); ++i)
      values.emplace(v->labels[i], v->values[i]);
  std::int32_t id = render::kFirstSceneExtraId;
  for (const SkinPart& part : taxels->parts)
    for (std::size_t i = 0; i < part.positions.size(); ++i) {
      render::DrawItem item;
      item.mesh = taxel_mesh_;
      // Half out of the skin along its normal, so that the surface does not hide it.
      Eigen::Vector3d at = part.positions[i];
      if (i < part.normals.size()) at += 0.5 * config_.taxel_radius * part.normals[i];
      item.pose_root.translation() = at;
      double value = 0.0;
      if (!values.empty() && i < part.taxel_ids.size()) {
        const auto it = values.find(fmt::format("{}/{}", part.name, part.taxel_ids[i]));
        value = it == values.end() ? std::nan("") : it->second;
      }
      item.colour = taxel_colour(value);
      item.id = id++;
      items.push_back(item);
    }
}

Spectator::Inputs Spectator::copy_inputs() const {
  Inputs in;
  in.link_poses = ports_.link_poses->poses.empty() ? rest_poses_ : ports_.link_poses->poses;
  if (const ObjectStates* objects = ports_.objects.get()) in.objects = *objects;
  if (const SkinTaxels* taxels = ports_.taxels.get()) in.taxels = *taxels;
  if (const TaxelValues* values = ports_.taxel_values.get()) in.taxel_values = *values;
  return in;
}

std::vector<render::DrawItem> Spectator::draw_items(const Inputs& in) {
  std::vector<render::DrawItem> items;
  scene_->add_robot(in.link_poses, items);
  if (in.objects) scene_->add_objects(*in.objects, items);
  add_taxels(in.taxels ? &*in.taxels : nullptr, in.taxel_values ? &*in.taxel_values : nullptr,
             items);
  return items;
}

void Spectator::publish(cv::Mat rgb, double time_s, NodeContext& ctx) {
  Image& out = *ports_.rgb;
  out.data = std::move(rgb);
  out.encoding = ImageEncoding::kRgb8;
  out.camera = ctx.node_name();
  out.time_s = time_s;
  out.frame = ++frame_;
}

void Spectator::step(NodeContext& ctx) {
  if (!worker_) {
    publish(renderer_->render(draw_items(copy_inputs()), camera_, options_).rgb, ctx.time_s(), ctx);
    return;
  }
  if (pending_) {
    worker_->wait();  // rethrows the frame's rendering error
    publish(std::move(pending_rgb_), pending_time_s_, ctx);
    pending_ = false;
  }
  // Items are made on the render thread: new object shapes upload meshes to its context.
  worker_->submit([this, in = copy_inputs()](render::RenderContext&) {
    pending_rgb_ = renderer_->render(draw_items(in), camera_, options_).rgb;
  });
  pending_time_s_ = ctx.time_s();
  pending_ = true;
}

void Spectator::finish(NodeContext& ctx) {
  if (worker_) end_worker();
  ctx.report_metric("frames", frame_);
  scene_.reset();
  renderer_.reset();
  context_.reset();
}

}  // namespace somasim::plugins
