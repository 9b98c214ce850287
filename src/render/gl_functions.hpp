#pragma once
// The OpenGL 3.3 core functions the renderer calls, loaded through a function
// loader (OSMesaGetProcAddress, glfwGetProcAddress, ...) into a table. Private
// to src/render (renderer.cpp and offscreen.cpp).
#include <GL/glcorearb.h>

#include <string>

#include "vgd/render/renderer.hpp"

namespace vgd::render::gl {

// X(type of the pointer, name without the "gl" prefix)
#define VGD_GL_FUNCTIONS(X)                                              \
  X(PFNGLGETSTRINGPROC, GetString)                                       \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                   \
  X(PFNGLGETERRORPROC, GetError)                                         \
  X(PFNGLENABLEPROC, Enable)                                             \
  X(PFNGLDISABLEPROC, Disable)                                           \
  X(PFNGLVIEWPORTPROC, Viewport)                                         \
  X(PFNGLCLEARCOLORPROC, ClearColor)                                     \
  X(PFNGLCLEARDEPTHPROC, ClearDepth)                                     \
  X(PFNGLCLEARPROC, Clear)                                               \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                       \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                       \
  X(PFNGLCOLORMASKPROC, ColorMask)                                       \
  X(PFNGLPOLYGONOFFSETPROC, PolygonOffset)                               \
  X(PFNGLDRAWBUFFERPROC, DrawBuffer)                                     \
  X(PFNGLREADBUFFERPROC, ReadBuffer)                                     \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                     \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                   \
  X(PFNGLFINISHPROC, Finish)                                             \
  X(PFNGLCREATESHADERPROC, CreateShader)                                 \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                 \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                               \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                   \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                         \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                 \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                               \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                 \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                   \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                 \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                       \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                               \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                     \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                     \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                       \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                                       \
  X(PFNGLUNIFORM2FPROC, Uniform2f)                                       \
  X(PFNGLUNIFORM3FPROC, Uniform3f)                                       \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                         \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                           \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                           \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                     \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                                     \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                     \
  X(PFNGLBUFFERDATAPROC, BufferData)                                     \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                               \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                   \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)           \
  X(PFNGLDRAWELEMENTSPROC, DrawElements)                                 \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                                     \
  X(PFNGLGENTEXTURESPROC, GenTextures)                                   \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                                   \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                     \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                               \
  X(PFNGLTEXPARAMETERFVPROC, TexParameterfv)                             \
  X(PFNGLGENERATEMIPMAPPROC, GenerateMipmap)                             \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                               \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                             \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                           \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                           \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)                 \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)           \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)             \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                     \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                         \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                         \
  X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)                   \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)

struct Functions {
#define VGD_GL_MEMBER(type, name) type name = nullptr;
  VGD_GL_FUNCTIONS(VGD_GL_MEMBER)
#undef VGD_GL_MEMBER

  // Loads every function; returns the name of the first one missing, or empty.
  std::string load(Renderer::ProcLoader loader);
};

}  // namespace vgd::render::gl
