#pragma once
/// @file
/// An off-screen OpenGL context through EGL without a window system, with no surface at all
/// (EGL_KHR_surfaceless_context). The display is, by the environment variable
/// SOMASIM_EGL_PLATFORM:
/// - `auto` (unset or empty): the first hardware EGL device (EGL_EXT_platform_device, skipping
///   Mesa's software device) that initialises, which is how NVIDIA's driver renders headless;
///   otherwise Mesa's surfaceless platform (EGL_MESA_platform_surfaceless), which renders on the
///   GPU through its render node where Mesa drives it and with llvmpipe otherwise. With
///   LIBGL_ALWAYS_SOFTWARE set (not 0), only the surfaceless platform is tried.
/// - `device`: a hardware EGL device only; `surfaceless`: Mesa's surfaceless platform only.
/// Renders from different GPUs or drivers may differ in pixels; on one machine they repeat.
/// GL functions come through eglGetProcAddress.
///
/// Threads and framebuffers as for every RenderContext (somasim/render/context.hpp): one context
/// per thread, rendering only into framebuffer objects (there is no default framebuffer).
///
/// All EglContexts of a process share one EGL display, initialised by the first context and kept
/// until the process exits (terminating it would unload Mesa's driver).
#include <memory>
#include <string>

#include "somasim/render/context.hpp"

namespace somasim::render {

/// RAII EGL context with an OpenGL core profile of at least the requested version.
class EglContext : public RenderContext {
 public:
  /// Creates a core-profile context of version >= major.minor and makes it current on this
  /// thread. Throws somasim::RunError naming the failed EGL call and the EGL error code
  /// ("render: eglCreateContext failed for an OpenGL 9.9 core-profile context: EGL_BAD_MATCH"),
  /// naming what was tried and the missing package when no EGL display renders without a
  /// window, an unknown SOMASIM_EGL_PLATFORM, when this thread already
  /// has a context, or when a GL function is missing.
  explicit EglContext(int major = 3, int minor = 3);
  ~EglContext() override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// "EGL_BAD_MATCH" etc. for eglGetError codes; "unknown EGL error 0x...." for others.
std::string egl_error_name(int code);

}  // namespace somasim::render
