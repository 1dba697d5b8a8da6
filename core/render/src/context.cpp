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

#include "somasim/error.hpp"

namespace somasim::render {

namespace {

// The OsmesaContext of this thread, if any (one per thread).
thread_local const OsmesaContext* g_thread_context = nullptr;

std::string gl_string(const GlApi& gl, GLenum name) {
  const GLubyte* s = gl.GetString(name);
  return s == nullptr ? std::string("?") : std::string(reinterpret_cast<const char*>(s));
}

}  // namespace

struct OsmesaContext::Impl {
  OSMesaContext context = nullptr;
  std::array<unsigned char, 4> dummy{};  // 1 x 1 RGBA: the context's own buffer, never read
};

OsmesaContext::OsmesaContext(int major, int minor) : impl_(std::make_unique<Impl>()) {
  if (g_thread_context != nullptr)
    throw RunError(
        "render: this thread already has an OSMesa context (one context per thread; create one "
        "context per rendering thread)");
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
    gl_ = load_gl_api([](const char* name) -> GlProc { return OSMesaGetProcAddress(name); });
  } catch (...) {
    OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
    OSMesaDestroyContext(impl_->context);
    throw;
  }
  renderer_ = gl_string(gl_, GL_RENDERER);
  version_ = gl_string(gl_, GL_VERSION);
  g_thread_context = this;
}

OsmesaContext::~OsmesaContext() {
  if (OSMesaGetCurrentContext() == impl_->context) OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
  OSMesaDestroyContext(impl_->context);
  if (g_thread_context == this) g_thread_context = nullptr;
}

}  // namespace somasim::render
