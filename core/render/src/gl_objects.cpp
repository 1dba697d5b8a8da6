#include "somasim/render/gl_objects.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <utility>
#include <vector>

#include "somasim/error.hpp"

namespace somasim::render {

// ---------------------------------------------------------------------------------------------
// Framebuffer

int max_framebuffer_side(const GlApi& gl) {
  GLint texture = 0, renderbuffer = 0;
  std::array<GLint, 2> viewport = {0, 0};
  gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &texture);
  gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbuffer);
  gl.GetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport.data());
  return std::min({texture, renderbuffer, viewport[0], viewport[1]});
}

Framebuffer::Framebuffer(const GlApi& gl, int width, int height, std::string owner)
    : gl_(&gl), width_(width), height_(height), owner_(std::move(owner)) {
  check_gl(gl, fmt::format("{}: before creating the framebuffer", owner_));
  if (width < 1 || height < 1)
    throw RunError(fmt::format("{}: image size {} x {} px: both sides must be at least 1 px",
                               owner_, width, height));
  if (const int max_side = max_framebuffer_side(gl); width > max_side || height > max_side)
    throw RunError(fmt::format(
        "{}: image size {} x {} px is above the maximum of this OpenGL context: at most {} px "
        "per side (GL_MAX_TEXTURE_SIZE, GL_MAX_RENDERBUFFER_SIZE, GL_MAX_VIEWPORT_DIMS)",
        owner_, width, height, max_side));
  try {
    gl.GenFramebuffers(1, &fbo_);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo_);

    const auto texture = [&](GLuint& tex, GLint internal, GLenum format, GLenum type) {
      gl.GenTextures(1, &tex);
      gl.BindTexture(GL_TEXTURE_2D, tex);
      gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      gl.TexImage2D(GL_TEXTURE_2D, 0, internal, width, height, 0, format, type, nullptr);
    };
    texture(colour_, GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour_, 0);
    texture(ids_, GL_R32I, GL_RED_INTEGER, GL_INT);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, ids_, 0);
    gl.BindTexture(GL_TEXTURE_2D, 0);

    gl.GenRenderbuffers(1, &depth_);
    gl.BindRenderbuffer(GL_RENDERBUFFER, depth_);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, width, height);
    gl.BindRenderbuffer(GL_RENDERBUFFER, 0);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
    check_gl(gl, fmt::format("{}: creating a {} x {} framebuffer", owner_, width, height));

    check_framebuffer_complete(gl, fmt::format("{}: framebuffer {} x {}", owner_, width, height));
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
  } catch (...) {
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    release();
    throw;
  }
}

Framebuffer::~Framebuffer() {
  release();
}

Framebuffer::Framebuffer(Framebuffer&& other) noexcept
    : gl_(other.gl_),
      width_(other.width_),
      height_(other.height_),
      owner_(std::move(other.owner_)),
      fbo_(std::exchange(other.fbo_, 0)),
      colour_(std::exchange(other.colour_, 0)),
      ids_(std::exchange(other.ids_, 0)),
      depth_(std::exchange(other.depth_, 0)) {}

Framebuffer& Framebuffer::operator=(Framebuffer&& other) noexcept {
  if (this != &other) {
    release();
    gl_ = other.gl_;
    width_ = other.width_;
    height_ = other.height_;
    owner_ = std::move(other.owner_);
    fbo_ = std::exchange(other.fbo_, 0);
    colour_ = std::exchange(other.colour_, 0);
    ids_ = std::exchange(other.ids_, 0);
    depth_ = std::exchange(other.depth_, 0);
  }
  return *this;
}

void Framebuffer::release() noexcept {
  if (fbo_ != 0) gl_->DeleteFramebuffers(1, &fbo_);
  if (colour_ != 0) gl_->DeleteTextures(1, &colour_);
  if (ids_ != 0) gl_->DeleteTextures(1, &ids_);
  if (depth_ != 0) gl_->DeleteRenderbuffers(1, &depth_);
  fbo_ = colour_ = ids_ = depth_ = 0;
}

void Framebuffer::bind() const {
  gl_->BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  const std::array<GLenum, 2> buffers = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  gl_->DrawBuffers(2, buffers.data());
  gl_->Viewport(0, 0, width_, height_);
}

// ---------------------------------------------------------------------------------------------
// ShaderProgram

namespace {

std::string shader_log(const GlApi& gl, GLuint shader) {
  GLint length = 0;
  gl.GetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  GLsizei written = 0;
  gl.GetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), &written, log.data());
  log.resize(static_cast<std::size_t>(written));
  while (!log.empty() && (log.back() == '\n' || log.back() == ' ')) log.pop_back();
  return log.empty() ? "(empty info log)" : log;
}

std::string program_log(const GlApi& gl, GLuint program) {
  GLint length = 0;
  gl.GetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  GLsizei written = 0;
  gl.GetProgramInfoLog(program, static_cast<GLsizei>(log.size()), &written, log.data());
  log.resize(static_cast<std::size_t>(written));
  while (!log.empty() && (log.back() == '\n' || log.back() == ' ')) log.pop_back();
  return log.empty() ? "(empty info log)" : log;
}

GLuint compile(const GlApi& gl, GLenum type, const std::string& source, const std::string& name) {
  const char* kind = type == GL_VERTEX_SHADER ? "vertex" : "fragment";
  const GLuint shader = gl.CreateShader(type);
  if (shader == 0) throw RunError(fmt::format("{}: glCreateShader failed ({} shader)", name, kind));
  const char* text = source.c_str();
  const auto length = static_cast<GLint>(source.size());
  gl.ShaderSource(shader, 1, &text, &length);
  gl.CompileShader(shader);
  GLint ok = GL_FALSE;
  gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = shader_log(gl, shader);
    gl.DeleteShader(shader);
    throw RunError(fmt::format("{}: {} shader does not compile: {}", name, kind, log));
  }
  return shader;
}

}  // namespace

ShaderProgram::ShaderProgram(const GlApi& gl, std::string name, const std::string& vertex_source,
                             const std::string& fragment_source)
    : gl_(&gl), name_(std::move(name)) {
  check_gl(gl, fmt::format("{}: before building the shader program", name_));
  const GLuint vs = compile(gl, GL_VERTEX_SHADER, vertex_source, name_);
  GLuint fs = 0;
  try {
    fs = compile(gl, GL_FRAGMENT_SHADER, fragment_source, name_);
  } catch (...) {
    gl.DeleteShader(vs);
    throw;
  }
  program_ = gl.CreateProgram();
  gl.AttachShader(program_, vs);
  gl.AttachShader(program_, fs);
  gl.BindAttribLocation(program_, 0, "position");
  gl.BindAttribLocation(program_, 1, "normal");
  gl.BindFragDataLocation(program_, 0, "out_colour");
  gl.BindFragDataLocation(program_, 1, "out_id");
  gl.LinkProgram(program_);
  gl.DeleteShader(vs);  // flagged for deletion; freed with the program
  gl.DeleteShader(fs);
  GLint ok = GL_FALSE;
  gl.GetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = program_log(gl, program_);
    gl.DeleteProgram(program_);
    program_ = 0;
    throw RunError(fmt::format("{}: shader program does not link: {}", name_, log));
  }
  try {
    check_gl(gl, fmt::format("{}: building the shader program", name_));
  } catch (...) {
    gl.DeleteProgram(program_);
    program_ = 0;
    throw;
  }
}

ShaderProgram::~ShaderProgram() {
  if (program_ != 0) gl_->DeleteProgram(program_);
}

ShaderProgram::ShaderProgram(ShaderProgram&& other) noexcept
    : gl_(other.gl_), name_(std::move(other.name_)), program_(std::exchange(other.program_, 0)) {}

ShaderProgram& ShaderProgram::operator=(ShaderProgram&& other) noexcept {
  if (this != &other) {
    if (program_ != 0) gl_->DeleteProgram(program_);
    gl_ = other.gl_;
    name_ = std::move(other.name_);
    program_ = std::exchange(other.program_, 0);
  }
  return *this;
}

void ShaderProgram::use() const {
  gl_->UseProgram(program_);
}

GLint ShaderProgram::uniform(const char* uniform_name) const {
  const GLint location = gl_->GetUniformLocation(program_, uniform_name);
  if (location < 0)
    throw RunError(
        fmt::format("{}: the shader program has no active uniform '{}'", name_, uniform_name));
  return location;
}

// ---------------------------------------------------------------------------------------------
// MeshBuffer

MeshBuffer::MeshBuffer(const GlApi& gl, const TriangleMesh& mesh, const std::string& owner)
    : gl_(&gl), bounds_(render::bounds(mesh)) {
  const std::size_t n = mesh.positions.size();
  if (mesh.normals.size() != n)
    throw RunError(
        fmt::format("{}: mesh has {} positions but {} normals", owner, n, mesh.normals.size()));
  if (mesh.indices.size() % 3 != 0)
    throw RunError(
        fmt::format("{}: mesh has {} indices, not a multiple of 3", owner, mesh.indices.size()));
  for (const std::uint32_t i : mesh.indices)
    if (i >= n)
      throw RunError(fmt::format("{}: mesh index {} out of range ({} vertices)", owner, i, n));
  std::vector<float> interleaved;
  interleaved.reserve(6 * n);
  for (std::size_t i = 0; i < n; ++i) {
    interleaved.insert(interleaved.end(), mesh.positions[i].data(), mesh.positions[i].data() + 3);
    interleaved.insert(interleaved.end(), mesh.normals[i].data(), mesh.normals[i].data() + 3);
  }
  count_ = static_cast<GLsizei>(mesh.indices.size());

  check_gl(gl, fmt::format("{}: before uploading a mesh", owner));
  gl.GenVertexArrays(1, &vao_);
  gl.BindVertexArray(vao_);
  gl.GenBuffers(1, &vbo_);
  gl.BindBuffer(GL_ARRAY_BUFFER, vbo_);
  gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(interleaved.size() * sizeof(float)),
                interleaved.data(), GL_STATIC_DRAW);
  gl.GenBuffers(1, &ibo_);
  gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo_);  // recorded in the vertex array
  gl.BufferData(GL_ELEMENT_ARRAY_BUFFER,
                static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
                mesh.indices.data(), GL_STATIC_DRAW);
  const auto stride = static_cast<GLsizei>(6 * sizeof(float));
  gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
  // GL takes the byte offset of the normals in the bound buffer as a pointer value.
  const auto normal_offset = std::bit_cast<const void*>(std::uintptr_t{3 * sizeof(float)});
  gl.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, normal_offset);
  gl.EnableVertexAttribArray(0);
  gl.EnableVertexAttribArray(1);
  gl.BindVertexArray(0);
  gl.BindBuffer(GL_ARRAY_BUFFER, 0);
  try {
    check_gl(gl, fmt::format("{}: uploading a mesh of {} triangles", owner, count_ / 3));
  } catch (...) {
    release();
    throw;
  }
}

MeshBuffer::~MeshBuffer() {
  release();
}

MeshBuffer::MeshBuffer(MeshBuffer&& other) noexcept
    : gl_(other.gl_),
      vao_(std::exchange(other.vao_, 0)),
      vbo_(std::exchange(other.vbo_, 0)),
      ibo_(std::exchange(other.ibo_, 0)),
      count_(std::exchange(other.count_, 0)),
      bounds_(std::move(other.bounds_)) {}

MeshBuffer& MeshBuffer::operator=(MeshBuffer&& other) noexcept {
  if (this != &other) {
    release();
    gl_ = other.gl_;
    vao_ = std::exchange(other.vao_, 0);
    vbo_ = std::exchange(other.vbo_, 0);
    ibo_ = std::exchange(other.ibo_, 0);
    count_ = std::exchange(other.count_, 0);
    bounds_ = other.bounds_;
  }
  return *this;
}

void MeshBuffer::release() noexcept {
  if (vao_ != 0) gl_->DeleteVertexArrays(1, &vao_);
  if (vbo_ != 0) gl_->DeleteBuffers(1, &vbo_);
  if (ibo_ != 0) gl_->DeleteBuffers(1, &ibo_);
  vao_ = vbo_ = ibo_ = 0;
}

void MeshBuffer::draw() const {
  gl_->BindVertexArray(vao_);
  if (count_ > 0) gl_->DrawElements(GL_TRIANGLES, count_, GL_UNSIGNED_INT, nullptr);
}

}  // namespace somasim::render
