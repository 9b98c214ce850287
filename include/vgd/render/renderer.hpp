#pragma once
// The drawing code: OpenGL 3.3 core, in whatever context is current.
//
// One drawing path, two backends (docs/render.md): `vgd render` makes an OSMesa
// off-screen context (offscreen.hpp) and draws into a supersampled framebuffer;
// the studio draws in its window's context with the same Renderer, into a
// texture it shows (draw_to_texture). The Renderer reaches OpenGL only through the function
// loader it is given (OSMesaGetProcAddress, glfwGetProcAddress, ...), so this
// header and its users need no GL headers.
//
//   Renderer r(loader);        // a GL 3.3 core context is current
//   r.set_scene(scene);        // uploads the meshes
//   r.draw(camera, {fbo, w, h});
#include <memory>
#include <string>

#include "vgd/render/camera.hpp"
#include "vgd/render/scene.hpp"

namespace vgd::render {

// How a frame looks. Colours are sRGB.
struct RenderOptions {
  Colour background{0.95f, 0.95f, 0.94f};
  bool floor = true;                       // a ground at the lowest point of the scene, fading into the background
  Colour floor_colour{0.88f, 0.87f, 0.85f};
  bool shadow = true;                      // the soft shadow of everything on the floor (light from above)
  float shadow_strength = 0.45f;           // 0 none … 1 black, under the body
  float shadow_softness_m = 0.05f;         // width of the penumbra, m
  int shadow_map_size = 1024;              // texels per side
};

// Where to draw: a framebuffer object (0 = the context's default framebuffer)
// and its size in pixels.
struct Target {
  unsigned framebuffer = 0;
  int width = 0, height = 0;
};

class Renderer {
 public:
  using GlProc = void (*)();
  using ProcLoader = GlProc (*)(const char* name);

  // Loads the GL functions and compiles the shaders. A GL 3.3 core (or newer)
  // context must be current, and stay current for every call below.
  explicit Renderer(ProcLoader loader);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Uploads the scene's meshes (normals computed where missing). Throws
  // vgd::Error for a malformed scene (check_scene).
  void set_scene(const Scene& scene);

  // Bounds of the uploaded scene, and of its body meshes only.
  const Box& scene_bounds() const;
  const Box& body_bounds() const;

  // Draws one frame into the target: clear, floor with its shadow, meshes.
  void draw(const Camera& camera, const Target& target, const RenderOptions& options = {});

  // Draws one frame as draw() does into a colour texture the renderer keeps
  // (RGBA8, width × height, rows bottom first as OpenGL stores them) and
  // returns the texture's name, valid in the current context until the next
  // call or the renderer's end; the framebuffer bound before is bound again.
  // For a window that shows the frame among its widgets (the studio's 3-D
  // view) with no copy through the CPU.
  unsigned draw_to_texture(const Camera& camera, int width, int height, const RenderOptions& options = {});

  // "OpenGL 4.5 (Core Profile) Mesa 22.3.6, llvmpipe (LLVM 15.0.6, 256 bits)".
  std::string gl_description() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vgd::render
