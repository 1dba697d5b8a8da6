#pragma once
/// @file
/// Batches of body hypotheses rendered as binary silhouettes (or their contours) inside a region
/// of interest, for the body-schema particle filter ("mental images" of the arm).
///
/// A batch: N hypotheses, each a list of poses (root <- mesh) for the same subset of the
/// uploaded meshes, seen by one or more cameras (left and right eye). Per camera, the region of
/// interest (ROI) is the pixel rectangle covering the projected bounding boxes of the drawn
/// meshes under all hypotheses, grown by a margin and clipped to the image. Every hypothesis of
/// that camera is drawn into a tile of the ROI's size; all tiles of a worker go into one
/// framebuffer (one glViewport per tile) and come back with one read-back.
///
/// Exactness: a tile equals the crop, at the ROI, of a full-image SceneRenderer id mask of the
/// same meshes (id > 0 -> 255), pixel for pixel. Both draw with the camera's full-image
/// view-projection matrix (the same float matrix, so clip coordinates and clipping are
/// identical), both vertex shaders round vertices to the rasterizer's 1/256 px grid in image
/// pixels, and a tile's viewport is SceneRenderer's shifted by whole pixels, which llvmpipe then
/// applies without rounding (src/subpixel_snap.hpp); a scissor box keeps each tile in its slot.
/// Exception: triangles crossing the near plane (the ROI is then the whole image) get vertices
/// from llvmpipe's clipper, whose rounding still depends on the tile's place: measured 8 of
/// 118,026 silhouette-boundary pixels differ (an edge through a pixel centre). Results do not
/// depend on the worker count. No depth test on GL: a silhouette is the union of all meshes (the
/// software rasterizer tests depth for inner contours and occluders).
///
/// Cost: one draw call per tile (the batch's meshes are concatenated into one vertex buffer,
/// posed by an array of at most kMaxMeshesPerHypothesis matrices).
///
/// Threads: a HypothesisRenderer owns W worker threads, each with its own GL context (OSMesa or
/// EGL: somasim/render/context.hpp) and its own copy of the meshes. Hypotheses are split into W
/// contiguous, equal (± 1) slices in order. The tile layout (slot = hypothesis × cameras + camera,
/// in a grid fixed by N, the cameras and the ROIs) does not depend on W and each worker draws its
/// tiles in their own slots, so results are byte-identical for any W.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "somasim/name_table.hpp"
#include "somasim/render/camera.hpp"
#include "somasim/render/context.hpp"
#include "somasim/render/tessellate.hpp"

namespace somasim::render {

/// Most meshes one hypothesis may pose (all of a hypothesis is drawn in one call).
inline constexpr std::size_t kMaxMeshesPerHypothesis = 16;

/// Poses root <- mesh [m], one per entry of HypothesisBatch::meshes, in the same order.
using Hypothesis = std::vector<Eigen::Isometry3d>;

/// A mesh posed once for the whole batch (another body part in front of the hypotheses, e.g.
/// the other hand): drawn into every tile's depth test only, it hides the parts of a hypothesis
/// behind it and is itself never part of a silhouette or contour. Nor is the line where it
/// hides a hypothesis (the occluder's outline, not the hypothesis'), as the image border is not;
/// where a hypothesis lies in front of it, its outline there is part of the contour (1 px wide).
/// Software rasterizer only.
struct Occluder {
  std::size_t mesh = 0;                                    ///< index of the renderer's meshes
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< root <- mesh [m]
};

struct HypothesisBatch {
  /// Indices of the renderer's meshes to draw (e.g. forearm and hand proxies); 1 to
  /// kMaxMeshesPerHypothesis of them.
  std::vector<std::size_t> meshes;
  std::vector<Hypothesis> hypotheses;  ///< N >= 1
  std::vector<Camera> cameras;         ///< >= 1 (left and right eye)
  /// Drawn in every hypothesis' tiles as occluders (at most kMaxMeshesPerHypothesis; they do not
  /// widen the ROI). Empty: none.
  std::vector<Occluder> occluders{};
};

struct HypothesisBatchOptions {
  int margin_px = 4;  ///< added on every side of the projected bounds before clipping [px], >= 0
  /// false: filled silhouettes; true: their inner boundary, `contour_width` px wide.
  bool contour = false;
  int contour_width = 1;  ///< 1 or 2 [px]; see silhouette_contour()
  /// false: the tiles are drawn and read back as usual, but no silhouette or contour is
  /// extracted and every CameraTiles::tiles entry stays empty (the bare cost of drawing and
  /// reading back, which benchmarks measure the extraction against).
  bool extract = true;
  /// With `contour`: also the boundaries inside the silhouette where one of the batch's meshes
  /// occludes another (a thumb over the palm): the meshes are drawn with a depth test, and a
  /// pixel of mesh a with a 4-neighbour of mesh b is a contour pixel when a is nearer there
  /// (one px wide, on the occluding side; see inner_contour()). Software rasterizer only.
  bool inner_contours = false;
  /// With `inner_contours`: also the creases inside one mesh, where its smooth patches meet
  /// (faces at 60° or more: a box's edges, a cylinder's rims), on the nearer side, 1 px. Every
  /// hypothesis' meshes together may have at most 255 patches.
  bool crease_contours = false;
};

/// The tiles of one camera.
struct CameraTiles {
  cv::Rect roi;                ///< in image pixels (x = column, y = row of the top-left corner)
  std::vector<cv::Mat> tiles;  ///< one per hypothesis: CV_8U, roi.height × roi.width, 0 / 255
};

struct HypothesisBatchResult {
  std::vector<CameraTiles> cameras;  ///< in the order of HypothesisBatch::cameras
};

/// The region of interest of `camera` for `batch` (see the file comment), computed from the
/// meshes' vertex bounds [mesh frame]. A box partly behind the near plane makes the ROI the
/// whole image; a box wholly behind it adds nothing. Returns an empty rectangle when nothing
/// projects into the image.
cv::Rect region_of_interest(const std::vector<Bounds>& mesh_bounds, const HypothesisBatch& batch,
                            const Camera& camera, int margin_px);

/// The inner boundary of a 0 / 255 silhouette: silhouette pixels within `width` (1 or 2) steps
/// of a background pixel along 4-neighbour paths. With width 1, every contour pixel is a
/// silhouette pixel with a background 4-neighbour. Pixels outside the image are not background
/// (an object cut by the ROI's edge is not outlined along it).
cv::Mat silhouette_contour(const cv::Mat& silhouette, int width);

/// The occluding boundaries inside a labelled tile: pixels whose label (CV_8U, 0 = background,
/// else the nearest mesh + 1) differs from a 4-neighbour's non-zero label while the pixel is
/// nearer than that neighbour (`inverse_depth`: CV_32F, 1 / camera depth [1/m], larger =
/// nearer). Returns CV_8U 0 / 255; boundaries with the background are not included (see
/// silhouette_contour()).
cv::Mat inner_contour(const cv::Mat& labels, const cv::Mat& inverse_depth);

/// How tiles are drawn.
enum class Rasterizer : std::uint8_t {
  kGl,        ///< OpenGL (the back end's context per worker; exact, see the file comment)
  kSoftware,  ///< on the CPU, no GL context: the same projection and 1/256 px vertex grid,
              ///< pixel centres filled with the top-left rule (software_tiler.hpp); equal to
              ///< the GL tiles except on pixels whose centre lies on an edge
};
inline constexpr NamedValue<Rasterizer> kRasterizerNames[] = {{Rasterizer::kGl, "gl"},
                                                              {Rasterizer::kSoftware, "software"}};
constexpr std::span<const NamedValue<Rasterizer>> name_table(Rasterizer) {
  return kRasterizerNames;
}

/// Pool of W worker threads rendering hypothesis batches (see the file comment).
class HypothesisRenderer {
 public:
  /// Starts `workers` (>= 1) threads, each creating a context of `backend` and uploading
  /// `meshes` (the software rasterizer: no context, `backend` unused). Throws
  /// somasim::InputError for workers < 1, somasim::RunError when a context cannot be made (the
  /// back end's message) or a mesh does not upload. Both back ends on llvmpipe give
  /// byte-identical results.
  HypothesisRenderer(const std::vector<TriangleMesh>& meshes, int workers,
                     RenderBackend backend = RenderBackend::kOsmesa,
                     Rasterizer rasterizer = Rasterizer::kGl);
  ~HypothesisRenderer();
  HypothesisRenderer(const HypothesisRenderer&) = delete;
  HypothesisRenderer& operator=(const HypothesisRenderer&) = delete;
  HypothesisRenderer(HypothesisRenderer&&) = delete;
  HypothesisRenderer& operator=(HypothesisRenderer&&) = delete;

  /// Renders the batch. Throws somasim::InputError for an empty batch, an unknown mesh index,
  /// a hypothesis with the wrong number of poses or a non-finite pose, occluders on the GL
  /// rasterizer or with a non-finite pose, invalid options or intrinsics; somasim::RunError naming
  /// the camera when its ROI is empty (nothing projects into its image) and for GL errors. One call
  /// at a time (not to be called concurrently on the same renderer); the calling thread needs no GL
  /// context.
  HypothesisBatchResult render(const HypothesisBatch& batch,
                               const HypothesisBatchOptions& options = {});

  int worker_count() const;
  RenderBackend backend() const;
  Rasterizer rasterizer() const;
  std::size_t mesh_count() const { return bounds_.size(); }

 private:
  void validate_occluders(const std::vector<Occluder>& occluders) const;

  struct Pool;
  std::vector<Bounds> bounds_;
  std::unique_ptr<Pool> pool_;
};

}  // namespace somasim::render
