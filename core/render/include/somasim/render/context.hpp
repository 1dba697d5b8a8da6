#pragma once
/// @file
/// An off-screen OpenGL context on Mesa's OSMesa (software rendering with llvmpipe; no display,
/// no GPU).
///
/// Threads: one context per thread. The constructor makes the context current on the calling
/// thread and it stays current there for its whole life; every GL object (Framebuffer,
/// ShaderProgram, SceneRenderer, ...) made with its `gl()` table must be created, used and
/// destroyed on that same thread, before the context is destroyed. A second OsmesaContext on a
/// thread that already has one is refused. Parallel rendering = one context per worker thread
/// (with llvmpipe, two single-thread contexts in two threads beat one context using llvmpipe's
/// own threads).
///
/// The context's own (dummy, 1 × 1) buffer is never read: rendering goes to framebuffer objects.
#include <memory>
#include <string>

#include "somasim/render/gl_api.hpp"

namespace somasim::render {

/// RAII OSMesa context with an OpenGL core profile of at least the requested version.
class OsmesaContext {
 public:
  /// Creates a core-profile context of version >= major.minor and makes it current on this
  /// thread. Throws somasim::RunError when OSMesa cannot create it or make it current, when this
  /// thread already has an OsmesaContext, or when a GL function is missing.
  explicit OsmesaContext(int major = 3, int minor = 3);
  ~OsmesaContext();
  OsmesaContext(const OsmesaContext&) = delete;
  OsmesaContext& operator=(const OsmesaContext&) = delete;
  OsmesaContext(OsmesaContext&&) = delete;
  OsmesaContext& operator=(OsmesaContext&&) = delete;

  /// The GL function table of this context.
  const GlApi& gl() const { return gl_; }
  /// GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)" (for the caller's log).
  const std::string& renderer() const { return renderer_; }
  /// GL_VERSION, e.g. "4.5 (Core Profile) Mesa 22.3.6" (for the caller's log).
  const std::string& version() const { return version_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  GlApi gl_;
  std::string renderer_, version_;
};

}  // namespace somasim::render
