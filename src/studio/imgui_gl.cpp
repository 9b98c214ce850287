// ImGui's OpenGL 3 renderer, compiled from the sources libimgui-dev ships
// (/usr/share/doc/libimgui-dev/examples/backends), with its stripped gl3w
// loader filled through the host's function loader instead of dlopen("libGL")
// + glXGetProcAddress: under OSMesa there is no GLX context, and glvnd's
// dispatch stubs would draw nothing.
#define IMGUI_IMPL_OPENGL_LOADER_CUSTOM
#define IMGL3W_IMPL
#include <imgui_impl_opengl3_loader.h>

#include VGD_IMGUI_OPENGL3_BACKEND  // imgui_impl_opengl3.cpp (path set by CMake)

#include "gl.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/studio/studio.hpp"

namespace vgd::studio {

namespace {
bool g_ready = false;
}

void init_gl(GlLoader loader) {
  if (imgl3wInit2(reinterpret_cast<GL3WGetProcAddressProc>(loader)) != 0)
    throw Error("", "OpenGL", "cannot load the OpenGL 3.3 functions the studio draws with");
  if (!ImGui_ImplOpenGL3_Init("#version 330 core"))
    throw Error("", "OpenGL", "ImGui's OpenGL 3 renderer did not start");
  g_ready = true;
}

void shutdown_gl() {
  if (!g_ready) return;
  ImGui_ImplOpenGL3_Shutdown();
  g_ready = false;
}

void new_frame_gl() { ImGui_ImplOpenGL3_NewFrame(); }

void render_gl(ImDrawData* data) { ImGui_ImplOpenGL3_RenderDrawData(data); }

namespace gl {

bool ready() { return g_ready; }

unsigned upload_texture(const render::Image& image, unsigned reuse) {
  GLuint tex = reuse;
  if (!tex) glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, image.width, image.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
               image.rgba.data());
  return tex;
}

void delete_texture(unsigned texture) {
  if (!texture || !g_ready) return;
  GLuint t = texture;
  glDeleteTextures(1, &t);
}

}  // namespace gl
}  // namespace vgd::studio
