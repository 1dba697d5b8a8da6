#pragma once
/// @file
/// Off-screen OpenGL contexts: the back-end choice (OSMesa or EGL), the common RenderContext
/// interface and the OSMesa context (software rendering with Mesa's llvmpipe; no display, no
/// GPU). The EGL context (somasim/render/egl_context.hpp) renders on a GPU when the node has one
/// and Mesa's llvmpipe otherwise.
///
/// Threads: one context per thread, whatever its back end. The constructor makes the context
/// current on the calling thread and it stays current there for its whole life; every GL object
/// (Framebuffer, ShaderProgram, SceneRenderer, ...) made with its `gl()` table must be created,
/// used and destroyed on that same thread, before the context is destroyed. A second context on
/// a thread that already has one (of either back end) is refused. Parallel rendering = one
/// context per worker thread (with llvmpipe, two single-thread contexts in two threads beat one
/// context using llvmpipe's own threads).
///
/// Rendering goes to framebuffer objects: a context's own default framebuffer (1 × 1 for OSMesa,
/// none for EGL) is never used. The library logs nothing: callers log renderer() and version().
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "somasim/name_table.hpp"
#include "somasim/render/gl_api.hpp"

namespace somasim::render {

/// Where the GL context comes from.
enum class RenderBackend {
  kOsmesa,  ///< "osmesa": Mesa's OSMesa, always llvmpipe (software)
  kEgl,     ///< "egl": EGL's surfaceless platform (Mesa): the GPU's driver, or llvmpipe
};
inline constexpr NamedValue<RenderBackend> kRenderBackendNames[] = {
    {RenderBackend::kOsmesa, "osmesa"}, {RenderBackend::kEgl, "egl"}};
/// "osmesa", "egl".
constexpr std::span<const NamedValue<RenderBackend>> name_table(RenderBackend) {
  return kRenderBackendNames;
}

/// Parses "osmesa" or "egl". Throws somasim::InputError naming the valid names otherwise.
RenderBackend parse_render_backend(const std::string& name);
/// "osmesa" or "egl" (the names parse_render_backend accepts).
std::string render_backend_name(RenderBackend backend);
/// The names parse_render_backend accepts, in the order of RenderBackend.
std::vector<std::string> render_backend_names();

/// An OpenGL core-profile context current on the thread that created it (see the file comment).
class RenderContext {
 public:
  virtual ~RenderContext();
  RenderContext(const RenderContext&) = delete;
  RenderContext& operator=(const RenderContext&) = delete;
  RenderContext(RenderContext&&) = delete;
  RenderContext& operator=(RenderContext&&) = delete;

  RenderBackend backend() const { return backend_; }
  /// The GL function table of this context.
  const GlApi& gl() const { return gl_; }
  /// GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)" (for the caller's log).
  const std::string& renderer() const { return renderer_; }
  /// GL_VERSION, e.g. "4.5 (Core Profile) Mesa 22.3.6" (for the caller's log).
  const std::string& version() const { return version_; }

 protected:
  /// Claims this thread for the new context. Throws somasim::RunError when the thread already
  /// has a context.
  explicit RenderContext(RenderBackend backend);
  /// Loads the GL table through `loader` and reads the renderer and version strings; the new
  /// context must be current. Throws somasim::RunError naming missing GL functions.
  void load_gl(const GlProcLoader& loader);

 private:
  RenderBackend backend_;
  GlApi gl_;
  std::string renderer_, version_;
};

/// Creates a context of `backend` with an OpenGL core profile of version >= major.minor, current
/// on this thread. Throws somasim::RunError as the back end's constructor does.
std::unique_ptr<RenderContext> make_render_context(RenderBackend backend, int major = 3,
                                                   int minor = 3);

/// RAII OSMesa context with an OpenGL core profile of at least the requested version.
class OsmesaContext : public RenderContext {
 public:
  /// Creates a core-profile context of version >= major.minor and makes it current on this
  /// thread. Throws somasim::RunError when OSMesa cannot create it or make it current, when this
  /// thread already has a context, or when a GL function is missing.
  explicit OsmesaContext(int major = 3, int minor = 3);
  ~OsmesaContext() override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace somasim::render
