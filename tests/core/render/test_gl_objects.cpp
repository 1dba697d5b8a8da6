// The OSMesa context, the GL function table and the RAII GL objects, with their named errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <string>
#include <thread>

#include "somasim/error.hpp"
#include "somasim/render/context.hpp"
#include "somasim/render/gl_objects.hpp"

using namespace somasim;
using namespace somasim::render;

namespace {

// Runs `f` and returns the RunError message it throws ("" and a failure when it does not).
template <typename F>
std::string run_error(F&& f) {
  try {
    f();
  } catch (const RunError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no RunError thrown";
  return "";
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

constexpr const char* kVertex = R"(#version 330 core
in vec3 position;
void main() { gl_Position = vec4(position, 1.0); }
)";
constexpr const char* kFragment = R"(#version 330 core
out vec4 out_colour;
void main() { out_colour = vec4(1.0); }
)";

}  // namespace

TEST(OsmesaContext, GivesACoreProfileOfAtLeast33) {
  OsmesaContext context;
  std::cout << "renderer: " << context.renderer() << "\nversion: " << context.version() << "\n";
  EXPECT_TRUE(contains(context.version(), "Core Profile")) << context.version();
  GLint major = 0, minor = 0;
  context.gl().GetIntegerv(GL_MAJOR_VERSION, &major);
  context.gl().GetIntegerv(GL_MINOR_VERSION, &minor);
  EXPECT_GE(major * 10 + minor, 33);
  EXPECT_NO_THROW(check_gl(context.gl(), "querying the version"));
}

TEST(OsmesaContext, OneContextPerThread) {
  OsmesaContext context;
  const std::string m = run_error([] { OsmesaContext second; });
  EXPECT_TRUE(contains(m, "one context per thread")) << m;
  // Another thread may have its own.
  std::string renderer;
  std::thread worker([&] {
    OsmesaContext other;
    renderer = other.renderer();
  });
  worker.join();
  EXPECT_EQ(renderer, context.renderer());
  // After the first is gone, this thread may make a new one.
}

TEST(OsmesaContext, ANewContextAfterTheFirstIsDestroyed) {
  { OsmesaContext first; }
  EXPECT_NO_THROW(OsmesaContext second);
}

TEST(GlApi, MissingFunctionsAreNamed) {
  const std::string m = run_error([] {
    load_gl_api([](const char* name) -> GlProc {
      return std::string(name) == "glDrawElements" ? nullptr : reinterpret_cast<GlProc>(&abort);
    });
  });
  EXPECT_TRUE(contains(m, "does not provide glDrawElements")) << m;
}

TEST(GlApi, CheckGlNamesWhatFailedAndTheError) {
  OsmesaContext context;
  const GlApi& gl = context.gl();
  gl.Enable(0x1234);  // not a capability
  const std::string m = run_error([&] { check_gl(gl, "camera 'left': enabling"); });
  EXPECT_EQ(m, "camera 'left': enabling: GL error GL_INVALID_ENUM");
  EXPECT_NO_THROW(check_gl(gl, "after the error was read"));
  EXPECT_EQ(gl_error_name(0x9999), "unknown GL error 0x9999");
}

TEST(ShaderProgram, BuildsAndFindsUniforms) {
  OsmesaContext context;
  ShaderProgram p(context.gl(), "flat", kVertex, kFragment);
  EXPECT_NE(p.id(), 0u);
  const std::string m = run_error([&] { p.uniform("missing"); });
  EXPECT_TRUE(contains(m, "flat: the shader program has no active uniform 'missing'")) << m;
}

TEST(ShaderProgram, CompileErrorCarriesTheInfoLog) {
  OsmesaContext context;
  const std::string broken = "#version 330 core\nout vec4 c;\nvoid main() { c = vec4(1.0) }\n";
  const std::string m =
      run_error([&] { ShaderProgram p(context.gl(), "camera 'left' shader", kVertex, broken); });
  EXPECT_TRUE(contains(m, "camera 'left' shader: fragment shader does not compile: ")) << m;
  EXPECT_TRUE(contains(m, "error")) << m;  // Mesa's log: "0:3(27): error: syntax error, ..."
  std::cout << m << "\n";
}

TEST(ShaderProgram, LinkErrorCarriesTheInfoLog) {
  OsmesaContext context;
  // The fragment shader calls a function that is declared but defined in no shader.
  const std::string reads_missing =
      "#version 330 core\nvec4 v_missing();\nout vec4 c;\nvoid main() { c = v_missing(); }\n";
  const std::string m =
      run_error([&] { ShaderProgram p(context.gl(), "scene", kVertex, reads_missing); });
  EXPECT_TRUE(contains(m, "scene: shader program does not link: ")) << m;
  EXPECT_TRUE(contains(m, "v_missing")) << m;
  std::cout << m << "\n";
}

TEST(Framebuffer, CompleteWithColourIdAndDepth) {
  OsmesaContext context;
  Framebuffer fb(context.gl(), 64, 48, "camera 'left'");
  EXPECT_EQ(fb.width(), 64);
  fb.bind();
  EXPECT_NO_THROW(check_gl(context.gl(), "binding"));
  Framebuffer moved = std::move(fb);
  EXPECT_EQ(moved.height(), 48);
}

TEST(Framebuffer, IncompleteFramebufferIsNamed) {
  OsmesaContext context;
  const GlApi& gl = context.gl();
  GLuint fbo = 0;  // a framebuffer without attachments
  gl.GenFramebuffers(1, &fbo);
  gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
  const std::string m =
      run_error([&] { check_framebuffer_complete(gl, "camera 'left': framebuffer 8 x 8"); });
  gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl.DeleteFramebuffers(1, &fbo);
  EXPECT_EQ(m,
            "camera 'left': framebuffer 8 x 8 is incomplete "
            "(GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT)");
}

TEST(Framebuffer, EmptySizeIsRefusedBeforeAnyGlCall) {
  OsmesaContext context;
  EXPECT_EQ(run_error([&] { Framebuffer fb(context.gl(), 0, 0, "camera 'left'"); }),
            "camera 'left': image size 0 x 0 px: both sides must be at least 1 px");
  EXPECT_EQ(run_error([&] { Framebuffer fb(context.gl(), 64, -3, "camera 'left'"); }),
            "camera 'left': image size 64 x -3 px: both sides must be at least 1 px");
  EXPECT_NO_THROW(check_gl(context.gl(), "after the refusal"));
}

TEST(Framebuffer, OversizedFramebufferNamesItsOwnerAndTheMaximum) {
  OsmesaContext context;
  const GlApi& gl = context.gl();
  GLint texture = 0, renderbuffer = 0;
  GLint viewport[2] = {0, 0};
  gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &texture);
  gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbuffer);
  gl.GetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  const int max_side = max_framebuffer_side(gl);
  EXPECT_EQ(max_side, std::min({texture, renderbuffer, viewport[0], viewport[1]}));
  std::cout << "max texture " << texture << ", renderbuffer " << renderbuffer << ", viewport "
            << viewport[0] << " x " << viewport[1] << " px\n";
  const std::string tail =
      " px is above the maximum of this OpenGL context: at most " + std::to_string(max_side) +
      " px per side (GL_MAX_TEXTURE_SIZE, GL_MAX_RENDERBUFFER_SIZE, GL_MAX_VIEWPORT_DIMS)";
  EXPECT_EQ(run_error([&] { Framebuffer fb(gl, max_side + 1, 1, "camera 'right'"); }),
            "camera 'right': image size " + std::to_string(max_side + 1) + " x 1" + tail);
  EXPECT_EQ(run_error([&] { Framebuffer fb(gl, 1, max_side + 1, "camera 'right'"); }),
            "camera 'right': image size 1 x " + std::to_string(max_side + 1) + tail);
  EXPECT_NO_THROW(check_gl(gl, "after the refusal"));
  EXPECT_NO_THROW(Framebuffer(gl, max_side, 1, "camera 'right'"));  // the maximum itself works
}

TEST(MeshBuffer, RejectsInconsistentMeshes) {
  OsmesaContext context;
  TriangleMesh m = tessellate_box({0.1, 0.1, 0.1});
  EXPECT_NO_THROW(MeshBuffer(context.gl(), m, "box"));
  m.indices.back() = 1000;
  EXPECT_TRUE(contains(run_error([&] { MeshBuffer(context.gl(), m, "box"); }),
                       "box: mesh index 1000 out of range (24 vertices)"));
  m.indices.pop_back();
  EXPECT_TRUE(
      contains(run_error([&] { MeshBuffer(context.gl(), m, "box"); }), "not a multiple of 3"));
}
