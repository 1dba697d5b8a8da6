#include "mask_framebuffer.hpp"

#include <fmt/format.h>

namespace somasim::render {

MaskFramebuffer::MaskFramebuffer(const GlApi& gl, int width, int height, const std::string& owner)
    : gl_(&gl), width_(width), height_(height) {
  check_gl(gl, fmt::format("{}: before creating the mask framebuffer", owner));
  try {
    gl.GenFramebuffers(1, &fbo_);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
    gl.GenRenderbuffers(1, &colour_);
    gl.BindRenderbuffer(GL_RENDERBUFFER, colour_);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_R8, width, height);
    gl.BindRenderbuffer(GL_RENDERBUFFER, 0);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
    check_gl(gl, fmt::format("{}: creating a {} x {} mask framebuffer", owner, width, height));
    check_framebuffer_complete(gl,
                               fmt::format("{}: mask framebuffer {} x {}", owner, width, height));
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
  } catch (...) {
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    release();
    throw;
  }
}

MaskFramebuffer::~MaskFramebuffer() {
  release();
}

void MaskFramebuffer::bind() const {
  const GlApi& gl = *gl_;
  gl.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  const GLenum buffer = GL_COLOR_ATTACHMENT0;
  gl.DrawBuffers(1, &buffer);
  gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl.Viewport(0, 0, width_, height_);
}

void MaskFramebuffer::release() noexcept {
  if (colour_ != 0) gl_->DeleteRenderbuffers(1, &colour_);
  if (fbo_ != 0) gl_->DeleteFramebuffers(1, &fbo_);
  colour_ = fbo_ = 0;
}

}  // namespace somasim::render
