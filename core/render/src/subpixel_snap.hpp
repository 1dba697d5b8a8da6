#pragma once
// Internal: vertex positions snapped to the rasterizer's sub-pixel grid in the vertex shader, so
// that an image drawn at a whole-pixel offset in a larger framebuffer (a hypothesis tile)
// rasterizes exactly like the same image drawn at offset 0 (SceneRenderer).
//
// Why: llvmpipe maps clip coordinates to window coordinates in float (x * (1 / w) * scale +
// translate, the translate being the viewport's origin) and only then rounds them to its fixed
// sub-pixel grid (FIXED_ORDER = 8: 1/256 px, lp_rast.h / lp_setup_tri.c). A whole-pixel shift of
// the viewport changes the float rounding of that sum, so a vertex within a float ulp of a
// rounding midpoint can land on a neighbouring grid point and flip a pixel whose centre lies on
// an edge.
//
// What: both vertex shaders compute the vertex's window coordinate in the full image (pixel
// u + 0.5, row v + 0.5), round it to the 1/256 px grid, and write clip coordinates that map back
// onto that grid point through a square viewport of V × V px (V a power of two, default 8192)
// centred on the integer pixel C of the image (about its centre). Because V/2 and the shifts are
// powers of two or integers, llvmpipe's float round trip lands within 1.25 · 2^-10 px of
// grid + offset for every vertex it rasterizes unclipped (|window| < 16384 px), less than half a
// grid step (2^-9 px), so it snaps to exactly grid + offset at every offset. w (and z) are the
// original clip coordinates: perspective-correct interpolation, depth and near/far clipping are
// unchanged. The large viewport also keeps triangles that leave the image from being clipped at
// the image border (a tile needs a scissor box instead).
//
// Not exact: vertices the clipper makes (triangles crossing the near or far plane, or reaching
// more than V/2 - W/2 px beyond the image), whose window coordinates llvmpipe computes itself.
// The bound above is llvmpipe's arithmetic (Mesa 22.3: draw_llvm.c generate_viewport, then
// lp_setup_tri.c calc_fixed_position); other rasterizers with at least 8 sub-pixel bits see
// grid-aligned vertices too, but their exactness depends on their own viewport arithmetic.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <string>

#include "somasim/error.hpp"
#include "somasim/render/camera.hpp"
#include "somasim/render/gl_api.hpp"
#include "somasim/render/gl_objects.hpp"

namespace somasim::render {

/// GLSL for a vertex shader, after its #version line: uniforms snap_image (W/2, H/2, Cx, Cy)
/// [px] and snap_ndc_per_px (2 / V), and vec4 snap_to_subpixel_grid(vec4 clip), which maps the
/// full image's clip coordinates to those of the snapping viewport. Vertices behind the eye
/// (w <= 0) or more than 32768 px away are mapped without rounding (clipping replaces them).
/// gl_Position is invariant so that both programs compute the window coordinate with the same
/// operations.
inline constexpr const char* kSubpixelSnapGlsl = R"(
uniform vec4 snap_image;
uniform float snap_ndc_per_px;
invariant gl_Position;
vec4 snap_to_subpixel_grid(vec4 clip) {
  vec2 window = clip.xy / clip.w * snap_image.xy + snap_image.xy;
  if (!(clip.w > 0.0) || !all(lessThan(abs(window), vec2(32768.0))))
    return vec4((clip.xy * snap_image.xy + clip.w * (snap_image.xy - snap_image.zw)) *
                snap_ndc_per_px, clip.z, clip.w);
  vec2 grid = floor(window * 256.0 + 0.5) * (1.0 / 256.0);
  return vec4((grid - snap_image.zw) * snap_ndc_per_px * clip.w, clip.z, clip.w);
}
)";

/// Side of the snapping viewport for images up to 4096 px [px].
inline constexpr int kSnapViewportSide = 8192;

/// The snapping viewport of one image size: V × V px centred on image pixel corner C.
struct SnapViewport {
  int side = 0;      ///< V [px], a power of two
  int centre_x = 0;  ///< Cx [px] (window coordinate in the image, an integer)
  int centre_y = 0;  ///< Cy [px]
};

/// Largest viewport side this context allows [px].
inline int largest_viewport_side(const GlApi& gl) {
  std::array<GLint, 2> dims = {0, 0};
  gl.GetIntegerv(GL_MAX_VIEWPORT_DIMS, dims.data());
  return std::min(dims[0], dims[1]);
}

/// The snapping viewport of `k`'s image: V = 8192 (exact snapping, see the file comment) or, for
/// images above 4096 px, the smallest power of two covering twice the image. Throws RunError
/// naming `owner` when that exceeds `largest_side` (GL_MAX_VIEWPORT_DIMS).
inline SnapViewport snap_viewport(const PinholeIntrinsics& k, int largest_side,
                                  const std::string& owner) {
  SnapViewport s;
  s.side = kSnapViewportSide;
  while (s.side < 2 * std::max(k.width, k.height)) s.side *= 2;
  if (s.side > largest_side)
    throw RunError(
        fmt::format("{}: a {} x {} image needs a {} px viewport, but this OpenGL "
                    "allows at most {} px",
                    owner, k.width, k.height, s.side, largest_side));
  s.centre_x = k.width / 2;
  s.centre_y = k.height / 2;
  return s;
}

/// Uniform locations of a program whose vertex shader includes kSubpixelSnapGlsl.
struct SnapUniforms {
  GLint image = -1;
  GLint ndc_per_px = -1;

  static SnapUniforms of(const ShaderProgram& program) {
    return {program.uniform("snap_image"), program.uniform("snap_ndc_per_px")};
  }

  /// Sets the uniforms of the program in use.
  void set(const GlApi& gl, const PinholeIntrinsics& k, const SnapViewport& s) const {
    gl.Uniform4f(image, static_cast<GLfloat>(0.5 * k.width), static_cast<GLfloat>(0.5 * k.height),
                 static_cast<GLfloat>(s.centre_x), static_cast<GLfloat>(s.centre_y));
    gl.Uniform1f(ndc_per_px, 2.0f / static_cast<GLfloat>(s.side));
  }
};

/// glViewport such that image window coordinate (x, y) lands at framebuffer (x + dx, y + dy).
inline void set_snap_viewport(const GlApi& gl, const SnapViewport& s, int dx, int dy) {
  gl.Viewport(dx + s.centre_x - s.side / 2, dy + s.centre_y - s.side / 2, s.side, s.side);
}

}  // namespace somasim::render
