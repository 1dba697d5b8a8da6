#include "somasim/render/hypothesis_batch.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace somasim::render {

cv::Rect region_of_interest(const std::vector<Bounds>& mesh_bounds, const HypothesisBatch& batch,
                            const Camera& camera, int margin_px) {
  const PinholeIntrinsics& k = camera.intrinsics;
  const Eigen::Isometry3d camera_root = camera.pose_root.inverse(Eigen::Isometry);
  double umin = INFINITY, umax = -INFINITY, vmin = INFINITY, vmax = -INFINITY;
  bool whole_image = false;
  for (const Hypothesis& poses : batch.hypotheses) {
    for (std::size_t m = 0; m < batch.meshes.size() && !whole_image; ++m) {
      const Bounds& b = mesh_bounds[batch.meshes[m]];
      const Eigen::Isometry3d camera_mesh = camera_root * poses[m];
      int in_front = 0;
      double u0 = INFINITY, u1 = -INFINITY, v0 = INFINITY, v1 = -INFINITY;
      for (int c = 0; c < 8; ++c) {
        const Eigen::Vector3d corner((c & 1) ? b.max.x() : b.min.x(),
                                     (c & 2) ? b.max.y() : b.min.y(),
                                     (c & 4) ? b.max.z() : b.min.z());
        const Eigen::Vector3d p = camera_mesh * corner;
        if (!(p.z() > k.near)) continue;
        ++in_front;
        const double u = k.fx * p.x() / p.z() + k.cx, v = k.fy * p.y() / p.z() + k.cy;
        u0 = std::min(u0, u);
        u1 = std::max(u1, u);
        v0 = std::min(v0, v);
        v1 = std::max(v1, v);
      }
      if (in_front == 0) continue;           // wholly clipped by the near plane: draws nothing
      if (in_front < 8) whole_image = true;  // crosses the near plane: unbounded projection
      umin = std::min(umin, u0);
      umax = std::max(umax, u1);
      vmin = std::min(vmin, v0);
      vmax = std::max(vmax, v1);
    }
  }
  if (whole_image) return {0, 0, k.width, k.height};
  if (!(umin <= umax)) return {};
  // Pixel c covers [c - 0.5, c + 0.5) (camera.hpp). Clamp in double before converting to int.
  const auto column = [](double u, double limit) {
    return static_cast<int>(std::clamp(std::floor(u + 0.5), -1.0e6, limit + 1.0e6));
  };
  const int x0 = std::max(0, column(umin, k.width) - margin_px);
  const int x1 = std::min(k.width - 1, column(umax, k.width) + margin_px);
  const int y0 = std::max(0, column(vmin, k.height) - margin_px);
  const int y1 = std::min(k.height - 1, column(vmax, k.height) + margin_px);
  if (x0 > x1 || y0 > y1) return {};
  return {x0, y0, x1 - x0 + 1, y1 - y0 + 1};
}

cv::Mat silhouette_contour(const cv::Mat& silhouette, int width) {
  CV_Assert(silhouette.type() == CV_8U);
  // Erode `width` times with the 4-neighbour cross; outside the image counts as silhouette
  // (replicated border, isolated: a tile that is a view into a larger buffer never sees its
  // neighbours). The contour is what the erosion removed: silhouette (255) > inside (0).
  static const cv::Mat cross = cv::getStructuringElement(cv::MORPH_CROSS, cv::Size(3, 3));
  cv::Mat inside, contour;
  cv::erode(silhouette, inside, cross, cv::Point(-1, -1), width,
            cv::BORDER_REPLICATE | cv::BORDER_ISOLATED);
  cv::compare(silhouette, inside, contour, cv::CMP_GT);
  return contour;
}

cv::Mat inner_contour(const cv::Mat& labels, const cv::Mat& inverse_depth) {
  CV_Assert(labels.type() == CV_8U && inverse_depth.type() == CV_32F &&
            labels.size() == inverse_depth.size());
  cv::Mat contour(labels.size(), CV_8U, cv::Scalar(0));
  const int rows = labels.rows, cols = labels.cols;
  for (int r = 0; r < rows; ++r) {
    const std::uint8_t* label = labels.ptr<std::uint8_t>(r);
    const float* depth = inverse_depth.ptr<float>(r);
    std::uint8_t* out = contour.ptr<std::uint8_t>(r);
    // Neighbours outside the tile are not meshes: they never make a pixel a contour pixel.
    const std::uint8_t* label_up = r > 0 ? labels.ptr<std::uint8_t>(r - 1) : nullptr;
    const float* depth_up = r > 0 ? inverse_depth.ptr<float>(r - 1) : nullptr;
    const std::uint8_t* label_down = r + 1 < rows ? labels.ptr<std::uint8_t>(r + 1) : nullptr;
    const float* depth_down = r + 1 < rows ? inverse_depth.ptr<float>(r + 1) : nullptr;
    for (int c = 0; c < cols; ++c) {
      const std::uint8_t here = label[c];
      if (here == 0) continue;
      const auto occludes = [&](std::uint8_t other, float other_depth) {
        return other != 0 && other != here && depth[c] > other_depth;
      };
      if ((c > 0 && occludes(label[c - 1], depth[c - 1])) ||
          (c + 1 < cols && occludes(label[c + 1], depth[c + 1])) ||
          (label_up != nullptr && occludes(label_up[c], depth_up[c])) ||
          (label_down != nullptr && occludes(label_down[c], depth_down[c])))
        out[c] = 255;
    }
  }
  return contour;
}

}  // namespace somasim::render
