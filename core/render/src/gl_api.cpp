#include "somasim/render/gl_api.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <vector>

#include "somasim/error.hpp"

namespace somasim::render {

GlApi load_gl_api(const GlProcLoader& loader) {
  GlApi gl;
  std::vector<std::string> missing;
#define SOMASIM_RENDER_GL_LOAD(type, name)              \
  gl.name = reinterpret_cast<type>(loader("gl" #name)); \
  if (gl.name == nullptr) missing.emplace_back("gl" #name);
  SOMASIM_RENDER_GL_FUNCTIONS(SOMASIM_RENDER_GL_LOAD)
#undef SOMASIM_RENDER_GL_LOAD
  if (!missing.empty())
    throw RunError(fmt::format("render: the OpenGL implementation does not provide {}",
                               fmt::join(missing, ", ")));
  return gl;
}

std::string gl_error_name(GLenum error) {
  switch (error) {
    case GL_NO_ERROR:
      return "GL_NO_ERROR";
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW:
      return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW:
      return "GL_STACK_OVERFLOW";
    default:
      return fmt::format("unknown GL error 0x{:04X}", error);
  }
}

std::string gl_framebuffer_status_name(GLenum status) {
  switch (status) {
    case GL_FRAMEBUFFER_COMPLETE:
      return "GL_FRAMEBUFFER_COMPLETE";
    case GL_FRAMEBUFFER_UNDEFINED:
      return "GL_FRAMEBUFFER_UNDEFINED";
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT:
      return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT:
      return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER:
      return "GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER";
    case GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER:
      return "GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER";
    case GL_FRAMEBUFFER_UNSUPPORTED:
      return "GL_FRAMEBUFFER_UNSUPPORTED";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE:
      return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
    case GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS:
      return "GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS";
    case 0:
      return "an error while checking (status 0)";
    default:
      return fmt::format("unknown framebuffer status 0x{:04X}", status);
  }
}

void check_gl(const GlApi& gl, std::string_view what) {
  std::vector<std::string> errors;
  // A context reports each error flag once; a bounded loop guards against a lost context that
  // would report GL_CONTEXT_LOST (or anything) forever.
  for (int i = 0; i < 16; ++i) {
    const GLenum e = gl.GetError();
    if (e == GL_NO_ERROR) break;
    errors.push_back(gl_error_name(e));
  }
  if (!errors.empty())
    throw RunError(fmt::format("{}: GL error {}", what, fmt::join(errors, ", ")));
}

void check_framebuffer_complete(const GlApi& gl, std::string_view what) {
  const GLenum status = gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw RunError(fmt::format("{} is incomplete ({})", what, gl_framebuffer_status_name(status)));
}

}  // namespace somasim::render
