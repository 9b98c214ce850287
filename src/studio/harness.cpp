#include "vgd/studio/harness.hpp"

#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <optional>
#include <sstream>
#include <thread>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/render/image.hpp"
#include "vgd/render/offscreen.hpp"

namespace vgd::studio {

namespace fs = std::filesystem;

namespace {

// Key indices of the harness's own key map (ImGui 1.86: io.KeyMap[ImGuiKey_*]
// says which io.KeysDown[] index each named key is).
constexpr int kKeyBase = 256;

int key_index(std::string_view name) {
  if (name.size() == 1 && name[0] >= 'a' && name[0] <= 'z') return 'A' + (name[0] - 'a');
  if (name == "delete") return kKeyBase + ImGuiKey_Delete;
  if (name == "escape") return kKeyBase + ImGuiKey_Escape;
  if (name == "enter") return kKeyBase + ImGuiKey_Enter;
  if (name == "tab") return kKeyBase + ImGuiKey_Tab;
  if (name == "backspace") return kKeyBase + ImGuiKey_Backspace;
  if (name == "f5") return kF5Key;
  if (name == "space") return kKeyBase + ImGuiKey_Space;
  return -1;
}

}  // namespace

struct Harness::Impl {
  int width, height;
  std::optional<render::OffscreenContext> context;  // off-screen, unless drawing into `window`
  HarnessWindow window;
  ImGuiContext* imgui = nullptr;
  std::unique_ptr<Studio> studio;

  Impl(int w, int h, const HarnessWindow* win) : width(w), height(h) {
    if (win) {
      VGD_ASSERT(win->loader && win->make_current && win->present, "a harness window needs a loader, make_current and present");
      window = *win;
    } else {
      context.emplace(w, h);
    }
    IMGUI_CHECKVERSION();
    imgui = ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // no imgui.ini next to the tests
    io.LogFilename = nullptr;
    io.DisplaySize = {static_cast<float>(w), static_cast<float>(h)};
    io.DeltaTime = 1.0f / 60.0f;
    for (int k = 0; k < ImGuiKey_COUNT; ++k) io.KeyMap[k] = kKeyBase + k;
    // Letters are their ASCII codes (ImGui's text shortcuts and the studio's read KeyMap).
    io.KeyMap[ImGuiKey_A] = 'A', io.KeyMap[ImGuiKey_C] = 'C', io.KeyMap[ImGuiKey_V] = 'V';
    io.KeyMap[ImGuiKey_X] = 'X', io.KeyMap[ImGuiKey_Y] = 'Y', io.KeyMap[ImGuiKey_Z] = 'Z';
    ImGui::StyleColorsLight();
    make_current();
    init_gl(context ? render::OffscreenContext::loader() : window.loader);
    studio = std::make_unique<Studio>();
    studio->set_restore_context([this] { make_current(); });
  }

  ~Impl() {
    studio.reset();
    make_current();
    shutdown_gl();
    ImGui::DestroyContext(imgui);
  }

  void make_current() { context ? context->make_current() : window.make_current(); }

  // One frame, and whether it was drawn; in a window presented unless
  // `present` is false (a screenshot reads it first).
  bool frame(bool present = true) {
    make_current();
    ImGui::SetCurrentContext(imgui);
    new_frame_gl();
    ImGui::NewFrame();
    studio->draw();
    ImGui::Render();
    // Drawn when it changed (or a window's back buffer is to be read); one
    // frame in flight at most, as a window's swap has it.
    if (!render_gl_if_changed(ImGui::GetDrawData(), studio->picture_count(), !context && !present)) return false;
    if (context) context->end_frame();
    else if (present) window.present();
    return true;
  }
};

Harness::Harness(int width, int height) : impl_(std::make_unique<Impl>(width, height, nullptr)) {}
Harness::Harness(const HarnessWindow& window, int width, int height)
    : impl_(std::make_unique<Impl>(width, height, &window)) {}
Harness::~Harness() = default;

Studio& Harness::studio() { return *impl_->studio; }

void Harness::frame() {
  ImGui::SetCurrentContext(impl_->imgui);
  impl_->frame();
}

void Harness::frames(int n) {
  for (int i = 0; i < n; ++i) frame();
}

void Harness::click_at(float x, float y, bool shift, bool alt, bool ctrl) {
  ImGui::SetCurrentContext(impl_->imgui);
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = {x, y};
  io.KeyShift = shift;
  io.KeyAlt = alt;
  io.KeyCtrl = ctrl;
  frame();
  io.MouseDown[0] = true;
  frame();
  io.MouseDown[0] = false;
  frame();
  io.KeyShift = false;
  io.KeyAlt = false;
  io.KeyCtrl = false;
  frame();
}

void Harness::click(std::string_view name, bool shift) {
  auto r = studio().widget(name);
  if (!r) {
    frame();  // the widget may appear once the last input is seen
    r = studio().widget(name);
  }
  if (!r) throw Error("", std::string(name), "no such widget on screen to click");
  click_at(r->cx(), r->cy(), shift);
}

void Harness::drag(float x0, float y0, float x1, float y1, int steps, bool shift, bool alt) {
  ImGui::SetCurrentContext(impl_->imgui);
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = {x0, y0};
  io.KeyShift = shift;
  io.KeyAlt = alt;
  frame();
  io.MouseDown[0] = true;
  frame();
  for (int i = 1; i <= steps; ++i) {
    const float f = static_cast<float>(i) / steps;
    io.MousePos = {x0 + f * (x1 - x0), y0 + f * (y1 - y0)};
    frame();
  }
  io.MouseDown[0] = false;
  frame();
  if (shift || alt) {
    io.KeyShift = false;
    io.KeyAlt = false;
    frame();
  }
}

void Harness::press(float x, float y, bool ctrl) {
  ImGui::SetCurrentContext(impl_->imgui);
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = {x, y};
  io.KeyCtrl = ctrl;
  frame();
  io.MouseDown[0] = true;
  frame();
}

void Harness::move_mouse(float x, float y) {
  ImGui::SetCurrentContext(impl_->imgui);
  ImGui::GetIO().MousePos = {x, y};
  frame();
}

void Harness::release() {
  ImGui::SetCurrentContext(impl_->imgui);
  ImGuiIO& io = ImGui::GetIO();
  io.MouseDown[0] = false;
  frame();
  io.KeyCtrl = false;
  frame();
}

void Harness::scroll(float x, float y, float notches) {
  ImGui::SetCurrentContext(impl_->imgui);
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = {x, y};
  frame();
  io.MouseWheel = notches;
  frame();
  io.MouseWheel = 0;
  frame();
}

void Harness::key(std::string_view chord) {
  ImGui::SetCurrentContext(impl_->imgui);
  ImGuiIO& io = ImGui::GetIO();
  bool ctrl = false, shift = false;
  std::string_view rest = chord;
  for (;;) {
    if (rest.rfind("ctrl+", 0) == 0) ctrl = true, rest.remove_prefix(5);
    else if (rest.rfind("shift+", 0) == 0) shift = true, rest.remove_prefix(6);
    else break;
  }
  const int k = key_index(rest);
  if (k < 0) throw Error("", std::string(chord), "unknown key (letters a-z, delete, escape, enter, tab, backspace, f5, space)");
  io.KeyCtrl = ctrl, io.KeyShift = shift;
  io.KeysDown[k] = true;
  frame();
  io.KeysDown[k] = false;
  io.KeyCtrl = io.KeyShift = false;
  frame();
}

void Harness::type(std::string_view text) {
  ImGui::SetCurrentContext(impl_->imgui);
  ImGui::GetIO().AddInputCharactersUTF8(std::string(text).c_str());
  frame();
}

render::Image Harness::screenshot() {
  if (impl_->context) return impl_->context->read_back();
  ImGui::SetCurrentContext(impl_->imgui);
  impl_->frame(false);
  render::Image img = read_framebuffer(impl_->width, impl_->height);
  impl_->window.present();
  return img;
}

Harness::FrameTimes Harness::frames_timed(int n) {
  FrameTimes out;
  std::vector<double> ms, drawn_ms;
  using clock = std::chrono::steady_clock;
  const auto period = std::chrono::microseconds(16667);
  auto next = clock::now();
  for (int i = 0; i < n; ++i) {
    std::this_thread::sleep_until(next);
    const auto t0 = clock::now();
    ImGui::SetCurrentContext(impl_->imgui);
    const bool drawn = impl_->frame();
    const auto t1 = clock::now();
    ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    if (drawn) drawn_ms.push_back(ms.back());
    next = std::max(t0 + period, t1);
  }
  if (ms.empty()) return out;
  const auto p95 = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, static_cast<std::size_t>(0.95 * static_cast<double>(v.size())))];
  };
  out.frames = n;
  out.drawn = static_cast<int>(drawn_ms.size());
  for (const double m : ms) out.mean_ms += m / n, out.max_ms = std::max(out.max_ms, m);
  out.p95_ms = p95(ms);
  if (!drawn_ms.empty()) {
    for (const double m : drawn_ms) out.drawn_mean_ms += m / static_cast<double>(drawn_ms.size());
    out.drawn_p95_ms = p95(drawn_ms);
  }
  return out;
}

void Harness::run_script(const fs::path& script, std::ostream* report) {
  std::ifstream in(script);
  if (!in) throw Error(script.string(), "", "cannot read the script");
  const fs::path base = script.parent_path();
  auto resolve = [&](const std::string& p) { return fs::path(p).is_absolute() ? fs::path(p) : base / p; };
  std::string line;
  int n = 0;
  frame();
  while (std::getline(in, line)) {
    ++n;
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    std::istringstream ls(line);
    std::string cmd;
    if (!(ls >> cmd)) continue;
    std::string arg;
    std::getline(ls >> std::ws, arg);
    while (!arg.empty() && (arg.back() == ' ' || arg.back() == '\r')) arg.pop_back();
    auto fail = [&](const std::string& why) { throw Error(script.string(), cmd, why, n); };
    try {
      if (cmd == "open") {
        if (!studio().open(resolve(arg))) fail(studio().status());
        frame();
      } else if (cmd == "save") {
        if (!studio().save(arg.empty() ? fs::path() : resolve(arg))) fail(studio().status());
      } else if (cmd == "export-vrml") {
        if (!studio().export_vrml(resolve(arg))) fail(studio().status());
      } else if (cmd == "click") {
        click(arg);
      } else if (cmd == "click-stretch") {
        std::istringstream as(arg);
        std::string pat, seq;
        as >> pat >> seq;
        auto r = studio().stretch_on_screen(pat, seq);
        if (!r) fail("stretch " + seq + " of " + pat + " is not on screen");
        click_at(r->cx(), r->cy());
      } else if (cmd == "click-piece") {
        // click-piece PATTERN [DX DY]: at the piece's middle, moved by (DX, DY) px.
        std::istringstream as(arg);
        std::string pat;
        float dx = 0, dy = 0;
        as >> pat;
        if (!(as >> std::ws).eof() && !(as >> dx >> dy)) fail("expected PATTERN [DX DY], got '" + arg + "'");
        auto r = studio().piece_on_screen(pat);
        if (!r) fail("piece " + pat + " is not on screen");
        click_at(r->cx() + dx, r->cy() + dy);
      } else if (cmd == "drop-piece") {
        // drop-piece PATTERN POINT: the piece dragged from the pattern view onto
        // an arrangement point of the 3-D view (Arrange on), e.g. "torso back".
        const auto sp = arg.find(' ');
        if (sp == std::string::npos) fail("expected PATTERN POINT, e.g. drop-piece pattern1 torso back");
        const std::string pat = arg.substr(0, sp), point = arg.substr(sp + 1);
        const auto from = studio().piece_on_screen(pat);
        if (!from) fail("piece " + pat + " is not on screen");
        const auto to = studio().arrangement_point_on_screen(point);
        if (!to) fail("no arrangement point '" + point + "' on screen (Arrange shows them)");
        drag(from->cx(), from->cy(), to->cx(), to->cy());
      } else if (cmd == "drag-point") {
        // drag-point PATTERN SEQ INDEX DX DY: the outline point dragged by (DX, DY) px.
        std::istringstream as(arg);
        xvc::OutlinePoint pt;
        float dx = 0, dy = 0;
        if (!(as >> pt.pattern_id >> pt.sequence_id >> pt.index >> dx >> dy))
          fail("give the pattern, the stretch, the point's index and the drag in px: drag-point pattern1 seq2 3 20 -10");
        auto r = studio().point_on_screen(pt);
        if (!r) fail("point " + std::to_string(pt.index) + " of " + pt.pattern_id + "/" + pt.sequence_id + " is not on screen");
        drag(r->cx(), r->cy(), r->cx() + dx, r->cy() + dy);
      } else if (cmd == "drag-arranged") {
        // drag-arranged PATTERN DX DY [shift|alt]: an arranged piece dragged in the 3-D view.
        std::istringstream as(arg);
        std::string pattern_id, how;
        float dx = 0, dy = 0;
        if (!(as >> pattern_id >> dx >> dy)) fail("give the pattern and the drag in px: drag-arranged pattern9 0 -30 [shift|alt]");
        as >> how;
        if (!how.empty() && how != "shift" && how != "alt") fail("the drag's key is shift or alt, not \"" + how + "\"");
        const auto r = studio().arranged_piece_on_screen(pattern_id);
        if (!r) fail(pattern_id + " cannot be taken in the 3-D view: it is not arranged (click Arrange first) or other pieces cover it from this view");
        drag(r->cx(), r->cy(), r->cx() + dx, r->cy() + dy, 8, how == "shift", how == "alt");
      } else if (cmd == "pin-arranged") {
        // pin-arranged PATTERN: an Alt+click on an arranged piece, where drag-arranged takes it.
        const std::string pattern_id(trim(arg));
        if (pattern_id.empty()) fail("give the pattern: pin-arranged pattern9");
        const auto r = studio().arranged_piece_on_screen(pattern_id);
        if (!r) fail(pattern_id + " cannot be taken in the 3-D view: it is not arranged (click Arrange first) or other pieces cover it from this view");
        click_at(r->cx(), r->cy(), false, true);
      } else if (cmd == "key") {
        key(arg);
      } else if (cmd == "type") {
        type(arg);
      } else if (cmd == "frames") {
        frames(std::stoi(arg));
      } else if (cmd == "frames-timed") {
        // frames-timed N: N frames, their wall times reported with the drape's state.
        const FrameTimes t = frames_timed(std::stoi(arg));
        const DrapeStatus d = studio().drape_status();
        if (report)
          *report << script.filename().string() << ":" << n << ": " << t.frames << " frames: mean " << format_fixed(t.mean_ms, 2)
                  << " ms, p95 " << format_fixed(t.p95_ms, 2) << " ms, max " << format_fixed(t.max_ms, 2) << " ms; "
                  << t.drawn << " drawn: mean " << format_fixed(t.drawn_mean_ms, 2) << " ms, p95 "
                  << format_fixed(t.drawn_p95_ms, 2) << " ms; drape "
                  << (d.running ? "running" : "not running") << (d.stage.empty() ? "" : " (" + d.stage + ")") << ", "
                  << format_fixed(d.t, 2) << " s simulated\n";
      } else if (cmd == "wait-drape") {
        studio().wait_for_drape();
        frames(3);
      } else if (cmd == "screenshot") {
        frame();
        render::write_png(screenshot(), resolve(arg));
      } else if (cmd == "expect-status") {
        if (studio().status().find(arg) == std::string::npos)
          fail("the status bar says \"" + studio().status() + "\", not \"" + arg + "\"");
      } else {
        fail("unknown command (open, save, export-vrml, click, click-stretch, click-piece, drop-piece, drag-point, drag-arranged, pin-arranged, key, type, frames, "
             "frames-timed, "
             "wait-drape, screenshot, expect-status)");
      }
    } catch (const Error& e) {
      if (e.diagnostic().line == n) throw;
      throw Error(script.string(), cmd, e.what(), n);
    } catch (const std::exception& e) {
      throw Error(script.string(), cmd, e.what(), n);
    }
  }
}

}  // namespace vgd::studio
