#pragma once
// The studio without a window: an OSMesa context the size of the "screen",
// ImGui fed with synthetic mouse and keyboard input (ImGui 1.86: io.MousePos,
// io.MouseDown, io.KeysDown), and the frame read back as an image. Tests and
// `vgd-studio --headless --script` drive the studio through it, so what they
// check is what a user's clicks do.
//
//   Harness h(1280, 800);
//   h.studio().open("data/garments/t-shirt.xvc");
//   h.click("quality");            // opens the combo
//   h.click("quality:precise");    // picks the item
//   h.click("Drape");
//   h.studio().wait_for_drape();
//   render::write_png(h.screenshot(), "studio.png");
//
// Deterministic: the same script gives the same pixels on the same machine
// (ImGui's own font; llvmpipe's thread count pinned; time steps fixed at
// 1/60 s per frame). A frame that would draw what the last one drew is not
// drawn (render_gl_if_changed); one that is ends as a window's swap does,
// with at most one frame in flight (OffscreenContext::end_frame).
#include <filesystem>
#include <functional>
#include <ostream>
#include <memory>
#include <string>
#include <string_view>

#include "vgd/render/image.hpp"
#include "vgd/studio/studio.hpp"

namespace vgd::studio {

// A window for the harness to draw into instead of its off-screen context:
// the window's OpenGL 3.3 core context (made current by make_current) and
// what ends each frame (swap the buffers, poll the window's events). Input
// still comes from the harness, so a script runs in a window exactly as it
// runs off-screen (vgd-studio --script without --headless).
struct HarnessWindow {
  GlLoader loader = nullptr;
  std::function<void()> make_current;
  std::function<void()> present;
};

class Harness {
 public:
  Harness(int width = 1280, int height = 800);
  // Drawing into `window`, whose framebuffer is width × height pixels.
  Harness(const HarnessWindow& window, int width, int height);
  ~Harness();
  Harness(const Harness&) = delete;
  Harness& operator=(const Harness&) = delete;

  Studio& studio();

  // One frame: input as set, NewFrame, draw, Render, draw into the buffer.
  void frame();
  // Several frames (animations, popups opening, the preview catching up).
  void frames(int n);
  // Moves the mouse to (x, y) and clicks the left button (four frames: move,
  // press, release, settle), with Shift, Alt and Ctrl held when asked.
  void click_at(float x, float y, bool shift = false, bool alt = false, bool ctrl = false);
  // Clicks the middle of a named widget of the last frame (Studio::widget);
  // throws vgd::Error naming it when there is no such widget on screen.
  void click(std::string_view widget, bool shift = false);
  // Drags with the left button from (x0, y0) to (x1, y1) in `steps` moves,
  // with Shift and Alt held when asked.
  void drag(float x0, float y0, float x1, float y1, int steps = 8, bool shift = false, bool alt = false);
  // The left button held down at (x, y) (with Ctrl when asked), the mouse
  // moved while it is held, and let go: for drags that must last.
  void press(float x, float y, bool ctrl = false);
  void move_mouse(float x, float y);
  void release();
  // Turns the mouse wheel by `notches` (positive: away from the user) at (x, y).
  void scroll(float x, float y, float notches);
  // Presses a key with modifiers: "ctrl+z", "ctrl+shift+z", "ctrl+s", "delete",
  // "f5", "escape", "enter".
  void key(std::string_view chord);
  // Types text into the focused text field.
  void type(std::string_view text);
  // The last frame, row 0 at the top (in a window: drawn once more and read
  // before it is presented).
  render::Image screenshot();

  // Runs a script, one command per line ('#' starts a comment):
  //   open FILE | save [FILE] | export-vrml FILE.wrl | click WIDGET | click-stretch PATTERN SEQ
  //   click-piece PATTERN [DX DY] | drop-piece PATTERN POINT | drag-point PATTERN SEQ INDEX DX DY (px)
  //   drag-arranged PATTERN DX DY [shift|alt] (px)
  //   key CHORD | type TEXT | frames N | frames-timed N | wait-drape | screenshot FILE.png
  //   expect-status TEXT (fails unless the status bar contains TEXT)
  // Paths are relative to the script's folder. What a command reports
  // (frames-timed: the frames' wall times) goes to `report` when given.
  // Throws vgd::Error naming the script, the line and the problem.
  void run_script(const std::filesystem::path& script, std::ostream* report = nullptr);

  // `n` frames at most 60 a second, as a window with vertical sync draws
  // them, and each one's wall time (ms): mean, 95th percentile, longest; and
  // of those drawn (the others showed what the last one did:
  // render_gl_if_changed) how many, their mean and 95th percentile.
  struct FrameTimes {
    int frames = 0, drawn = 0;
    double mean_ms = 0, p95_ms = 0, max_ms = 0;
    double drawn_mean_ms = 0, drawn_p95_ms = 0;
  };
  FrameTimes frames_timed(int n);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vgd::studio
