#include "hypothesis_tiler.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "somasim/error.hpp"
#include "subpixel_snap.hpp"

namespace somasim::render {

namespace {

// One draw call per tile: the batch's meshes are concatenated into one buffer whose "normal"
// attribute carries, in x, the index of the part (the mesh of the batch) each vertex belongs to.
// The position is snapped to the rasterizer's sub-pixel grid in full-image pixel coordinates,
// exactly as SceneRenderer's shader does (subpixel_snap.hpp).
std::string vertex_shader() {
  return std::string("#version 330 core\n") + kSubpixelSnapGlsl + R"(
uniform mat4 mvp[16];
in vec3 position;
in vec3 normal;
void main() {
  gl_Position = snap_to_subpixel_grid(mvp[int(normal.x + 0.5)] * vec4(position, 1.0));
}
)";
}

constexpr const char* kFragmentShader = R"(#version 330 core
out vec4 out_colour;
void main() {
  out_colour = vec4(1.0);
}
)";

// Largest framebuffer side we allocate [px]: one byte per pixel, at most 16 MiB per worker.
constexpr int kMaxFramebufferSide = 4096;

}  // namespace

HypothesisTiler::HypothesisTiler(const GlApi& gl, const std::vector<TriangleMesh>& meshes)
    : gl_(&gl),
      program_(gl, "render: hypothesis silhouette shader", vertex_shader(), kFragmentShader) {
  u_mvp_ = program_.uniform("mvp");
  snap_ = SnapUniforms::of(program_);
  largest_viewport_ = largest_viewport_side(gl);
  meshes_ = meshes;
  GLint texture = 0, renderbuffer = 0;
  std::array<GLint, 2> viewport = {0, 0};
  gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &texture);
  gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbuffer);
  gl.GetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport.data());
  max_size_ = std::min({kMaxFramebufferSide, texture, renderbuffer, viewport[0], viewport[1]});
  check_gl(gl, "render: creating the hypothesis renderer");
}

const MeshBuffer& HypothesisTiler::combined(const std::vector<std::size_t>& parts) {
  auto found = combined_.find(parts);
  if (found != combined_.end()) return found->second;
  TriangleMesh mesh;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const TriangleMesh& part = meshes_[parts[p]];
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), part.positions.begin(), part.positions.end());
    mesh.normals.insert(mesh.normals.end(), part.positions.size(),
                        Eigen::Vector3f(static_cast<float>(p), 0.0f, 0.0f));
    for (const std::uint32_t i : part.indices) mesh.indices.push_back(base + i);
  }
  return combined_.emplace(parts, MeshBuffer(*gl_, mesh, "render: hypothesis meshes"))
      .first->second;
}

void HypothesisTiler::render(const HypothesisBatch& batch, const std::vector<cv::Rect>& rois,
                             std::size_t begin, std::size_t end,
                             const HypothesisBatchOptions& options, std::vector<CameraTiles>& out) {
  if (begin >= end) return;
  const GlApi& gl = *gl_;
  // The layout is a function of the whole batch, never of this worker's slice: a tile's place
  // in the framebuffer still changes the rounding of vertices made by near-plane clipping (see
  // hypothesis_batch.hpp), so every worker count must put every tile in the same place. Slots
  // are numbered hypothesis-major (slot = h * cameras + c) so that a slice of hypotheses is a
  // run of slots; all slots share the largest ROI's size and fill a roughly square grid of
  // passes no larger than the framebuffer limit.
  int slot_w = 1, slot_h = 1;
  for (const cv::Rect& r : rois) {
    slot_w = std::max(slot_w, r.width);
    slot_h = std::max(slot_h, r.height);
  }
  const std::size_t cameras = rois.size();
  const std::size_t total = batch.hypotheses.size() * cameras;
  const int max_cols = std::max(1, max_size_ / slot_w), max_rows = std::max(1, max_size_ / slot_h);
  const int cols = std::clamp(
      static_cast<int>(std::ceil(std::sqrt(static_cast<double>(total) * slot_h / slot_w))), 1,
      max_cols);
  const int rows = std::min(static_cast<int>((total + cols - 1) / cols), max_rows);
  const std::size_t per_pass = static_cast<std::size_t>(cols) * rows;

  // Per camera: the full image's projection and snapping viewport, exactly as SceneRenderer
  // computes them; each tile's viewport is SceneRenderer's shifted by whole pixels so that the
  // ROI lands on the tile. The clip coordinates (snapped to the sub-pixel grid in image pixels)
  // and the clipping are then bit-identical to a full render's, and the viewport shift is exact
  // (subpixel_snap.hpp). The viewport reaches far beyond the image, so a scissor box keeps each
  // tile's drawing inside its ROI.
  std::vector<Eigen::Matrix4d> view_projection(cameras);
  std::vector<SnapViewport> snap(cameras);
  for (std::size_t c = 0; c < cameras; ++c) {
    view_projection[c] = batch.cameras[c].view_projection();
    snap[c] = snap_viewport(batch.cameras[c].intrinsics, largest_viewport_,
                            fmt::format("camera '{}'", batch.cameras[c].name));
  }
  const MeshBuffer& parts = combined(batch.meshes);
  std::array<Eigen::Matrix4f, kMaxMeshesPerHypothesis> mvp;
  const std::array<GLfloat, 4> clear = {0.0f, 0.0f, 0.0f, 0.0f};

  const std::size_t first_slot = begin * cameras, end_slot = end * cameras;
  for (std::size_t pass = first_slot / per_pass; pass * per_pass < end_slot; ++pass) {
    const std::size_t base = pass * per_pass;
    const std::size_t first = std::max(first_slot, base),
                      last = std::min(end_slot, base + per_pass);
    const int row_lo = static_cast<int>((first - base) / cols);
    const int row_hi = static_cast<int>((last - 1 - base) / cols);
    const int fb_w = cols * slot_w, fb_h = (row_hi + 1) * slot_h;
    if (!framebuffer_ || framebuffer_->width() < fb_w || framebuffer_->height() < fb_h) {
      const int w = framebuffer_ ? std::max(fb_w, framebuffer_->width()) : fb_w;
      const int h = framebuffer_ ? std::max(fb_h, framebuffer_->height()) : fb_h;
      framebuffer_.reset();
      framebuffer_.emplace(gl, w, h, "render: hypothesis batch");
    }
    framebuffer_->bind();
    gl.Disable(GL_DEPTH_TEST);
    gl.Disable(GL_CULL_FACE);
    gl.Disable(GL_BLEND);
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    program_.use();
    gl.Disable(GL_SCISSOR_TEST);
    gl.ClearBufferfv(GL_COLOR, 0, clear.data());
    gl.Enable(GL_SCISSOR_TEST);
    std::size_t snap_camera = cameras;  // camera whose snapping uniforms are set
    for (std::size_t slot = first; slot < last; ++slot) {
      const std::size_t h = slot / cameras, c = slot % cameras;
      const int i = static_cast<int>(slot - base);
      const cv::Rect& roi = rois[c];
      const int tile_x = (i % cols) * slot_w, tile_y = (i / cols) * slot_h;
      if (c != snap_camera) {
        snap_.set(gl, batch.cameras[c].intrinsics, snap[c]);
        snap_camera = c;
      }
      set_snap_viewport(gl, snap[c], tile_x - roi.x, tile_y - roi.y);
      gl.Scissor(tile_x, tile_y, roi.width, roi.height);
      const Hypothesis& poses = batch.hypotheses[h];
      for (std::size_t m = 0; m < batch.meshes.size(); ++m)
        // Same arithmetic as SceneRenderer: (view_projection * pose) in double, then float.
        mvp[m] = (view_projection[c] * poses[m].matrix()).cast<float>();
      gl.UniformMatrix4fv(u_mvp_, static_cast<GLsizei>(batch.meshes.size()), GL_FALSE,
                          mvp.front().data());
      parts.draw();
    }
    gl.BindVertexArray(0);
    gl.Disable(GL_SCISSOR_TEST);
    // One read-back of the rows this worker drew in this pass.
    pixels_.create((row_hi - row_lo + 1) * slot_h, fb_w, CV_8U);
    gl.ReadPixels(0, row_lo * slot_h, fb_w, pixels_.rows, GL_RED, GL_UNSIGNED_BYTE, pixels_.data);
    check_gl(gl, fmt::format("render: hypothesis batch: drawing and reading {} tiles of {} x {}",
                             last - first, slot_w, slot_h));
    if (!options.extract) continue;
    for (std::size_t slot = first; slot < last; ++slot) {
      const std::size_t h = slot / cameras, c = slot % cameras;
      const int i = static_cast<int>(slot - base);
      const cv::Rect at((i % cols) * slot_w, (i / cols - row_lo) * slot_h, rois[c].width,
                        rois[c].height);
      out[c].tiles[h] = options.contour ? silhouette_contour(pixels_(at), options.contour_width)
                                        : pixels_(at).clone();
    }
  }
  gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace somasim::render
