#pragma once
// Headless previews: the Renderer in an OSMesa off-screen context (llvmpipe),
// supersampled and read back as an Image (docs/render.md).
//
//   render::Image img = render::render_view(scene, *render::find_view("front"), 1024, 1024);
//   render::write_png(img, "front.png");
//
// Deterministic: the same scene and options give the same bytes on the same
// machine. Mesa's llvmpipe splits the frame into tiles drawn by threads; the
// first context of the process pins LP_NUM_THREADS (to kLpNumThreads unless
// the environment already sets it) so the work is split the same way on every
// run.
#include <memory>
#include <string>
#include <vector>

#include "vgd/render/camera.hpp"
#include "vgd/render/image.hpp"
#include "vgd/render/renderer.hpp"
#include "vgd/render/scene.hpp"

namespace vgd::render {

// The llvmpipe thread count pinned before the first OSMesa context.
inline constexpr int kLpNumThreads = 2;

// An OSMesa OpenGL 3.3 core context (OSMesaCreateContextAttribs). Throws
// vgd::Error when OSMesa cannot make one. Not thread-safe: one per thread.
class OffscreenContext {
 public:
  OffscreenContext();
  // A context whose own colour buffer is width × height pixels (1–4096 each),
  // for drawing into the default framebuffer (the studio's off-screen frames).
  OffscreenContext(int width, int height);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  void make_current();
  // Waits until the drawing so far is done (glFinish).
  void finish();
  // Ends a frame as a window's buffer swap does: waits until the frame before
  // this one is drawn and marks this one (a fence), so one frame at most is
  // drawn while the next is prepared. A loop drawing frames faster than the
  // rasteriser finishes them would otherwise queue them (llvmpipe: dozens),
  // and the next wait (a read-back, a new texture) would pay for them all.
  void end_frame();
  static Renderer::ProcLoader loader();  // OSMesaGetProcAddress
  // The context's own colour buffer after the drawing so far (glFinish), row
  // 0 at the top. Makes the context current.
  Image read_back();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct OffscreenOptions {
  RenderOptions look;
  int supersample = 3;         // anti-aliasing: draw at supersample × the size, then box-filter down
  double margin = 0.05;        // free border round the framed box, fraction of the image
  bool frame_on_garment = false;  // frame the garment's bounds instead of the body's
};

// A context, a Renderer and a supersampled framebuffer, for many views of one
// scene (the context and the shaders are made once).
class OffscreenRenderer {
 public:
  OffscreenRenderer();
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  void set_scene(const Scene& scene);
  // The preset framed on the body (or the whole scene when it has no body, or
  // the garment with frame_on_garment).
  Image render(const ViewPreset& view, int width, int height, const OffscreenOptions& options = {});
  // Any camera.
  Image render(const Camera& camera, int width, int height, const OffscreenOptions& options = {});
  // The box the presets are framed on.
  Box framing_box(const OffscreenOptions& options) const;
  std::string gl_description() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// One view of a scene, width × height pixels (1–4096 each).
Image render_view(const Scene& scene, const ViewPreset& view, int width, int height,
                  const OffscreenOptions& options = {});

}  // namespace vgd::render
