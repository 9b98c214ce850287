// The OSMesa off-screen context: the only file that includes OSMesa.
//
// OSMesaCreateContextAttribs with a core profile, version 3.3 requested (Mesa
// 22 gives 4.5 core on llvmpipe; ../shared/docs/verified-here.md). The context
// needs a colour buffer to be made current; the renderer draws into its own
// framebuffer objects, so a small one is enough.
#include <GL/osmesa.h>

#include <algorithm>
#include <cstdlib>
#include <mutex>
#include <string>
#include <vector>

#include "vgd/core/diagnostics.hpp"
#include "vgd/render/offscreen.hpp"

namespace vgd::render {

namespace {

// llvmpipe reads LP_NUM_THREADS once, when the first context of the process
// is made: pin it then (unless the environment already says).
void pin_llvmpipe_threads() {
  static std::once_flag once;
  std::call_once(once, [] { ::setenv("LP_NUM_THREADS", std::to_string(kLpNumThreads).c_str(), 0); });
}

constexpr int kBufferSize = 16;  // pixels per side of the context's own (unused) colour buffer

}  // namespace

// Mesa's OSMesa keeps every buffer it was made current with in a global list
// and never frees it (about 200 bytes per context). Tell LeakSanitizer, so
// that `make asan` reports our leaks, not Mesa's.
#if defined(__SANITIZE_ADDRESS__)
#define VGD_RENDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define VGD_RENDER_ASAN 1
#endif
#endif
#ifdef VGD_RENDER_ASAN
extern "C" const char* __lsan_default_suppressions() { return "leak:libOSMesa.so\n"; }
#endif

struct OffscreenContext::Impl {
  OSMesaContext context = nullptr;
  int width = kBufferSize, height = kBufferSize;
  std::vector<unsigned char> buffer;
};

OffscreenContext::OffscreenContext() : OffscreenContext(kBufferSize, kBufferSize) {}

OffscreenContext::OffscreenContext(int width, int height) : impl_(std::make_unique<Impl>()) {
  if (width < 1 || height < 1 || width > 4096 || height > 4096)
    throw Error("", "OSMesa", "a " + std::to_string(width) + " x " + std::to_string(height) +
                                  " off-screen buffer is out of range (1-4096 pixels per side)");
  impl_->width = width, impl_->height = height;
  impl_->buffer.assign(static_cast<std::size_t>(width) * height * 4, 0);
  pin_llvmpipe_threads();
  const int attributes[] = {OSMESA_FORMAT,       OSMESA_RGBA,         OSMESA_DEPTH_BITS,
                            24,                  OSMESA_STENCIL_BITS, 0,
                            OSMESA_ACCUM_BITS,   0,                   OSMESA_PROFILE,
                            OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 3,
                            OSMESA_CONTEXT_MINOR_VERSION, 3,          0};
  impl_->context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (!impl_->context)
    throw Error("", "OSMesa", "cannot create an OpenGL 3.3 core off-screen context (is libosmesa6 installed?)");
  make_current();
}

OffscreenContext::~OffscreenContext() {
  if (impl_->context) OSMesaDestroyContext(impl_->context);
}

void OffscreenContext::make_current() {
  if (!OSMesaMakeCurrent(impl_->context, impl_->buffer.data(), GL_UNSIGNED_BYTE, impl_->width, impl_->height))
    throw Error("", "OSMesa", "cannot make the off-screen context current");
}

Image OffscreenContext::read_back() {
  make_current();
  using Finish = void (*)();
  reinterpret_cast<Finish>(OSMesaGetProcAddress("glFinish"))();
  // OSMesa's buffer holds the bottom row first (OSMESA_Y_UP).
  Image img(impl_->width, impl_->height);
  const std::size_t row = static_cast<std::size_t>(impl_->width) * 4;
  for (int y = 0; y < impl_->height; ++y)
    std::copy_n(impl_->buffer.data() + (impl_->height - 1 - y) * row, row, img.rgba.data() + y * row);
  return img;
}

Renderer::ProcLoader OffscreenContext::loader() {
  return [](const char* name) -> Renderer::GlProc { return OSMesaGetProcAddress(name); };
}

}  // namespace vgd::render
