#pragma once
// Internal: draws hypothesis tiles on the context current on this thread (one per worker).
#include <cstddef>
#include <map>
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "mask_framebuffer.hpp"
#include "somasim/render/gl_api.hpp"
#include "somasim/render/gl_objects.hpp"
#include "somasim/render/hypothesis_batch.hpp"
#include "subpixel_snap.hpp"

namespace somasim::render {

class HypothesisTiler {
 public:
  /// Builds the silhouette shader and uploads `meshes` on the current context.
  HypothesisTiler(const GlApi& gl, const std::vector<TriangleMesh>& meshes);

  /// Draws hypotheses [begin, end) of `batch` for every camera into one framebuffer (more only
  /// when the tiles exceed the largest framebuffer), reads it back once and writes the
  /// silhouettes (or their contours, per `options`) to out[camera].tiles[hypothesis] (which
  /// must already have N entries).
  void render(const HypothesisBatch& batch, const std::vector<cv::Rect>& rois, std::size_t begin,
              std::size_t end, const HypothesisBatchOptions& options,
              std::vector<CameraTiles>& out);

 private:
  const GlApi* gl_;
  ShaderProgram program_;
  GLint u_mvp_ = -1;
  SnapUniforms snap_;         // sub-pixel snapping uniforms (subpixel_snap.hpp)
  int largest_viewport_ = 0;  // GL_MAX_VIEWPORT_DIMS [px]
  // The batch's meshes concatenated into one buffer (built once per list of mesh indices).
  const MeshBuffer& combined(const std::vector<std::size_t>& parts);

  std::vector<TriangleMesh> meshes_;
  std::map<std::vector<std::size_t>, MeshBuffer> combined_;
  std::optional<MaskFramebuffer> framebuffer_;
  cv::Mat pixels_;    // read-back buffer, kept to avoid page faults per batch
  int max_size_ = 0;  // largest framebuffer side used [px]
};

}  // namespace somasim::render
