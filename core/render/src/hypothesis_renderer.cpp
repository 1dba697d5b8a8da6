// HypothesisRenderer: validation of a batch, ROIs, and the pool of worker threads, each with its
// own GL context (OSMesa or EGL) and HypothesisTiler.
#include <fmt/format.h>

#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>

#include "hypothesis_tiler.hpp"
#include "software_tiler.hpp"
#include "somasim/error.hpp"
#include "somasim/render/context.hpp"
#include "somasim/render/hypothesis_batch.hpp"

namespace somasim::render {

struct HypothesisRenderer::Pool {
  struct Job {
    const HypothesisBatch* batch = nullptr;
    const std::vector<cv::Rect>* rois = nullptr;
    const HypothesisBatchOptions* options = nullptr;
    std::vector<CameraTiles>* out = nullptr;
  };

  std::mutex mutex;
  std::condition_variable work, done;
  std::uint64_t generation = 0;  // incremented per job
  int started = 0;               // workers that finished (or failed) their start-up
  int pending = 0;               // workers still busy with the current job
  bool stop = false;
  Job job;
  std::vector<std::exception_ptr> errors;  // per worker, of start-up or of the current job
  std::vector<std::thread> threads;
  RenderBackend backend = RenderBackend::kOsmesa;
  Rasterizer rasterizer = Rasterizer::kGl;

  void run(std::size_t index, const std::vector<TriangleMesh>& meshes) {
    try {
      if (rasterizer == Rasterizer::kSoftware) {
        SoftwareTiler tiler(meshes);
        serve(index, tiler);
      } else {
        const std::unique_ptr<RenderContext> context = make_render_context(backend);
        HypothesisTiler tiler(context->gl(), meshes);
        serve(index, tiler);
      }
    } catch (...) {
      {
        std::lock_guard lock(mutex);
        errors[index] = std::current_exception();
        ++started;
      }
      done.notify_all();
    }
  }

  /// Reports the start-up, then renders each job's slice with `tiler` until stopped.
  template <class Tiler>
  void serve(std::size_t index, Tiler& tiler) {
    const std::size_t workers = threads.size();
    {
      std::uint64_t seen = 0;
      {
        std::lock_guard lock(mutex);
        ++started;
      }
      done.notify_all();
      for (;;) {
        Job current;
        {
          std::unique_lock lock(mutex);
          work.wait(lock, [&] { return stop || generation != seen; });
          if (stop) return;
          seen = generation;
          current = job;
        }
        try {
          // Contiguous slices in hypothesis order: deterministic for a given worker count, and
          // each tile depends only on its own hypothesis.
          const std::size_t n = current.batch->hypotheses.size();
          tiler.render(*current.batch, *current.rois, n * index / workers,
                       n * (index + 1) / workers, *current.options, *current.out);
        } catch (...) {
          std::lock_guard lock(mutex);
          errors[index] = std::current_exception();
        }
        {
          std::lock_guard lock(mutex);
          --pending;
        }
        done.notify_all();
      }
    }
  }

  void shut_down() {
    {
      std::lock_guard lock(mutex);
      stop = true;
    }
    work.notify_all();
    for (std::thread& t : threads)
      if (t.joinable()) t.join();
  }

  void rethrow_first_error() {
    for (std::exception_ptr& e : errors)
      if (e) std::rethrow_exception(std::exchange(e, nullptr));
  }
};

HypothesisRenderer::HypothesisRenderer(const std::vector<TriangleMesh>& meshes, int workers,
                                       RenderBackend backend, Rasterizer rasterizer)
    : pool_(std::make_unique<Pool>()) {
  if (workers < 1)
    throw InputError(fmt::format("hypothesis renderer: needs at least 1 worker, got {}", workers));
  bounds_.reserve(meshes.size());
  for (const TriangleMesh& mesh : meshes) bounds_.push_back(bounds(mesh));
  Pool& pool = *pool_;
  pool.backend = backend;
  pool.rasterizer = rasterizer;
  pool.errors.resize(static_cast<std::size_t>(workers));
  pool.threads.resize(static_cast<std::size_t>(workers));
  for (std::size_t i = 0; i < pool.threads.size(); ++i)
    pool.threads[i] = std::thread([&pool, &meshes, i] { pool.run(i, meshes); });
  {
    std::unique_lock lock(pool.mutex);
    pool.done.wait(lock, [&] { return pool.started == workers; });
  }
  for (const std::exception_ptr& e : pool.errors)
    if (e) {
      pool.shut_down();
      pool.rethrow_first_error();
    }
}

HypothesisRenderer::~HypothesisRenderer() {
  pool_->shut_down();
}

int HypothesisRenderer::worker_count() const {
  return static_cast<int>(pool_->threads.size());
}

RenderBackend HypothesisRenderer::backend() const {
  return pool_->backend;
}

Rasterizer HypothesisRenderer::rasterizer() const {
  return pool_->rasterizer;
}

void HypothesisRenderer::validate_occluders(const std::vector<Occluder>& occluders) const {
  if (occluders.empty()) return;
  if (pool_->rasterizer != Rasterizer::kSoftware)
    throw InputError("hypothesis batch: occluders need the software rasterizer");
  if (occluders.size() > kMaxMeshesPerHypothesis)
    throw InputError(fmt::format("hypothesis batch: at most {} occluders, got {}",
                                 kMaxMeshesPerHypothesis, occluders.size()));
  for (std::size_t o = 0; o < occluders.size(); ++o) {
    if (occluders[o].mesh >= bounds_.size())
      throw InputError(
          fmt::format("hypothesis batch: occluder {} is mesh {}, but {} meshes were uploaded", o,
                      occluders[o].mesh, bounds_.size()));
    if (!occluders[o].pose.matrix().allFinite())
      throw InputError(fmt::format("hypothesis batch: occluder {} has a non-finite pose", o));
  }
}

HypothesisBatchResult HypothesisRenderer::render(const HypothesisBatch& batch,
                                                 const HypothesisBatchOptions& options) {
  if (batch.hypotheses.empty()) throw InputError("hypothesis batch: no hypotheses");
  if (batch.cameras.empty()) throw InputError("hypothesis batch: no cameras");
  if (batch.meshes.empty()) throw InputError("hypothesis batch: no meshes to draw");
  if (batch.meshes.size() > kMaxMeshesPerHypothesis)
    throw InputError(fmt::format("hypothesis batch: at most {} meshes per hypothesis, got {}",
                                 kMaxMeshesPerHypothesis, batch.meshes.size()));
  if (options.margin_px < 0)
    throw InputError(
        fmt::format("hypothesis batch: margin_px must be >= 0, got {}", options.margin_px));
  if (options.contour && (options.contour_width < 1 || options.contour_width > 2))
    throw InputError(fmt::format("hypothesis batch: contour_width must be 1 or 2, got {}",
                                 options.contour_width));
  if (options.inner_contours && !options.contour)
    throw InputError("hypothesis batch: inner_contours needs contour");
  if (options.inner_contours && pool_->rasterizer != Rasterizer::kSoftware)
    throw InputError("hypothesis batch: inner_contours needs the software rasterizer");
  if (options.crease_contours && !options.inner_contours)
    throw InputError("hypothesis batch: crease_contours needs inner_contours");
  for (std::size_t m = 0; m < batch.meshes.size(); ++m)
    if (batch.meshes[m] >= bounds_.size())
      throw InputError(
          fmt::format("hypothesis batch: mesh {} is index {}, but {} meshes were "
                      "uploaded",
                      m, batch.meshes[m], bounds_.size()));
  for (std::size_t h = 0; h < batch.hypotheses.size(); ++h) {
    const Hypothesis& poses = batch.hypotheses[h];
    if (poses.size() != batch.meshes.size())
      throw InputError(
          fmt::format("hypothesis batch: hypothesis {} has {} poses, expected {} "
                      "(one per mesh)",
                      h, poses.size(), batch.meshes.size()));
    for (std::size_t m = 0; m < poses.size(); ++m)
      if (!poses[m].matrix().allFinite())
        throw InputError(
            fmt::format("hypothesis batch: hypothesis {} has a non-finite pose of mesh {}", h, m));
  }
  validate_occluders(batch.occluders);
  HypothesisBatchResult result;
  result.cameras.resize(batch.cameras.size());
  std::vector<cv::Rect> rois(batch.cameras.size());
  for (std::size_t c = 0; c < batch.cameras.size(); ++c) {
    const Camera& camera = batch.cameras[c];
    validate(camera.intrinsics, camera.name);
    if (!camera.pose_root.matrix().allFinite())
      throw InputError(fmt::format("camera '{}': the camera pose is not finite", camera.name));
    rois[c] = region_of_interest(bounds_, batch, camera, options.margin_px);
    if (rois[c].empty())
      throw RunError(
          fmt::format("camera '{}': hypothesis batch: the region of interest is empty "
                      "(no mesh of any of the {} hypotheses projects into the image)",
                      camera.name, batch.hypotheses.size()));
    result.cameras[c].roi = rois[c];
    result.cameras[c].tiles.resize(batch.hypotheses.size());
  }

  Pool& pool = *pool_;
  {
    std::lock_guard lock(pool.mutex);
    pool.job = {&batch, &rois, &options, &result.cameras};
    pool.pending = worker_count();
    ++pool.generation;
  }
  pool.work.notify_all();
  {
    std::unique_lock lock(pool.mutex);
    pool.done.wait(lock, [&] { return pool.pending == 0; });
  }
  pool.rethrow_first_error();
  return result;
}

}  // namespace somasim::render
