#include "somasim/render/context.hpp"

// osmesa.h includes GL/gl.h, whose legacy declarations must not meet glcorearb.h (already
// included through gl_api.hpp): gl.h's include guard is set so that osmesa.h only adds its own
// declarations, whose types glcorearb.h defines (GLAPIENTRY is gl.h's calling-convention macro,
// empty on Linux).
#define __gl_h_
#ifndef GLAPIENTRY
#define GLAPIENTRY
#endif
#include <GL/osmesa.h>
#undef __gl_h_

#include <fmt/format.h>

#include <array>

#include "somasim/diagnostics.hpp"
#include "somasim/error.hpp"
#include "somasim/render/egl_context.hpp"

namespace somasim::render {

namespace {

// The context of this thread, if any (one per thread, whatever its back end: Mesa's GL dispatch
// has one current context per thread).
thread_local const RenderContext* g_thread_context = nullptr;

std::string gl_string(const GlApi& gl, GLenum name) {
  const GLubyte* s = gl.GetString(name);
  return s == nullptr ? std::string("?") : std::string(reinterpret_cast<const char*>(s));
}

const char* backend_label(RenderBackend backend) {
  return backend == RenderBackend::kEgl ? "EGL" : "OSMesa";
}

}  // namespace

RenderBackend parse_render_backend(const std::string& name) {
  if (const auto backend = parse_enum<RenderBackend>(name)) return *backend;
  throw InputError(fmt::format("unknown render backend '{}'; expected 'osmesa' or 'egl'{}", name,
                               did_you_mean(name, render_backend_names())));
}

std::string render_backend_name(RenderBackend backend) {
  return std::string(enum_name(backend));
}

std::vector<std::string> render_backend_names() {
  return enum_names<RenderBackend>();
}

RenderContext::RenderContext(RenderBackend backend) : backend_(backend) {
  if (g_thread_context != nullptr)
    throw RunError(fmt::format(
        "render: this thread already has an {} context (one context per thread; create one "
        "context per rendering thread)",
        backend_label(g_thread_context->backend())));
  g_thread_context = this;
}

RenderContext::~RenderContext() {
  if (g_thread_context == this) g_thread_context = nullptr;
}

void RenderContext::load_gl(const GlProcLoader& loader) {
  gl_ = load_gl_api(loader);
  renderer_ = gl_string(gl_, GL_RENDERER);
  version_ = gl_string(gl_, GL_VERSION);
}

std::unique_ptr<RenderContext> make_render_context(RenderBackend backend, int major, int minor) {
  if (backend == RenderBackend::kEgl) return std::make_unique<EglContext>(major, minor);
  return std::make_unique<OsmesaContext>(major, minor);
}

struct OsmesaContext::Impl {
  OSMesaContext context = nullptr;
  std::array<unsigned char, 4> dummy{};  // 1 x 1 RGBA: the context's own buffer, never read
};

OsmesaContext::OsmesaContext(int major, int minor)
    : RenderContext(RenderBackend::kOsmesa), impl_(std::make_unique<Impl>()) {
  const std::array<int, 11> attribs = {OSMESA_FORMAT,
                                       OSMESA_RGBA,
                                       OSMESA_PROFILE,
                                       OSMESA_CORE_PROFILE,
                                       OSMESA_CONTEXT_MAJOR_VERSION,
                                       major,
                                       OSMESA_CONTEXT_MINOR_VERSION,
                                       minor,
                                       OSMESA_DEPTH_BITS,
                                       0,
                                       0};
  impl_->context = OSMesaCreateContextAttribs(attribs.data(), nullptr);
  if (impl_->context == nullptr)
    throw RunError(fmt::format(
        "render: OSMesaCreateContextAttribs failed for an OpenGL {}.{} core-profile context "
        "(is Mesa's libOSMesa installed: Debian package libosmesa6?)",
        major, minor));
  if (OSMesaMakeCurrent(impl_->context, impl_->dummy.data(), GL_UNSIGNED_BYTE, 1, 1) != GL_TRUE) {
    OSMesaDestroyContext(impl_->context);
    throw RunError("render: OSMesaMakeCurrent failed for a new OSMesa context");
  }
  try {
    load_gl([](const char* name) -> GlProc { return OSMesaGetProcAddress(name); });
  } catch (...) {
    OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
    OSMesaDestroyContext(impl_->context);
    throw;
  }
}

OsmesaContext::~OsmesaContext() {
  if (OSMesaGetCurrentContext() == impl_->context) OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
  OSMesaDestroyContext(impl_->context);
}

}  // namespace somasim::render
