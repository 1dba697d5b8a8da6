#pragma once
/// @file
/// The OpenGL core-profile functions somasim::render uses, loaded at run time.
///
/// No gl* symbol is linked directly: libOSMesa and libOpenGL (EGL) both export them, and which
/// one would win depends on the link order. Instead each context back end hands `load_gl_api` its
/// proc-address function (OSMesaGetProcAddress today, eglGetProcAddress later) and every GL call
/// of the library goes through the resulting table: `gl.Clear(GL_COLOR_BUFFER_BIT)`.
///
/// Types, enums and the PFN typedefs come from <GL/glcorearb.h> (core profile only; no GL/gl.h).
#include <functional>
#include <string>
#include <string_view>

#include <GL/glcorearb.h>

namespace somasim::render {

/// X-macro list of the functions of the table: X(PFN type, member name = GL name without "gl").
#define SOMASIM_RENDER_GL_FUNCTIONS(X)                         \
  X(PFNGLGETERRORPROC, GetError)                               \
  X(PFNGLGETSTRINGPROC, GetString)                             \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                         \
  X(PFNGLENABLEPROC, Enable)                                   \
  X(PFNGLDISABLEPROC, Disable)                                 \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                             \
  X(PFNGLDEPTHMASKPROC, DepthMask)                             \
  X(PFNGLCOLORMASKPROC, ColorMask)                             \
  X(PFNGLVIEWPORTPROC, Viewport)                               \
  X(PFNGLSCISSORPROC, Scissor)                                 \
  X(PFNGLFINISHPROC, Finish)                                   \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                         \
  X(PFNGLREADPIXELSPROC, ReadPixels)                           \
  X(PFNGLREADBUFFERPROC, ReadBuffer)                           \
  X(PFNGLDRAWBUFFERSPROC, DrawBuffers)                         \
  X(PFNGLCLEARPROC, Clear)                                     \
  X(PFNGLCLEARBUFFERFVPROC, ClearBufferfv)                     \
  X(PFNGLCLEARBUFFERIVPROC, ClearBufferiv)                     \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                 \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)           \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                 \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)       \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer) \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)   \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)               \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)         \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)               \
  X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)         \
  X(PFNGLGENTEXTURESPROC, GenTextures)                         \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                   \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                         \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                           \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                     \
  X(PFNGLCREATESHADERPROC, CreateShader)                       \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                       \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                     \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                         \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)               \
  X(PFNGLDELETESHADERPROC, DeleteShader)                       \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                     \
  X(PFNGLATTACHSHADERPROC, AttachShader)                       \
  X(PFNGLBINDATTRIBLOCATIONPROC, BindAttribLocation)           \
  X(PFNGLBINDFRAGDATALOCATIONPROC, BindFragDataLocation)       \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                         \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                       \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)             \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                     \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                           \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)           \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                             \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                             \
  X(PFNGLUNIFORM3FPROC, Uniform3f)                             \
  X(PFNGLUNIFORM4FPROC, Uniform4f)                             \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)               \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                 \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)           \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                 \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                           \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                     \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                           \
  X(PFNGLBUFFERDATAPROC, BufferData)                           \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)         \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray) \
  X(PFNGLDRAWELEMENTSPROC, DrawElements)                       \
  X(PFNGLGENQUERIESPROC, GenQueries)                           \
  X(PFNGLDELETEQUERIESPROC, DeleteQueries)                     \
  X(PFNGLBEGINQUERYPROC, BeginQuery)                           \
  X(PFNGLENDQUERYPROC, EndQuery)                               \
  X(PFNGLGETQUERYOBJECTUIVPROC, GetQueryObjectuiv)

/// Table of GL function pointers, valid for the context that was current when it was loaded (and
/// for contexts sharing its dispatch, as every Mesa context of one process does).
struct GlApi {
#define SOMASIM_RENDER_GL_MEMBER(type, name) type name = nullptr;
  SOMASIM_RENDER_GL_FUNCTIONS(SOMASIM_RENDER_GL_MEMBER)
#undef SOMASIM_RENDER_GL_MEMBER
};

/// A generic function pointer, as OSMesaGetProcAddress and eglGetProcAddress return.
using GlProc = void (*)();
/// Returns the address of the GL function `name` ("glClear"), or nullptr when unknown.
using GlProcLoader = std::function<GlProc(const char* name)>;

/// Fills the table through `loader`. Throws somasim::RunError naming every function the loader
/// did not provide.
GlApi load_gl_api(const GlProcLoader& loader);

/// "GL_INVALID_OPERATION" etc.; "unknown GL error 0x...." for codes outside the core list.
std::string gl_error_name(GLenum error);

/// "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT" etc. for glCheckFramebufferStatus results.
std::string gl_framebuffer_status_name(GLenum status);

/// Throws somasim::RunError "`what`: GL error GL_..." when glGetError reports errors (all pending
/// errors are drained and named).
void check_gl(const GlApi& gl, std::string_view what);

/// Throws somasim::RunError "`what` is incomplete (GL_FRAMEBUFFER_...)" unless the bound
/// framebuffer is complete.
void check_framebuffer_complete(const GlApi& gl, std::string_view what);

}  // namespace somasim::render
