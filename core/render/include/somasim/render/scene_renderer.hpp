#pragma once
/// @file
/// Renders a list of posed, coloured, labelled meshes as a camera sees them, and reads back the
/// colour image, the metric depth and the id mask.
///
/// Shading: Lambert + ambient with one directional light, per pixel:
///   colour = albedo · (ambient + (1 - ambient) · max(0, n · l)),
/// n the interpolated surface normal, l the unit direction towards the light (root frame).
/// No anti-aliasing (id masks have exact labels); no back-face culling (meshes may be open).
///
/// Rasterization: the vertex shader rounds every vertex to the rasterizer's sub-pixel grid
/// (1/256 px) in image pixel coordinates before the viewport transform (a V × V viewport, V =
/// 8192 for images up to 4096 px, centred on the image), so that the same geometry drawn at any
/// whole-pixel offset of a larger framebuffer (hypothesis tiles, hypothesis_batch.hpp) covers
/// exactly the same pixels. Vertices move by at most 1/512 px; depth and the interpolation of
/// normals are those of the unrounded vertices. Images larger than half of GL_MAX_VIEWPORT_DIMS
/// (8192 px on llvmpipe) are refused with RunError.
///
/// Outputs (all `height` rows × `width` columns, row 0 = top of the image, see camera.hpp):
///   - rgb:   CV_8UC3, channel order R, G, B (use cv::cvtColor(..., cv::COLOR_RGB2BGR) before
///            cv::imwrite);
///   - depth: CV_32F, metres along the camera's z axis (not along the ray); 0 where nothing was
///            drawn;
///   - ids:   CV_32S, the id of the item seen at each pixel; 0 = background.
/// Each requested output is one glReadPixels of the framebuffer.
///
/// "Never a silent black frame": with `check_drawn` on, after reading back, every item with a
/// vertex between the near and far planes that projects into the image at least 1 px inside its
/// border, and whose vertex bounds span at least 2 px there, but whose id has no pixel in the id
/// mask is drawn again alone; if it still covers no pixel (so it was not merely hidden behind
/// other items) render() throws RunError "camera 'X': item N (id I) projects into the image but
/// drew no pixel". The extra cost is one scan of the id mask, plus a vertex scan and a redraw
/// only for items that show no pixel. Not checked: items smaller than 2 px, slivers within a
/// pixel of the image border (they may cover no pixel centre), items seen only through a
/// triangle whose vertices all lie outside the image. Items sharing an id are checked together
/// (drawn alone as a group; the error names the group's first item): a sub-pixel bar of a
/// backdrop whose plane is hidden behind a near object is no error.
///
/// Threads: as every GL object, a SceneRenderer lives on its context's thread (context.hpp).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "somasim/render/camera.hpp"
#include "somasim/render/gl_api.hpp"
#include "somasim/render/gl_objects.hpp"
#include "somasim/render/tessellate.hpp"

namespace somasim::render {

struct SnapViewport;  // internal (src/subpixel_snap.hpp)

/// Index of an uploaded mesh in its SceneRenderer.
struct MeshHandle {
  std::size_t index = static_cast<std::size_t>(-1);
};

/// One thing to draw.
struct DrawItem {
  MeshHandle mesh;
  Eigen::Isometry3d pose_root = Eigen::Isometry3d::Identity();  ///< root <- mesh frame
  Eigen::Vector3f colour = Eigen::Vector3f::Constant(0.8f);     ///< albedo R, G, B in [0, 1]
  std::int32_t id = 1;  ///< label in the id mask; must not be 0 (the background)
};

struct RenderOptions {
  Eigen::Vector3f background = Eigen::Vector3f::Zero();  ///< R, G, B in [0, 1]
  /// Direction from the scene towards the light (root frame; normalised when used).
  Eigen::Vector3d light_direction_root = Eigen::Vector3d(0.0, 0.0, 1.0);
  float ambient = 0.3f;  ///< share of the albedo seen without light, in [0, 1]
  bool read_rgb = true;
  bool read_depth = true;
  bool read_ids = true;     ///< the ids are read anyway when check_drawn is on
  bool check_drawn = true;  ///< see the file comment
};

/// The read-back images; an output that was not requested is an empty cv::Mat.
struct RenderedImages {
  cv::Mat rgb;    ///< CV_8UC3, R G B
  cv::Mat depth;  ///< CV_32F [m] along the camera z; 0 = nothing
  cv::Mat ids;    ///< CV_32S; 0 = background
};

class SceneRenderer {
 public:
  /// Builds the shader program. `gl` must be the table of the context current on this thread.
  explicit SceneRenderer(const GlApi& gl);
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;
  SceneRenderer(SceneRenderer&&) = delete;
  SceneRenderer& operator=(SceneRenderer&&) = delete;

  /// Uploads a mesh once (vertex and index buffers); draw items refer to it by the handle.
  /// Throws RunError on a GL error or an inconsistent mesh.
  MeshHandle upload(const TriangleMesh& mesh);
  std::size_t mesh_count() const { return meshes_.size(); }

  /// Renders `items` as `camera` sees them. The framebuffer is (re)made when the image size
  /// changes. Throws somasim::InputError for invalid intrinsics, somasim::RunError naming the
  /// camera for an unknown mesh handle, id 0, a non-finite pose, any GL error, or an item that
  /// projects into the image but drew no pixel (see the file comment).
  RenderedImages render(const std::vector<DrawItem>& items, const Camera& camera,
                        const RenderOptions& options = {});

 private:
  void draw_items(const std::vector<DrawItem>& items, const Camera& camera,
                  const RenderOptions& options, const SnapViewport& snap) const;
  void check_drawn(const std::vector<DrawItem>& items, const Camera& camera,
                   const cv::Mat& ids) const;

  const GlApi* gl_;
  ShaderProgram program_;
  GLint u_mvp_ = -1, u_light_ = -1, u_albedo_ = -1, u_ambient_ = -1, u_id_ = -1;
  GLint u_snap_image_ = -1, u_snap_ndc_per_px_ = -1;  // see src/subpixel_snap.hpp
  int largest_viewport_ = 0;                          // GL_MAX_VIEWPORT_DIMS [px]
  std::vector<MeshBuffer> meshes_;
  std::vector<std::vector<Eigen::Vector3f>> vertices_;  ///< per mesh, for check_drawn
  std::optional<Framebuffer> framebuffer_;
  GLuint query_ = 0;
};

}  // namespace somasim::render
