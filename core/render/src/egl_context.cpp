#include "somasim/render/egl_context.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <fmt/format.h>

#include <array>
#include <cstdlib>
#include <mutex>
#include <string>
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

// An initialised display that can make contexts current without a surface, or EGL_NO_DISPLAY
// (after eglTerminate) when `display` does not initialise or lacks surfaceless contexts.
EGLDisplay initialised_surfaceless_capable(EGLDisplay display) {
  if (display == EGL_NO_DISPLAY) return EGL_NO_DISPLAY;
  EGLint major = 0, minor = 0;
  if (eglInitialize(display, &major, &minor) != EGL_TRUE) return EGL_NO_DISPLAY;
  if (!has_extension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context")) {
    eglTerminate(display);
    return EGL_NO_DISPLAY;
  }
  return display;
}

// Mesa's surfaceless platform: the GPU through its render node where Mesa drives it, llvmpipe
// otherwise. EGL_NO_DISPLAY when the EGL library has no such platform.
EGLDisplay mesa_surfaceless_display(const char* client, std::string* tried) {
  *tried += "surfaceless platform: ";
  if (!has_extension(client, "EGL_MESA_platform_surfaceless")) {
    *tried += "absent (EGL_MESA_platform_surfaceless; Debian package libegl-mesa0)";
    return EGL_NO_DISPLAY;
  }
  const auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  const EGLDisplay display = initialised_surfaceless_capable(
      get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
  *tried +=
      display == EGL_NO_DISPLAY ? fmt::format("failed ({})", egl_error_name(eglGetError())) : "ok";
  return display;
}

// The first hardware EGL device (not Mesa's software device) that gives a display able to render
// without a surface: how NVIDIA's driver renders off-screen. EGL_NO_DISPLAY when there is none.
EGLDisplay hardware_device_display(const char* client, std::string* tried) {
  *tried += "device platform: ";
  // Device enumeration comes alone or within EGL_EXT_device_base (NVIDIA lists only the latter).
  if (!has_extension(client, "EGL_EXT_platform_device") ||
      !(has_extension(client, "EGL_EXT_device_enumeration") ||
        has_extension(client, "EGL_EXT_device_base"))) {
    *tried += "absent (EGL_EXT_platform_device, EGL_EXT_device_enumeration or _base)";
    return EGL_NO_DISPLAY;
  }
  const auto query_devices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  const auto query_device_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
      eglGetProcAddress("eglQueryDeviceStringEXT"));
  const auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (query_devices == nullptr || query_device_string == nullptr) {
    *tried += "eglQueryDevicesEXT or eglQueryDeviceStringEXT missing";
    return EGL_NO_DISPLAY;
  }
  constexpr EGLint kMaxDevices = 16;
  std::array<EGLDeviceEXT, kMaxDevices> devices{};
  EGLint count = 0;
  if (query_devices(kMaxDevices, devices.data(), &count) != EGL_TRUE) count = 0;
  int hardware = 0;
  for (EGLint i = 0; i < count; ++i) {
    if (has_extension(query_device_string(devices[i], EGL_EXTENSIONS), "EGL_MESA_device_software"))
      continue;
    ++hardware;
    const EGLDisplay display = initialised_surfaceless_capable(
        get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr));
    if (display != EGL_NO_DISPLAY) {
      *tried += fmt::format("device {} of {}", i, count);
      return display;
    }
  }
  *tried += fmt::format("{} devices, {} of them hardware, none usable", count, hardware);
  return EGL_NO_DISPLAY;
}

// Which displays SOMASIM_EGL_PLATFORM allows: "auto" (unset or empty: a hardware EGL device
// first, then Mesa's surfaceless platform; only the latter when LIBGL_ALWAYS_SOFTWARE asks for
// software rendering), "device" or "surfaceless".
struct PlatformChoice {
  bool device = true;
  bool surfaceless = true;
};

bool software_rendering_asked() {
  const char* value = std::getenv("LIBGL_ALWAYS_SOFTWARE");  // NOLINT(concurrency-mt-unsafe)
  if (value == nullptr) return false;
  const std::string_view text(value);
  return !text.empty() && text != "0" && text != "false";
}

PlatformChoice platform_choice() {
  const char* value = std::getenv("SOMASIM_EGL_PLATFORM");  // NOLINT(concurrency-mt-unsafe)
  const std::string_view choice = value == nullptr ? "auto" : value;
  if (choice == "auto" || choice.empty())
    return {.device = !software_rendering_asked(), .surfaceless = true};
  if (choice == "device") return {.device = true, .surfaceless = false};
  if (choice == "surfaceless") return {.device = false, .surfaceless = true};
  throw RunError(fmt::format(
      "render: SOMASIM_EGL_PLATFORM is '{}'; expected auto, device or surfaceless", choice));
}

// The process's one EGL display, initialised by the first EglContext and never terminated:
// eglTerminate would end it for every thread at once (EGL does not count initialisations) and
// unload the driver, whose remaining allocations then show as leaks.
EGLDisplay process_display() {
  static std::mutex mutex;
  static EGLDisplay display = EGL_NO_DISPLAY;
  std::lock_guard lock(mutex);
  if (display != EGL_NO_DISPLAY) return display;
  const PlatformChoice choice = platform_choice();
  // Client extensions (EGL_EXT_client_extensions): NULL when the EGL library has none.
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!has_extension(client, "EGL_EXT_platform_base") ||
      eglGetProcAddress("eglGetPlatformDisplayEXT") == nullptr)
    throw RunError(
        "render: EGL has no platform displays (client extension EGL_EXT_platform_base or "
        "eglGetPlatformDisplayEXT missing): the egl backend needs Mesa's EGL driver, Debian "
        "package libegl-mesa0, or a GPU driver's EGL (or use backend: osmesa)");
  std::string tried;
  EGLDisplay candidate = EGL_NO_DISPLAY;
  if (choice.device) candidate = hardware_device_display(client, &tried);
  if (candidate == EGL_NO_DISPLAY && choice.surfaceless) {
    if (!tried.empty()) tried += "; ";
    candidate = mesa_surfaceless_display(client, &tried);
  }
  if (candidate == EGL_NO_DISPLAY)
    throw RunError(fmt::format(
        "render: no EGL display renders without a window ({}): the egl backend needs Mesa's EGL "
        "driver, Debian package libegl-mesa0, or a GPU driver's EGL (or use backend: osmesa)",
        tried));
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
    egl.display = process_display();
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
