#include "somasim/render/egl_context.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <fmt/format.h>

#include <array>
#include <mutex>
#include <string_view>

#include "somasim/error.hpp"

namespace somasim::render {

namespace {

// Throws the RunError of a failed EGL call (its error code read now).
[[noreturn]] void throw_egl(std::string_view call, std::string_view what) {
  throw RunError(fmt::format("render: {} failed{}: {}", call, what, egl_error_name(eglGetError())));
}

// Whether the space-separated extension list `list` names `extension`.
bool has_extension(const char* list, std::string_view extension) {
  if (list == nullptr) return false;
  for (std::string_view rest(list); !rest.empty();) {
    const std::size_t end = rest.find(' ');
    if (rest.substr(0, end) == extension) return true;
    if (end == std::string_view::npos) break;
    rest.remove_prefix(end + 1);
  }
  return false;
}

// The process's one surfaceless display, initialised by the first EglContext and never
// terminated: eglTerminate would end it for every thread at once (EGL does not count
// initialisations) and unload Mesa's driver, whose remaining allocations then show as leaks.
EGLDisplay surfaceless_display() {
  static std::mutex mutex;
  static EGLDisplay display = EGL_NO_DISPLAY;
  std::lock_guard lock(mutex);
  if (display != EGL_NO_DISPLAY) return display;
  // Client extensions (EGL_EXT_client_extensions): NULL when the EGL library has none.
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!has_extension(client, "EGL_EXT_platform_base") ||
      !has_extension(client, "EGL_MESA_platform_surfaceless"))
    throw RunError(
        "render: EGL has no surfaceless platform (client extension "
        "EGL_MESA_platform_surfaceless missing): the egl backend needs Mesa's EGL driver, Debian "
        "package libegl-mesa0 (or use backend: osmesa)");
  const auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (get_platform_display == nullptr)
    throw RunError(
        "render: EGL lists EGL_EXT_platform_base but eglGetProcAddress does not give "
        "eglGetPlatformDisplayEXT");
  EGLDisplay candidate =
      get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (candidate == EGL_NO_DISPLAY)
    throw_egl("eglGetPlatformDisplayEXT", " for the surfaceless platform");
  EGLint major = 0, minor = 0;
  if (eglInitialize(candidate, &major, &minor) != EGL_TRUE)
    throw_egl("eglInitialize", " on the surfaceless platform");
  display = candidate;
  return display;
}

}  // namespace

struct EglContext::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;

  // Undoes whatever of the constructor succeeded (also the destructor's work).
  void release() {
    if (context != EGL_NO_CONTEXT) {
      if (eglGetCurrentContext() == context)
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(display, context);
      context = EGL_NO_CONTEXT;
    }
    eglReleaseThread();  // this thread's EGL state (bound API, last error)
  }
};

EglContext::EglContext(int major, int minor)
    : RenderContext(RenderBackend::kEgl), impl_(std::make_unique<Impl>()) {
  Impl& egl = *impl_;
  try {
    egl.display = surfaceless_display();
    if (!has_extension(eglQueryString(egl.display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context"))
      throw RunError(
          "render: the EGL display lacks EGL_KHR_surfaceless_context (needed to render without "
          "a window or pbuffer surface)");
    if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE)
      throw_egl("eglBindAPI(EGL_OPENGL_API)", " (EGL without desktop OpenGL)");
    // Any configuration that renders OpenGL: the context draws only into framebuffer objects,
    // so its own colour and depth buffers do not matter.
    const std::array<EGLint, 5> config_attribs = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                                  EGL_SURFACE_TYPE, EGL_DONT_CARE, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configs = 0;
    if (eglChooseConfig(egl.display, config_attribs.data(), &config, 1, &configs) != EGL_TRUE)
      throw_egl("eglChooseConfig", " for an OpenGL configuration");
    if (configs < 1)
      throw RunError(
          "render: eglChooseConfig found no configuration that renders desktop OpenGL on the "
          "surfaceless platform");
    const std::array<EGLint, 7> context_attribs = {EGL_CONTEXT_MAJOR_VERSION,
                                                   major,
                                                   EGL_CONTEXT_MINOR_VERSION,
                                                   minor,
                                                   EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                                   EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                                   EGL_NONE};
    egl.context = eglCreateContext(egl.display, config, EGL_NO_CONTEXT, context_attribs.data());
    if (egl.context == EGL_NO_CONTEXT)
      throw_egl("eglCreateContext",
                fmt::format(" for an OpenGL {}.{} core-profile context", major, minor));
    if (eglMakeCurrent(egl.display, EGL_NO_SURFACE, EGL_NO_SURFACE, egl.context) != EGL_TRUE)
      throw_egl("eglMakeCurrent", " without a surface");
    load_gl([](const char* name) -> GlProc { return eglGetProcAddress(name); });
  } catch (...) {
    egl.release();
    throw;
  }
}

EglContext::~EglContext() {
  impl_->release();
}

std::string egl_error_name(int code) {
  switch (code) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE:
      return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP:
      return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW:
      return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
      return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST:
      return "EGL_CONTEXT_LOST";
    default:
      return fmt::format("unknown EGL error 0x{:04X}", code);
  }
}

}  // namespace somasim::render
