#pragma once
// Internal: draws hypothesis tiles on the CPU (HypothesisRenderer's software rasterizer): the
// triangles of each hypothesis' meshes projected with the pinhole model, vertices snapped to the
// 1/256 px grid as the GL path snaps them (subpixel_snap.hpp), clipped at the near plane, and
// filled by pixel centres with the top-left rule in integer arithmetic, one row span at a time.
// Of a closed, consistently wound mesh only the triangles of one winding on screen are drawn:
// they cover the same pixels as all of them. With inner contours every triangle is drawn with a
// depth test (1 / depth interpolated at pixel centres) into a label tile.
#include <array>
#include <cstddef>
#include <vector>

#include <opencv2/core.hpp>

#include "somasim/render/hypothesis_batch.hpp"

namespace somasim::render {

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
  /// covers; with `cull_negative`, none if it winds clockwise on screen (a closed mesh's other
  /// half covers the same pixels).
  template <class Span>
  static void for_each_span(const std::array<long long, 3>& x, const std::array<long long, 3>& y,
                            bool cull_negative, const cv::Rect& roi, Span&& span);

  /// Draws one camera-frame triangle (all vertices at z >= near) of mesh `label` - 1 into
  /// labels_ / inverse_depth_ where it is nearer than what is there.
  void draw_labelled(const std::array<Eigen::Vector3d, 3>& triangle,
                     const PinholeIntrinsics& intrinsics, const cv::Rect& roi, std::uint8_t label);

  std::vector<TriangleMesh> meshes_;
  std::vector<bool> closed_;  // per mesh: closed and consistently wound (back faces culled)
  std::vector<Eigen::Vector3d> camera_points_;  // one mesh's vertices in the camera frame
  cv::Mat tile_;                                // scratch silhouette
  cv::Mat labels_;                              // inner contours: nearest mesh + 1 per pixel
  cv::Mat inverse_depth_;                       // inner contours: 1 / its depth [1/m], CV_32F
};

}  // namespace somasim::render
