#pragma once
// Internal: draws hypothesis tiles on the CPU (HypothesisRenderer's software rasterizer): the
// triangles of each hypothesis' meshes projected with the pinhole model, vertices snapped to the
// 1/256 px grid as the GL path snaps them (subpixel_snap.hpp), clipped at the near plane, and
// filled by pixel centres with the top-left rule in integer arithmetic, one row span at a time.
// Of a closed, consistently wound mesh only the triangles of one winding on screen are drawn:
// they cover the same pixels as all of them.
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
  /// Fills the pixels of `tile` (the ROI `roi` of the image) whose centres the triangle with
  /// window vertices (x, y) [1/256 px, window = pixel + 0.5] covers; with `cull_negative`, not
  /// if it winds clockwise on screen (a closed mesh's other half covers the same pixels).
  static void fill_triangle(const std::array<long long, 3>& x, const std::array<long long, 3>& y,
                            bool cull_negative, const cv::Rect& roi, cv::Mat& tile);

  std::vector<TriangleMesh> meshes_;
  std::vector<bool> closed_;  // per mesh: closed and consistently wound (back faces culled)
  std::vector<Eigen::Vector3d> camera_points_;  // one mesh's vertices in the camera frame
  cv::Mat tile_;                                // scratch silhouette
};

}  // namespace somasim::render
