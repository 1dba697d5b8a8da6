#pragma once
/// @file
/// RAII owners of the GL objects somasim::render draws with: framebuffers, shader programs and
/// mesh buffers.
///
/// Each object keeps a reference to the GlApi table of its context: it must be created, used and
/// destroyed on that context's thread, while the context is alive (see context.hpp). Objects are
/// movable, not copyable. Every failure throws somasim::RunError naming the owner given at
/// construction (a camera name, a shader name) and the GL error or log.
#include <string>

#include "somasim/render/gl_api.hpp"
#include "somasim/render/tessellate.hpp"

namespace somasim::render {

/// Largest side [px] of a Framebuffer this context can make: the smallest of
/// GL_MAX_TEXTURE_SIZE, GL_MAX_RENDERBUFFER_SIZE and both GL_MAX_VIEWPORT_DIMS (16384 on
/// llvmpipe).
int max_framebuffer_side(const GlApi& gl);

/// Framebuffer object of width × height pixels with three attachments:
///   - colour attachment 0: RGBA8 texture (the shaded image),
///   - colour attachment 1: R32I texture (the id mask),
///   - depth: DEPTH_COMPONENT32F renderbuffer.
/// The size is checked before any GL call, completeness at construction.
class Framebuffer {
 public:
  /// Throws RunError
  ///   "`owner`: image size W x H px: both sides must be at least 1 px",
  ///   "`owner`: image size W x H px is above the maximum of this OpenGL context: at most M px
  ///    per side (GL_MAX_TEXTURE_SIZE, GL_MAX_RENDERBUFFER_SIZE, GL_MAX_VIEWPORT_DIMS)"
  ///    (M = max_framebuffer_side()),
  /// "`owner`: framebuffer W x H is incomplete (GL_...)", or one naming the GL error.
  Framebuffer(const GlApi& gl, int width, int height, std::string owner);
  ~Framebuffer();
  Framebuffer(Framebuffer&& other) noexcept;
  Framebuffer& operator=(Framebuffer&& other) noexcept;
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;

  /// Binds it as the draw and read framebuffer with both colour attachments as draw buffers and
  /// sets the viewport to the whole framebuffer.
  void bind() const;
  int width() const { return width_; }
  int height() const { return height_; }
  const std::string& owner() const { return owner_; }
  GLuint id() const { return fbo_; }

 private:
  void release() noexcept;

  const GlApi* gl_;
  int width_ = 0, height_ = 0;
  std::string owner_;
  GLuint fbo_ = 0, colour_ = 0, ids_ = 0, depth_ = 0;
};

/// Linked GLSL program made of a vertex and a fragment shader.
class ShaderProgram {
 public:
  /// Compiles and links. Vertex attributes `position` and `normal` are bound to locations 0 and
  /// 1, fragment outputs `out_colour` and `out_id` to draw buffers 0 and 1 (unused names are
  /// fine). Throws RunError "`name`: vertex shader does not compile: <GL info log>" (or fragment
  /// shader, or "does not link").
  ShaderProgram(const GlApi& gl, std::string name, const std::string& vertex_source,
                const std::string& fragment_source);
  ~ShaderProgram();
  ShaderProgram(ShaderProgram&& other) noexcept;
  ShaderProgram& operator=(ShaderProgram&& other) noexcept;
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  void use() const;
  /// Location of a uniform; throws RunError when the program has no active uniform `name`.
  GLint uniform(const char* name) const;
  const std::string& name() const { return name_; }
  GLuint id() const { return program_; }

 private:
  const GlApi* gl_;
  std::string name_;
  GLuint program_ = 0;
};

/// A TriangleMesh uploaded once: vertex array object with positions at attribute 0, normals at
/// attribute 1 (float × 3 each) and an index buffer.
class MeshBuffer {
 public:
  /// Throws RunError naming `owner` on a GL error, or when positions, normals and indices are
  /// inconsistent (an index out of range, a count not a multiple of 3).
  MeshBuffer(const GlApi& gl, const TriangleMesh& mesh, const std::string& owner);
  ~MeshBuffer();
  MeshBuffer(MeshBuffer&& other) noexcept;
  MeshBuffer& operator=(MeshBuffer&& other) noexcept;
  MeshBuffer(const MeshBuffer&) = delete;
  MeshBuffer& operator=(const MeshBuffer&) = delete;

  /// Binds the vertex array and draws all triangles (with the current program).
  void draw() const;
  GLsizei index_count() const { return count_; }
  /// Bounds of the mesh's vertices [m, mesh frame].
  const Bounds& bounds() const { return bounds_; }

 private:
  void release() noexcept;

  const GlApi* gl_;
  GLuint vao_ = 0, vbo_ = 0, ibo_ = 0;
  GLsizei count_ = 0;
  Bounds bounds_;
};

}  // namespace somasim::render
