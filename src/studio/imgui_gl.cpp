// ImGui's OpenGL 3 renderer, compiled from the sources libimgui-dev ships
// (/usr/share/doc/libimgui-dev/examples/backends), with its stripped gl3w
// loader filled through the host's function loader instead of dlopen("libGL")
// + glXGetProcAddress: under OSMesa there is no GLX context, and glvnd's
// dispatch stubs would draw nothing.
#define IMGUI_IMPL_OPENGL_LOADER_CUSTOM
#define IMGL3W_IMPL
#include <imgui_impl_opengl3_loader.h>

#include VGD_IMGUI_OPENGL3_BACKEND  // imgui_impl_opengl3.cpp (path set by CMake)

#include <functional>
#include <optional>
#include <string_view>

#include "gl.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/studio/studio.hpp"

namespace vgd::studio {

namespace {

// The framebuffer cleared to the style's window background: the studio's
// main window draws none of its own.
void clear_frame(const ImDrawData* data) {
  const ImVec4 bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
  glViewport(0, 0, static_cast<GLsizei>(data->DisplaySize.x * data->FramebufferScale.x),
             static_cast<GLsizei>(data->DisplaySize.y * data->FramebufferScale.y));
  glClearColor(bg.x, bg.y, bg.z, bg.w);
  glClear(GL_COLOR_BUFFER_BIT);
}

bool g_ready = false;
std::optional<std::size_t> g_last_frame;  // hash of the last frame drawn (render_gl_if_changed)
GlLoader g_loader = nullptr;
}

void init_gl(GlLoader loader) {
  g_loader = loader;
  // Not imgl3wInit2(): in ImGui 1.86 its table's ptr[] holds 53 entries for
  // 54 names (the union's struct has all 54, so the write stays inside the
  // table, but UBSan rightly reports the index). Fill the same table through
  // a pointer to its storage, each name to its struct member in order.
  constexpr std::size_t n = sizeof(proc_names) / sizeof(proc_names[0]);
  static_assert(sizeof(imgl3wProcs) >= n * sizeof(GL3WglProc), "gl3w's table holds every name");
  auto* table = reinterpret_cast<GL3WglProc*>(&imgl3wProcs);
  for (std::size_t i = 0; i < n; ++i) table[i] = reinterpret_cast<GL3WglProc>(loader(proc_names[i]));
  if (parse_version() != GL3W_OK)
    throw Error("", "OpenGL", "cannot load the OpenGL 3.3 functions the studio draws with");
  if (!ImGui_ImplOpenGL3_Init("#version 330 core"))
    throw Error("", "OpenGL", "ImGui's OpenGL 3 renderer did not start");
  g_ready = true;
  g_last_frame.reset();
}

void shutdown_gl() {
  g_last_frame.reset();
  if (!g_ready) return;
  ImGui_ImplOpenGL3_Shutdown();
  g_ready = false;
}

void new_frame_gl() { ImGui_ImplOpenGL3_NewFrame(); }

bool render_gl_if_changed(ImDrawData* data, std::uint64_t pictures, bool force) {
  // What the frame draws, hashed piece by piece: every list's vertices and
  // indices, and per command its texture, clip rectangle and range; the
  // display; the picture count.
  std::size_t h = 0;
  const auto add = [&](const void* p, std::size_t n) {
    h = (h ^ std::hash<std::string_view>{}(std::string_view(static_cast<const char*>(p), n))) * 1099511628211ULL;
  };
  add(&pictures, sizeof pictures);
  add(&data->DisplayPos, sizeof data->DisplayPos);
  add(&data->DisplaySize, sizeof data->DisplaySize);
  add(&data->FramebufferScale, sizeof data->FramebufferScale);
  for (int i = 0; i < data->CmdListsCount; ++i) {
    const ImDrawList* l = data->CmdLists[i];
    add(l->VtxBuffer.Data, static_cast<std::size_t>(l->VtxBuffer.Size) * sizeof(ImDrawVert));
    add(l->IdxBuffer.Data, static_cast<std::size_t>(l->IdxBuffer.Size) * sizeof(ImDrawIdx));
    for (const ImDrawCmd& c : l->CmdBuffer) {
      add(&c.ClipRect, sizeof c.ClipRect);
      add(&c.TextureId, sizeof c.TextureId);
      add(&c.VtxOffset, sizeof c.VtxOffset);
      add(&c.IdxOffset, sizeof c.IdxOffset);
      add(&c.ElemCount, sizeof c.ElemCount);
      const bool callback = c.UserCallback != nullptr;
      add(&callback, sizeof callback);
    }
  }
  if (!force && g_last_frame && *g_last_frame == h) return false;
  clear_frame(data);
  ImGui_ImplOpenGL3_RenderDrawData(data);
  g_last_frame = h;
  return true;
}

render::Image read_framebuffer(int width, int height) {
  render::Image img(width, height);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
  // OpenGL's rows go up from the bottom.
  const std::size_t row = static_cast<std::size_t>(width) * 4;
  std::vector<std::uint8_t> tmp(row);
  for (int y = 0; y < height / 2; ++y) {
    auto* a = img.rgba.data() + y * row;
    auto* b = img.rgba.data() + (height - 1 - y) * row;
    std::copy_n(a, row, tmp.data());
    std::copy_n(b, row, a);
    std::copy_n(tmp.data(), row, b);
  }
  return img;
}

namespace gl {

bool ready() { return g_ready; }

GlLoader loader() { return g_loader; }

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
