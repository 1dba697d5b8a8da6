#include "camera_plugin.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "backdrop.hpp"
#include "render_thread.hpp"
#include "somasim/error.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/kinematics.hpp"

namespace somasim::plugins {
namespace {

std::vector<std::string> words(const std::string& text) {
  std::string s = text;
  for (char& c : s)
    if (c == ',') c = ' ';
  std::istringstream in(s);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

}  // namespace

template <class V>
void CameraPlugin::Config::visit(V& v) {
  v.block(robot);
  v.field("cameras", cameras)
      .doc(
          "1 or 2 cameras of the robot model; the first feeds the ports left_eye_*, the second "
          "right_eye_*");
  v.field("outputs", outputs)
      .one_of({kRgb, kDepth, kMask})
      .doc("images to render (the others stay empty)");
  v.field("background", background)
      .doc(
          "'R G B' in [0, 1], a name (black, white, grey, blue) or 'textured': clutter "
          "(rectangles and bars of random colours from the node's random stream) on a plane "
          "1.2 m in front of the first camera at q = 0");
  v.field("resolution", resolution)
      .range(3, 256)
      .doc("segments around curved primitives (spheres, cylinders, capsules)");
  v.field("backend", backend)
      .doc(
          "where the OpenGL context comes from: osmesa (Mesa's llvmpipe, software) or egl "
          "(EGL's surfaceless platform: the node's GPU through Mesa, else llvmpipe; needs "
          "libegl-mesa0); camera nodes on one thread share one context and so one backend");
  v.field("save_every", save_every)
      .at_least(0)
      .doc(
          "write every N-th frame's images as PNG under frames/NODE.PORT/ in the run folder "
          "(encodings as when recorded: somasim/render/ports.hpp); 0 = never");
  v.field("sheet_times", sheet_times)
      .max_size(64)
      .doc(
          "[s] sim times of the rows of the contact sheet figures/stereo_frames.png (the RGB "
          "views side by side); empty = no sheet");
}

template <class V>
void CameraPlugin::Ports::visit(V& v) {
  v.port("link_poses", link_poses,
         "poses of all robot links (root frame): world.link_poses for the true eyes, "
         "believed link poses for believed eye kinematics; empty = q = 0");
  v.port("objects", objects, "the world's objects (drawn with their shapes)");
  for (std::size_t i = 0; i < kSlots.size(); ++i) {
    const std::string slot = kSlots[i];
    v.port(slot + "_" + kRgb, rgb[i], "rgb8 view of that camera (somasim/render/ports.hpp)");
    v.port(slot + "_" + kDepth, depth[i], "depth32f [m] along the optical axis");
    v.port(slot + "_" + kMask, mask[i], "id32s: what each pixel shows");
  }
}

PluginSpec CameraPlugin::spec() {
  return make_plugin_spec<Config, Ports>(
      "camera",
      "The robot's eyes: renders the views of the robot model's cameras (OSMesa or "
      "EGL, Lambert + ambient shading) from the world's link and object poses: RGB, metric "
      "depth and id masks (link i -> i + 1, object k -> 1000 + k, backdrop 60000).");
}

void CameraPlugin::parse_background(NodeContext& ctx) {
  const std::string text = config_.background;
  if (text == "textured") return;  // backdrop items made once the scene exists
  const std::vector<std::string> w = words(text);
  if (w.size() == 1) {
    if (w[0] == "black") return void(options_.background = {0.f, 0.f, 0.f});
    if (w[0] == "white") return void(options_.background = {1.f, 1.f, 1.f});
    if (w[0] == "grey" || w[0] == "gray") return void(options_.background = {0.5f, 0.5f, 0.5f});
    if (w[0] == "blue") return void(options_.background = {0.35f, 0.45f, 0.55f});
  }
  bool ok = w.size() == 3;
  for (int i = 0; ok && i < 3; ++i) {
    try {
      std::size_t used = 0;
      const double v = std::stod(w[i], &used);
      ok = used == w[i].size() && v >= 0.0 && v <= 1.0;
      options_.background[i] = static_cast<float>(v);
    } catch (const std::exception&) {
      ok = false;
    }
  }
  if (!ok)
    config_error(ctx, config_, config_.background,
                 fmt::format("expected 'R G B' (three numbers in [0, 1]), black, white, grey, "
                             "blue or textured, got '{}'",
                             text));
}

void CameraPlugin::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  bind_ports(ctx, ports_);
  model_ = robot::experiment_robot(ctx, config_.robot);
  const auto wants = [&](const char* kind) {
    return std::find(config_.outputs.begin(), config_.outputs.end(), kind) != config_.outputs.end();
  };
  want_rgb_ = wants(kRgb);
  want_depth_ = wants(kDepth);
  want_mask_ = wants(kMask);
  const auto cameras = config_.cameras;
  if (cameras.empty() || cameras.size() > kSlots.size())
    config_error(ctx, config_, config_.cameras,
                 fmt::format("expected 1 or 2 camera names (ports left_eye_*, "
                             "right_eye_*), got {}",
                             cameras.size()));
  robot::RobotData rest(*model_);
  robot::forward_kinematics(*model_, rest, Eigen::VectorXd::Zero(model_->num_dofs()));
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    try {
      render::camera_for(*model_, cameras[i], rest.link_poses);
    } catch (const InputError& e) {
      config_error(ctx, config_, config_.cameras, e.what());
    }
    View v;
    v.camera = cameras[i];
    v.slot = kSlots[i];
    v.rgb = &ports_.rgb[i].get();
    v.depth = &ports_.depth[i].get();
    v.mask = &ports_.mask[i].get();
    views_.push_back(v);
  }
  parse_background(ctx);
  if (!config_.sheet_times.empty() && !want_rgb_)
    config_error(ctx, config_, config_.sheet_times,
                 "the contact sheet needs the rgb output (outputs: rgb ...)");
  options_.check_drawn = true;  // an item in view that draws nothing is an error (never blank)
  options_.light_direction_root = Eigen::Vector3d(0.7, 0.2, 1.0);  // above, behind the eyes
  choose_images(ctx);

  const render::RenderBackend backend = config_.backend;
  const std::string backend_name = render::render_backend_name(backend);
  bool created = false;
  context_ = thread_render_context(backend, created);
  if (context_->backend() != backend)
    config_error(ctx, config_, config_.backend,
                 fmt::format("'{}', but another camera node on this thread already renders with "
                             "'{}' (one OpenGL context per thread: give the camera nodes of a "
                             "thread the same backend)",
                             backend_name, render::render_backend_name(context_->backend())));
  if (created)
    ctx.log().info("camera: OpenGL renderer '{}', version '{}' (backend {})", context_->renderer(),
                   context_->version(), backend_name);
  renderer_ = std::make_unique<render::SceneRenderer>(context_->gl());
  render::RobotSceneOptions scene_options;
  scene_options.segments = config_.resolution;
  scene_ = std::make_unique<render::RobotScene>(*renderer_, model_, scene_options);
  if (config_.background == "textured") {
    const render::Camera first = render::camera_for(*model_, cameras[0], rest.link_poses);
    const Eigen::Vector3d forward = first.pose_root.linear().col(2);
    BackdropSpec spec;
    spec.centre_root = first.pose_root.translation() + 1.2 * forward;
    spec.normal_root = -forward;
    spec.id = render::kFirstSceneExtraId;
    backdrop_ = make_backdrop(*renderer_, spec, ctx.rng());
  }
  std::string read;
  for (const View& v : views_)
    read += fmt::format(" {}:{}{}{}", v.slot, v.options.read_rgb ? " rgb" : "",
                        v.options.read_depth ? " depth" : "", v.options.read_ids ? " mask" : "");
  ctx.log().info("camera: {} view(s) of robot '{}' ({} triangles), outputs{}{}{}; read:{}",
                 views_.size(), model_->name(), scene_->triangle_count(), want_rgb_ ? " rgb" : "",
                 want_depth_ ? " depth" : "", want_mask_ ? " mask" : "", read);
  link_poses_ = &ports_.link_poses.get();
  objects_ = ports_.objects.get();
  rest_poses_ = rest.link_poses;
}

void CameraPlugin::choose_images(const NodeContext& ctx) {
  const bool saving = config_.save_every > 0;
  const bool sheet = !config_.sheet_times.empty();
  for (View& v : views_) {
    const auto read = [&](const char* kind) { return ctx.is_read(v.slot + "_" + kind) || saving; };
    v.options = options_;
    v.options.read_rgb = want_rgb_ && (read(kRgb) || sheet);
    v.options.read_depth = want_depth_ && read(kDepth);
    v.options.read_ids = want_mask_ && read(kMask);
    v.rendered = v.options.read_rgb || v.options.read_depth || v.options.read_ids;
  }
}

void CameraPlugin::step(NodeContext& ctx) {
  const auto& poses = link_poses_->poses.empty() ? rest_poses_ : link_poses_->poses;
  ++frame_;
  const bool sheet_row = sheet_.size() < config_.sheet_times.size() &&
                         ctx.time_s() + 1e-9 >= config_.sheet_times[sheet_.size()];
  if (sheet_row) sheet_.push_back({ctx.time_s(), {}});
  for (const View& v : views_) {
    if (!v.rendered) continue;
    const render::Camera camera = render::camera_for(*model_, v.camera, poses);
    const Eigen::Vector3d viewpoint = camera.pose_root.translation();
    items_.clear();
    scene_->add_robot(poses, items_, &viewpoint);
    if (objects_) scene_->add_objects(*objects_, items_);
    items_.insert(items_.end(), backdrop_.begin(), backdrop_.end());
    render::RenderedImages images = renderer_->render(items_, camera, v.options);
    ++views_rendered_;
    auto fill = [&](Image* out, cv::Mat data, ImageEncoding encoding) {
      out->data = std::move(data);
      out->encoding = encoding;
      out->camera = v.camera;
      out->time_s = ctx.time_s();
      out->frame = frame_;
    };
    if (v.options.read_rgb) fill(v.rgb, images.rgb, ImageEncoding::kRgb8);
    if (v.options.read_depth) fill(v.depth, images.depth, ImageEncoding::kDepth32f);
    if (v.options.read_ids) fill(v.mask, images.ids, ImageEncoding::kId32s);
    if (config_.save_every > 0 &&
        (frame_ - 1) % static_cast<std::uint64_t>(config_.save_every) == 0)
      save_frames(ctx, v);
    if (sheet_row) sheet_.back().views.push_back(images.rgb.clone());
  }
}

void CameraPlugin::save_frames(NodeContext& ctx, const View& view) {
  for (const auto& [image, kind] :
       {std::pair{view.rgb, kRgb}, std::pair{view.depth, kDepth}, std::pair{view.mask, kMask}}) {
    if (image->frame != frame_) continue;
    const std::string folder = fmt::format("frames/{}.{}_{}", ctx.node_name(), view.slot, kind);
    const std::string file = fmt::format("{:06d}.png", frame_);
    render::write_png(*image, ctx.output_path(folder + "/" + file));
    // index.csv beside the images: which frame, at what simulated time, in which file.
    const std::filesystem::path index = ctx.output_path(folder + "/index.csv");
    const bool fresh = !std::filesystem::exists(index);
    std::ofstream out(index, std::ios::app);
    if (fresh) out << "time [s],frame,file\n";
    out << fmt::format("{},{},{}\n", image->time_s, frame_, file);
    if (!out) throw RunError("cannot write " + index.string());
  }
}

void CameraPlugin::finish(NodeContext& ctx) {
  ctx.report_metric("frames", frame_);
  ctx.report_metric("views_rendered", views_rendered_);
  if (!sheet_.empty()) {
    std::vector<std::string> names;
    for (const View& v : views_) names.push_back(v.camera);
    if (sheet_.back().views.size() < views_.size()) sheet_.pop_back();  // interrupted row
    write_contact_sheet(sheet_, names, ctx.figure_path("stereo_frames.png"));
  }
  // GL objects before the context (all on this thread).
  scene_.reset();
  renderer_.reset();
  context_.reset();
}

}  // namespace somasim::plugins
