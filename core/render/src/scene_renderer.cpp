#include "somasim/render/scene_renderer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>

#include "somasim/error.hpp"
#include "subpixel_snap.hpp"

namespace somasim::render {

namespace {

// The position is snapped to the rasterizer's sub-pixel grid exactly as the hypothesis tiler's
// shader does (subpixel_snap.hpp), so that tiles equal crops of these images pixel for pixel.
std::string vertex_shader() {
  return std::string("#version 330 core\n") + kSubpixelSnapGlsl + R"(
uniform mat4 mvp;
in vec3 position;
in vec3 normal;
out vec3 v_normal;
void main() {
  v_normal = normal;
  gl_Position = snap_to_subpixel_grid(mvp * vec4(position, 1.0));
}
)";
}

// light_dir is the unit direction towards the light in the mesh frame, so the normal needs no
// transformation.
constexpr const char* kFragmentShader = R"(#version 330 core
uniform vec3 light_dir;
uniform vec3 albedo;
uniform float ambient;
uniform int id;
in vec3 v_normal;
out vec4 out_colour;
out int out_id;
void main() {
  float lambert = max(dot(normalize(v_normal), light_dir), 0.0);
  out_colour = vec4(albedo * (ambient + (1.0 - ambient) * lambert), 1.0);
  out_id = id;
}
)";

std::string owner_of(const Camera& camera) {
  return fmt::format("camera '{}'", camera.name);
}

}  // namespace

SceneRenderer::SceneRenderer(const GlApi& gl)
    : gl_(&gl), program_(gl, "render: scene shader", vertex_shader(), kFragmentShader) {
  u_mvp_ = program_.uniform("mvp");
  const SnapUniforms snap = SnapUniforms::of(program_);
  u_snap_image_ = snap.image;
  u_snap_ndc_per_px_ = snap.ndc_per_px;
  largest_viewport_ = largest_viewport_side(gl);
  u_light_ = program_.uniform("light_dir");
  u_albedo_ = program_.uniform("albedo");
  u_ambient_ = program_.uniform("ambient");
  u_id_ = program_.uniform("id");
  gl.GenQueries(1, &query_);
  check_gl(gl, "render: creating the scene renderer");
}

SceneRenderer::~SceneRenderer() {
  if (query_ != 0) gl_->DeleteQueries(1, &query_);
}

MeshHandle SceneRenderer::upload(const TriangleMesh& mesh) {
  meshes_.emplace_back(*gl_, mesh, fmt::format("render: mesh {}", meshes_.size()));
  vertices_.push_back(mesh.positions);
  return MeshHandle{meshes_.size() - 1};
}

RenderedImages SceneRenderer::render(const std::vector<DrawItem>& items, const Camera& camera,
                                     const RenderOptions& options) {
  const GlApi& gl = *gl_;
  const PinholeIntrinsics& k = camera.intrinsics;
  validate(k, camera.name);
  const std::string owner = owner_of(camera);
  if (!camera.pose_root.matrix().allFinite())
    throw RunError(fmt::format("{}: the camera pose is not finite", owner));
  for (std::size_t i = 0; i < items.size(); ++i) {
    const DrawItem& item = items[i];
    if (item.mesh.index >= meshes_.size())
      throw RunError(fmt::format("{}: item {} refers to mesh {}, but {} meshes were uploaded",
                                 owner, i, item.mesh.index, meshes_.size()));
    if (item.id == 0)
      throw RunError(fmt::format("{}: item {} has id 0, which is the background", owner, i));
    if (!item.pose_root.matrix().allFinite())
      throw RunError(fmt::format("{}: item {} (id {}) has a non-finite pose", owner, i, item.id));
  }

  const SnapViewport snap = snap_viewport(k, largest_viewport_, owner);

  check_gl(gl, fmt::format("{}: before rendering", owner));
  if (!framebuffer_ || framebuffer_->width() != k.width || framebuffer_->height() != k.height) {
    framebuffer_.reset();
    framebuffer_.emplace(gl, k.width, k.height, owner);
  }
  framebuffer_->bind();
  set_snap_viewport(gl, snap, 0, 0);
  draw_items(items, camera, options, snap);
  check_gl(gl, fmt::format("{}: drawing {} items", owner, items.size()));

  RenderedImages out;
  gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  if (options.read_rgb) {
    out.rgb.create(k.height, k.width, CV_8UC3);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl.ReadPixels(0, 0, k.width, k.height, GL_RGB, GL_UNSIGNED_BYTE, out.rgb.data);
  }
  if (options.read_ids || options.check_drawn) {
    out.ids.create(k.height, k.width, CV_32S);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT1);
    gl.ReadPixels(0, 0, k.width, k.height, GL_RED_INTEGER, GL_INT, out.ids.data);
  }
  if (options.read_depth) {
    out.depth.create(k.height, k.width, CV_32F);
    gl.ReadPixels(0, 0, k.width, k.height, GL_DEPTH_COMPONENT, GL_FLOAT, out.depth.data);
    // Window depth d in [0, 1] -> z_ndc = 2 d - 1 -> z = 2 f n / ((f + n) - (f - n) z_ndc).
    const double n = k.near, f = k.far;
    auto* z = out.depth.ptr<float>();
    for (std::size_t i = 0, count = out.depth.total(); i < count; ++i) {
      const double d = z[i];
      z[i] =
          d >= 1.0 ? 0.0f : static_cast<float>(2.0 * f * n / ((f + n) - (f - n) * (2.0 * d - 1.0)));
    }
  }
  check_gl(gl, fmt::format("{}: reading back the images", owner));

  if (options.check_drawn) check_drawn(items, camera, out.ids);
  gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
  if (!options.read_ids) out.ids.release();
  return out;
}

void SceneRenderer::draw_items(const std::vector<DrawItem>& items, const Camera& camera,
                               const RenderOptions& options, const SnapViewport& snap) const {
  const GlApi& gl = *gl_;
  gl.Enable(GL_DEPTH_TEST);
  gl.DepthFunc(GL_LESS);
  gl.DepthMask(GL_TRUE);
  gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  gl.Disable(GL_CULL_FACE);
  gl.Disable(GL_BLEND);
  const std::array<GLfloat, 4> background = {options.background.x(), options.background.y(),
                                             options.background.z(), 1.0f};
  const std::array<GLint, 4> no_id = {0, 0, 0, 0};
  const GLfloat far_depth = 1.0f;
  gl.ClearBufferfv(GL_COLOR, 0, background.data());
  gl.ClearBufferiv(GL_COLOR, 1, no_id.data());
  gl.ClearBufferfv(GL_DEPTH, 0, &far_depth);

  program_.use();
  SnapUniforms{u_snap_image_, u_snap_ndc_per_px_}.set(gl, camera.intrinsics, snap);
  gl.Uniform1f(u_ambient_, options.ambient);
  const Eigen::Matrix4d view_projection = camera.view_projection();
  const Eigen::Vector3d light = options.light_direction_root.normalized();
  for (const DrawItem& item : items) {
    const Eigen::Matrix4f mvp = (view_projection * item.pose_root.matrix()).cast<float>();
    const Eigen::Vector3f light_item = (item.pose_root.linear().transpose() * light).cast<float>();
    gl.UniformMatrix4fv(u_mvp_, 1, GL_FALSE, mvp.data());  // Eigen is column-major, as GL
    gl.Uniform3f(u_light_, light_item.x(), light_item.y(), light_item.z());
    gl.Uniform3f(u_albedo_, item.colour.x(), item.colour.y(), item.colour.z());
    gl.Uniform1i(u_id_, item.id);
    meshes_[item.mesh.index].draw();
  }
  gl.BindVertexArray(0);
}

void SceneRenderer::check_drawn(const std::vector<DrawItem>& items, const Camera& camera,
                                const cv::Mat& ids) const {
  // Ids present in the mask: one scan, recording an id where a run of equal ids starts.
  std::vector<std::int32_t> present;
  std::int32_t last = 0;
  const auto* id = ids.ptr<std::int32_t>();
  for (std::size_t i = 0, count = ids.total(); i < count; ++i)
    if (id[i] != last) {
      last = id[i];
      if (last != 0) present.push_back(last);
    }
  std::sort(present.begin(), present.end());
  present.erase(std::unique(present.begin(), present.end()), present.end());

  const PinholeIntrinsics& k = camera.intrinsics;
  const Eigen::Isometry3d camera_root = camera.pose_root.inverse(Eigen::Isometry);
  const GlApi& gl = *gl_;
  // Items of ids absent from the mask that should have shown, grouped by id (an id's items are
  // checked together: a sub-pixel bar of a backdrop whose plane is hidden is no error).
  std::map<std::int32_t, std::vector<std::size_t>> missing;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const DrawItem& item = items[i];
    if (std::binary_search(present.begin(), present.end(), item.id)) continue;
    // Does one of its vertices lie between the clipping planes and project into the image, at
    // least 1 px inside its border? (Its bounding box would be too coarse: a thin, turned part
    // at the image edge can have its box overlap the image while the part itself is outside;
    // and a vertex within a pixel of the border may belong to a sliver that covers no pixel
    // centre.) Items smaller than 2 px across may legitimately cover no pixel centre either.
    const Eigen::Isometry3d camera_item = camera_root * item.pose_root;
    const std::vector<Eigen::Vector3f>& vertices = vertices_[item.mesh.index];
    Eigen::AlignedBox3f box;
    for (const Eigen::Vector3f& vertex : vertices) box.extend(vertex);
    const double size_m = vertices.empty() ? 0.0 : static_cast<double>(box.diagonal().norm());
    for (const Eigen::Vector3f& vertex : vertices) {
      const Eigen::Vector3d p = camera_item * vertex.cast<double>();
      if (!(p.z() > k.near && p.z() < k.far)) continue;
      const double u = k.fx * p.x() / p.z() + k.cx, v = k.fy * p.y() / p.z() + k.cy;
      const bool inside = u >= 0.5 && u <= k.width - 1.5 && v >= 0.5 && v <= k.height - 1.5;
      if (inside && std::min(k.fx, k.fy) * size_m / p.z() >= 2.0) {
        missing[item.id].push_back(i);
        break;
      }
    }
  }
  // Hidden behind other items, or really drawing nothing? Draw each id's items alone (depth
  // only).
  for (const auto& [item_id, group] : missing) {
    gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    const GLfloat far_depth = 1.0f;
    gl.ClearBufferfv(GL_DEPTH, 0, &far_depth);
    gl.BeginQuery(GL_ANY_SAMPLES_PASSED, query_);
    program_.use();
    for (const std::size_t i : group) {
      const Eigen::Matrix4f mvp =
          (camera.view_projection() * items[i].pose_root.matrix()).cast<float>();
      gl.UniformMatrix4fv(u_mvp_, 1, GL_FALSE, mvp.data());
      meshes_[items[i].mesh.index].draw();
    }
    gl.EndQuery(GL_ANY_SAMPLES_PASSED);
    GLuint any_sample = 0;
    gl.GetQueryObjectuiv(query_, GL_QUERY_RESULT, &any_sample);
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.BindVertexArray(0);
    check_gl(gl,
             fmt::format("{}: checking item {} (id {})", owner_of(camera), group.front(), item_id));
    if (any_sample == 0)
      throw RunError(fmt::format("{}: item {} (id {}) projects into the image but drew no pixel",
                                 owner_of(camera), group.front(), item_id));
  }
}

}  // namespace somasim::render
