#include "software_tiler.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>

#include <fmt/format.h>

#include "somasim/error.hpp"

namespace somasim::render {
namespace {

constexpr double kGrid = 256.0;  // sub-pixel steps per pixel (llvmpipe's FIXED_ORDER = 8)

/// floor(a / b) and ceil(a / b) for b > 0.
long long floor_div(long long a, long long b) {
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}
long long ceil_div(long long a, long long b) {
  return -floor_div(-a, b);
}

/// A camera-frame point's window coordinate on the sub-pixel grid [1/256 px]; window = pixel
/// coordinate + 0.5 (pixel c covers [c - 0.5, c + 0.5), camera.hpp).
long long snapped(double pixel) {
  return static_cast<long long>(std::floor((pixel + 0.5) * kGrid + 0.5));
}

/// Per vertex of `mesh`, an id shared by the vertices at the same position (meshes repeat
/// positions with other normals).
std::vector<std::uint32_t> position_ids(const TriangleMesh& mesh) {
  std::map<std::array<float, 3>, std::uint32_t> ids;
  std::vector<std::uint32_t> id(mesh.positions.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const Eigen::Vector3f& p = mesh.positions[v];
    id[v] = ids.emplace(std::array<float, 3>{p.x(), p.y(), p.z()},
                        static_cast<std::uint32_t>(ids.size()))
                .first->second;
  }
  return id;
}

/// True when every edge of `mesh` is shared by exactly two triangles that run along it in
/// opposite directions: then the triangles of either winding cover its whole projection.
bool closed_and_oriented(const TriangleMesh& mesh) {
  // Every directed edge between positions must be met once in each direction.
  const std::vector<std::uint32_t> id = position_ids(mesh);
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
    for (std::size_t i = 0; i < 3; ++i)
      ++edges[{id[mesh.indices[t + i]], id[mesh.indices[t + (i + 1) % 3]]}];
  if (edges.empty()) return false;
  for (const auto& [edge, count] : edges) {
    const auto back = edges.find({edge.second, edge.first});
    if (count != 1 || back == edges.end() || back->second != 1) return false;
  }
  return true;
}

/// Per triangle of `mesh`, its smooth patch (0, 1, ... in order of first triangle): triangles
/// sharing an edge are in one patch when their normals are less than kCreaseAngleDeg apart.
std::vector<std::uint8_t> smooth_patches(const TriangleMesh& mesh, std::uint8_t& count) {
  const std::size_t triangles = mesh.indices.size() / 3;
  const std::vector<std::uint32_t> id = position_ids(mesh);
  std::vector<Eigen::Vector3f> normal(triangles);
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> edges;
  for (std::size_t t = 0; t < triangles; ++t) {
    const Eigen::Vector3f& a = mesh.positions[mesh.indices[3 * t]];
    normal[t] = (mesh.positions[mesh.indices[3 * t + 1]] - a)
                    .cross(mesh.positions[mesh.indices[3 * t + 2]] - a)
                    .normalized();
    for (std::size_t i = 0; i < 3; ++i) {
      const std::uint32_t p = id[mesh.indices[3 * t + i]];
      const std::uint32_t q = id[mesh.indices[3 * t + (i + 1) % 3]];
      edges[{std::min(p, q), std::max(p, q)}].push_back(t);
    }
  }
  std::vector<std::size_t> parent(triangles);
  for (std::size_t t = 0; t < triangles; ++t) parent[t] = t;
  auto root = [&](std::size_t t) {
    while (parent[t] != t) t = parent[t] = parent[parent[t]];
    return t;
  };
  const float smooth = static_cast<float>(std::cos(kCreaseAngleDeg * M_PI / 180.0));
  for (const auto& [edge, sharing] : edges)
    for (std::size_t i = 1; i < sharing.size(); ++i)
      if (normal[sharing[0]].dot(normal[sharing[i]]) > smooth)
        parent[root(sharing[i])] = root(sharing[0]);
  std::map<std::size_t, std::uint8_t> patch_of_root;
  std::vector<std::uint8_t> patch(triangles);
  for (std::size_t t = 0; t < triangles; ++t) {
    const std::size_t r = root(t);
    const auto found = patch_of_root.find(r);
    if (found != patch_of_root.end()) {
      patch[t] = found->second;
      continue;
    }
    const auto next = static_cast<std::uint8_t>(std::min<std::size_t>(patch_of_root.size(), 254));
    patch_of_root.emplace(r, next);
    patch[t] = next;
  }
  count = static_cast<std::uint8_t>(std::min<std::size_t>(patch_of_root.size(), 255));
  return patch;
}

}  // namespace

SoftwareTiler::SoftwareTiler(const std::vector<TriangleMesh>& meshes) : meshes_(meshes) {
  for (const TriangleMesh& mesh : meshes_) {
    closed_.push_back(closed_and_oriented(mesh));
    double volume = 0.0;  // six times the signed volume: > 0 when wound outward
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
      volume += mesh.positions[mesh.indices[t]].cast<double>().dot(
          mesh.positions[mesh.indices[t + 1]].cast<double>().cross(
              mesh.positions[mesh.indices[t + 2]].cast<double>()));
    outward_.push_back(volume > 0.0);
    std::uint8_t count = 0;
    patches_.push_back(smooth_patches(mesh, count));
    patch_count_.push_back(count);
  }
}

template <class Span>
void SoftwareTiler::for_each_span(const std::array<long long, 3>& x,
                                  const std::array<long long, 3>& y, int skip_sign,
                                  const cv::Rect& roi, Span&& span) {
  // Orient counter-clockwise in (x right, y down) so that the inside is E >= 0 for every edge.
  const long long area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
  if (area == 0 || (skip_sign < 0 && area < 0) || (skip_sign > 0 && area > 0)) return;
  std::array<int, 3> order = {0, 1, 2};
  if (area < 0) std::swap(order[1], order[2]);
  // Edge i from vertex order[i] to order[i+1]: E(px, py) = a px + b py + c.
  std::array<long long, 3> a{}, b{}, c{}, bias{};
  for (int i = 0; i < 3; ++i) {
    const int p = order[static_cast<std::size_t>(i)];
    const int q = order[static_cast<std::size_t>((i + 1) % 3)];
    const long long dx = x[q] - x[p], dy = y[q] - y[p];
    a[i] = -dy;
    b[i] = dx;
    c[i] = dy * x[p] - dx * y[p];
    // Top-left rule (y down): a pixel centre on a top edge (horizontal, the inside below it:
    // dx > 0 in this orientation) or a left edge (the inside to its right: dy < 0) is covered;
    // on any other edge it is not (E must be > 0).
    const bool top = dy == 0 && dx > 0;
    const bool left = dy < 0;
    bias[i] = top || left ? 0 : 1;
  }
  const long long y_lo = std::min({y[0], y[1], y[2]}), y_hi = std::max({y[0], y[1], y[2]});
  // Rows whose centre (256 r + 128) lies in [y_lo, y_hi], within the ROI.
  const int row0 = std::max(roi.y, static_cast<int>(ceil_div(y_lo - 128, 256)));
  const int row1 = std::min(roi.y + roi.height - 1, static_cast<int>(floor_div(y_hi - 128, 256)));
  for (int r = row0; r <= row1; ++r) {
    const long long py = 256LL * r + 128;
    long long lo = roi.x, hi = roi.x + roi.width - 1;
    for (int i = 0; i < 3 && lo <= hi; ++i) {
      // E at column col: A col + K >= bias, A = 256 a, K = 128 a + b py + c.
      const long long big_a = 256 * a[i], k = 128 * a[i] + b[i] * py + c[i];
      if (big_a > 0)
        lo = std::max(lo, ceil_div(bias[i] - k, big_a));
      else if (big_a < 0)
        hi = std::min(hi, floor_div(k - bias[i], -big_a));
      else if (k < bias[i])
        hi = lo - 1;
    }
    if (lo > hi) continue;
    span(r, static_cast<int>(lo), static_cast<int>(hi));
  }
}

void SoftwareTiler::draw_labelled(const std::array<Eigen::Vector3d, 3>& triangle,
                                  const PinholeIntrinsics& k, const cv::Rect& roi,
                                  std::uint8_t label, int skip_sign) {
  // 1 / z is affine in pixel coordinates (u, v): fit the plane through the three vertices.
  std::array<long long, 3> x{}, y{};
  std::array<double, 3> u{}, v{}, w{};
  for (std::size_t i = 0; i < 3; ++i) {
    const Eigen::Vector3d& p = triangle[i];
    u[i] = k.fx * p.x() / p.z() + k.cx;
    v[i] = k.fy * p.y() / p.z() + k.cy;
    w[i] = 1.0 / p.z();
    x[i] = snapped(u[i]);
    y[i] = snapped(v[i]);
  }
  const double det = (u[1] - u[0]) * (v[2] - v[0]) - (u[2] - u[0]) * (v[1] - v[0]);
  if (det == 0.0) return;
  const double dw_du = ((w[1] - w[0]) * (v[2] - v[0]) - (w[2] - w[0]) * (v[1] - v[0])) / det;
  const double dw_dv = ((u[1] - u[0]) * (w[2] - w[0]) - (u[2] - u[0]) * (w[1] - w[0])) / det;
  // Coincident faces of two meshes (a finger's end on the palm's face) keep the first drawn:
  // a later surface must be nearer by more than this fraction of the depth.
  constexpr double kNearerBy = 1e-5;
  for_each_span(x, y, skip_sign, roi, [&](int r, int lo, int hi) {
    auto* labels = labels_.ptr<std::uint8_t>(r - roi.y);
    auto* depth = inverse_depth_.ptr<float>(r - roi.y);
    for (int c = lo; c <= hi; ++c) {
      const double inverse = w[0] + dw_du * (c - u[0]) + dw_dv * (r - v[0]);
      float& here = depth[c - roi.x];
      if (inverse <= static_cast<double>(here) * (1.0 + kNearerBy)) continue;
      here = static_cast<float>(inverse);
      labels[c - roi.x] = label;
    }
  });
}

template <class Draw>
void SoftwareTiler::for_each_triangle_in_front(const TriangleMesh& mesh,
                                               const Eigen::Isometry3d& to_camera, double near,
                                               Draw&& draw) {
  camera_points_.resize(mesh.positions.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    camera_points_[v] = to_camera * mesh.positions[v].cast<double>();
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::array<Eigen::Vector3d, 3> tri = {camera_points_[mesh.indices[t]],
                                                camera_points_[mesh.indices[t + 1]],
                                                camera_points_[mesh.indices[t + 2]]};
    int in_front = 0;
    for (const auto& p : tri) in_front += p.z() >= near;
    if (in_front == 0) continue;
    if (in_front == 3) {
      draw(tri, t);
      continue;
    }
    // Crossing the near plane: clip the polygon at z = near, then fan it.
    std::vector<Eigen::Vector3d> polygon;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d& p = tri[static_cast<std::size_t>(i)];
      const Eigen::Vector3d& q = tri[static_cast<std::size_t>((i + 1) % 3)];
      const bool p_in = p.z() >= near, q_in = q.z() >= near;
      if (p_in) polygon.push_back(p);
      if (p_in != q_in) polygon.push_back(p + (q - p) * ((near - p.z()) / (q.z() - p.z())));
    }
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
      draw(std::array<Eigen::Vector3d, 3>{polygon[0], polygon[i], polygon[i + 1]}, t);
  }
}

void SoftwareTiler::draw_occluders(const HypothesisBatch& batch, const Camera& camera,
                                   const cv::Rect& roi) {
  labels_.create(roi.height, roi.width, CV_8U);
  labels_.setTo(0);
  inverse_depth_.create(roi.height, roi.width, CV_32F);
  inverse_depth_.setTo(0.0F);
  const Eigen::Isometry3d root_to_camera = camera.pose_root.inverse();
  for (const Occluder& occluder : batch.occluders)
    for_each_triangle_in_front(meshes_[occluder.mesh], root_to_camera * occluder.pose,
                               camera.intrinsics.near,
                               [&](const std::array<Eigen::Vector3d, 3>& tri, std::size_t) {
                                 draw_labelled(tri, camera.intrinsics, roi, kOccluderLabel, 0);
                               });
}

cv::Mat SoftwareTiler::contour_beside_occluders(int width) const {
  // Along the background as without occluders; where an occluder hides the hypothesis, its
  // outline is not the hypothesis'; where the hypothesis is in front of one, the hypothesis'
  // outline (1 px, as inner contours): the depth test between the two, all the hypothesis'
  // meshes as one label.
  cv::Mat contour = silhouette_contour(labels_ > 0, width) & tile_;
  cv::Mat two_labels(labels_.size(), CV_8U, cv::Scalar(0));
  two_labels.setTo(1, tile_);
  two_labels.setTo(2, labels_ == kOccluderLabel);
  return contour | (inner_contour(two_labels, inverse_depth_) & tile_);
}

void SoftwareTiler::render(const HypothesisBatch& batch, const std::vector<cv::Rect>& rois,
                           std::size_t begin, std::size_t end,
                           const HypothesisBatchOptions& options, std::vector<CameraTiles>& out) {
  const bool occluded = !batch.occluders.empty();
  if (options.crease_contours) {
    int patches = 0;
    for (const std::size_t mesh : batch.meshes) patches += patch_count_[mesh];
    const int most = occluded ? kOccluderLabel - 1 : 255;
    if (patches > most)
      throw InputError(fmt::format(
          "hypothesis batch: crease_contours: the meshes have {} smooth patches, at most {}",
          patches, most));
  }
  // The occluders are the same in every hypothesis: drawn once per camera, copied per tile.
  std::vector<cv::Mat> occluder_labels(batch.cameras.size()), occluder_depth(batch.cameras.size());
  if (occluded)
    for (std::size_t cam = 0; cam < batch.cameras.size(); ++cam) {
      draw_occluders(batch, batch.cameras[cam], rois[cam]);
      occluder_labels[cam] = labels_.clone();
      occluder_depth[cam] = inverse_depth_.clone();
    }
  for (std::size_t h = begin; h < end; ++h)
    for (std::size_t cam = 0; cam < batch.cameras.size(); ++cam) {
      const Camera& camera = batch.cameras[cam];
      const PinholeIntrinsics& k = camera.intrinsics;
      const cv::Rect& roi = rois[cam];
      const bool labelled = options.inner_contours || occluded;
      tile_.create(roi.height, roi.width, CV_8U);
      tile_.setTo(0);
      if (occluded) {
        occluder_labels[cam].copyTo(labels_);
        occluder_depth[cam].copyTo(inverse_depth_);
      } else if (labelled) {
        labels_.create(roi.height, roi.width, CV_8U);
        labels_.setTo(0);
        inverse_depth_.create(roi.height, roi.width, CV_32F);
        inverse_depth_.setTo(0.0F);
      }
      const Eigen::Isometry3d root_to_camera = camera.pose_root.inverse();
      int first_label = 1;  // of the mesh's first patch (creases) or of the mesh
      for (std::size_t m = 0; m < batch.meshes.size(); ++m) {
        const TriangleMesh& mesh = meshes_[batch.meshes[m]];
        const bool cull = closed_[batch.meshes[m]];  // half the triangles cover a closed mesh
        const std::vector<std::uint8_t>& patch = patches_[batch.meshes[m]];
        auto label_of = [&](std::size_t t) {
          return static_cast<std::uint8_t>(first_label +
                                           (options.crease_contours ? patch[t / 3] : 0));
        };
        first_label += options.crease_contours ? patch_count_[batch.meshes[m]] : 1;
        // Creases tell a closed mesh's faces apart: its back faces, never seen, are not drawn
        // (where rounding let one win a pixel it would draw a crease that is not there).
        // A triangle facing the camera has its normal toward -z: a negative area on screen (x
        // right, y down) when the mesh winds counter-clockwise seen from outside.
        const int skip_back = !(options.crease_contours && cull) ? 0
                              : outward_[batch.meshes[m]]        ? 1
                                                                 : -1;
        for_each_triangle_in_front(
            mesh, root_to_camera * batch.hypotheses[h][m], k.near,
            [&](const std::array<Eigen::Vector3d, 3>& tri, std::size_t t) {
              if (labelled) {
                draw_labelled(tri, k, roi, label_of(t), skip_back);
                return;
              }
              std::array<long long, 3> x{}, y{};
              for (std::size_t i = 0; i < 3; ++i) {
                x[i] = snapped(k.fx * tri[i].x() / tri[i].z() + k.cx);
                y[i] = snapped(k.fy * tri[i].y() / tri[i].z() + k.cy);
              }
              for_each_span(x, y, cull ? -1 : 0, roi, [&](int r, int lo, int hi) {
                std::uint8_t* row = tile_.ptr<std::uint8_t>(r - roi.y);
                std::fill(row + (lo - roi.x), row + (hi - roi.x) + 1, std::uint8_t{255});
              });
            });
      }
      if (labelled) {
        cv::compare(labels_, 0, tile_, cv::CMP_GT);
        if (occluded) tile_ &= labels_ != kOccluderLabel;
      }
      if (!options.extract) continue;
      cv::Mat tile;
      if (!options.contour)
        tile = tile_.clone();
      else if (occluded)
        tile = contour_beside_occluders(options.contour_width);
      else
        tile = silhouette_contour(tile_, options.contour_width);
      if (options.inner_contours && options.contour) {
        cv::Mat inner = inner_contour(labels_, inverse_depth_);
        if (occluded) inner &= tile_;  // the occluder's own boundaries are not the hypothesis'
        tile |= inner;
      }
      out[cam].tiles[h] = tile;
    }
}

}  // namespace somasim::render
