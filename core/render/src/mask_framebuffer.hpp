#pragma once
// Internal: a framebuffer with a single 8-bit colour attachment (GL_R8 renderbuffer) and no
// depth, for silhouette tiles: clears and read-backs move one byte per pixel, with no format
// conversion.
#include <string>

#include "somasim/render/gl_api.hpp"

namespace somasim::render {

class MaskFramebuffer {
 public:
  /// Throws RunError "`owner`: mask framebuffer W x H is incomplete (GL_...)" or naming the GL
  /// error.
  MaskFramebuffer(const GlApi& gl, int width, int height, const std::string& owner);
  ~MaskFramebuffer();
  MaskFramebuffer(const MaskFramebuffer&) = delete;
  MaskFramebuffer& operator=(const MaskFramebuffer&) = delete;
  MaskFramebuffer(MaskFramebuffer&&) = delete;
  MaskFramebuffer& operator=(MaskFramebuffer&&) = delete;

  /// Binds it as the draw and read framebuffer (colour attachment 0 as draw and read buffer).
  void bind() const;
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  void release() noexcept;

  const GlApi* gl_;
  int width_ = 0, height_ = 0;
  GLuint fbo_ = 0, colour_ = 0;
};

}  // namespace somasim::render
