// The OSMesa off-screen context: the only file that includes OSMesa.
//
// OSMesaCreateContextAttribs with a core profile, version 3.3 requested (Mesa
// 22 gives 4.5 core on llvmpipe; ../shared/docs/verified-here.md). The context
// needs a colour buffer to be made current; the renderer draws into its own
// framebuffer objects, so a small one is enough.
//
// libOSMesa is opened (dlopen) when the first context is made, not linked:
// it brings LLVM (llvmpipe) with some 400 000 relocations, which every
// command that draws nothing would pay at start-up (docs/performance.md,
// "Start-up"). The header gives the functions' types; the library's four
// entry points are looked up once.
#include <GL/osmesa.h>
#include <dlfcn.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <mutex>
#include <string>
#include <type_traits>
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

// OSMesa's entry points, from the library opened on first use.
struct OsMesa {
  decltype(&OSMesaCreateContextAttribs) create = nullptr;
  decltype(&OSMesaDestroyContext) destroy = nullptr;
  decltype(&OSMesaMakeCurrent) make_current = nullptr;
  decltype(&OSMesaGetProcAddress) get_proc = nullptr;
};

// Opens libOSMesa once per process (kept open: contexts and the functions
// they hand out live in it). Throws vgd::Error saying what is missing.
const OsMesa& osmesa() {
  static const OsMesa api = [] {
    void* lib = nullptr;
    std::string why;
    for (const char* name : {"libOSMesa.so.8", "libOSMesa.so"}) {
      lib = ::dlopen(name, RTLD_NOW | RTLD_LOCAL);
      if (lib) break;
      if (const char* e = ::dlerror()) why = e;
    }
    if (!lib)
      throw Error("", "OSMesa", "cannot load the off-screen OpenGL library libOSMesa.so.8 (" + why +
                                    "; install libosmesa6)");
    OsMesa a;
    auto find = [&](auto& fn, const char* symbol) {
      fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(::dlsym(lib, symbol));
      if (!fn) throw Error("", "OSMesa", std::string("libOSMesa.so.8 lacks ") + symbol);
    };
    find(a.create, "OSMesaCreateContextAttribs");
    find(a.destroy, "OSMesaDestroyContext");
    find(a.make_current, "OSMesaMakeCurrent");
    find(a.get_proc, "OSMesaGetProcAddress");
    return a;
  }();
  return api;
}

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
  void* last_frame = nullptr;  // the fence (GLsync) ending the frame before, or none
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
  impl_->context = osmesa().create(attributes, nullptr);
  if (!impl_->context)
    throw Error("", "OSMesa", "cannot create an OpenGL 3.3 core off-screen context (is libosmesa6 installed?)");
  make_current();
}

OffscreenContext::~OffscreenContext() {
  if (impl_->context && impl_->last_frame) {
    make_current();
    reinterpret_cast<void (*)(void*)>(osmesa().get_proc("glDeleteSync"))(impl_->last_frame);
  }
  if (impl_->context) osmesa().destroy(impl_->context);
}

void OffscreenContext::make_current() {
  if (!osmesa().make_current(impl_->context, impl_->buffer.data(), GL_UNSIGNED_BYTE, impl_->width, impl_->height))
    throw Error("", "OSMesa", "cannot make the off-screen context current");
}

void OffscreenContext::finish() {
  make_current();
  using Finish = void (*)();
  reinterpret_cast<Finish>(osmesa().get_proc("glFinish"))();
}

void OffscreenContext::end_frame() {
  // OpenGL 3.2 sync objects (GL_SYNC_GPU_COMMANDS_COMPLETE, GL_SYNC_FLUSH_COMMANDS_BIT).
  using FenceSync = void* (*)(unsigned, unsigned);
  using ClientWaitSync = unsigned (*)(void*, unsigned, std::uint64_t);
  using DeleteSync = void (*)(void*);
  static const auto fence = reinterpret_cast<FenceSync>(osmesa().get_proc("glFenceSync"));
  static const auto wait = reinterpret_cast<ClientWaitSync>(osmesa().get_proc("glClientWaitSync"));
  static const auto remove = reinterpret_cast<DeleteSync>(osmesa().get_proc("glDeleteSync"));
  make_current();
  if (!fence || !wait || !remove) return finish();
  if (impl_->last_frame) {
    wait(impl_->last_frame, 0x1, ~std::uint64_t{0});  // until it is drawn
    remove(impl_->last_frame);
  }
  impl_->last_frame = fence(0x9117, 0);
}

Image OffscreenContext::read_back() {
  finish();
  // OSMesa's buffer holds the bottom row first (OSMESA_Y_UP).
  Image img(impl_->width, impl_->height);
  const std::size_t row = static_cast<std::size_t>(impl_->width) * 4;
  for (int y = 0; y < impl_->height; ++y)
    std::copy_n(impl_->buffer.data() + (impl_->height - 1 - y) * row, row, img.rgba.data() + y * row);
  return img;
}

Renderer::ProcLoader OffscreenContext::loader() {
  osmesa();  // loaded (or a clear error) before the renderer asks for a function
  return [](const char* name) -> Renderer::GlProc { return osmesa().get_proc(name); };
}

}  // namespace vgd::render
