// vgd-studio: the designer's GUI (docs/studio.md).
//
//   vgd-studio data/garments/t-shirt.xvc                    a window (GLFW, OpenGL 3.3)
//   vgd-studio --headless --script session.txt              off-screen, scripted (tests, QA)
//   vgd-studio --script session.txt                         the same script in a window
//   vgd-studio --headless t-shirt.xvc --screenshot s.png    one frame of the studio as a PNG
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <omp.h>

#include <CLI/CLI.hpp>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/render/image.hpp"
#include "vgd/studio/harness.hpp"
#include "vgd/studio/studio.hpp"

namespace {

struct Options {
  std::string file, script, screenshot;
  std::string avatar, unit = "auto", up = "auto", facing = "auto";
  std::string server, token_file;
  std::string file_dialog;  // "" = zenity with a window, none headless; "none" = typed paths
  bool headless = false;
  int width = 1280, height = 800, threads = 1, quit_after = 0;
  double autosave_s = 120;
};

// Where the window keeps its recent files: $XDG_STATE_HOME/vgd/recent-files,
// else ~/.local/state/vgd/recent-files (none without a home).
std::filesystem::path recent_store() {
  std::filesystem::path base;
  if (const char* x = std::getenv("XDG_STATE_HOME"); x && *x) base = x;
  else if (const char* h = std::getenv("HOME"); h && *h) base = std::filesystem::path(h) / ".local" / "state";
  if (base.empty()) return {};
  std::error_code ec;
  std::filesystem::create_directories(base / "vgd", ec);
  return base / "vgd" / "recent-files";
}

// The program of the desktop's file dialogs: --file-dialog (a name found on
// PATH or a path; "none": typed paths), else zenity with a window when it is
// installed. Empty: the studio's own dialog.
std::filesystem::path file_dialog(const Options& o, bool window) {
  std::string name = o.file_dialog;
  if (name == "none" || (name.empty() && !window)) return {};
  if (name.empty()) name = "zenity";
  if (name.find('/') != std::string::npos) return name;
  if (const char* path = std::getenv("PATH"))
    for (const auto& dir : vgd::split(path, ':')) {
      const std::filesystem::path candidate = std::filesystem::path(dir.empty() ? "." : dir) / name;
      if (::access(candidate.c_str(), X_OK) == 0) return candidate;
    }
  if (!o.file_dialog.empty()) std::fprintf(stderr, "vgd-studio: %s is not on PATH: typed paths instead\n", name.c_str());
  return {};
}

// The server's token: --token-file, else $VGD_TOKEN (as vgd remote).
std::string token(const Options& o) {
  if (!o.token_file.empty()) return std::string(vgd::trim(vgd::read_file(o.token_file)));
  if (const char* t = std::getenv("VGD_TOKEN")) return t;
  return "";
}

// A window with an OpenGL 3.3 core context, current; nullptr (said, GLFW
// ended) when there is no display or no such context.
GLFWwindow* open_window(const Options& o, const char* title, bool resizable) {
  glfwSetErrorCallback([](int code, const char* text) { std::fprintf(stderr, "vgd-studio: GLFW %d: %s\n", code, text); });
  if (!glfwInit()) {
    std::fprintf(stderr, "vgd-studio: error: no display to open a window on (use --headless for off-screen runs)\n");
    return nullptr;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_RESIZABLE, resizable ? GLFW_TRUE : GLFW_FALSE);
  GLFWwindow* window = glfwCreateWindow(o.width, o.height, title, nullptr, nullptr);
  if (!window) {
    std::fprintf(stderr, "vgd-studio: error: cannot open an OpenGL 3.3 window\n");
    glfwTerminate();
    return nullptr;
  }
  glfwMakeContextCurrent(window);
  return window;
}

int run_window(const Options& o) {
  GLFWwindow* window = open_window(o, "vgd studio", true);
  if (!window) return 1;
  glfwSwapInterval(1);
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui::StyleColorsLight();
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  int code = 0;
  try {
    vgd::studio::init_gl(reinterpret_cast<vgd::studio::GlLoader>(glfwGetProcAddress));
    {
      vgd::studio::Studio studio;
      studio.set_restore_context([window] { glfwMakeContextCurrent(window); });
      if (!o.avatar.empty()) studio.set_body(o.avatar, o.unit, o.up, o.facing);
      studio.set_server(o.server, token(o));
      studio.set_autosave_seconds(o.autosave_s);
      studio.set_recent_store(recent_store());
      studio.set_file_dialog_program(file_dialog(o, /*window=*/true));
      if (!o.file.empty() && !studio.open(o.file)) std::fprintf(stderr, "vgd-studio: %s\n", studio.status().c_str());
      for (int frame = 1; !studio.quit_confirmed(); ++frame) {
        // The close button asks about unsaved changes first (Studio::request_close).
        if (glfwWindowShouldClose(window)) {
          if (studio.request_close()) break;
          glfwSetWindowShouldClose(window, GLFW_FALSE);
        }
        glfwPollEvents();
        vgd::studio::new_frame_gl();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        studio.draw();
        ImGui::Render();
        // Drawn and shown only when it changed (the last frame, to be read, always).
        const bool last = o.quit_after > 0 && frame >= o.quit_after;
        const bool drawn = vgd::studio::render_gl_if_changed(ImGui::GetDrawData(), studio.picture_count(), last);
        if (last) {
          if (!o.screenshot.empty()) {
            int w = 0, h = 0;
            glfwGetFramebufferSize(window, &w, &h);
            vgd::render::write_png(vgd::studio::read_framebuffer(w, h), o.screenshot);
          }
          std::printf("%s\n", studio.status().c_str());
          break;
        }
        if (drawn)
          glfwSwapBuffers(window);  // at the display's rate (vertical sync)
        else
          glfwWaitEventsTimeout(1.0 / 60.0);  // nothing new to show: wait for input, or the next frame's time
      }
    }
    vgd::studio::shutdown_gl();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vgd-studio: error: %s\n", e.what());
    code = 1;
  }
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  return code;
}

// The studio driven by the harness (off-screen, or in a window for a
// script): the file opened, the script run, the last frame written.
int run_scripted(vgd::studio::Harness& h, const Options& o) {
  if (!o.avatar.empty()) h.studio().set_body(o.avatar, o.unit, o.up, o.facing);
  h.studio().set_server(o.server, token(o));
  h.studio().set_autosave_seconds(o.autosave_s);
  h.studio().set_file_dialog_program(file_dialog(o, /*window=*/false));
  if (!o.file.empty() && !h.studio().open(o.file)) {
    std::fprintf(stderr, "vgd-studio: error: %s\n", h.studio().status().c_str());
    return 1;
  }
  if (!o.script.empty()) h.run_script(o.script, &std::cout);
  h.frames(3);
  if (!o.screenshot.empty()) vgd::render::write_png(h.screenshot(), o.screenshot);
  std::printf("%s\n", h.studio().status().c_str());
  return h.studio().status_is_error() ? 3 : 0;
}

int run_headless(const Options& o) {
  vgd::studio::Harness h(o.width, o.height);
  return run_scripted(h, o);
}

// A script run in a window: what it does is seen as it happens, drawn by the
// window's OpenGL (the input is the script's, not the window's).
int run_window_script(const Options& o) {
  GLFWwindow* window = open_window(o, "vgd studio (script)", false);
  if (!window) return 1;
  glfwSwapInterval(0);  // a script runs as fast as it draws (frames-timed paces itself)
  int code = 0;
  {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window, &w, &h);
    vgd::studio::HarnessWindow win;
    win.loader = reinterpret_cast<vgd::studio::GlLoader>(glfwGetProcAddress);
    win.make_current = [window] { glfwMakeContextCurrent(window); };
    win.present = [window] {
      glfwSwapBuffers(window);
      glfwPollEvents();
    };
    vgd::studio::Harness harness(win, w, h);
    code = run_scripted(harness, o);
  }
  glfwDestroyWindow(window);
  glfwTerminate();
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"vgd studio: open an XVC garment, pick seams, choose a quality preset, drape it and see it in 3-D"};
  Options o;
  app.add_option("FILE", o.file, "XVC document to open")->check(CLI::ExistingFile);
  app.add_flag("--headless", o.headless, "No window: draw off-screen (OSMesa), for scripts and screenshots");
  app.add_option("--script", o.script,
                 "Run these studio commands, off-screen with --headless, else in a window (open, save, export-vrml, click, click-stretch, "
                 "click-piece, drop-piece, drag-point, drag-arranged, pin-arranged, key, type, frames, frames-timed, wait-drape, screenshot, "
                 "expect-status; docs/studio.md)")
      ->check(CLI::ExistingFile);
  app.add_option("--avatar", o.avatar, "Body to drape on (OBJ, PLY, STL, glTF/GLB, FBX, Collada) instead of the mannequin")
      ->check(CLI::ExistingFile);
  app.add_option("--unit", o.unit, "--avatar's unit: auto (from the file, else the body's height), m, dm, cm, mm, in")
      ->check(CLI::IsMember({"auto", "m", "dm", "cm", "mm", "in"}))->capture_default_str();
  app.add_option("--up", o.up, "--avatar's up axis: auto (from the body), x, y, z, -x, -y, -z")
      ->check(CLI::IsMember({"auto", "x", "y", "z", "-x", "-y", "-z"}))->capture_default_str();
  app.add_option("--facing", o.facing, "Where --avatar faces once up is +Y: auto (from the feet), +z, -z, +x, -x")
      ->check(CLI::IsMember({"auto", "+z", "-z", "+x", "-x"}))->capture_default_str();
  app.add_option("--server", o.server, "A vgd-server for \"Simulate on server\" (http://HOST:PORT; also in the simulate panel)");
  app.add_option("--token-file", o.token_file, "File holding that server's token (default: $VGD_TOKEN)")
      ->check(CLI::ExistingFile);
  app.add_option("--autosave-seconds", o.autosave_s,
                 "Write unsaved changes to FILE.autosave this often (0: at every change; recovery is offered when "
                 "the studio did not close)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--file-dialog", o.file_dialog,
                 "File > Open, Save as and Export ask through this program, answering as zenity does (default with a "
                 "window: zenity when installed; 'none': the studio's own dialog, a typed path)");
  app.add_option("--screenshot", o.screenshot, "Write the last frame to this PNG (a window: with --quit-after)");
  app.add_option("--quit-after", o.quit_after, "A window: close after this many frames (smoke tests)")
      ->check(CLI::PositiveNumber);
  app.add_option("--width", o.width, "Window or off-screen width, pixels (default 1280)")->check(CLI::Range(640, 4096));
  app.add_option("--height", o.height, "Window or off-screen height, pixels (default 800)")->check(CLI::Range(480, 4096));
  // One by default, as vgd: the studio's own drawing (llvmpipe's threads)
  // shares the cores with the drape, and OpenMP's spinning barriers make two
  // threads on shared cores 10-500x slower (docs/performance.md, "Threads").
  app.add_option("--threads", o.threads, "Threads for the drape's force kernels (default 1; 0 = all cores)")
      ->check(CLI::NonNegativeNumber);
  app.footer("Exit codes: 0 done, 1 bad input or a failed script line (the message names it), 3 the studio ended "
             "with an error in its status bar.");
  CLI11_PARSE(app, argc, argv);
  if (!o.headless && o.script.empty() && !o.screenshot.empty() && o.quit_after == 0) {
    std::fprintf(stderr, "vgd-studio: error: --screenshot needs --headless, --script or --quit-after\n");
    return 2;
  }
  omp_set_num_threads(o.threads > 0 ? o.threads : omp_get_num_procs());
  try {
    return o.headless ? run_headless(o) : !o.script.empty() ? run_window_script(o) : run_window(o);
  } catch (const vgd::Error& e) {
    std::fprintf(stderr, "vgd-studio: error: %s\n", e.diagnostic().format().c_str());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vgd-studio: error: %s\n", e.what());
    return 1;
  }
}
