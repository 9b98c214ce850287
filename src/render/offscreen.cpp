// Off-screen previews: the Renderer drawing into a supersampled framebuffer of
// an OSMesa context, read back and box-filtered down (anti-aliasing).
#include "vgd/render/offscreen.hpp"

#include "gl_functions.hpp"
#include "vgd/core/diagnostics.hpp"

namespace vgd::render {

struct OffscreenRenderer::Impl {
  OffscreenContext context;  // made first, destroyed last
  gl::Functions gl;
  std::unique_ptr<Renderer> renderer;
  GLuint fbo = 0, colour = 0, depth = 0;
  int fb_width = 0, fb_height = 0;
  Box garment_box;

  // The colour + depth framebuffer, (re)made at this size.
  void ensure_framebuffer(int w, int h) {
    if (fbo && fb_width == w && fb_height == h) return;
    release_framebuffer();
    gl.GenRenderbuffers(1, &colour);
    gl.BindRenderbuffer(GL_RENDERBUFFER, colour);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    gl.GenRenderbuffers(1, &depth);
    gl.BindRenderbuffer(GL_RENDERBUFFER, depth);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
    gl.GenFramebuffers(1, &fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw Error("", "OpenGL", "cannot make a " + std::to_string(w) + " x " + std::to_string(h) + " framebuffer");
    fb_width = w, fb_height = h;
  }

  void release_framebuffer() {
    if (fbo) gl.DeleteFramebuffers(1, &fbo);
    if (colour) gl.DeleteRenderbuffers(1, &colour);
    if (depth) gl.DeleteRenderbuffers(1, &depth);
    fbo = colour = depth = 0;
  }
};

OffscreenRenderer::OffscreenRenderer() : impl_(std::make_unique<Impl>()) {
  const std::string missing = impl_->gl.load(OffscreenContext::loader());
  if (!missing.empty()) throw Error("", "OSMesa", "the off-screen context lacks " + missing);
  impl_->renderer = std::make_unique<Renderer>(OffscreenContext::loader());
}

OffscreenRenderer::~OffscreenRenderer() {
  impl_->context.make_current();
  impl_->release_framebuffer();
  impl_->renderer.reset();
}

void OffscreenRenderer::set_scene(const Scene& scene) {
  impl_->context.make_current();
  impl_->renderer->set_scene(scene);
  impl_->garment_box = bounds(scene, MeshKind::garment);
}

Box OffscreenRenderer::framing_box(const OffscreenOptions& options) const {
  if (options.frame_on_garment && !impl_->garment_box.empty()) return impl_->garment_box;
  const Box& body = impl_->renderer->body_bounds();
  return body.empty() ? impl_->renderer->scene_bounds() : body;
}

Image OffscreenRenderer::render(const ViewPreset& view, int width, int height, const OffscreenOptions& options) {
  const Box box = framing_box(options);
  if (box.empty()) throw Error("", "scene", "nothing to draw: the scene has no triangles");
  VGD_ASSERT(width > 0 && height > 0, "the image size must be positive");
  return render(frame_camera(view, box, static_cast<double>(width) / height, options.margin), width, height, options);
}

Image OffscreenRenderer::render(const Camera& camera, int width, int height, const OffscreenOptions& options) {
  VGD_ASSERT(width >= 1 && width <= 4096 && height >= 1 && height <= 4096, "the image size must be 1–4096 pixels");
  VGD_ASSERT(options.supersample >= 1 && options.supersample <= 4, "supersample must be 1–4");
  auto& I = *impl_;
  I.context.make_current();
  const int s = options.supersample, w = width * s, h = height * s;
  GLint max_size = 0;
  I.gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  if (w > max_size || h > max_size)
    throw Error("", "OpenGL", std::to_string(width) + " x " + std::to_string(height) + " at " + std::to_string(s) +
                                  "x supersampling exceeds the largest framebuffer (" + std::to_string(max_size) + ")");
  I.ensure_framebuffer(w, h);

  // Draw, read back (bottom row first), flip and filter down.
  I.renderer->draw(camera, {I.fbo, w, h}, options.look);
  Image big(w, h);
  I.gl.BindFramebuffer(GL_FRAMEBUFFER, I.fbo);
  I.gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
  I.gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  I.gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, big.rgba.data());
  const GLenum err = I.gl.GetError();
  if (err != GL_NO_ERROR) throw Error("", "OpenGL", "drawing failed with GL error " + std::to_string(err));
  flip_rows(big);
  return downsample(big, s);
}

std::string OffscreenRenderer::gl_description() const {
  impl_->context.make_current();
  return impl_->renderer->gl_description();
}

Image render_view(const Scene& scene, const ViewPreset& view, int width, int height, const OffscreenOptions& options) {
  OffscreenRenderer r;
  r.set_scene(scene);
  return r.render(view, width, height, options);
}

}  // namespace vgd::render
