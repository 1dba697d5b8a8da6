#pragma once
// Internal: draws hypothesis tiles on the CPU (HypothesisRenderer's software rasterizer): the
// triangles of each hypothesis' meshes projected with the pinhole model, vertices snapped to the
// 1/256 px grid as the GL path snaps them (subpixel_snap.hpp), clipped at the near plane, and
// filled by pixel centres with the top-left rule in integer arithmetic, one row span at a time.
// Of a closed, consistently wound mesh only the triangles of one winding on screen are drawn:
// they cover the same pixels as all of them. With inner contours every triangle is drawn with a
// depth test (1 / depth interpolated at pixel centres) into a label tile; with creases the labels
// tell the smooth patches of each mesh apart (faces meeting at kCreaseAngleDeg or more).
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "somasim/render/hypothesis_batch.hpp"

namespace somasim::render {

/// Triangles sharing an edge whose normals differ by this much or more meet at a crease [deg]
/// (the box's and the cylinders' cap edges at 90°; an 8-sided cylinder's sides, 45°, do not).
inline constexpr double kCreaseAngleDeg = 60.0;

/// Label of an occluder's pixels in the label tile (hypothesis labels stay below it).
inline constexpr int kOccluderLabel = 255;

class SoftwareTiler {
 public:
  explicit SoftwareTiler(const std::vector<TriangleMesh>& meshes);

  /// As HypothesisTiler::render: hypotheses [begin, end) of `batch` for every camera, the
  /// silhouettes (or their contours, per `options`) to out[camera].tiles[hypothesis].
  void render(const HypothesisBatch& batch, const std::vector<cv::Rect>& rois, std::size_t begin,
              std::size_t end, const HypothesisBatchOptions& options,
              std::vector<CameraTiles>& out);

 private:
  /// Calls span(row, first column, last column) [image pixels] for the pixels of the ROI `roi`
  /// whose centres the triangle with window vertices (x, y) [1/256 px, window = pixel + 0.5]
  /// covers; none if its signed area on screen has the sign of `skip_sign` (-1, +1; 0: none
  /// skipped): either winding of a closed mesh covers its whole projection.
  template <class Span>
  static void for_each_span(const std::array<long long, 3>& x, const std::array<long long, 3>& y,
                            int skip_sign, const cv::Rect& roi, Span&& span);

  /// Draws one camera-frame triangle (all vertices at z >= near) with `label` into labels_ /
  /// inverse_depth_ where it is nearer than what is there; nothing if its signed area on screen
  /// has the sign of `skip_sign` (0: always drawn).
  void draw_labelled(const std::array<Eigen::Vector3d, 3>& triangle,
                     const PinholeIntrinsics& intrinsics, const cv::Rect& roi, std::uint8_t label,
                     int skip_sign);

  /// Calls draw(triangle, first index of the mesh triangle) for every triangle of `mesh` posed
  /// by `to_camera` (camera <- mesh) in front of the near plane: whole, or clipped at z = near
  /// and fanned.
  template <class Draw>
  void for_each_triangle_in_front(const TriangleMesh& mesh, const Eigen::Isometry3d& to_camera,
                                  double near, Draw&& draw);

  /// labels_ / inverse_depth_ of `roi` cleared and the batch's occluders drawn into them with
  /// kOccluderLabel.
  void draw_occluders(const HypothesisBatch& batch, const Camera& camera, const cv::Rect& roi);

  /// The contour of the hypothesis in tile_ among the occluders in labels_ / inverse_depth_:
  /// its boundary with the background (`width` px) and, 1 px, where it lies in front of an
  /// occluder; not where an occluder hides it.
  cv::Mat contour_beside_occluders(int width) const;

  std::vector<TriangleMesh> meshes_;
  std::vector<bool> closed_;   // per mesh: closed and consistently wound (back faces culled)
  std::vector<bool> outward_;  // per mesh: wound counter-clockwise seen from outside
  std::vector<std::vector<std::uint8_t>> patches_;  // per mesh, per triangle: its smooth patch
  std::vector<std::uint8_t> patch_count_;           // per mesh
  std::vector<Eigen::Vector3d> camera_points_;      // one mesh's vertices in the camera frame
  cv::Mat tile_;                                    // scratch silhouette
  cv::Mat labels_;                                  // inner contours: nearest mesh + 1 per pixel
  cv::Mat inverse_depth_;                           // inner contours: 1 / its depth [1/m], CV_32F
};

}  // namespace somasim::render
