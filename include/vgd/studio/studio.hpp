#pragma once
// vgd studio: the designer's window onto the pipeline (seed 000's VIGDES,
// seed 002's interactive seam picking), drawn with Dear ImGui.
//
//   tree       the XVC document as a tree; select an element, edit its
//              attributes (undoable commands), delete it
//   patterns   the pieces of one size, flat; hover a stretch of an outline
//              and click to pick it, pick a second, "Add seam"
//   simulate   size, quality preset (preview / standard / precise), self-
//              collision, mesh spacing, time limit, the body (the mannequin or
//              a file, with unit / up / facing overrides and the importer's
//              notes shown); "Drape" runs the drape on
//              a worker thread with per-stage progress, "Simulate on
//              server" sends it to a vgd-server (its address in the
//              panel) and follows its frames' stream; "Stop" ends either
//   preview    the body and the garment in 3-D (the render stage's off-screen
//              renderer, shown as a texture), updated live while draping,
//              here or on the server;
//              drag to turn it
//
// Immediate mode, as the XVC commands expect (commands.hpp): every panel is
// drawn from the Document each frame and every change goes back as a Command
// through one UndoStack, so undo, the tree and the saved file never drift.
//
// The Studio knows nothing about windows. A host makes the ImGui context and
// an OpenGL 3.3 context, calls init_gl() once, then per frame new_frame_gl(),
// ImGui::NewFrame(),
// Studio::draw(), ImGui::Render() and render_gl_if_changed(). Two hosts exist: the GLFW
// window of apps/vgd-studio, and the Harness (harness.hpp), an OSMesa
// off-screen host that scripts and tests drive with synthetic mouse and keys.
#include <cstdint>
#include <array>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vgd/render/image.hpp"
#include "vgd/dress/certificate.hpp"
#include "vgd/xvc/commands.hpp"
#include "vgd/dress/drape.hpp"
#include "vgd/sim/effects/hand.hpp"
#include "vgd/xvc/document.hpp"

struct ImDrawData;

namespace vgd::studio {

// A widget's box on screen, pixels, from the last frame.
struct Rect {
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  float cx() const { return 0.5f * (x0 + x1); }
  float cy() const { return 0.5f * (y0 + y1); }
};

// Loads the OpenGL functions of the current context through `loader`
// (OSMesaGetProcAddress, glfwGetProcAddress) and sets up ImGui's OpenGL 3
// renderer. An ImGui context must exist. Throws vgd::Error when it fails.
using GlProc = void (*)();
using GlLoader = GlProc (*)(const char* name);
void init_gl(GlLoader loader);
void shutdown_gl();
// Before ImGui::NewFrame(): makes the renderer's font texture and shaders the
// first time.
void new_frame_gl();
// Draws ImGui's frame into the current framebuffer (cleared to the style's
// window background first) only when it differs from the last frame drawn (its vertices,
// indices, textures and clip rectangles) or the studio has drawn a new
// picture since (Studio::picture_count: same texture, new pixels); `force`
// draws it anyway (a window's back buffer to read). Returns whether it drew:
// a host presents only a drawn frame. On a software OpenGL a 1280 × 800
// frame costs 8-10 ms of rasterising; an unchanged one costs nothing and
// leaves the processor to the drape.
bool render_gl_if_changed(ImDrawData* data, std::uint64_t pictures, bool force = false);
// The current framebuffer's pixels (width × height from the origin), row 0
// at the top: a window's back buffer before it is swapped.
render::Image read_framebuffer(int width, int height);

// The io.KeysDown index hosts give F5 (GLFW_KEY_F5); letters are at their
// upper-case ASCII codes (as GLFW's are).
inline constexpr int kF5Key = 294;

// Where the drape stands, for the progress bar.
struct DrapeStatus {
  bool running = false;
  std::string stage;          // placing, sewing, settling, done, stopped, failed
  double t = 0, time_limit = 0;  // s simulated
  double wall_s = 0;
  int seams_closed = 0, seam_pairs = 0;
  int seams_waiting = 0;  // seams waiting for others before they pull (sleeves first)
  bool paused = false;        // held after the frame at `t` (Pause; Step runs one frame more)
  std::string message;        // the outcome when finished
  std::vector<std::string> body_notes;  // an imported body: the importer's decisions (unit, up, facing) and what it left out
};

// How a DXF pattern file is imported (the import dialog; vgd import's options).
struct DxfImport {
  std::string units = "auto";  // auto: as the file says (mm when it says nothing); mm, cm, in
  bool unfold_mirrored = true;   // half pieces unfolded about their mirror line
  bool join_per_side = true;     // pieces written once per side joined (CLO's halves)
  bool sew_on_sew_lines = true;  // pieces with a sew line sewn on it, the allowance cut off
};

class Studio {
 public:
  Studio();
  ~Studio();
  Studio(const Studio&) = delete;
  Studio& operator=(const Studio&) = delete;

  // Opens an XVC document (a .dxf: the import dialog, import_dxf); on
  // failure keeps the current one, shows the error
  // (naming the file and the problem) and returns false. When the open
  // document has unsaved changes it is not replaced: a dialog asks to save
  // them, discard them or cancel, and open() returns false (the dialog opens
  // the file once answered), unless `discard_changes`.
  bool open(const std::filesystem::path& file, bool discard_changes = false);
  // A DXF pattern file (AAMA/ASTM) as a new document: imported with
  // `options`, its half pieces unfolded and pieces written per side joined as
  // asked; the document is unsaved, named FILE.xvc beside the DXF (FILE-2.xvc
  // ... when that exists: nothing is overwritten). The import's report
  // (pieces, sizes, units, repairs, warnings) is shown in a dialog and kept
  // in import_report(). open() on a .dxf opens the import dialog instead
  // (and returns true: the dialog imports it).
  // False (and the error shown) when the file cannot be imported.
  bool import_dxf(const std::filesystem::path& file, const DxfImport& options = {});
  const std::vector<std::string>& import_report() const;

  // The host wants to close (a window's close button): true when it may,
  // false while unsaved changes wait on the same dialog. quit_confirmed()
  // turns true once the dialog said to save or discard them.
  bool request_close();
  bool quit_confirmed() const;
  // Saves to `file` (or where it came from) through a temporary file renamed
  // into place. Shows and returns false on failure.
  bool save(const std::filesystem::path& file = {});

  // Recent files (File > Open Recent, newest first, ten at most): read from
  // and kept in `file` (one path a line); without one, for this run only.
  void set_recent_store(const std::filesystem::path& file);
  const std::vector<std::filesystem::path>& recent_files() const;

  // Autosave (never lose work): a document with unsaved changes is written
  // to FILE.autosave every `seconds` of changes (0: at every change) and at
  // every drape's start; the file is removed when the document is saved or
  // the studio closes. Opening a document that has one (the studio did not
  // close: a crash, a kill) offers to recover it (a dialog: Recover, Discard).
  void set_autosave_seconds(double seconds);
  bool recovery_offered() const;  // the dialog is waiting for an answer

  // File > Open..., Save as... and Export VRML... ask through the desktop's
  // own file dialog: `program` answering as zenity does (the chosen path on
  // stdout and exit 0; exit 1 when cancelled), run with zenity's arguments
  // (--file-selection, --save, --filename, --file-filter). Empty (the
  // default), or a program that cannot be run (said in the status bar): the
  // studio's own dialog, a typed path. vgd-studio sets zenity when it has a
  // window on a desktop that has it.
  void set_file_dialog_program(const std::filesystem::path& program);

  // Writes the last drape (garment and body) as static VRML97, through a
  // temporary file renamed into place. Shows and returns false on failure.
  bool export_vrml(const std::filesystem::path& file);

  // Builds the frame's widgets; between ImGui::NewFrame() and ImGui::Render().
  void draw();

  // ---- state, for hosts, scripts and tests ----
  const xvc::Document& document() const;
  const std::filesystem::path& file() const;
  bool modified() const;
  const std::string& status() const;       // the last message of the status bar
  bool status_is_error() const;
  // Drape settings (quality, size, ...), as the simulate panel shows them.
  // The vgd-server "Simulate on server" sends drapes to ("http://host:port";
  // "" = none) and its token (sent as Authorization: Bearer, never shown).
  void set_server(const std::string& url, const std::string& token = "");
  const std::string& server() const;
  // The server's id of the job the panels follow ("" for a drape run here).
  std::string server_job() const;
  dress::DrapeOptions& drape_options();
  // The body to drape on, as the simulate panel's body row sets it: a file
  // with the importer's unit, up axis and facing ("auto" or forced); an empty
  // path is the mannequin of the garment's size.
  void set_body(const std::filesystem::path& file, const std::string& unit = "auto", const std::string& up = "auto",
                const std::string& facing = "auto");
  DrapeStatus drape_status() const;
  // The certificate of the last finished drape.
  const std::optional<dress::Certificate>& certificate() const;
  // What the last drape decided for the document, as vgd dress says it
  // (seams suggested, pieces left out, the body): dress::Preparation::decisions.
  const std::vector<std::string>& preparation() const;
  // Blocks until the drape worker has finished (for scripts and tests).
  void wait_for_drape();
  // The id of the element selected in the tree ("" when none).
  const std::string& selected() const;
  // The stretches picked for the next seam: (pattern id, C2DSEQ id); the
  // first picked_first_side() of them are hem A (a click picks for hem B, the
  // first for hem A; Shift+click adds to hem A).
  const std::vector<std::pair<std::string, std::string>>& picked() const;
  std::size_t picked_first_side() const;

  // Boxes of the last frame's named widgets: buttons and menu items by their
  // label ("Drape", "Add seam", "Undo"), combo items as "<combo>:<item>"
  // ("quality:precise", "size:38"), tree rows as "tree:<id>".
  std::optional<Rect> widget(std::string_view name) const;
  // The screen point of the middle of a stretch in the pattern view (to
  // click it), if it is shown.
  std::optional<Rect> stretch_on_screen(std::string_view pattern_id, std::string_view stretch_id) const;
  // The screen point of an outline point (the C2D at `index` of the stretch)
  // and of a piece's middle in the pattern view, if shown; the view's scale
  // (px per m: a drag of d px moves a point d / scale m).
  std::optional<Rect> point_on_screen(const xvc::OutlinePoint& point) const;
  std::optional<Rect> piece_on_screen(std::string_view pattern_id) const;
  // A notch's handle (the inner end of its cut) on screen, by its POSITION id.
  std::optional<Rect> notch_on_screen(std::string_view pattern_id, std::string_view notch_id) const;
  // An end (0: its first point, 1: its second) of a piece's grain line on screen.
  std::optional<Rect> grain_end_on_screen(std::string_view pattern_id, int end) const;
  float pattern_scale() const;
  // The outline point selected for editing (a click on it, the piece selected).
  std::optional<xvc::OutlinePoint> selected_point() const;
  // The measuring tool's last distance (m) between two points of the pattern
  // view (Measure; outline points snap).
  std::optional<double> measured() const;
  // Pulling the cloth by hand (Ctrl+drag in the 3-D view during a drape run
  // here): the particle held, the live cloth's particles (m) as the preview
  // last drew them, and where one is on screen in that preview.
  std::optional<int> held_particle() const;
  std::vector<std::array<float, 3>> cloth_positions() const;
  std::optional<Rect> particle_on_screen(int particle) const;
  // Whether the 3-D view is drawn in the UI's own GL context (render::Renderer
  // into a texture) rather than off-screen through OSMesa and uploaded.
  bool view_in_window_context() const;
  // Arranging (the Arrange button): whether the 3-D view shows the drape's
  // start, where an arrangement point ("torso front", "left arm", ...) is on
  // screen, and a point of an arranged piece (the particle nearest its
  // middle) on screen; the particles of that piece as drawn (m).
  // Pins set in the 3-D view while a drape runs here (Alt+click a particle,
  // Alt+Shift+click a piece to freeze it): the particles held and where
  // (m), by increasing particle.
  std::vector<sim::HandControl::Pin> pins() const;
  // How many pictures the 3-D view has drawn into its textures so far: a
  // frame whose draw data is unchanged still shows something new when this
  // changed (render_gl_if_changed).
  std::uint64_t picture_count() const;
  bool arranging() const;
  std::optional<Rect> arrangement_point_on_screen(std::string_view label) const;
  // Where an arranged piece can be taken in the 3-D view: of its particles,
  // the one nearest its middle that a press there takes (no other piece in
  // front of it); nothing when other pieces cover it from this view.
  std::optional<Rect> arranged_piece_on_screen(std::string_view pattern_id, int copy = 0) const;
  std::vector<std::array<float, 3>> arranged_piece(std::string_view pattern_id, int copy = 0) const;

  // Called after the 3-D preview drew off-screen, to make the UI's GL context
  // current again (both may be OSMesa contexts in one thread).
  void set_restore_context(std::function<void()> restore);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vgd::studio
