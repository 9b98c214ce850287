#include "vgd/studio/studio.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>
#include <omp.h>

#include <algorithm>
#include <cctype>
#include <ctime>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <set>
#include <unistd.h>

#include "drape_job.hpp"
#include "file_dialog.hpp"
#include "gl.hpp"
#include "vgd/core/data.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/dress/arrange.hpp"
#include "vgd/dress/dress.hpp"
#include "vgd/dress/prepare.hpp"
#include "vgd/io/dxf/import.hpp"
#include "vgd/core/units.hpp"
#include "vgd/io/vrml/looks.hpp"
#include "vgd/io/vrml/vrml.hpp"
#include "vgd/mesh/mesh.hpp"
#include "vgd/mesh/surface.hpp"
#include "vgd/pattern/contour.hpp"
#include "vgd/render/fit_map.hpp"
#include "vgd/render/looks.hpp"
#include "vgd/render/offscreen.hpp"
#include "vgd/render/renderer.hpp"
#include "vgd/scene/material.hpp"
#include "vgd/scene/quality.hpp"
#include "vgd/sim/effects/hand.hpp"
#include "vgd/xvc/arrangement.hpp"
#include "vgd/xvc/commands.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/seams.hpp"
#include "vgd/xvc/style.hpp"

namespace vgd::studio {

namespace fs = std::filesystem;

namespace {

constexpr float kPickRadius = 8.0f;  // px: how near the mouse a stretch must be to pick it
constexpr float kPointRadius = 6.0f;  // px: how near an outline point must be to grab it
constexpr float kDropRadius = 18.0f;  // px: how near an arrangement point a piece must be let go to drop on it
constexpr float kClickTravel = 3.0f;  // px: a press let go within this of where it was made is a click
constexpr double kPreviewInterval = 0.25;  // s of UI time between live preview renders

// One stretch of a piece's outline as the pattern view draws it.
struct StretchView {
  std::string id;
  std::vector<pattern::Vec2> points;  // m, laid out: its points and the next stretch's first
  std::vector<pattern::PointKind> kinds;  // of its own points
  std::size_t first = 0;              // its first point's index along the outline
  std::vector<std::string> seams;     // ids of the SEAMs that sew it
};

struct PieceView {
  std::string pattern_id, name;
  std::vector<StretchView> stretches;
  pattern::Vec2 centre = pattern::Vec2::Zero();
  pattern::Vec2 shift = pattern::Vec2::Zero();  // m: layout position minus the piece's own
  std::vector<pattern::Vec2> outline;           // m, laid out: every boundary point, for hit tests
  std::vector<std::vector<pattern::Vec2>> lines;  // m, laid out: its internal lines (a closed one repeats its first point)
  std::optional<std::array<pattern::Vec2, 2>> grain;  // m, laid out: its grain line's ends
  struct NotchView {
    std::string id;       // its POSITION
    pattern::Vec2 at;     // m, laid out
    double angle_deg = 0;  // the cut's direction
  };
  std::vector<NotchView> notches;
  std::vector<pattern::Vec2> pins;  // m, laid out: its pins (xvc::Pin)
};

const char* kQualityNames[] = {"preview", "standard", "precise"};
// An imported body's overrides (body/avatar_io.hpp): "auto" lets the importer decide.
const char* kUnits[] = {"auto", "m", "dm", "cm", "mm", "in"};
const char* kUps[] = {"auto", "y", "z", "x", "-y", "-z", "-x"};
const char* kFacings[] = {"auto", "+z", "-z", "+x", "-x"};
const char* kQualityHelp[] = {
    "Implicit Euler, 10 ms steps, self-collision, stopped at 10x the rest threshold: sooner and less settled, "
    "never through itself. Measured error and cost: docs/accuracy-vs-time.md.",
    "Implicit Euler, 10 ms steps, self-collision: the default of vgd drape.",
    "Implicit Euler, 5 ms steps, self-collision: about twice the cost of standard."};

ImU32 rgb(int r, int g, int b, int a = 255) { return IM_COL32(r, g, b, a); }

float distance_to_segment(ImVec2 p, ImVec2 a, ImVec2 b) {
  const float dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
  float t = l2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / l2 : 0.0f;
  t = std::clamp(t, 0.0f, 1.0f);
  const float ex = a.x + t * dx - p.x, ey = a.y + t * dy - p.y;
  return std::sqrt(ex * ex + ey * ey);
}

}  // namespace

struct Studio::Impl {
  // The document and its history.
  xvc::Document doc;
  std::unique_ptr<xvc::UndoStack> undo = std::make_unique<xvc::UndoStack>(doc);
  fs::path file;
  xvc::Document saved;  // as last opened or saved, for the modified mark
  int revision = 0;     // bumped by every change of doc
  int modified_rev = -1;
  bool modified = false;

  // Autosave: the document with unsaved changes written to FILE.autosave
  // every `autosave_s` seconds of changes and at every drape's start; removed
  // when the document is saved or the studio closes. One found when a
  // document is opened means the studio did not close: recovery is offered.
  double autosave_s = 120.0;
  int autosaved_rev = -1;
  double last_autosave = -1e300;
  bool want_recovery = false;  // the dialog is to open
  std::optional<xvc::Document> recovered;  // the autosave's document, while the dialog asks
  std::string recovery_when;               // its time, for the dialog

  std::string status = "Open an XVC document (File > Open, Ctrl+O).";
  bool status_error = false;
  std::string error_text;
  bool error_pending = false;

  std::map<std::string, Rect, std::less<>> widgets;
  std::string selected;
  std::string editing, edit_buffer;  // the attribute field being edited ("<id>/<name>") and its text
  bool was_running = false;          // the drape was running at the last frame

  // Pattern view.
  std::vector<std::string> sizes;
  int layout_rev = -1;
  std::string layout_size;
  // The view's frame (lo, hi) is fitted to the pieces when they are first
  // shown, when another set of pieces is shown and on a right double click;
  // edits that move a piece or its points keep it, so nothing jumps.
  std::string layout_ids;
  bool refit = true;
  std::vector<PieceView> pieces;
  pattern::Vec2 lo{0, 0}, hi{1, 1};  // layout bounds, m
  ImVec2 origin{0, 0};
  float scale = 1;  // px per m
  float zoom = 1;   // × the scale that fits every piece
  ImVec2 pan{0, 0};  // px
  std::optional<std::pair<std::string, std::string>> hovered;
  // The measuring tool (the pattern view's Measure): its points in layout
  // coordinates (m; at most two, snapped to outline points) and their distance.
  bool measuring = false;
  std::vector<pattern::Vec2> measure_points;
  std::optional<double> measured;
  // Drawing in the pattern view: an internal line on the selected piece
  // (draw_on), or a new piece; its points in layout coordinates (m), outline
  // points snapping as the measuring tool's do.
  enum class Drawing { none, line, piece };
  Drawing drawing = Drawing::none;
  std::string draw_on;
  std::vector<pattern::Vec2> drawn_points;
  std::vector<bool> drawn_curve;  // per drawn point: Shift+clicked, a point a smooth curve passes through
  std::vector<std::pair<std::string, std::string>> picked;
  std::size_t picked_a = 0;  // the first picked_a picks are hem A (Shift+click adds to it), the rest hem B
  std::string seam_name = "seam";
  std::map<std::pair<std::string, std::string>, Rect> stretch_rects;
  // Outline editing (a PATTERN selected): the point selected, the one being
  // dragged and where the drag is now (m, in the piece's own frame).
  std::optional<xvc::OutlinePoint> point_sel;
  std::optional<xvc::OutlinePoint> dragging;
  pattern::Vec2 drag_to = pattern::Vec2::Zero();
  ImVec2 drag_from{0, 0};
  // An end (0 or 1) of the selected piece's grain line being dragged, from where.
  std::optional<int> grain_drag;
  ImVec2 grain_from{0, 0};
  std::optional<std::string> notch_drag;  // a notch of the selected piece being dragged (its POSITION id)
  double rotate_deg = 90;
  std::vector<xvc::SeamSuggestion> suggestions;  // the dialog's, while it is open
  std::vector<char> accepted;                    // per suggestion: ticked
  bool want_suggestions = false;

  // Drape.
  dress::DrapeOptions drape;
  std::string body_text;  // the body file typed in; "" = the mannequin of the size
  // Other garments worn with the document, innermost first: under it, then
  // over it (as vgd drape skirt.xvc t-shirt.xvc), and the path being typed.
  std::vector<fs::path> under, over;
  std::string layer_text;
  std::vector<std::string> body_notes;  // what the importer decided for the last drape's body
  std::vector<std::string> preparation;  // what the last drape decided for the document (dress::Preparation)
  DrapeJob here;          // draped in this process
  RemoteJob on_server;    // draped by a vgd-server
  LiveJob* job = &here;   // the one the panels follow: the last started
  std::string server_url;    // "" = no server
  std::string server_token;  // Authorization: Bearer (never shown)
  std::optional<dress::Certificate> cert;
  fs::path work_dir;

  // Preview.
  std::unique_ptr<render::OffscreenRenderer> renderer;
  // The camera of the last preview drawn and its size (px): where the live
  // cloth's particles are on screen, for pulling them.
  std::optional<render::Camera> preview_camera;
  int preview_w = 0, preview_h = 0;
  // Pulling the cloth by hand (Ctrl+drag in the 3-D view while a drape runs
  // here): the hand effect every local drape carries (sim/effects/hand.hpp),
  // the particle held and its depth in the view (m).
  std::shared_ptr<sim::HandControl> hand = std::make_shared<sim::HandControl>();
  std::optional<int> pulling;
  double pull_depth = 0;
  unsigned texture = 0;
  int tex_w = 0, tex_h = 0;
  // The 3-D view drawn in the window's own GL context (render::Renderer into
  // a texture of its own, shown flipped: its rows go up); the OSMesa renderer
  // and an uploaded picture only if that cannot start. A fit map's legend is
  // an overlay texture, transparent but for the legend.
  std::unique_ptr<render::Renderer> view;
  bool view_failed = false;
  unsigned view_texture = 0, legend_texture = 0;
  bool legend_shown = false;
  std::uint64_t pictures = 0;  // pictures drawn or uploaded into the view's textures (Studio::picture_count)
  bool preview_dirty = false;
  double last_preview = -1e9;
  bool turning = false;        // the 3-D view is being turned (dragged)
  bool preview_fast = false;   // the picture shown was drawn fast (to be refined once still)
  double azimuth = 35, elevation = 8;
  int fit_map = 0;  // 0: the pieces' colours; k: render::FitMap k − 1 (warp, weft, shear, stretch, stress, pressure)
  // The stress map's fabric of each piece drawn, by name, resolved once per drape.
  mutable std::map<std::string, render::Membrane> membranes;
  mutable std::string fabric_problem;  // why a piece's fabric could not be read (said once)
  mutable bool pressure_missing_said = false;  // the pressure map's "no drape finished here" (once per choice)
  fs::path dialog_program;  // the desktop's file dialog (zenity); empty: typed paths
  mutable render::TextureCache textures;  // the document's texture images, read once for the preview
  mutable std::string looks_problem;      // why the preview's textures were left out
  bool looks_said = false;                // looks_problem said (once)

  // The shipped fabrics (data/materials/*.xvc, the fabric lab's), read once:
  // file, MATERIAL id, short name, for a tooltip its full name and figures,
  // and the MATERIAL itself (copied into a document for a piece's fabric).
  struct Fabric {
    fs::path file;
    std::string id, name, figures;
    xvc::Node material;
  };
  std::optional<std::vector<Fabric>> fabrics;
  const std::vector<Fabric>& fabric_library() {
    if (fabrics) return *fabrics;
    fabrics.emplace();
    try {
      std::vector<fs::path> files;
      for (const auto& e : fs::directory_iterator(data_file("materials/shirting.xvc").parent_path()))
        if (e.path().extension() == ".xvc" && e.path().stem() != "seed-flag") files.push_back(e.path());
      std::sort(files.begin(), files.end());
      for (const auto& f : files) {
        const xvc::Document d = xvc::load_file(f);
        const auto* mats = d.container("MATERIALS");
        if (!mats || mats->children.empty()) continue;
        const xvc::Node& m = mats->children.front();
        Fabric fab{f, std::string(m.id()), f.stem().string(), std::string(m.attribute("name")), m};
        for (const auto& p : m.children) {
          const std::string name(p.attribute("name"));
          if (name == "density" || name == "spring.warp" || name == "spring.weft" || name == "E_warp" ||
              name == "E_weft" || name == "G")
            fab.figures += "\n" + name + " " + std::string(p.attribute("value")) + " " + std::string(p.attribute("unit"));
        }
        fabrics->push_back(std::move(fab));
      }
    } catch (const std::exception& e) {
      say(std::string("The fabric library cannot be read: ") + e.what(), true);
    }
    return *fabrics;
  }
  std::optional<mesh::SurfaceMesh> body;
  LiveCloth cloth;
  std::function<void()> restore;

  // Arranging (the Arrange button): the preview shows where a drape would
  // start, the body and every piece placed round it, with the body's
  // arrangement points (dress/arrange.hpp). A piece dragged from the pattern
  // view onto a point is put there; a piece dragged in 3-D moves along its
  // segment. Each is one SetArrangements command.
  bool arranging = false;
  int arranged_rev = -1;        // the revision the arrangement shows
  std::string arranged_for;     // the size and body it was made for
  std::optional<body::Avatar> arrange_body;
  std::string arrange_body_key;
  xvc::Document arrange_doc;    // the document as the drape reads it (dress/prepare.hpp)
  std::map<std::string, std::vector<xvc::Arrangement>> arrange_current;  // by PATTERN id, as the drape uses them
  std::vector<dress::ArrangementPoint> arrange_points;
  std::vector<std::pair<std::string, int>> arranged_pieces;  // per cloth piece: its PATTERN and copy
  std::vector<int> particle_piece;                           // per cloth particle: its piece
  struct ArrangedPin {
    int particle = -1;       // the cloth particle it holds
    std::string pattern, id;  // its PATTERN and POSITION
  };
  std::vector<ArrangedPin> arranged_pins;  // the document's pins (xvc::Pin), on the arranged cloth
  std::optional<std::string> piece_drag;  // a piece dragged from the pattern view (moved on it, or dropped on the body)
  ImVec2 piece_drag_from;                 // where the drag started
  ImVec2 canvas_lo, canvas_hi;            // the pattern view on screen
  std::optional<std::size_t> drop_target;  // the arrangement point under it
  struct Lift {
    // A plain drag slides the piece along its segment, Shift+drag turns it
    // round the body to another side, Alt+drag moves it off the body (or nearer).
    enum class How { along, around, off } how = How::along;
    int piece = 0;
    int particle = -1;   // the particle the press took
    float travel = 0;    // px: the furthest the mouse went from the press (an Alt+click pins)
    ImVec2 from;
    double depth = 0;
    std::vector<std::array<float, 3>> start;  // the cloth's positions when it was taken
    body::Vec3 along = body::Vec3::Zero();    // the move so far, along the segment (m)
    std::optional<xvc::Arrangement> to;       // around, off: the arrangement it takes when let go
  };
  std::optional<Lift> lifting;  // a piece dragged in 3-D

  // Dialogs.
  bool want_open = false, want_save_as = false, want_export = false;
  // Recent files, newest first (File > Open Recent), kept in `recent_store`
  // when the host gives one.
  fs::path recent_store;
  std::vector<fs::path> recent;
  void remember(const fs::path& f) {
    const fs::path a = fs::absolute(f);
    recent.erase(std::remove(recent.begin(), recent.end(), a), recent.end());
    recent.insert(recent.begin(), a);
    if (recent.size() > 10) recent.resize(10);
    if (recent_store.empty()) return;
    std::string text;
    for (const auto& r : recent) text += r.string() + "\n";
    try {
      write_file_atomic(recent_store, text);
    } catch (const std::exception&) {
      // A list of recent files is a convenience: not worth an error dialog.
    }
  }
  // DXF import: the dialog's file and choices, then its report.
  bool want_import = false, want_import_report = false;
  fs::path import_path;
  DxfImport import_options;
  std::vector<std::string> import_report;
  // What waits on the unsaved-changes dialog: opening `pending_file`, or quitting.
  enum class Pending { none, open, quit } pending = Pending::none;
  fs::path pending_file;
  bool want_unsaved = false, quit_ok = false;

  void ask_unsaved(Pending what, fs::path f) {
    pending = what, pending_file = std::move(f), want_unsaved = true;
    status = (file.empty() ? std::string("The document") : file.filename().string()) +
             " has unsaved changes: save them, discard them or cancel.";
    status_error = false;
  }
  std::string path_text;

  ~Impl() {
    drop_autosave();  // a normal close: the user answered for the changes (kept while recovery is unanswered)
    for (LiveJob* j : {static_cast<LiveJob*>(&here), static_cast<LiveJob*>(&on_server)}) {
      j->request_stop();
      j->wait();
    }
    if (restore) restore();  // the view's GL objects go with the UI's context current
    view.reset();
    gl::delete_texture(texture);
    gl::delete_texture(legend_texture);
    if (!work_dir.empty()) {
      std::error_code ec;
      fs::remove_all(work_dir, ec);
    }
  }

  void track(const std::string& name) {
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    widgets[name] = {a.x, a.y, b.x, b.y};
  }

  void say(std::string text, bool error = false) {
    status = std::move(text);
    status_error = error;
    if (error) {
      error_text = status;
      error_pending = true;
    }
  }

  void changed() { ++revision; }

  // Runs an undoable command; errors go to the status bar, the document stays.
  void run(std::unique_ptr<xvc::Command> cmd) {
    const std::string label = cmd->label();
    try {
      const std::string id = undo->execute(std::move(cmd));
      changed();
      if (!id.empty() && doc.find(id)) selected = id;
      say(label + ".");
    } catch (const std::exception& e) {
      say(label + " failed: " + e.what(), true);
    }
  }

  void do_undo() {
    if (!undo->can_undo()) return;
    const std::string l = undo->undo_label();
    undo->undo();
    changed();
    say("Undid " + l + ".");
  }
  void do_redo() {
    if (!undo->can_redo()) return;
    const std::string l = undo->redo_label();
    undo->redo();
    changed();
    say("Redid " + l + ".");
  }

  bool is_modified() {
    if (modified_rev != revision) {
      modified = !(doc == saved);
      modified_rev = revision;
    }
    return modified;
  }

  static fs::path autosave_path(const fs::path& f) { return f.string() + ".autosave"; }

  // Writes the autosave when the document has changes not yet in it and
  // `force` or the interval has passed since the last one.
  void autosave(bool force) {
    if (file.empty() || autosaved_rev == revision || !is_modified()) return;
    const double now = ImGui::GetCurrentContext() ? ImGui::GetTime() : 0.0;
    if (!force && now - last_autosave < autosave_s) return;
    try {
      xvc::save_file(doc, autosave_path(file));
      autosaved_rev = revision;
      last_autosave = now;
    } catch (const std::exception& e) {
      say("Cannot autosave to " + autosave_path(file).string() + ": " + e.what(), true);
      last_autosave = now;  // not again at every frame
    }
  }

  // Removes the autosave, unless it waits on the recovery dialog (`answered`:
  // the dialog's Discard).
  void drop_autosave(bool answered = false) {
    if (file.empty() || (recovered && !answered)) return;
    std::error_code ec;
    fs::remove(autosave_path(file), ec);
    autosaved_rev = -1;
  }

  // After opening `file`: an autosave beside it that differs from it is
  // offered for recovery.
  void look_for_autosave() {
    std::error_code ec;
    const fs::path a = autosave_path(file);
    if (!fs::exists(a, ec)) return;
    try {
      xvc::Document d = xvc::load_file(a);
      if (d == doc) {
        fs::remove(a, ec);
        return;
      }
      const auto t = fs::last_write_time(a, ec);
      const auto sys = std::chrono::file_clock::to_sys(t);
      const std::time_t tt = std::chrono::system_clock::to_time_t(sys);
      char when[64] = "";
      std::tm local{};
      if (localtime_r(&tt, &local)) std::strftime(when, sizeof when, "%Y-%m-%d %H:%M", &local);
      recovery_when = when;
      recovered = std::move(d);
      want_recovery = true;
      say(file.filename().string() + " has unsaved changes from " + recovery_when +
          " (the studio did not close normally): recover them or discard them.");
    } catch (const std::exception& e) {
      say("An autosave of " + file.filename().string() + " cannot be read (" + e.what() + "); it is left as " +
              a.string(),
          true);
    }
  }

  // A new document in place of the open one (opened or imported): its file,
  // what counts as saved, a fresh history, nothing of the last drape.
  void replace_document(xvc::Document d, fs::path f, xvc::Document as_saved) {
    drop_autosave();  // the document left: saved, or its changes discarded when asked (kept while unanswered)
    recovered.reset();
    undo.reset();
    doc = std::move(d);
    refit = true;  // the new document's pieces fitted to the view
    undo = std::make_unique<xvc::UndoStack>(doc);
    saved = std::move(as_saved);
    file = std::move(f);
    selected.clear();
    picked.clear(), picked_a = 0;
    drape.size.clear();
    cert.reset();
    body.reset();
    cloth = {};
    autosaved_rev = -1;
    changed();
    refresh_sizes();
  }

  void recover(bool yes) {
    if (yes && recovered) {
      undo.reset();
      doc = std::move(*recovered);
      undo = std::make_unique<xvc::UndoStack>(doc);
      changed();
      refresh_sizes();
      say("Recovered the unsaved changes of " + file.filename().string() + " from " + recovery_when +
          "; save to keep them.");
    } else {
      drop_autosave(/*answered=*/true);
      say("Discarded the unsaved changes of " + file.filename().string() + " from " + recovery_when + ".");
    }
    recovered.reset();
  }

  // ---- pattern layout ------------------------------------------------------

  void refresh_sizes() {
    sizes.clear();
    for (const xvc::Node* p : doc.patterns()) {
      const std::string s(p->attribute("size"));
      if (std::find(sizes.begin(), sizes.end(), s) == sizes.end()) sizes.push_back(s);
    }
    if (std::find(sizes.begin(), sizes.end(), drape.size) == sizes.end()) {
      drape.size = sizes.empty() ? "" : sizes.front();
      try {
        const std::string sample = xvc::to_style(doc).sample_size;
        if (std::find(sizes.begin(), sizes.end(), sample) != sizes.end()) drape.size = sample;
      } catch (const std::exception&) {
      }
    }
  }

  void layout(float aspect) {
    if (layout_rev == revision && layout_size == drape.size) return;
    if (layout_size != drape.size) zoom = 1, pan = {0, 0};
    layout_rev = revision;
    layout_size = drape.size;
    refresh_sizes();
    pieces.clear();
    // Which stretches are sewn: every stretch from..to of every HEM.
    std::map<std::pair<std::string, std::string>, std::vector<std::string>> sewn;
    try {
      for (const auto& seam : xvc::list_seams(doc))
        for (const auto& h : seam.hems) {
          const xvc::Node* pat = doc.find(h.pattern);
          if (!pat) continue;
          bool in = false;
          for (const auto& st : xvc::boundary_stretches(*pat)) {
            if (st.id == h.from) in = true;
            if (in) sewn[{h.pattern, st.id}].push_back(seam.id);
            if (st.id == h.to) break;
          }
        }
    } catch (const std::exception&) {
    }
    struct Raw {
      PieceView view;
      pattern::Vec2 lo, hi;
    };
    std::vector<Raw> raw;
    for (const xvc::Node* p : doc.patterns()) {
      if (p->attribute("size") != drape.size) continue;
      pattern::Piece piece;
      try {
        piece = xvc::to_piece(doc, p->id());
      } catch (const std::exception&) {
        continue;
      }
      if (piece.boundary.size() < 3) continue;
      Raw r;
      r.view.pattern_id = std::string(p->id());
      r.view.name = piece.name;
      const auto stretches = xvc::boundary_stretches(*p);
      const std::size_t n = piece.boundary.size();
      for (const auto& st : stretches) {
        StretchView sv;
        sv.id = st.id;
        sv.first = st.first;
        for (std::size_t k = 0; k <= st.count; ++k) sv.points.push_back(piece.boundary[(st.first + k) % n].p);
        for (std::size_t k = 0; k < st.count; ++k) sv.kinds.push_back(piece.boundary[(st.first + k) % n].kind);
        if (auto it = sewn.find({r.view.pattern_id, st.id}); it != sewn.end()) sv.seams = it->second;
        r.view.stretches.push_back(std::move(sv));
      }
      r.lo = r.hi = piece.boundary.front().p;
      for (const auto& c : piece.boundary) r.lo = r.lo.cwiseMin(c.p), r.hi = r.hi.cwiseMax(c.p);
      for (const auto& l : piece.internal_lines) {
        r.view.lines.push_back(l.points);
        if (l.closed && !l.points.empty()) r.view.lines.back().push_back(l.points.front());
      }
      if (piece.grain_line) r.view.grain = std::array<pattern::Vec2, 2>{piece.grain_line->a, piece.grain_line->b};
      for (const auto& c : p->children)
        if (c.tag == "POSITION" && c.attribute("type") == "notch") {
          const auto x = parse_double(c.attribute("x")), y = parse_double(c.attribute("y"));
          if (x && y) r.view.notches.push_back({std::string(c.id()), pattern::Vec2(*x, *y), parse_double(c.attribute("angle")).value_or(0.0)});
        }
      for (const auto& pin : xvc::pins_of(*p)) r.view.pins.emplace_back(pin.x, pin.y);
      raw.push_back(std::move(r));
    }
    if (raw.empty()) return;
    // Rows in document order; the row count that lets the pieces be drawn largest.
    const double gap = 0.03;
    double best = -1;
    std::size_t best_rows = 1;
    for (std::size_t rows = 1; rows <= raw.size(); ++rows) {
      const std::size_t per = (raw.size() + rows - 1) / rows;
      double width = 0, height = 0;
      for (std::size_t r0 = 0; r0 < raw.size(); r0 += per) {
        double w = 0, h = 0;
        for (std::size_t i = r0; i < std::min(raw.size(), r0 + per); ++i)
          w += raw[i].hi.x() - raw[i].lo.x() + gap, h = std::max(h, raw[i].hi.y() - raw[i].lo.y());
        width = std::max(width, w), height += h + gap;
      }
      const double s = std::min(aspect / width, 1.0 / height);
      if (s > best) best = s, best_rows = rows;
    }
    const std::size_t per = (raw.size() + best_rows - 1) / best_rows;
    double y = 0;
    for (std::size_t r0 = 0; r0 < raw.size(); r0 += per) {
      double x = 0, h = 0;
      for (std::size_t i = r0; i < std::min(raw.size(), r0 + per); ++i) h = std::max(h, raw[i].hi.y() - raw[i].lo.y());
      for (std::size_t i = r0; i < std::min(raw.size(), r0 + per); ++i) {
        pattern::Vec2 shift(x - raw[i].lo.x(), y - h - raw[i].lo.y());
        // A piece moved on the sheet lies where it was put (its row keeps its
        // slot, so the others stay where they were).
        if (const xvc::Node* pn = doc.find(raw[i].view.pattern_id))
          if (const auto at = xvc::sheet_position(*pn)) shift = pattern::Vec2((*at)[0], (*at)[1]);
        for (auto& sv : raw[i].view.stretches) {
          for (auto& q : sv.points) q += shift;
          raw[i].view.outline.insert(raw[i].view.outline.end(), sv.points.begin(), sv.points.end() - 1);
        }
        for (auto& l : raw[i].view.lines)
          for (auto& q : l) q += shift;
        if (raw[i].view.grain)
          for (auto& q : *raw[i].view.grain) q += shift;
        for (auto& nv : raw[i].view.notches) nv.at += shift;
        for (auto& q : raw[i].view.pins) q += shift;
        raw[i].view.centre = 0.5 * (raw[i].lo + raw[i].hi) + shift;
        raw[i].view.shift = shift;
        x += raw[i].hi.x() - raw[i].lo.x() + gap;
        pieces.push_back(std::move(raw[i].view));
      }
      y -= h + gap;
    }
    // The sheet: every piece where it lies.
    pattern::Vec2 blo = pieces.front().outline.front(), bhi = blo;
    std::string ids;
    for (const auto& pv : pieces) {
      ids += pv.pattern_id + " ";
      for (const auto& q : pv.outline) blo = blo.cwiseMin(q), bhi = bhi.cwiseMax(q);
    }
    if (refit || ids != layout_ids) lo = blo, hi = bhi, layout_ids = ids, refit = false;
  }

  ImVec2 to_screen(const pattern::Vec2& p) const {
    return {origin.x + static_cast<float>((p.x() - lo.x()) * scale), origin.y + static_cast<float>((hi.y() - p.y()) * scale)};
  }
  pattern::Vec2 from_screen(const ImVec2& q) const {
    return {lo.x() + (q.x - origin.x) / scale, hi.y() - (q.y - origin.y) / scale};
  }
  const PieceView* piece_view(std::string_view pattern_id) const {
    for (const auto& pv : pieces)
      if (pv.pattern_id == pattern_id) return &pv;
    return nullptr;
  }
  // An outline point laid out (m), or nullopt when it is not in the view.
  std::optional<pattern::Vec2> laid_out(const xvc::OutlinePoint& pt) const {
    if (const PieceView* pv = piece_view(pt.pattern_id))
      for (const auto& sv : pv->stretches)
        if (sv.id == pt.sequence_id && pt.index + 1 < sv.points.size()) return sv.points[pt.index];
    return std::nullopt;
  }

  // A grain line: a line with an arrowhead at each end (the garment-pattern
  // sign); the selected piece's with its ends as handles, the one dragged
  // following the mouse.
  void draw_grain(ImDrawList* dl, const PieceView& pv, const ImVec2& mouse) const {
    ImVec2 e[2] = {to_screen((*pv.grain)[0]), to_screen((*pv.grain)[1])};
    const bool mine = pv.pattern_id == selected;
    if (mine && grain_drag) {
      ImVec2& q = e[*grain_drag];
      q = {q.x + mouse.x - grain_from.x, q.y + mouse.y - grain_from.y};
    }
    const ImU32 col = mine ? rgb(20, 120, 80) : rgb(110, 110, 110);
    dl->AddLine(e[0], e[1], col, mine ? 2.0f : 1.0f);
    const float len = std::hypot(e[1].x - e[0].x, e[1].y - e[0].y);
    if (len > 1) {
      const float ux = (e[1].x - e[0].x) / len, uy = (e[1].y - e[0].y) / len, h = 7, w = 3.5f;
      for (int k = 0; k < 2; ++k) {
        const float s = k == 0 ? 1.0f : -1.0f;  // each head points outwards
        const ImVec2 tip = e[k], base{tip.x + s * h * ux, tip.y + s * h * uy};
        dl->AddTriangleFilled(tip, {base.x - w * uy, base.y + w * ux}, {base.x + w * uy, base.y - w * ux}, col);
      }
    }
    if (mine)
      for (const ImVec2& q : e) dl->AddCircle(q, 4.5f, col, 0, 2.0f);
  }

  // A notch's cut: 8 px into the piece along its angle (its handle at the inner end).
  ImVec2 notch_handle(const PieceView::NotchView& nv) const {
    const ImVec2 q = to_screen(nv.at);
    const double a = nv.angle_deg * std::numbers::pi / 180.0;
    return {q.x + 8.0f * static_cast<float>(std::cos(a)), q.y - 8.0f * static_cast<float>(std::sin(a))};
  }
  void draw_notches(ImDrawList* dl, const PieceView& pv, const ImVec2& mouse) const {
    const bool mine = pv.pattern_id == selected;
    for (const auto& nv : pv.notches) {
      const ImU32 col = mine ? rgb(170, 40, 40) : rgb(120, 70, 70);
      dl->AddLine(to_screen(nv.at), notch_handle(nv), col, mine ? 2.0f : 1.5f);
      if (!mine) continue;
      dl->AddCircle(notch_handle(nv), 3.5f, col, 0, 1.5f);
      if (notch_drag && *notch_drag == nv.id) {
        if (const auto v = nearest_vertex(pv, mouse)) dl->AddCircle(to_screen(v->second), 6.0f, col, 0, 2.0f);
      }
    }
  }
  // The outline vertex of a piece nearest the mouse: its index over the
  // concatenated boundary and where it is laid out.
  std::optional<std::pair<std::size_t, pattern::Vec2>> nearest_vertex(const PieceView& pv, const ImVec2& mouse) const {
    std::optional<std::pair<std::size_t, pattern::Vec2>> best;
    float d2 = 1e30f;
    for (const auto& sv : pv.stretches)
      for (std::size_t k = 0; k + 1 < sv.points.size(); ++k) {
        const ImVec2 q = to_screen(sv.points[k]);
        if (const float d = (q.x - mouse.x) * (q.x - mouse.x) + (q.y - mouse.y) * (q.y - mouse.y); d < d2)
          d2 = d, best = std::make_pair(sv.first + k, sv.points[k]);
      }
    return best;
  }
  void end_notch_drag(const ImVec2& mouse) {
    const std::string id = *std::exchange(notch_drag, std::nullopt);
    const PieceView* pv = piece_view(selected);
    if (!pv) return;
    const auto v = nearest_vertex(*pv, mouse);
    if (!v) return;
    for (const auto& nv : pv->notches)
      if (nv.id == id && (nv.at - v->second).norm() < 1e-12) return;  // where it was
    run(std::make_unique<xvc::MoveNotch>(pv->pattern_id, id, v->first));
  }

  // Where a drag of a grain line's end ends: the line set (one undo step),
  // unless the mouse came back to where it started.
  void end_grain_drag(const ImVec2& mouse) {
    const int end = *std::exchange(grain_drag, std::nullopt);
    const PieceView* pv = piece_view(selected);
    if (!pv || !pv->grain || scale <= 0) return;
    if (std::hypot(mouse.x - grain_from.x, mouse.y - grain_from.y) < 1.0f) return;
    std::array<pattern::Vec2, 2> g = *pv->grain;
    g[static_cast<std::size_t>(end)] += pattern::Vec2(mouse.x - grain_from.x, grain_from.y - mouse.y) / scale;
    const pattern::Vec2 a = g[0] - pv->shift, b = g[1] - pv->shift;
    run(std::make_unique<xvc::SetGrainLine>(pv->pattern_id, std::array<double, 2>{a.x(), a.y()},
                                            std::array<double, 2>{b.x(), b.y()}));
  }

  // Where a drag of an outline point ends: the point moved (one undo step),
  // unless the mouse came back to where it started.
  void end_point_drag() {
    const xvc::OutlinePoint pt = *dragging;
    dragging.reset();
    const auto at = laid_out(pt);
    const PieceView* pv = piece_view(pt.pattern_id);
    if (!at || !pv) return;
    const pattern::Vec2 was = *at - pv->shift;
    if ((drag_to - was).norm() * scale < 0.5) return;
    run(std::make_unique<xvc::MovePoint>(pt, drag_to.x(), drag_to.y()));
    point_sel = pt;
    selected = pt.pattern_id;
  }

  // ---- panels ---------------------------------------------------------------

  void menu_bar(Studio& self) {
    if (!ImGui::BeginMenuBar()) return;
    const bool file_open = ImGui::BeginMenu("File");
    track("File");
    if (file_open) {
      if (ImGui::MenuItem("Open...", "Ctrl+O")) want_open = true;
      track("Open...");
      const bool recent_open = ImGui::BeginMenu("Open Recent", !recent.empty());
      track("Open Recent");
      if (recent_open) {
        fs::path chosen;
        for (std::size_t k = 0; k < recent.size(); ++k) {
          if (ImGui::MenuItem(recent[k].filename().string().c_str())) chosen = recent[k];
          track("recent:" + std::to_string(k + 1));
          if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", recent[k].string().c_str());
        }
        ImGui::EndMenu();
        if (!chosen.empty()) self.open(chosen);
      }
      if (ImGui::MenuItem("Save", "Ctrl+S", false, !file.empty())) self.save();
      track("Save");
      if (ImGui::MenuItem("Save as...")) want_save_as = true;
      track("Save as...");
      ImGui::Separator();
      if (ImGui::MenuItem("Export VRML...", nullptr, false, !cloth.positions.empty() && !job->running()))
        want_export = true;
      track("Export VRML...");
      ImGui::EndMenu();
    }
    const bool edit_open = ImGui::BeginMenu("Edit");
    track("Edit");
    if (edit_open) {
      const std::string u = undo->can_undo() ? "Undo " + undo->undo_label() : "Undo";
      const std::string r = undo->can_redo() ? "Redo " + undo->redo_label() : "Redo";
      if (ImGui::MenuItem((u + "###undo").c_str(), "Ctrl+Z", false, undo->can_undo())) do_undo();
      track("Undo");
      if (ImGui::MenuItem((r + "###redo").c_str(), "Ctrl+Y", false, undo->can_redo())) do_redo();
      track("Redo");
      if (ImGui::MenuItem("Delete", "Del", false, !selected.empty())) delete_selected();
      track("Delete selected");
      ImGui::EndMenu();
    }
    const bool sim_open = ImGui::BeginMenu("Simulate");
    track("Simulate");
    if (sim_open) {
      if (ImGui::MenuItem("Drape", "F5", false, !job->running())) start_drape();
      track("Drape menu");
      if (ImGui::MenuItem("Simulate on server", nullptr, false, !job->running() && !server_url.empty()))
        start_drape(/*remote=*/true);
      track("Simulate on server menu");
      if (ImGui::MenuItem("Stop", nullptr, false, job->running())) job->request_stop();
      track("Stop menu");
      const bool held = job->status().paused;
      if (ImGui::MenuItem(held ? "Resume" : "Pause", nullptr, false, job->running() && job->pausable())) toggle_pause();
      track("Pause menu");
      if (ImGui::MenuItem("Step", nullptr, false, held)) job->step();
      track("Step menu");
      ImGui::EndMenu();
    }
    std::string title = file.empty() ? std::string("(no file)") : file.filename().string();
    if (is_modified()) title += " *";
    ImGui::SameLine(ImGui::GetWindowWidth() - ImGui::CalcTextSize(title.c_str()).x - 16);
    ImGui::TextUnformatted(title.c_str());
    ImGui::EndMenuBar();
  }

  void tree_node(const xvc::Node& node, int depth) {
    const std::string id(node.id());
    std::string label = node.tag;
    for (const char* key : {"name", "piece", "size"})
      if (const std::string* v = node.find_attribute(key)) label += std::string(" ") + *v;
    if (!id.empty()) label += "  [" + id + "]";
    const bool geometry = node.tag == "C2DSEQ";  // its C2D points are not listed
    if (geometry) label += "  (" + std::to_string(node.children.size()) + " points)";
    ImGuiTreeNodeFlags flags = ImGuiTreeNodeFlags_OpenOnArrow | ImGuiTreeNodeFlags_SpanAvailWidth;
    const bool leaf = node.children.empty() || geometry || node.tag == "C2D";
    if (leaf) flags |= ImGuiTreeNodeFlags_Leaf | ImGuiTreeNodeFlags_NoTreePushOnOpen;
    if (!id.empty() && id == selected) flags |= ImGuiTreeNodeFlags_Selected;
    if (depth < 2) ImGui::SetNextItemOpen(true, ImGuiCond_Once);
    ImGui::PushID(&node);
    const bool open = ImGui::TreeNodeEx("node", flags, "%s", label.c_str());
    if (!id.empty()) {
      track("tree:" + id);
      if (ImGui::IsItemClicked() && !ImGui::IsItemToggledOpen()) select(id);
    }
    if (open && !leaf) {
      for (const auto& c : node.children) tree_node(c, depth + 1);
      ImGui::TreePop();
    }
    ImGui::PopID();
  }

  // Selects an element; a PATTERN, or a SEAM by its first hem's pattern, also
  // brings its size into the pattern view.
  void select(const std::string& id) {
    selected = id;
    if (point_sel && point_sel->pattern_id != id) point_sel.reset();
    const xvc::Node* n = doc.find(id);
    if (!n) return;
    const xvc::Node* pattern = n->tag == "PATTERN" ? n : nullptr;
    if (n->tag == "SEAM") {
      try {
        for (const auto& seam : xvc::list_seams(doc))
          if (seam.id == id && !seam.hems.empty()) pattern = doc.find(seam.hems.front().pattern);
      } catch (const std::exception&) {
      }
    }
    if (pattern && !job->running()) {
      const std::string size(pattern->attribute("size"));
      if (std::find(sizes.begin(), sizes.end(), size) != sizes.end()) drape.size = size;
    }
  }

  void delete_point() {
    const xvc::OutlinePoint pt = *point_sel;
    point_sel.reset();
    run(std::make_unique<xvc::DeletePoint>(pt));
  }

  void delete_selected() {
    if (selected.empty() || !doc.find(selected)) return;
    const std::string id = selected;
    selected.clear();
    run(std::make_unique<xvc::DeleteNode>(id));
  }

  void inspector() {
    const xvc::Node* node = selected.empty() ? nullptr : doc.find(selected);
    if (!node) {
      ImGui::TextDisabled("Select an element in the tree.");
      return;
    }
    ImGui::Text("%s  %s", node->tag.c_str(), selected.c_str());
    // A piece's selected outline point first: what was just clicked.
    if (node->tag == "PATTERN") point_inspector();
    if (ImGui::BeginTable("attributes", 2, ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_RowBg)) {
      ImGui::TableSetupColumn("attribute", ImGuiTableColumnFlags_WidthFixed, 90);
      ImGui::TableSetupColumn("value");
      for (const auto& a : node->attributes) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(a.name.c_str());
        ImGui::TableNextColumn();
        if (a.name == "id") {
          ImGui::TextUnformatted(a.value.c_str());
          continue;
        }
        // Edited in a copy; committed as one SetAttribute when the field is left.
        const std::string key = selected + "/" + a.name;
        std::string value = editing == key ? edit_buffer : a.value;
        ImGui::SetNextItemWidth(-1);
        const bool entered = ImGui::InputText(("##" + a.name).c_str(), &value, ImGuiInputTextFlags_EnterReturnsTrue);
        track("attr:" + a.name);
        if (ImGui::IsItemActive()) editing = key, edit_buffer = value;
        if (entered || ImGui::IsItemDeactivatedAfterEdit()) {
          editing.clear();
          if (value != a.value) {
            run(std::make_unique<xvc::SetAttribute>(selected, a.name, value));
            break;  // the node may have changed
          }
        }
      }
      ImGui::EndTable();
    }
    if (ImGui::Button("Delete")) delete_selected();
    track("Delete");
    if (node->tag == "SEAM") {
      ImGui::SameLine();
      if (ImGui::Button("Flip seam")) run(std::make_unique<xvc::FlipSeam>(selected));
      track("Flip seam");
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Sew the second side the other way along the first (a twisted seam untwisted): its hems in "
                          "reverse order, each reversed");
    }
    if (node->tag == "PATTERN") {
      // A piece: a copy of it (its own block, piece name and gradation), or
      // it mirrored about its grain line (a left piece from a right one).
      ImGui::SameLine();
      if (ImGui::Button("Duplicate")) run(std::make_unique<xvc::CopyPattern>(selected));
      track("Duplicate");
      ImGui::SameLine();
      if (ImGui::Button("Flip")) run(std::make_unique<xvc::MirrorPattern>(selected));
      track("Flip");
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Mirror the piece about its grain line (vertical without one); its seams follow it");
      // Turned against the grain line, which stays: the piece is cut at
      // another angle to the warp (45 for a bias cut).
      ImGui::SetNextItemWidth(70);
      ImGui::InputDouble("deg##rotate", &rotate_deg, 0, 0, "%.1f");
      track("rotate angle");
      ImGui::SameLine();
      if (ImGui::Button("Rotate")) run(std::make_unique<xvc::RotatePattern>(selected, rotate_deg));
      track("Rotate");
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Turn the piece counter-clockwise by this angle; the grain line stays, so the fabric's warp "
                          "runs across it at another angle");
      piece_fabric_combo(*node);
    }
  }

  // The selected outline point: where it is, its kind, a point added after
  // it, deleted. Drag it in the pattern view to move it.
  void point_inspector() {
    if (!point_sel || point_sel->pattern_id != selected) {
      ImGui::TextDisabled("Click a point of its outline to edit it; drag one to move it.");
      return;
    }
    const auto at = laid_out(*point_sel);
    const PieceView* pv = piece_view(selected);
    if (!at || !pv) return;
    const pattern::Vec2 q = *at - pv->shift;
    pattern::PointKind kind = pattern::PointKind::plain;
    for (const auto& sv : pv->stretches)
      if (sv.id == point_sel->sequence_id && point_sel->index < sv.kinds.size()) kind = sv.kinds[point_sel->index];
    ImGui::Text("Point %zu of %s: x %.1f mm, y %.1f mm", point_sel->index, point_sel->sequence_id.c_str(),
                1000 * q.x(), 1000 * q.y());
    int k = kind == pattern::PointKind::turn ? 1 : kind == pattern::PointKind::curve ? 2 : 0;
    const char* kinds[] = {"plain", "turn", "curve"};
    ImGui::SetNextItemWidth(70);
    if (ImGui::Combo("##point kind", &k, kinds, 3)) run(std::make_unique<xvc::SetPointKind>(*point_sel, kinds[k]));
    track("point kind");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("The point's kind: plain, turn (a corner, where stretches begin) or curve");
    ImGui::SameLine();
    if (ImGui::Button("Insert after")) {
      const int before = revision;
      run(std::make_unique<xvc::InsertPoint>(*point_sel));
      if (revision != before) point_sel->index += 1;  // the new point is the one selected
    }
    track("Insert point");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("A point half-way along the edge to the next one");
    ImGui::SameLine();
    if (ImGui::Button("Delete point")) delete_point();
    track("Delete point");
    ImGui::Separator();
  }

  void pattern_panel() {
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const float controls = 3 * ImGui::GetFrameHeightWithSpacing();
    const ImVec2 size(avail.x, std::max(60.0f, avail.y - controls));
    layout(size.x / std::max(1.0f, size.y));
    ImGui::InvisibleButton("pattern canvas", size);
    const bool canvas_hovered = ImGui::IsItemHovered();
    const ImVec2 p0 = ImGui::GetItemRectMin();
    canvas_lo = p0, canvas_hi = {p0.x + size.x, p0.y + size.y};
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddRectFilled(p0, {p0.x + size.x, p0.y + size.y}, rgb(252, 251, 248));
    stretch_rects.clear();
    hovered.reset();
    if (pieces.empty()) {
      dl->AddText({p0.x + 10, p0.y + 10}, rgb(120, 120, 120),
                  doc.patterns().empty() ? "No pattern pieces." : "No pieces in this size.");
    } else {
      const double w = hi.x() - lo.x(), h = hi.y() - lo.y();
      const float margin = 12;
      const float fit = static_cast<float>(std::min((size.x - 2 * margin) / w, (size.y - 2 * margin) / h));
      const ImVec2 fit_origin{p0.x + margin + static_cast<float>((size.x - 2 * margin - w * fit) / 2), p0.y + margin};
      const ImVec2 mouse = ImGui::GetIO().MousePos;
      // Zoom about the mouse with the wheel, pan with the right or middle
      // button; a double click with the right button fits the pieces again.
      if (canvas_hovered) {
        const float wheel = ImGui::GetIO().MouseWheel;
        if (wheel != 0) {
          const float z = std::clamp(zoom * std::pow(1.2f, wheel), 0.5f, 40.0f), k = z / zoom;
          // The point under the mouse stays put: pan' = (mouse - fit_origin) (1 - k) + k pan.
          pan = {(mouse.x - fit_origin.x) * (1 - k) + k * pan.x, (mouse.y - fit_origin.y) * (1 - k) + k * pan.y};
          zoom = z;
        }
        for (const ImGuiMouseButton b : {ImGuiMouseButton_Right, ImGuiMouseButton_Middle})
          if (ImGui::IsMouseDragging(b, 0)) pan.x += ImGui::GetIO().MouseDelta.x, pan.y += ImGui::GetIO().MouseDelta.y;
        if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Right)) zoom = 1, pan = {0, 0}, refit = true, layout_rev = -1;
      }
      scale = fit * zoom;
      origin = {fit_origin.x + pan.x, fit_origin.y + pan.y};
      dl->PushClipRect(p0, {p0.x + size.x, p0.y + size.y}, true);
      float best = kPickRadius;
      for (const auto& pv : pieces)
        for (const auto& sv : pv.stretches) {
          const ImVec2 mid = to_screen(sv.points[sv.points.size() / 2]);
          const ImVec2 a = to_screen(sv.points.front()), b = to_screen(sv.points.back());
          // The click target: the middle vertex of the stretch (or the middle of its one edge).
          const ImVec2 c = sv.points.size() == 2 ? ImVec2{(a.x + b.x) / 2, (a.y + b.y) / 2} : mid;
          stretch_rects[{pv.pattern_id, sv.id}] = {c.x - 2, c.y - 2, c.x + 2, c.y + 2};
          if (!canvas_hovered) continue;
          for (std::size_t k = 0; k + 1 < sv.points.size(); ++k) {
            const float d = distance_to_segment(mouse, to_screen(sv.points[k]), to_screen(sv.points[k + 1]));
            if (d < best) best = d, hovered = std::make_pair(pv.pattern_id, sv.id);
          }
        }
      // The selected piece's outline points: hovered (before its stretches), dragged.
      const PieceView* sel_piece = piece_view(selected);
      std::optional<xvc::OutlinePoint> point_hover;
      if (sel_piece && canvas_hovered && !dragging && !measuring && drawing == Drawing::none) {
        float near = kPointRadius;
        for (const auto& sv : sel_piece->stretches)
          for (std::size_t k = 0; k + 1 < sv.points.size(); ++k) {
            const ImVec2 q = to_screen(sv.points[k]);
            if (const float d = std::hypot(mouse.x - q.x, mouse.y - q.y); d < near)
              near = d, point_hover = xvc::OutlinePoint{sel_piece->pattern_id, sv.id, k};
          }
        if (point_hover) hovered.reset();
      }
      // The selected piece's grain line: its ends grabbed like points.
      std::optional<int> grain_hover;
      if (sel_piece && sel_piece->grain && canvas_hovered && !point_hover && !dragging && !grain_drag && !measuring &&
          drawing == Drawing::none)
        for (int e = 0; e < 2; ++e) {
          const ImVec2 q = to_screen((*sel_piece->grain)[static_cast<std::size_t>(e)]);
          if (std::hypot(mouse.x - q.x, mouse.y - q.y) < kPointRadius) grain_hover = e;
        }
      if (grain_hover) {
        hovered.reset();
        ImGui::SetTooltip("Drag to turn or move the grain line (the fabric's warp runs along it)");
        if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) grain_drag = grain_hover, grain_from = mouse;
      }
      if (grain_drag && !ImGui::IsMouseDown(ImGuiMouseButton_Left)) end_grain_drag(mouse);
      // Its notches: grabbed by the inner end of their cut, dropped on the outline vertex nearest the mouse.
      std::optional<std::string> notch_hover;
      if (sel_piece && canvas_hovered && !point_hover && !grain_hover && !dragging && !grain_drag && !notch_drag &&
          !measuring && drawing == Drawing::none)
        for (const auto& nv : sel_piece->notches) {
          const ImVec2 q = notch_handle(nv);
          if (std::hypot(mouse.x - q.x, mouse.y - q.y) < kPointRadius) notch_hover = nv.id;
        }
      if (notch_hover) {
        hovered.reset();
        ImGui::SetTooltip("Drag the notch to another point of the outline; Ctrl+click removes it");
        if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
          if (ImGui::GetIO().KeyCtrl)
            run(std::make_unique<xvc::DeleteNode>(*notch_hover));
          else
            notch_drag = notch_hover;
        }
      }
      if (notch_drag && !ImGui::IsMouseDown(ImGuiMouseButton_Left)) end_notch_drag(mouse);
      if (point_hover) ImGui::SetTooltip("Drag to move the point; Ctrl+click adds a notch here");
      if (point_hover && ImGui::IsMouseClicked(ImGuiMouseButton_Left) && ImGui::GetIO().KeyCtrl) {
        // A notch on this vertex (its index over the concatenated boundary).
        const std::string piece = sel_piece->pattern_id;
        std::optional<std::size_t> vertex;
        for (const auto& sv : sel_piece->stretches)
          if (sv.id == point_hover->sequence_id) vertex = sv.first + point_hover->index;
        if (vertex) {
          run(std::make_unique<xvc::AddNotch>(piece, *vertex));
          selected = piece;  // the piece stays selected, with its new notch
        }
      } else if (point_hover && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
        dragging = point_hover, point_sel = point_hover, drag_from = mouse;
        drag_to = *laid_out(*point_hover) - sel_piece->shift;
      }
      if (dragging) {
        if (const auto at = laid_out(*dragging); at && sel_piece && sel_piece->pattern_id == dragging->pattern_id) {
          drag_to = *at - sel_piece->shift + pattern::Vec2(mouse.x - drag_from.x, drag_from.y - mouse.y) / scale;
          if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) end_point_drag();
        } else {
          dragging.reset();
        }
      }
      for (const auto& pv : pieces) {
        for (const auto& sv : pv.stretches) {
          std::vector<ImVec2> pts;
          for (const auto& q : sv.points) pts.push_back(to_screen(q));
          const auto key = std::make_pair(pv.pattern_id, sv.id);
          const auto pick = std::find(picked.begin(), picked.end(), key);
          const bool sewn = !sv.seams.empty();
          const bool in_selected =
              std::find(sv.seams.begin(), sv.seams.end(), selected) != sv.seams.end() || pv.pattern_id == selected;
          ImU32 col = sewn ? rgb(40, 120, 200) : rgb(60, 60, 60);
          float thick = sewn ? 2.5f : 1.5f;
          if (in_selected) col = rgb(20, 160, 90), thick = 4.0f;  // the seam or piece selected in the tree
          if (pick != picked.end())
            col = static_cast<std::size_t>(pick - picked.begin()) < picked_a ? rgb(230, 110, 20) : rgb(200, 40, 140),
            thick = 3.5f;
          if (hovered && *hovered == key) col = rgb(240, 170, 0), thick = 4.0f;
          dl->AddPolyline(pts.data(), static_cast<int>(pts.size()), col, 0, thick);
          dl->AddCircleFilled(pts.front(), 2.5f, rgb(60, 60, 60));
        }
        for (const auto& l : pv.lines) {
          std::vector<ImVec2> pts;
          for (const auto& q : l) pts.push_back(to_screen(q));
          dl->AddPolyline(pts.data(), static_cast<int>(pts.size()), rgb(130, 130, 130), 0, 1.0f);
        }
        if (pv.grain) draw_grain(dl, pv, mouse);
        draw_notches(dl, pv, mouse);
        for (const auto& q : pv.pins) {  // pins: dark red squares, as in the 3-D view
          const ImVec2 c = to_screen(q);
          dl->AddRectFilled({c.x - 3, c.y - 3}, {c.x + 3, c.y + 3}, rgb(170, 20, 30));
        }
        const ImVec2 c = to_screen(pv.centre);
        const ImVec2 ts = ImGui::CalcTextSize(pv.name.c_str());
        dl->AddText({c.x - ts.x / 2, c.y - ts.y / 2}, rgb(90, 90, 90), pv.name.c_str());
      }
      draw_seam_pairing(dl);
      if (sel_piece) draw_points(dl, *sel_piece, point_hover);
      draw_measure(dl, mouse, canvas_hovered);
      draw_drawing(dl, mouse, canvas_hovered);
      if (const auto d = piece_drag_offset(mouse))
        if (const PieceView* pv = piece_view(*piece_drag)) {
          // Where the piece goes when let go here.
          for (const auto& sv : pv->stretches) {
            std::vector<ImVec2> pts;
            for (const auto& q : sv.points) pts.push_back({to_screen(q).x + d->x, to_screen(q).y + d->y});
            dl->AddPolyline(pts.data(), static_cast<int>(pts.size()), rgb(20, 160, 90, 170), 0, 2.0f);
          }
        }
      dl->PopClipRect();
      if (drawing != Drawing::none) {
        if (ImGui::IsItemClicked()) draw_at(mouse);
      } else if (measuring) {
        if (ImGui::IsItemClicked()) measure_at(mouse);
      } else if (hovered && ImGui::IsItemClicked()) {
        // A click picks for hem B (the first for hem A); Shift+click adds to
        // hem A; a click on a pick drops it.
        const auto it = std::find(picked.begin(), picked.end(), *hovered);
        if (it != picked.end()) {
          if (static_cast<std::size_t>(it - picked.begin()) < picked_a) --picked_a;
          picked.erase(it);
        } else if (picked.empty() || ImGui::GetIO().KeyShift) {
          picked.insert(picked.begin() + static_cast<std::ptrdiff_t>(picked_a), *hovered);
          ++picked_a;
        } else {
          picked.push_back(*hovered);
        }
        if (picked_a == 0 && !picked.empty()) picked_a = 1;  // hem A's last pick dropped: the next becomes A
      } else if (!point_hover && !grain_hover && !grain_drag && !notch_hover && !notch_drag && ImGui::IsItemClicked()) {
        // A click inside a piece selects it (its points to edit); outside every
        // piece, nothing.
        const pattern::Vec2 m = from_screen(mouse);
        std::string inside;
        for (const auto& pv : pieces)
          if (pv.outline.size() >= 3 && mesh::point_in_polygon(pv.outline, m)) inside = pv.pattern_id;
        if (!inside.empty() && inside != selected) select(inside);
        if (inside.empty()) point_sel.reset();
        if (!inside.empty()) piece_drag = inside, piece_drag_from = mouse;  // moved on the sheet, or onto the body
      }
      if (hovered) {
        std::string tip;
        for (const auto& pv : pieces)
          for (const auto& sv : pv.stretches)
            if (pv.pattern_id == hovered->first && sv.id == hovered->second) {
              double length = 0.0;  // along the stretch, m
              for (std::size_t k = 0; k + 1 < sv.points.size(); ++k) length += (sv.points[k + 1] - sv.points[k]).norm();
              tip = pv.name + ", stretch " + sv.id + ": " + format_fixed(100 * length, 1) + " cm long";
              for (const auto& id : sv.seams)
                if (const xvc::Node* n = doc.find(id)) tip += "\nsewn by " + std::string(n->attribute("name")) + " [" + id + "]";
            }
        if (measuring || drawing != Drawing::none) ImGui::SetTooltip("%s", tip.c_str());
        else ImGui::SetTooltip("%s\nclick to pick it for a new seam", tip.c_str());
      }
    }
    // Seam picking: hem A's picks are sewn forward to the others, reversed.
    std::string picks;
    for (std::size_t i = 0; i < picked.size(); ++i) {
      const xvc::Node* p = doc.find(picked[i].first);
      picks += (i == 0 ? "" : i == picked_a ? "  to  " : " + ") +
               (p ? std::string(p->attribute("piece")) : picked[i].first) + " " + picked[i].second;
    }
    ImGui::Text("Picked: %s", picks.empty() ? "(click stretches; Shift+click adds to the first side)" : picks.c_str());
    ImGui::SetNextItemWidth(160);
    ImGui::InputText("##seam name", &seam_name);
    track("seam name");
    ImGui::SameLine();
    ImGui::BeginDisabled(picked.size() < 2 || picked_a >= picked.size());
    if (ImGui::Button("Add seam")) add_seam();
    track("Add seam");
    ImGui::EndDisabled();
    ImGui::SameLine();
    if (ImGui::Button("Clear picks")) picked.clear(), picked_a = 0;
    track("Clear picks");
    ImGui::SameLine();
    if (ImGui::Button("Suggest seams")) suggest();
    track("Suggest seams");
    // On this row when it fits, else on the next (the canvas leaves a row for it).
    const ImGuiStyle& style = ImGui::GetStyle();
    ImGui::SameLine();
    if (ImGui::GetContentRegionAvail().x < ImGui::CalcTextSize("Measure").x + 2 * style.FramePadding.x) ImGui::NewLine();
    // Lit while measuring; a second press ends it.
    if (measuring) ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyleColorVec4(ImGuiCol_ButtonActive));
    const bool toggle = ImGui::Button("Measure");
    if (measuring) ImGui::PopStyleColor();
    if (toggle) {
      measuring = !measuring;
      measure_points.clear();
      say(measuring ? "Measure: click two points of the pattern view (outline points snap)." : "Measuring ended.");
    }
    track("Measure");
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Distances between two points of the pieces (outline points snap), and each stretch's length "
                        "when hovered");
    drawing_buttons();
  }

  // Draw line (on the selected piece) and Draw piece: lit while drawing; a
  // second press, or Enter, ends the drawing; Esc drops it.
  void drawing_buttons() {
    const ImGuiStyle& style = ImGui::GetStyle();
    const auto button = [&](const char* label, Drawing mode, bool enabled, const char* tip) {
      ImGui::SameLine();
      if (ImGui::GetContentRegionAvail().x < ImGui::CalcTextSize(label).x + 2 * style.FramePadding.x) ImGui::NewLine();
      const bool lit = drawing == mode;
      ImGui::BeginDisabled(!enabled && !lit);
      if (lit) ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyleColorVec4(ImGuiCol_ButtonActive));
      const bool pressed = ImGui::Button(label);
      if (lit) ImGui::PopStyleColor();
      ImGui::EndDisabled();
      track(label);
      if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("%s", tip);
      if (!pressed) return;
      if (lit) return finish_drawing();
      drawing = mode, drawn_points.clear(), drawn_curve.clear(), measuring = false, measure_points.clear();
      draw_on = mode == Drawing::line ? selected : "";
      const xvc::Node* p = doc.find(draw_on);
      say(mode == Drawing::line
              ? "Draw line on " + std::string(p ? p->attribute("piece") : "") +
                    ": click its points inside the piece; Enter or Draw line again ends it, Esc drops it."
              : "Draw piece: click its corners; a click on the first, Enter or Draw piece again closes it, Esc drops it.");
    };
    button("Draw line", Drawing::line, piece_view(selected) != nullptr,
           "An internal line on the selected piece (a fold, a pocket's place), point by point");
    button("Draw piece", Drawing::piece, true, "A new piece, corner by corner (each side a stretch to sew)");
  }

  // The outline point nearest the mouse within the grab radius, else the
  // point under the mouse (layout coordinates, m).
  pattern::Vec2 snapped(const ImVec2& mouse) const {
    pattern::Vec2 at = from_screen(mouse);
    float near = kPointRadius;
    for (const auto& pv : pieces)
      for (const auto& sv : pv.stretches)
        for (const auto& q : sv.points) {
          const ImVec2 sq = to_screen(q);
          if (const float d = std::hypot(mouse.x - sq.x, mouse.y - sq.y); d < near) near = d, at = q;
        }
    return at;
  }

  // A drawing click: the outline point nearest the mouse (within the grab
  // radius) or the point under it; a piece's first point again closes it.
  void draw_at(const ImVec2& mouse) {
    const pattern::Vec2 at = snapped(mouse);
    if (drawing == Drawing::piece && drawn_points.size() >= 3) {
      const ImVec2 first = to_screen(drawn_points.front());
      if (std::hypot(mouse.x - first.x, mouse.y - first.y) < kPointRadius) return finish_drawing();
    }
    drawn_points.push_back(at);
    drawn_curve.push_back(ImGui::GetIO().KeyShift);
  }

  // The drawing as it will be made: straight between corners, smooth through
  // Shift+clicked points (pattern::smooth_through, 5 mm pieces); `to` is the
  // point under the mouse, a corner, when given.
  std::vector<pattern::ContourPoint> drawn_outline(std::optional<pattern::Vec2> to = std::nullopt) const {
    std::vector<pattern::ContourPoint> c;
    for (std::size_t k = 0; k < drawn_points.size(); ++k)
      c.push_back({drawn_points[k], k < drawn_curve.size() && drawn_curve[k] ? pattern::PointKind::curve : pattern::PointKind::turn});
    if (to) c.push_back({*to, pattern::PointKind::turn});
    return pattern::smooth_through(c, drawing == Drawing::piece && !to, 0.005);
  }

  // The drawing becomes a command (one undo step): the line in its piece's own
  // frame, the piece where it was drawn, in the size shown.
  void finish_drawing() {
    const Drawing mode = drawing;
    if (mode == Drawing::none) return;
    const std::size_t clicks = drawn_points.size();
    const auto outline = drawn_outline();
    drawing = Drawing::none, drawn_points.clear(), drawn_curve.clear();
    if (clicks < (mode == Drawing::line ? 2u : 3u)) {
      say(mode == Drawing::line ? "Draw line ended: a line needs two points." : "Draw piece ended: a piece needs three corners.");
      return;
    }
    std::vector<std::array<double, 2>> xy;
    if (mode == Drawing::line) {
      const PieceView* pv = piece_view(draw_on);
      if (!pv) return say("Draw line ended: its piece is no longer shown.", true);
      for (const auto& q : outline) xy.push_back({q.p.x() - pv->shift.x(), q.p.y() - pv->shift.y()});
      run(std::make_unique<xvc::AddInternalLine>(draw_on, xy));
    } else {
      std::vector<bool> curve;
      for (const auto& q : outline) xy.push_back({q.p.x(), q.p.y()}), curve.push_back(q.kind == pattern::PointKind::curve);
      run(std::make_unique<xvc::AddDrawnPattern>("drawn piece", drape.size, xy, curve));
    }
  }

  void draw_drawing(ImDrawList* dl, const ImVec2& mouse, bool canvas_hovered) {
    if (drawing == Drawing::none || drawn_points.empty()) return;
    const ImU32 col = rgb(120, 40, 200);
    std::vector<ImVec2> pts;
    for (const auto& q : drawn_outline(canvas_hovered ? std::optional(from_screen(mouse)) : std::nullopt))
      pts.push_back(to_screen(q.p));
    dl->AddPolyline(pts.data(), static_cast<int>(pts.size()), col, 0, 2.0f);
    // Corners as squares, curve points as dots.
    for (std::size_t k = 0; k < drawn_points.size(); ++k) {
      const ImVec2 q = to_screen(drawn_points[k]);
      if (k < drawn_curve.size() && drawn_curve[k])
        dl->AddCircleFilled(q, 3.5f, col);
      else
        dl->AddRectFilled({q.x - 3.5f, q.y - 3.5f}, {q.x + 3.5f, q.y + 3.5f}, col);
    }
  }

  // A measuring click: the outline point nearest the mouse (within the grab
  // radius) or the point under it; the second gives the distance, a third
  // starts again.
  void measure_at(const ImVec2& mouse) {
    const pattern::Vec2 at = snapped(mouse);
    if (measure_points.size() == 2) measure_points.clear();
    measure_points.push_back(at);
    if (measure_points.size() == 2) {
      const pattern::Vec2 d = measure_points[1] - measure_points[0];
      measured = d.norm();
      say("Measured " + format_fixed(100 * *measured, 2) + " cm (across " + format_fixed(100 * std::abs(d.x()), 2) +
          " cm, up " + format_fixed(100 * std::abs(d.y()), 2) + " cm).");
    }
  }

  // The measuring tool's points and line (to the mouse while the second is awaited), with the distance.
  void draw_measure(ImDrawList* dl, const ImVec2& mouse, bool canvas_hovered) {
    if (!measuring || measure_points.empty()) return;
    const ImU32 col = rgb(200, 30, 30);
    const ImVec2 a = to_screen(measure_points[0]);
    const bool done = measure_points.size() == 2;
    if (!done && !canvas_hovered) {
      dl->AddCircleFilled(a, 4.0f, col);
      return;
    }
    const ImVec2 b = done ? to_screen(measure_points[1]) : mouse;
    const double d = done ? (measure_points[1] - measure_points[0]).norm() : (from_screen(mouse) - measure_points[0]).norm();
    dl->AddLine(a, b, col, 2.0f);
    dl->AddCircleFilled(a, 4.0f, col);
    dl->AddCircleFilled(b, 4.0f, col);
    const std::string label = format_fixed(100 * d, 1) + " cm";
    dl->AddText({(a.x + b.x) / 2 + 6, (a.y + b.y) / 2 - 16}, col, label.c_str());
  }

  // The selected piece's outline points: squares at turn points, dots
  // elsewhere; the selected point filled orange, the hovered one yellow. A
  // point being dragged is drawn where the mouse has it, with its two edges.
  void draw_points(ImDrawList* dl, const PieceView& pv, const std::optional<xvc::OutlinePoint>& hover) {
    const std::size_t n = pv.outline.size();
    if (dragging && dragging->pattern_id == pv.pattern_id)
      for (const auto& sv : pv.stretches)
        if (sv.id == dragging->sequence_id) {
          const std::size_t v = sv.first + dragging->index;
          const ImVec2 q = to_screen(drag_to + pv.shift);
          dl->AddLine(to_screen(pv.outline[(v + n - 1) % n]), q, rgb(230, 110, 20), 2.0f);
          dl->AddLine(q, to_screen(pv.outline[(v + 1) % n]), rgb(230, 110, 20), 2.0f);
        }
    auto same = [](const std::optional<xvc::OutlinePoint>& a, const std::string& seq, std::size_t k) {
      return a && a->sequence_id == seq && a->index == k;
    };
    for (const auto& sv : pv.stretches)
      for (std::size_t k = 0; k + 1 < sv.points.size(); ++k) {
        const bool sel = point_sel && point_sel->pattern_id == pv.pattern_id && same(point_sel, sv.id, k);
        const bool dragged = dragging && dragging->pattern_id == pv.pattern_id && same(dragging, sv.id, k);
        const ImVec2 q = to_screen(dragged ? drag_to + pv.shift : sv.points[k]);
        const ImU32 fill = sel ? rgb(230, 110, 20) : same(hover, sv.id, k) ? rgb(240, 170, 0) : rgb(255, 255, 255);
        const float r = sel ? 4.5f : 3.5f;
        if (sv.kinds[k] == pattern::PointKind::turn) {
          dl->AddRectFilled({q.x - r, q.y - r}, {q.x + r, q.y + r}, fill);
          dl->AddRect({q.x - r, q.y - r}, {q.x + r, q.y + r}, rgb(40, 40, 40));
        } else {
          dl->AddCircleFilled(q, r, fill);
          dl->AddCircle(q, r, rgb(40, 40, 40));
        }
      }
  }

  // The SEAM selected in the tree: lines from hem A's start to hem B's start
  // and from end to end (B: its hems one after another, each as sewn), a dot
  // at the starts, so the pairing and its direction show (a twisted seam's
  // lines cross).
  void draw_seam_pairing(ImDrawList* dl) {
    const xvc::Node* node = selected.empty() ? nullptr : doc.find(selected);
    if (!node || node->tag != "SEAM") return;
    std::vector<xvc::HemRef> hems;
    for (const auto& si : xvc::list_seams(doc))
      if (si.id == selected) hems = si.hems;
    if (hems.size() < 2) return;
    auto stretch = [&](const std::string& pattern, const std::string& id) -> const StretchView* {
      for (const auto& pv : pieces)
        if (pv.pattern_id == pattern)
          for (const auto& sv : pv.stretches)
            if (sv.id == id && !sv.points.empty()) return &sv;
      return nullptr;
    };
    // A hem's ends as sewn (screen), or nothing when a piece is not shown.
    auto ends = [&](const xvc::HemRef& h) -> std::optional<std::pair<ImVec2, ImVec2>> {
      const StretchView* a = stretch(h.pattern, h.from);
      const StretchView* b = stretch(h.pattern, h.to);
      if (!a || !b) return std::nullopt;
      const ImVec2 first = to_screen(a->points.front()), last = to_screen(b->points.back());
      return h.reverse ? std::make_pair(last, first) : std::make_pair(first, last);
    };
    const auto a = ends(hems.front()), b0 = ends(hems[1]), b1 = ends(hems.back());
    if (!a || !b0 || !b1) return;
    const ImU32 col = rgb(150, 60, 200);
    dl->AddLine(a->first, b0->first, col, 1.5f);
    dl->AddLine(a->second, b1->second, col, 1.5f);
    dl->AddCircleFilled(a->first, 4.0f, col);
    dl->AddCircleFilled(b0->first, 4.0f, col);
  }

  // Hem A: its picks, stretches following one another on one piece, as one
  // HEM from the first to the last in contour order (M:N seams); hem B: each
  // pick a HEM of its own, reversed (pieces face up, seams.hpp), in the order
  // picked.
  void add_seam() {
    xvc::HemRef a;
    a.pattern = picked[0].first;
    const xvc::Node* pat = doc.find(a.pattern);
    const auto stretches = pat ? xvc::boundary_stretches(*pat) : std::vector<xvc::Stretch>{};
    const std::size_t n = stretches.size();
    std::vector<std::size_t> at;  // hem A's stretches' places on the outline
    for (std::size_t i = 0; i < picked_a; ++i) {
      std::size_t k = 0;
      while (k < n && stretches[k].id != picked[i].second) ++k;
      if (picked[i].first != a.pattern || k == n) {
        say("Hem A's stretches must be on one piece: pick them again.", true);
        return;
      }
      at.push_back(k);
    }
    // The run's first stretch: the one whose predecessor (cyclically) is not picked.
    std::size_t first = at[0];
    for (std::size_t k : at)
      if (std::find(at.begin(), at.end(), (k + n - 1) % n) == at.end()) first = k;
    for (std::size_t j = 0; j < at.size(); ++j)
      if (std::find(at.begin(), at.end(), (first + j) % n) == at.end()) {
        say("Hem A's stretches must follow one another along the outline (" + std::to_string(at.size()) +
                " picked, not in a row): pick them again.",
            true);
        return;
      }
    a.from = stretches[first].id;
    a.to = stretches[(first + at.size() - 1) % n].id;
    std::vector<xvc::HemRef> hems{a};
    for (std::size_t i = picked_a; i < picked.size(); ++i) {
      xvc::HemRef h;
      h.pattern = picked[i].first;
      h.from = h.to = picked[i].second;
      h.reverse = true;
      hems.push_back(h);
    }
    std::vector<xvc::Node> nodes{xvc::seam_node(seam_name.empty() ? "seam" : seam_name, hems)};
    run(std::make_unique<xvc::AddSeams>(std::move(nodes)));
    picked.clear(), picked_a = 0;
  }

  // Suggest seams: vgd's suggestions for the size shown, listed in a dialog
  // to accept or reject one by one; the checked ones are added as one
  // undoable command.
  void suggest() {
    xvc::SeamOptions o;
    o.size = drape.size;
    try {
      suggestions = xvc::suggest_seams(doc, o);
    } catch (const std::exception& e) {
      say(std::string("Suggesting seams failed: ") + e.what(), true);
      return;
    }
    if (suggestions.empty()) {
      say("No seams to suggest for size " + drape.size + ".");
      return;
    }
    accepted.assign(suggestions.size(), 1);
    want_suggestions = true;
  }

  void suggestions_dialog() {
    if (want_suggestions) ImGui::OpenPopup("Suggested seams"), want_suggestions = false;
    if (!ImGui::BeginPopupModal("Suggested seams", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
    ImGui::Text("Size %s: tick the seams to add (hover one for why it was suggested).", drape.size.c_str());
    const float line = ImGui::GetFrameHeightWithSpacing();
    ImGui::BeginChild("suggestions", {760, std::min(16.0f, static_cast<float>(suggestions.size()) + 0.5f) * line}, false);
    auto piece = [&](const std::string& id) {
      const auto* n = doc.find(id);
      return n ? std::string(n->attribute("piece")) : id;
    };
    for (std::size_t k = 0; k < suggestions.size(); ++k) {
      const auto& sg = suggestions[k];
      std::string label = sg.name + ": " + (sg.hems.empty() ? std::string() : piece(sg.hems[0].pattern)) + " to ";
      for (std::size_t h = 1; h < sg.hems.size(); ++h) label += (h > 1 ? " + " : "") + piece(sg.hems[h].pattern);
      const double ease_mm = std::abs(1000 * sg.ease) < 0.05 ? 0.0 : 1000 * sg.ease;  // no "-0.0"
      label += ", ease " + format_fixed(ease_mm, 1) + " mm, score " + format_fixed(sg.score, 2) + "##" + std::to_string(k);
      bool on = accepted[k] != 0;
      if (ImGui::Checkbox(label.c_str(), &on)) accepted[k] = on ? 1 : 0;
      track("suggestion:" + std::to_string(k + 1));
      if (ImGui::IsItemHovered() && !sg.reason.empty()) ImGui::SetTooltip("%s", sg.reason.c_str());
    }
    ImGui::EndChild();
    const auto n = static_cast<std::size_t>(std::count(accepted.begin(), accepted.end(), 1));
    ImGui::BeginDisabled(n == 0);
    if (ImGui::Button(("Add " + std::to_string(n) + " seams").c_str())) {
      std::vector<xvc::Node> nodes;
      for (std::size_t k = 0; k < suggestions.size(); ++k)
        if (accepted[k]) nodes.push_back(xvc::seam_node(suggestions[k]));
      ImGui::CloseCurrentPopup();
      run(std::make_unique<xvc::AddSeams>(std::move(nodes)));
      suggestions.clear();
    }
    track("suggestions:add");
    ImGui::EndDisabled();
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) {
      ImGui::CloseCurrentPopup();
      suggestions.clear();
      say("No suggested seam added.");
    }
    track("suggestions:cancel");
    ImGui::EndPopup();
  }

  void simulate_panel() {
    const bool running = job->running();
    ImGui::BeginDisabled(running);
    ImGui::SetNextItemWidth(120);
    if (ImGui::BeginCombo("size", drape.size.empty() ? "-" : drape.size.c_str())) {
      for (const auto& s : sizes) {
        if (ImGui::Selectable(s.c_str(), s == drape.size)) drape.size = s;
        track("size:" + s);
      }
      ImGui::EndCombo();
    }
    track("size");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(120);
    const int q = static_cast<int>(drape.quality);
    if (ImGui::BeginCombo("quality", kQualityNames[q])) {
      for (int i = 0; i < 3; ++i) {
        if (ImGui::Selectable(kQualityNames[i], i == q)) drape.quality = static_cast<scene::Quality>(i);
        track(std::string("quality:") + kQualityNames[i]);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", kQualityHelp[i]);
      }
      ImGui::EndCombo();
    }
    track("quality");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", kQualityHelp[q]);
    ImGui::Checkbox("self-collision", &drape.self_collision);
    track("self-collision");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(90);
    double spacing_cm = drape.spacing * 100;
    if (ImGui::InputDouble("spacing cm", &spacing_cm, 0, 0, "%.2f")) drape.spacing = std::clamp(spacing_cm, 0.0, 10.0) / 100;
    track("spacing");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Mesh spacing; 0 = the document's mesh.spacing, else 1.5 cm");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(70);
    if (ImGui::InputDouble("limit s", &drape.time_limit, 0, 0, "%.1f"))
      drape.time_limit = std::clamp(drape.time_limit, 0.04, 120.0);
    track("time limit");
    fabric_combo();
    ImGui::SameLine();
    ImGui::Checkbox("sleeves first", &drape.sleeves_first);
    track("sleeves first");
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Sew each sleeve into a tube round its arm before pulling its cap to the armhole\n"
                        "(vgd drape --sleeves-first): for bodies with the arms swung forward, where an open\n"
                        "sleeve slides off its arm. Off by default: it changes which drapes pass elsewhere.");
    body_row();
    layers_row();
    server_row();
    ImGui::EndDisabled();

    ImGui::BeginDisabled(running || pieces.empty());
    if (ImGui::Button("Drape")) start_drape();
    track("Drape");
    ImGui::SameLine();
    ImGui::BeginDisabled(server_url.empty());
    if (ImGui::Button("Simulate on server")) start_drape(/*remote=*/true);
    track("Simulate on server");
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
      ImGui::SetTooltip(server_url.empty() ? "Give a vgd-server's address above first"
                                           : "Send the document to the server and watch its drape here as it runs");
    ImGui::EndDisabled();
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::BeginDisabled(!running);
    if (ImGui::Button("Stop")) job->request_stop();
    track("Stop");
    ImGui::EndDisabled();
    const DrapeStatus s = job->status();
    // Pause holds a drape run here after its current frame; Step runs one
    // frame more (1/fps s simulated); Resume lets it run on.
    ImGui::SameLine();
    ImGui::BeginDisabled(!running || !job->pausable());
    if (ImGui::Button(s.paused ? "Resume" : "Pause")) toggle_pause();
    track(s.paused ? "Resume" : "Pause");
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
      ImGui::SetTooltip(job->pausable() || !running ? "Hold the drape after its current frame (Step then runs one frame at a time)"
                                                     : "A server's drape runs on by itself");
    ImGui::SameLine();
    ImGui::BeginDisabled(!s.paused);
    if (ImGui::Button("Step")) job->step();
    track("Step");
    ImGui::EndDisabled();
    ImGui::EndDisabled();
    // Lit while arranging; a second press ends it.
    ImGui::SameLine();
    ImGui::BeginDisabled(running || pieces.empty());
    if (arranging) ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyleColorVec4(ImGuiCol_ButtonActive));
    const bool arrange_pressed = ImGui::Button("Arrange");
    if (arranging) ImGui::PopStyleColor();
    if (arrange_pressed) toggle_arrange();
    track("Arrange");
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
      ImGui::SetTooltip("Show where the drape starts: the pieces round the body and the body's arrangement points. "
                        "Drag a piece from the pattern view onto a point, or a piece in 3-D along its place");
    ImGui::EndDisabled();
    const float f = s.time_limit > 0 ? static_cast<float>(std::min(1.0, s.t / s.time_limit)) : 0.0f;
    std::string overlay = s.stage + (s.paused ? " (paused)" : "");
    if (s.running && s.stage != "placing")
      overlay += "  " + format_fixed(s.t, 2) + " s  seams " + std::to_string(s.seams_closed) + "/" +
                 std::to_string(s.seam_pairs) +
                 (s.seams_waiting > 0 ? " (" + std::to_string(s.seams_waiting) + " waiting)" : std::string());
    if (s.running || !s.stage.empty()) overlay += "  wall " + format_fixed(s.wall_s, 1) + " s";
    ImGui::ProgressBar(s.stage == "done" ? 1.0f : f, {-1, 0}, overlay.c_str());
    track("progress");
    if (cert) {
      const auto& c = *cert;
      const auto [closed, pairs] = c.seam_totals();
      const auto warnings = c.warnings();
      ImGui::Text("%s after %.2f s (%.1f s wall), %s%s; seams %d/%d; %d crossings; penetration %.2f mm",
                  c.stop_reason.c_str(), c.simulated_s, c.wall_s, c.passed() ? "checks passed" : "a check failed",
                  warnings.empty() ? "" : (", " + std::to_string(warnings.size()) + " warning").c_str(), closed, pairs,
                  c.triangle_intersections, c.max_penetration * 1000);
      track("certificate");
      if (ImGui::IsItemHovered()) {
        std::string all;
        for (const auto& fail : c.failures()) all += "failed: " + fail.kind + ": " + fail.detail + "\n";
        for (const auto& w : warnings) all += "warning: " + w.kind + ": " + w.detail + "\n";
        if (!all.empty()) ImGui::SetTooltip("%s", all.c_str());
      }
    }
  }

  // Garments worn with the document: a path typed, added under or over it;
  // each listed with its place and a button to take it off.
  void layers_row() {
    ImGui::SetNextItemWidth(-2 * ImGui::CalcTextSize("Add over").x - 4 * ImGui::GetStyle().ItemSpacing.x);
    ImGui::InputTextWithHint("##layer", "another garment worn with it (an XVC document)", &layer_text);
    track("layer");
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("An XVC garment draped with this one, under it (a skirt under a T-shirt) or over it, in the "
                        "same size; each is made ready as vgd dress makes it");
    for (const auto& [label, list] : {std::pair{"Add under", &under}, std::pair{"Add over", &over}}) {
      ImGui::SameLine();
      ImGui::BeginDisabled(layer_text.empty());
      if (ImGui::Button(label)) {
        std::error_code ec;
        const fs::path p = fs::absolute(layer_text, ec);
        if (!fs::is_regular_file(p, ec)) {
          say("No garment document " + layer_text + ".", true);
        } else {
          list->push_back(p);
          layer_text.clear();
        }
      }
      track(label);
      ImGui::EndDisabled();
    }
    auto listed = [&](std::vector<fs::path>& list, const char* where) {
      for (std::size_t k = 0; k < list.size(); ++k) {
        ImGui::PushID(static_cast<int>(k) + (where[0] == 'o' ? 1000 : 0));
        ImGui::TextDisabled("%s: %s", where, list[k].filename().string().c_str());
        ImGui::SameLine();
        const bool off = ImGui::SmallButton("take off");
        track(std::string("take off:") + list[k].filename().string());
        ImGui::PopID();
        if (off) {
          list.erase(list.begin() + static_cast<std::ptrdiff_t>(k));
          break;
        }
      }
    };
    listed(under, "under");
    listed(over, "over");
  }

  // The body: the mannequin of the garment's size, or a file (OBJ, glTF,
  // FBX, ...) with the importer's unit, up axis and facing, each "auto" or
  // forced, as vgd drape --avatar --unit --up --facing.
  void body_row() {
    text_row("body", "the mannequin of the size (or a body file)", body_text,
             "A body file (OBJ, PLY, STL, glTF/GLB, FBX, Collada) to drape on; empty: the mannequin");
    if (body_text.empty()) {
      drape.avatar.reset();
      body_notes.clear();
      return;
    }
    if (!drape.avatar || drape.avatar->kind != scene::AvatarDef::Kind::file) {
      drape.avatar = scene::AvatarDef{};
      drape.avatar->kind = scene::AvatarDef::Kind::file;
    }
    drape.avatar->file = body_text;
    bool first = true;  // the three on one line under the path
    auto combo = [&](const char* label, std::string& value, const char* const* items, int n) {
      if (!first) ImGui::SameLine();
      first = false;
      ImGui::SetNextItemWidth(60);
      if (ImGui::BeginCombo(label, value.c_str())) {
        for (int i = 0; i < n; ++i) {
          if (ImGui::Selectable(items[i], value == items[i])) value = items[i];
          track(std::string(label) + ":" + items[i]);
        }
        ImGui::EndCombo();
      }
      track(label);
    };
    combo("unit", drape.avatar->unit, kUnits, 6);
    combo("up", drape.avatar->up, kUps, 7);
    combo("facing", drape.avatar->facing, kFacings, 5);
    for (const auto& n : body_notes) ImGui::TextDisabled("%s", n.c_str());
  }

  // The fabric of the next drape: the garment's own (its document's MATERIAL,
  // else as vgd dress chooses: the shipped knit for legs cut for stretch,
  // shirting otherwise) or one of the shipped fabrics.
  void fabric_combo() {
    const Fabric* now = nullptr;
    for (const auto& f : fabric_library())
      if (!drape.material_xvc.empty() && f.file == drape.material_xvc) now = &f;
    const auto chosen = fabric_menu("fabric", now ? now->name : "garment's", now,
                                    "The fabric of the next drape: the garment's own MATERIAL (else shirting, or the "
                                    "shipped knit for legs cut for stretch) or a shipped fabric (docs/fabric-lab.md)");
    if (!chosen) return;
    if (*chosen) drape.material_xvc = (*chosen)->file, drape.material_id = (*chosen)->id;
    else drape.material_xvc.clear(), drape.material_id.clear();
  }

  // A combo of "garment's" and the shipped fabrics (their figures on hover),
  // tracked as "<label>:<item>". Returns what was picked this frame: nullptr
  // for "garment's", nullopt for nothing.
  std::optional<const Fabric*> fabric_menu(const char* label, const std::string& current, const Fabric* now,
                                           const char* tooltip) {
    std::optional<const Fabric*> chosen;
    ImGui::SetNextItemWidth(160);
    if (ImGui::BeginCombo(label, current.c_str())) {
      if (ImGui::Selectable("garment's", current == "garment's")) chosen = nullptr;
      track(std::string(label) + ":garment's");
      for (const auto& f : fabric_library()) {
        if (ImGui::Selectable(f.name.c_str(), &f == now)) chosen = &f;
        track(std::string(label) + ":" + f.name);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", f.figures.c_str());
      }
      ImGui::EndCombo();
    }
    track(label);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tooltip);
    return chosen;
  }

  // The selected piece's own fabric: the garment's, or a shipped fabric
  // copied into the document (xvc::SetPieceMaterial; the next drape cuts the
  // piece from it: its density, stiffness and look).
  void piece_fabric_combo(const xvc::Node& pattern) {
    const std::string own = xvc::piece_material(doc, pattern);
    std::string current = "garment's";
    if (!own.empty())
      if (const xvc::Node* m = doc.find(own)) current = m->attribute("name").empty() ? own : std::string(m->attribute("name"));
    const auto chosen = fabric_menu("piece fabric", current, nullptr,
                                    "The fabric this piece is cut from: the garment's, or a shipped fabric of its own "
                                    "(a collar in denim, cuffs in jersey); the next drape uses it");
    if (!chosen) return;
    const std::string piece(pattern.id());  // `pattern` may move with the edit
    run(std::make_unique<xvc::SetPieceMaterial>(piece, *chosen ? std::optional<xvc::Node>((*chosen)->material)
                                                               : std::nullopt));
    selected = piece;  // the piece stays selected, not its new MATERIAL
  }

  // The vgd-server that "Simulate on server" sends the drape to.
  void server_row() {
    text_row("server", "a vgd-server to simulate on (http://127.0.0.1:8765)", server_url,
             "vgd-server's address; its token comes from vgd-studio --token-file or $VGD_TOKEN");
  }

  // A text field across the panel, its label at the right, a hint when empty.
  void text_row(const char* label, const char* hint, std::string& value, const char* tooltip) {
    ImGui::SetNextItemWidth(-ImGui::CalcTextSize(label).x - ImGui::GetStyle().ItemInnerSpacing.x);
    ImGui::InputTextWithHint(label, hint, &value);
    track(label);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tooltip);
  }

  // A name the server takes (letters, digits, '.', '_', '-').
  static std::string server_name(const std::string& name, const std::string& fallback) {
    std::string out;
    for (char ch : name) out += std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '_' || ch == '-' ? ch : '_';
    while (!out.empty() && out[0] == '.') out.erase(0, 1);
    return out.empty() || out.size() > 100 ? fallback : out;
  }

  dress::PrepareOptions prepare_options() const {
    dress::PrepareOptions po;
    po.size = drape.size;
    if (drape.avatar && drape.avatar->kind == scene::AvatarDef::Kind::file) po.avatar = drape.avatar->file.string();
    po.fabric_given = !drape.material_xvc.empty();
    return po;
  }

  // The drape's settings for the document as it is now, unsaved edits
  // included, made ready as vgd dress makes it (dress/prepare.hpp): seams
  // suggested when it has none, the pieces no seam sews left out, the body's
  // table and size. The prepared copy is written to the studio's work folder
  // (and given back in `prepared_out` when asked).
  dress::DrapeOptions prepared_drape(dress::Preparation& prep, fs::path& copy, xvc::Document* prepared_out = nullptr) {
    if (work_dir.empty()) {
      work_dir = fs::temp_directory_path() / ("vgd-studio-" + std::to_string(::getpid()) + "-" +
                                              std::to_string(reinterpret_cast<std::uintptr_t>(this)));
      fs::create_directories(work_dir);
    }
    copy = work_dir / (file.empty() ? fs::path("garment.xvc") : file.filename());
    xvc::Document prepared = doc;
    prep = dress::prepare_garment(prepared, prepare_options());
    xvc::save_file(prepared, copy);
    if (prepared_out) *prepared_out = std::move(prepared);
    dress::DrapeOptions d = drape;
    d.garment = copy;
    if (d.pieces.empty()) d.pieces = prep.pieces;
    if (!d.avatar && d.mannequin_table.empty()) {
      d.mannequin_table = prep.body_table;
      if (prep.body_size != prep.size) {
        scene::AvatarDef a;
        a.kind = scene::AvatarDef::Kind::mannequin;
        a.size = prep.body_size;
        a.table = prep.body_table;
        d.avatar = a;
      }
    }
    return d;
  }

  void start_drape(bool remote = false) {
    if (job->running()) return;
    autosave(true);  // a drape is where a crash is likeliest
    if (pieces.empty()) {
      say("Nothing to drape: the document has no pieces in this size.", true);
      return;
    }
    arranging = false;  // the preview follows the drape
    try {
      dress::Preparation prep;
      fs::path copy;
      dress::DrapeOptions d = prepared_drape(prep, copy);
      preparation = prep.decisions;
      for (const auto& w : prep.warnings) preparation.push_back("warning: " + w);
      membranes.clear();  // fabrics may have changed
      std::string made;
      if (!prep.warnings.empty()) made += ", " + prep.warnings.front();
      if (prep.seams_added > 0) made += ", " + std::to_string(prep.seams_added) + " seams suggested (not in the document)";
      if (!prep.left_out.empty()) {
        made += ", left out:";
        for (const auto& n : prep.left_out) made += " " + n;
      }
      // Garments worn with it: each made ready likewise (their left-out
      // pieces marked drape="false" in their copies), innermost first.
      if (!under.empty() || !over.empty()) {
        if (remote) throw Error("", "", "garments worn with it are draped here only: take them off to simulate on a server");
        std::vector<fs::path> order;
        auto ready = [&](const fs::path& f, std::size_t k) {
          xvc::Document other = xvc::load_file(f);
          const dress::Preparation lp = dress::prepare_garment(other, prepare_options());
          for (const auto& dd : lp.decisions) preparation.push_back(f.filename().string() + ": " + dd);
          const fs::path c = work_dir / ("layer" + std::to_string(k)) / f.filename();  // pieces named after its stem
          fs::create_directories(c.parent_path());
          xvc::save_file(other, c);
          return c;
        };
        for (std::size_t k = 0; k < under.size(); ++k) order.push_back(ready(under[k], k));
        order.push_back(copy);
        for (std::size_t k = 0; k < over.size(); ++k) order.push_back(ready(over[k], under.size() + k));
        d.garment = order.front();
        d.over.assign(order.begin() + 1, order.end());
        d.pieces.clear();  // each document marks its own left-out pieces
        made += ", worn with " + std::to_string(under.size() + over.size()) + " other garment" +
                (under.size() + over.size() > 1 ? "s" : "");
      }
      scene::SceneDef def = dress::drape_scene(d);
      const std::string quality = kQualityNames[static_cast<int>(drape.quality)];
      if (remote && drape.sleeves_first)
        throw Error("", "", "sleeves first is for drapes here: a server sews every seam at once; untick it to simulate on a server");
      if (remote) {
        // The same document and settings as a job (docs/server.md): the
        // server's vgd dress makes the same decisions from them.
        net::JobRequest r;
        r.name = server_name(copy.filename().string(), "garment.xvc");
        if (fs::path(r.name).extension() != ".xvc") r.name += ".xvc";
        r.document = read_file(copy);
        r.size = prep.size;
        r.quality = quality;
        r.time_limit = drape.time_limit;
        r.spacing = drape.spacing;
        r.outputs = {"certificate", "trj"};
        if (!drape.material_xvc.empty()) r.fabric = drape.material_xvc.stem().string();  // a shipped fabric, by name
        if (drape.avatar && drape.avatar->kind == scene::AvatarDef::Kind::file) {
          r.avatar_name = server_name(drape.avatar->file.filename().string(), "body" + drape.avatar->file.extension().string());
          r.avatar_bytes = read_file(drape.avatar->file);
          r.unit = drape.avatar->unit, r.up = drape.avatar->up, r.facing = drape.avatar->facing;
        } else {
          r.body_size = prep.body_size;
          r.body_table = prep.body_table;
        }
        net::Client client(net::parse_server_url(server_url), server_token);
        cert.reset();
        cloth = {};
        job = &on_server;
        on_server.start(std::move(client), std::move(r), std::move(def), drape.time_limit);
        was_running = true;
        say("Draping size " + prep.size + " at quality " + quality + " on " + server_url + made + "...");
        return;
      }
      cert.reset();
      cloth = {};
      job = &here;
      release_hand();
      hand->unpin_all();  // pins hold for the run they were set in
      def.effects.hand = sim::HandDef{};
      def.effects.hand->control = hand;  // Ctrl+drag in the 3-D view pulls the cloth
      here.start(std::move(def), omp_get_max_threads());  // the UI thread's setting (--threads)
      was_running = true;
      say("Draping size " + prep.size + " at quality " + quality + made + "...");
    } catch (const std::exception& e) {
      say(std::string("The drape cannot start: ") + e.what(), true);
    }
  }

  void poll_job() {
    mesh::SurfaceMesh b;
    if (job->take_body(b)) body = std::move(b), preview_dirty = true;
    if (job->take_cloth(cloth)) preview_dirty = true;
    if (auto c = job->take_certificate()) cert = std::move(c);
    // The outcome goes to the status bar once, when the run ends.
    const DrapeStatus s = job->status();
    if (was_running && !s.running) say("Drape " + s.message + ".", s.stage == "failed");
    if (!s.body_notes.empty() && body_notes != s.body_notes) {
      body_notes = s.body_notes;
      std::string all;
      for (const auto& n : body_notes) all += (all.empty() ? "" : "; ") + n;
      say("Body: " + all);
    }
    was_running = s.running;
  }

  // Where a live particle is in the last preview (px from its top-left), if shown.
  std::optional<render::ScreenPoint> particle_screen(int i) const {
    if (!preview_camera || i < 0 || static_cast<std::size_t>(i) >= cloth.positions.size()) return std::nullopt;
    const auto& q = cloth.positions[static_cast<std::size_t>(i)];
    return render::project(*preview_camera, preview_w, preview_h, {q[0], q[1], q[2]});
  }

  // Ctrl+press on the 3-D view: of the particles drawn within 12 px of the
  // press, the nearest the eye is held, pulled to the mouse at its depth
  // until the button is let go.
  void grab_cloth(const ImVec2& at) {
    const auto hit = particle_under(at, 12);
    if (!hit) return say("Nothing of the cloth under the mouse to pull (Ctrl+drag on the garment).");
    const auto& q = cloth.positions[static_cast<std::size_t>(hit->first)];
    hand->grab(hit->first, sim::Vec3(q[0], q[1], q[2]));
    pulling = hit->first, pull_depth = hit->second;
    say("Pulling the cloth at particle " + std::to_string(hit->first) + ": drag it, let go to release it.");
  }

  // Alt+click on the cloth while it drapes here: the particle under the mouse
  // pinned where it is (pinned already: unpinned); with Shift, every particle
  // of its piece (the piece frozen; frozen already: freed).
  void pin_at(const ImVec2& at, bool piece) {
    if (!piece) {
      // On a pin's square: that pin let go.
      std::optional<int> near;
      double best = 12;  // px, as far as a click reaches to pin
      for (const auto& p : hand->pins())
        if (const auto q = render::project(*preview_camera, preview_w, preview_h, {p.at.x(), p.at.y(), p.at.z()}))
          if (const double d = std::hypot(q->x - at.x, q->y - at.y); d < best) best = d, near = p.particle;
      if (near) {
        hand->unpin({*near});
        return say("particle " + std::to_string(*near) + " unpinned (" + std::to_string(hand->pin_count()) + " pins left).");
      }
    }
    const auto hit = particle_under(at, 12);
    if (!hit) return say("Nothing of the cloth under the mouse to pin (Alt+click on the garment).");
    std::vector<int> which{hit->first};
    std::string what = "particle " + std::to_string(hit->first);
    if (piece && !cloth.triangle_piece.empty()) {
      // The piece: of the triangles using the particle, the first one's.
      int k = -1;
      for (std::size_t t = 0; t < cloth.triangles.size() && k < 0; ++t)
        for (const int i : cloth.triangles[t])
          if (i == hit->first) k = cloth.triangle_piece[t];
      std::set<int> in;
      for (std::size_t t = 0; t < cloth.triangles.size(); ++t)
        if (cloth.triangle_piece[t] == k) in.insert(cloth.triangles[t].begin(), cloth.triangles[t].end());
      which.assign(in.begin(), in.end());
      what = k >= 0 && static_cast<std::size_t>(k) < cloth.pieces.size() ? cloth.pieces[static_cast<std::size_t>(k)] : "the piece";
    }
    const auto pins = hand->pins();
    std::set<int> pinned;
    for (const auto& p : pins) pinned.insert(p.particle);
    const bool all = std::all_of(which.begin(), which.end(), [&](int i) { return pinned.count(i) > 0; });
    if (all) {
      hand->unpin(which);
      say((piece ? what + " freed" : what + " unpinned") + " (" + std::to_string(hand->pin_count()) + " pins left).");
      return;
    }
    std::vector<sim::HandControl::Pin> add;
    for (const int i : which) {
      const auto& q = cloth.positions[static_cast<std::size_t>(i)];
      add.push_back({i, sim::Vec3(q[0], q[1], q[2])});
    }
    hand->pin(add);
    say((piece ? what + " frozen where it is (" + std::to_string(which.size()) + " particles pinned)" : what + " pinned where it is") +
        "; Alt+click it again to let go.");
  }

  // The pins as small dark red squares where they hold.
  void draw_pins(const ImVec2& view_at) const {
    ImDrawList* dl = ImGui::GetWindowDrawList();
    for (const auto& p : hand->pins())
      if (const auto q = render::project(*preview_camera, preview_w, preview_h, {p.at.x(), p.at.y(), p.at.z()})) {
        const ImVec2 c{view_at.x + static_cast<float>(q->x), view_at.y + static_cast<float>(q->y)};
        dl->AddRectFilled({c.x - 2, c.y - 2}, {c.x + 2, c.y + 2}, rgb(170, 20, 30));
      }
  }

  void release_hand() {
    hand->release();
    if (pulling) say("Let go of the cloth.");
    pulling.reset();
  }

  std::string arrangement_settings() const {
    std::string k = drape.size + "|" + format_fixed(drape.spacing, 4) + "|" + body_text;
    if (drape.avatar) k += "|" + drape.avatar->unit + "|" + drape.avatar->up + "|" + drape.avatar->facing;
    return k;
  }

  // The preview shows the drape's start: the body of the size (or the body
  // file) and the pieces placed round it, as `vgd drape` would place them.
  void arrange() {
    arranged_rev = revision;
    arranged_for = arrangement_settings();
    lifting.reset();
    try {
      dress::Preparation prep;
      fs::path copy;
      xvc::Document prepared;
      const scene::SceneDef def = dress::drape_scene(prepared_drape(prep, copy, &prepared));
      if (!def.avatar) throw Error("", "", "the drape has no body");
      const scene::AvatarDef& a = *def.avatar;
      const std::string key = std::to_string(static_cast<int>(a.kind)) + "|" + a.size + "|" + a.table + "|" +
                              a.file.string() + "|" + a.unit + "|" + a.up + "|" + a.facing;
      if (!arrange_body || key != arrange_body_key) arrange_body = scene::build_avatar(def), arrange_body_key = key;
      const scene::MadeCloths made = dress::dress_garments(def, *arrange_body);
      arrange_doc = std::move(prepared);
      arrange_current = dress::garment_arrangements(arrange_doc, *arrange_body);
      arrange_points = dress::arrangement_points(*arrange_body);
      LiveCloth c;
      arranged_pieces.clear();
      particle_piece.clear();
      arranged_pins.clear();
      for (const auto& [index, mc] : made)
        for (const auto& mp : mc.pieces) {
          const int first = static_cast<int>(c.positions.size()), k = static_cast<int>(c.pieces.size());
          c.pieces.push_back(mp.name);
          arranged_pieces.emplace_back(mp.pattern, mp.copy);
          // The document's pins on this piece: the particles the drape holds (dress_garments).
          for (const auto& [node, id] : mp.pinned) arranged_pins.push_back({first + node, mp.pattern, id});
          for (Eigen::Index i = 0; i + 2 < mp.model.x0.size(); i += 3) {
            c.positions.push_back({static_cast<float>(mp.model.x0[i]), static_cast<float>(mp.model.x0[i + 1]),
                                   static_cast<float>(mp.model.x0[i + 2])});
            particle_piece.push_back(k);
          }
          for (const auto& q : mp.model.uv) c.uv.push_back({q.x(), q.y()});
          for (const auto& t : mp.model.triangles) {
            c.triangles.push_back({t[0] + first, t[1] + first, t[2] + first});
            c.triangle_piece.push_back(k);
          }
        }
      cloth = std::move(c);
      body = arrange_body->surface;
      cert.reset();
      preview_dirty = true;
    } catch (const std::exception& e) {
      say(std::string("The pieces cannot be arranged: ") + e.what(), true);
      arranging = false;
    }
  }

  void toggle_arrange() {
    arranging = !arranging;
    if (!arranging) {
      lifting.reset();
      cloth = {};
      body.reset();
      preview_dirty = true;
      return say("Arranging ended.");
    }
    arrange();
    if (arranging)
      say("Arranging size " + drape.size + ": drag a piece from the pattern view onto a point on the body, or a "
          "piece in 3-D along its place (up and down the trunk, along a limb); Shift+drag turns it round the "
          "body, Alt+drag moves it off the body.");
  }

  // The pattern's arrangements as the drape uses them (stored, else suggested).
  std::vector<xvc::Arrangement> current_arrangements(const std::string& pattern_id) const {
    const auto it = arrange_current.find(pattern_id);
    return it == arrange_current.end() ? std::vector<xvc::Arrangement>{} : it->second;
  }

  // A piece from the pattern view dropped on an arrangement point.
  void put_piece(const std::string& pattern_id, const dress::ArrangementPoint& point) {
    const xvc::Node* node = doc.find(pattern_id);
    if (!node) return;
    const std::string name(node->attribute("piece"));
    try {
      const xvc::Document& from = arrange_doc.find(pattern_id) ? arrange_doc : doc;
      const auto list = dress::put_on(current_arrangements(pattern_id), point, xvc::to_piece(from, pattern_id));
      run(std::make_unique<xvc::SetArrangements>(pattern_id, list));
      say(name + " put on the " + point.label + " (" + format_fixed(point.arrangement.height, 3) + " m)" +
          (list.size() > 1 ? ", its copies with it" : "") + ".");
    } catch (const std::exception& e) {
      say("Cannot put " + name + " there: " + e.what(), true);
    }
  }

  // Of the cloth's particles drawn within `reach` px of `at` (view pixels),
  // the one nearest the eye, and its depth.
  std::optional<std::pair<int, double>> particle_under(const ImVec2& at, double reach) const {
    std::optional<std::pair<int, double>> best;
    for (std::size_t i = 0; i < cloth.positions.size(); ++i) {
      const auto q = particle_screen(static_cast<int>(i));
      if (!q || std::hypot(q->x - at.x, q->y - at.y) > reach || (best && q->depth >= best->second)) continue;
      best = std::make_pair(static_cast<int>(i), q->depth);
    }
    return best;
  }

  // A press on an arranged piece in the 3-D view takes it; the move along its
  // segment is shown while it is held and made its arrangement's when let go.
  void lift_piece(const ImVec2& at, const ImVec2& mouse) {
    const auto hit = particle_under(at, 12);
    if (!hit || static_cast<std::size_t>(hit->first) >= particle_piece.size()) return;
    Lift l;
    const ImGuiIO& io = ImGui::GetIO();
    l.how = io.KeyShift ? Lift::How::around : io.KeyAlt ? Lift::How::off : Lift::How::along;
    l.piece = particle_piece[static_cast<std::size_t>(hit->first)];
    l.particle = hit->first;
    l.from = mouse;
    l.depth = hit->second;
    l.start = cloth.positions;
    lifting = std::move(l);
  }

  void follow_lift(const ImVec2& mouse, const ImVec2& view_at) {
    Lift& l = *lifting;
    l.travel = std::max(l.travel, std::hypot(mouse.x - l.from.x, mouse.y - l.from.y));
    if (l.how == Lift::How::off && l.travel < kClickTravel) return;  // an Alt+click, so far
    const auto& [pattern_id, copy] = arranged_pieces[static_cast<std::size_t>(l.piece)];
    const auto list = current_arrangements(pattern_id);
    if (static_cast<std::size_t>(copy) >= list.size() || !arrange_body) return;
    const auto p0 = render::unproject(*preview_camera, preview_w, preview_h, l.from.x - view_at.x,
                                      l.from.y - view_at.y, l.depth);
    const auto p1 = render::unproject(*preview_camera, preview_w, preview_h, mouse.x - view_at.x,
                                      mouse.y - view_at.y, l.depth);
    const body::Vec3 delta(p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]);
    const xvc::Arrangement& a = list[static_cast<std::size_t>(copy)];
    if (!arrange_body->segment(a.segment)) return;
    if (l.how == Lift::How::around) {
      // Round the body as far as the mouse went across the view, to the
      // nearest side (a tooltip names it); laid out there when let go.
      const auto& c = *preview_camera;
      const body::Vec3 toward(c.target[0] - c.eye[0], c.target[1] - c.eye[1], c.target[2] - c.eye[2]);
      l.to = dress::turned_by(a, *arrange_body, dress::drag_turn(a, *arrange_body, delta, toward.normalized()));
      const bool same = l.to->side == a.side && std::abs(l.to->around_deg - a.around_deg) < 0.5;
      ImGui::SetTooltip("%s", (same ? std::string("Drag round the body to turn the piece")
                                    : "Let go to turn it to the " + a.segment + "'s " + facing(*l.to))
                                  .c_str());
      return;
    }
    if (l.how == Lift::How::off) {
      // Off the body: the piece moved along its side's direction by the
      // clearance it will take (the layout there is made when let go).
      l.to = dress::moved_off(a, *arrange_body, delta);
      const body::Vec3 out = (l.to->clearance - a.clearance) * dress::side_direction(a, *arrange_body);
      for (std::size_t i = 0; i < cloth.positions.size(); ++i)
        if (particle_piece[i] == l.piece)
          for (int k = 0; k < 3; ++k) cloth.positions[i][k] = l.start[i][k] + static_cast<float>(out[k]);
      ImGui::SetTooltip("Clearance %.1f cm (was %.1f cm)", 100 * l.to->clearance, 100 * a.clearance);
      preview_dirty = true;
      return;
    }
    // Along the segment: the height it will take, clamped as the library clamps it.
    const double dh = dress::moved(a, *arrange_body, delta).height - a.height;
    l.along = dh * dress::height_direction(a, *arrange_body);
    for (std::size_t i = 0; i < cloth.positions.size(); ++i)
      if (particle_piece[i] == l.piece)
        for (int k = 0; k < 3; ++k) cloth.positions[i][k] = l.start[i][k] + static_cast<float>(l.along[k]);
    preview_dirty = true;
  }

  // The side a piece faces and how far past it: "left", "left turned 20° towards its back".
  static std::string facing(const xvc::Arrangement& a) {
    if (a.around_deg == 0) return a.side;
    static const std::vector<std::string> order = {"front", "left", "back", "right"};
    const auto at = std::find(order.begin(), order.end(), a.side);
    const std::size_t k = at == order.end() ? 0 : static_cast<std::size_t>(at - order.begin());
    return a.side + " turned " + format_fixed(std::abs(a.around_deg), 0) + "° towards its " +
           order[(k + (a.around_deg > 0 ? 1 : 3)) % 4];
  }

  void drop_lift() {
    const Lift l = *lifting;
    lifting.reset();
    if (l.how == Lift::How::off && l.travel < kClickTravel) {
      cloth.positions = l.start;
      preview_dirty = true;
      return toggle_document_pin(l.particle);
    }
    const auto& [pattern_id, copy] = arranged_pieces[static_cast<std::size_t>(l.piece)];
    auto list = current_arrangements(pattern_id);
    if (l.how != Lift::How::along && l.to && static_cast<std::size_t>(copy) < list.size() && doc.find(pattern_id)) {
      auto& a = list[static_cast<std::size_t>(copy)];
      const xvc::Arrangement before = a;
      if (l.to->side != before.side || std::abs(l.to->around_deg - before.around_deg) >= 0.5 ||
          std::abs(l.to->clearance - before.clearance) >= 1e-3) {
        a = *l.to;
        run(std::make_unique<xvc::SetArrangements>(pattern_id, list));
        const std::string name(doc.find(pattern_id)->attribute("piece"));
        say(l.how == Lift::How::around ? name + " turned round the " + a.segment + " from its " + facing(before) + " to its " + facing(a) + "."
                                       : name + " moved off the body: clearance " + format_fixed(100 * before.clearance, 1) +
                                             " to " + format_fixed(100 * a.clearance, 1) + " cm.");
        return;
      }
    }
    if (l.how != Lift::How::along || l.along.norm() < 1e-3 || static_cast<std::size_t>(copy) >= list.size() ||
        !doc.find(pattern_id)) {
      cloth.positions = l.start;
      preview_dirty = true;
      return;
    }
    auto& a = list[static_cast<std::size_t>(copy)];
    const double before = a.height;
    a = dress::moved(a, *arrange_body, l.along);
    run(std::make_unique<xvc::SetArrangements>(pattern_id, list));
    say(std::string(doc.find(pattern_id)->attribute("piece")) + " moved along the " + a.segment + " from " +
        format_fixed(before, 3) + " to " + format_fixed(a.height, 3) + " m.");
  }

  // An Alt+click on an arranged piece: a pin in the document at the point of
  // the piece the click took (xvc::AddPin: the cloth there is held where it
  // is arranged while the garment drapes); on one of its pins, drawn within
  // 8 px, that pin removed. One undo step either way.
  void toggle_document_pin(int particle) {
    if (particle < 0 || static_cast<std::size_t>(particle) >= particle_piece.size()) return;
    const auto taken = particle_screen(particle);
    for (const auto& pin : arranged_pins) {
      const auto q = particle_screen(pin.particle);
      if (!q || !taken || particle_piece[static_cast<std::size_t>(pin.particle)] != particle_piece[static_cast<std::size_t>(particle)] ||
          std::hypot(q->x - taken->x, q->y - taken->y) > 8)
        continue;
      if (!doc.find(pin.id)) return say("This pin is not in the document (the drape made this piece from it).", true);
      run(std::make_unique<xvc::DeleteNode>(pin.id));
      return say("Pin " + pin.id + " removed from " + std::string(doc.find(pin.pattern)->attribute("piece")) + ".");
    }
    const auto& [pattern_id, copy] = arranged_pieces[static_cast<std::size_t>(particle_piece[static_cast<std::size_t>(particle)])];
    if (!doc.find(pattern_id))
      return say("This piece is made for the drape from the document's pieces (" + pattern_id +
                     " is not in it): pin it on its own pattern.",
                 true);
    const mesh::MaterialFrame f = mesh::material_frame(xvc::to_piece(doc, pattern_id));
    const auto& uv = cloth.uv[static_cast<std::size_t>(particle)];
    const pattern::Vec2 p = f.origin + uv[0] * f.warp + uv[1] * f.weft;
    try {
      const std::string id = undo->execute(std::make_unique<xvc::AddPin>(pattern_id, std::array{p.x(), p.y()}));
      changed();
      say(std::string(doc.find(pattern_id)->attribute("piece")) + " pinned at (" + format_fixed(100 * p.x(), 1) + ", " +
          format_fixed(100 * p.y(), 1) + ") cm of its pattern (" + id +
          "): held where it is arranged while the garment drapes. Alt+click the pin to remove it.");
    } catch (const std::exception& e) {
      say(std::string("Pin not added: ") + e.what(), true);
    }
  }

  void toggle_pause() {
    const bool held = job->status().paused;
    job->set_paused(!held);
    say(held ? "Resumed." : "Paused: the drape holds after its current frame; Step runs one frame more, Resume runs on.");
  }

  render::Scene preview_scene() const {
    render::Scene sc;
    if (body) {
      render::Mesh m;
      m.name = "body";
      m.kind = render::MeshKind::body;
      m.colour = render::kBody;
      for (const auto& v : body->vertices)
        m.positions.push_back({static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())});
      m.triangles = body->triangles;
      sc.meshes.push_back(std::move(m));
    }
    if (!cloth.positions.empty()) {
      for (std::size_t p = 0; p < std::max<std::size_t>(1, cloth.pieces.size()); ++p) {
        render::Mesh m;
        m.name = p < cloth.pieces.size() ? cloth.pieces[p] : "garment";
        m.colour = render::piece_colour(static_cast<int>(p));
        m.positions = cloth.positions;
        for (std::size_t t = 0; t < cloth.triangles.size(); ++t)
          if (cloth.triangle_piece.empty() || cloth.triangle_piece[t] == static_cast<int>(p))
            m.triangles.push_back(cloth.triangles[t]);
        if (cloth.uv.size() == cloth.positions.size())
          for (const auto& q : cloth.uv) m.uv.push_back({static_cast<float>(q[0]), static_cast<float>(q[1])});
        if (fit_map > 0 && cloth.uv.size() == cloth.positions.size()) {
          // A fit map: the piece coloured by its strain against its rest shape.
          const auto map = static_cast<render::FitMap>(fit_map - 1);
          if (map == render::FitMap::pressure) {
            // The pressure on the body, from the finished drape's forces (its certificate).
            std::vector<double> kpa(m.positions.size(), 0.0);
            if (cert && cert->contact.particle_pressure.size() == m.positions.size())
              for (std::size_t i = 0; i < kpa.size(); ++i) kpa[i] = cert->contact.particle_pressure[i] / 1000.0;
            else if (p == 0 && !pressure_missing_said)
              pressure_missing_said = true, fabric_problem = "The contact-pressure map shows a drape that has finished here (its certificate); "
                               "this one has not, or ran on a server.";
            render::colour_by(m, kpa, render::default_scale(map));
          } else {
            const render::Membrane* fabric = map == render::FitMap::stress ? &membrane_of(m.name) : nullptr;
            render::colour_by(m, render::fit_values(m, map, fabric), render::default_scale(map));
          }
        }
        if (!m.triangles.empty()) sc.meshes.push_back(std::move(m));
      }
      if (fit_map == 0) {
        // The document's looks: each piece's colour and texture as the VRML
        // export and vgd render draw them (pieces it does not colour keep theirs).
        std::vector<render::Mesh*> garment;
        for (auto& m : sc.meshes)
          if (m.kind == render::MeshKind::garment) garment.push_back(&m);
        Diagnostics diags;
        std::vector<std::string> names;
        for (const auto* m : garment) names.push_back(m->name);
        const fs::path dir = fs::path(doc.name()).parent_path();
        std::vector<render::Look> looks;
        for (const auto& l : io::vrml::looks_from_xvc(doc, names, &diags)) {
          render::Look k;
          if (l.source.rfind("default", 0) != 0)  // a look the document did not colour: the piece keeps its own
            k.colour = render::Colour{static_cast<float>(l.colour.r), static_cast<float>(l.colour.g),
                                      static_cast<float>(l.colour.b)};
          if (!l.texture.empty()) k.texture = fs::path(l.texture).is_absolute() || dir.empty() ? fs::path(l.texture) : dir / l.texture;
          k.repeat_m = {l.repeat_u, l.repeat_v};
          k.rotation_deg = l.rotation_deg;
          looks.push_back(std::move(k));
        }
        try {
          render::apply_looks(garment, looks, true, diags, &textures);
        } catch (const Error& e) {
          if (looks_problem.empty()) looks_problem = std::string("Textures left out of the preview: ") + e.what();
          render::apply_looks(garment, looks, false, diags, &textures);
        }
      }
    }
    return sc;
  }

  // A piece's fabric for the stress map, as the drape cut it: its own
  // MATERIAL in the document, else the garment's (dress::garment_fabric: the
  // fabric chosen in the simulate panel, else the document's own, else shirting).
  const render::Membrane& membrane_of(const std::string& piece) const {
    if (const auto it = membranes.find(piece); it != membranes.end()) return it->second;
    scene::MaterialDef garment;
    try {
      garment = scene::piece_fabric(doc, piece, dress::garment_fabric_of(doc, file, drape.material_xvc, drape.material_id),
                                    file.string());
    } catch (const std::exception& e) {
      garment = scene::MaterialDef{};  // the default sheet moduli (sim::OrthotropicMaterial)
      fabric_problem = "The stress map uses default sheet moduli for " + piece + ": its fabric cannot be read (" +
                       e.what() + ").";
    }
    const auto o = scene::orthotropic_of(garment);
    return membranes[piece] = render::Membrane{o.E_warp, o.E_weft, o.G, o.nu_warp_weft};
  }

  // The arrangement points over the 3-D view: hovered, named; the one under
  // a piece dragged from the pattern view is where it drops.
  void arrange_overlay(const ImVec2& view_at, const ImVec2& mouse, bool view_hovered) {
    ImDrawList* dl = ImGui::GetWindowDrawList();
    std::optional<std::size_t> near;
    float best = kDropRadius;
    std::vector<std::optional<render::ScreenPoint>> at;
    for (std::size_t k = 0; k < arrange_points.size(); ++k) {
      const auto& p = arrange_points[k].at;
      at.push_back(render::project(*preview_camera, preview_w, preview_h, {p.x(), p.y(), p.z()}));
      if (!at.back() || !view_hovered) continue;
      const float d = std::hypot(mouse.x - view_at.x - static_cast<float>(at.back()->x),
                                 mouse.y - view_at.y - static_cast<float>(at.back()->y));
      if (d < best) best = d, near = k;
    }
    for (std::size_t k = 0; k < at.size(); ++k) {
      if (!at[k]) continue;
      const ImVec2 c{view_at.x + static_cast<float>(at[k]->x), view_at.y + static_cast<float>(at[k]->y)};
      const bool hot = near && *near == k;
      dl->AddCircleFilled(c, hot ? 8.0f : 5.0f, hot ? rgb(240, 150, 20) : rgb(30, 160, 150));
      dl->AddCircle(c, hot ? 8.0f : 5.0f, rgb(20, 60, 60), 0, 1.5f);
    }
    // The document's pins: dark red squares, as a drape's pins are drawn.
    for (const auto& pin : arranged_pins)
      if (const auto q = particle_screen(pin.particle)) {
        const ImVec2 c{view_at.x + static_cast<float>(q->x), view_at.y + static_cast<float>(q->y)};
        dl->AddRectFilled({c.x - 3, c.y - 3}, {c.x + 3, c.y + 3}, rgb(170, 20, 30));
      }
    if (piece_drag) drop_target = near;
    if (near) {
      const xvc::Node* dragged = piece_drag ? doc.find(*piece_drag) : nullptr;
      ImGui::SetTooltip("%s", (arrange_points[*near].label +
                               (dragged ? ": let go to put " + std::string(dragged->attribute("piece")) + " here"
                                        : ": drag a piece from the pattern view here"))
                                  .c_str());
    } else if (piece_drag && view_hovered) {
      ImGui::SetTooltip("Drop %s on a point of the body", std::string(doc.find(*piece_drag) ? doc.find(*piece_drag)->attribute("piece") : "").c_str());
    }
  }

  // The renderer in the UI's GL context, made once (nullptr when it cannot
  // be: the view is then drawn off-screen and uploaded).
  bool ensure_view() {
    if (!view && !view_failed && gl::ready()) {
      try {
        view = std::make_unique<render::Renderer>(reinterpret_cast<render::Renderer::ProcLoader>(gl::loader()));
      } catch (const std::exception& e) {
        view_failed = true;
        say(std::string("The 3-D view is drawn off-screen: ") + e.what(), true);
      }
    }
    return view != nullptr;
  }

  void preview_panel() {
    drop_target.reset();
    if (const std::size_t n = hand->pin_count(); n > 0) {
      ImGui::Text("%zu pinned", n);
      ImGui::SameLine();
      if (ImGui::SmallButton("Unpin all")) hand->unpin_all(), say("Every pin let go.");
      track("Unpin all");
      ImGui::SameLine();
    }
    if (arranging && !job->running() && !lifting &&
        (arranged_rev != revision || arranged_for != arrangement_settings()))
      arrange();  // the document, the size or the body changed
    if (!cloth.positions.empty()) {
      // The garment's colours, or a fit map (docs/studio.md).
      static const char* const kMaps[] = {"looks",           "warp strain", "weft strain",     "shear",
                                          "largest stretch", "stress",      "contact pressure"};
      ImGui::SetNextItemWidth(150);
      if (ImGui::BeginCombo("map", kMaps[fit_map])) {
        for (int k = 0; k < 7; ++k) {
          if (ImGui::Selectable(kMaps[k], k == fit_map) && k != fit_map)
            fit_map = k, preview_dirty = true, pressure_missing_said = false;
          track(std::string("map:") + kMaps[k]);
        }
        ImGui::EndCombo();
      }
      track("map");
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Colour the garment by its strain against the flat pattern (warp, weft, shear, largest "
                          "stretch), by the tension its fabric carries there (stress, N/m) or by how hard it "
                          "presses on the body (contact pressure, kPa, once a drape has finished), with a legend; "
                          "docs/render.md, Fit maps");
    }
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const int w = std::max(16, static_cast<int>(avail.x)), h = std::max(16, static_cast<int>(avail.y));
    const bool running = job->running();
    const double now = ImGui::GetTime();
    const bool resized = w != tex_w || h != tex_h;
    if (view && preview_fast && !running && !turning) preview_dirty = true;  // refined once still
    if ((body || !cloth.positions.empty()) && gl::ready() &&
        ((preview_dirty && (!running || now - last_preview >= kPreviewInterval)) ||
         (resized && (view ? view_texture : texture)))) {
      try {
        const render::ViewPreset preset{"studio", azimuth, elevation, 30};
        const bool map = fit_map > 0 && !cloth.positions.empty();
        ensure_view();
        if (view) {
          // In the window's context: drawn at twice the size when still, shown
          // halved (a 2 x 2 box filter by the texture's linear filtering).
          // Fast while the drape runs or the view turns (no floor shadow: on a
          // software GL it is most of a picture's cost); refined, at twice the
          // size and with the shadow, once still.
          view->set_scene(preview_scene());
          const render::Box& box = view->body_bounds().empty() ? view->scene_bounds() : view->body_bounds();
          const render::Camera cam = render::frame_camera(preset, box, static_cast<double>(w) / h);
          const bool fast = running || turning;
          render::RenderOptions ro;
          ro.shadow = !fast;
          const int s = fast ? 1 : 2;
          view_texture = view->draw_to_texture(cam, w * s, h * s, ro);
          ++pictures;
          preview_fast = fast;
          preview_camera = cam, preview_w = w, preview_h = h;
          legend_shown = map;
          if (map) {
            render::Image overlay(w, h, {0, 0, 0, 0});  // transparent
            const auto m = static_cast<render::FitMap>(fit_map - 1);
            render::draw_legend(overlay, m, render::default_scale(m));
            legend_texture = gl::upload_texture(overlay, legend_texture);
            ++pictures;
          }
        } else {
          if (!renderer) renderer = std::make_unique<render::OffscreenRenderer>();
          renderer->set_scene(preview_scene());
          render::OffscreenOptions o;
          o.supersample = running ? 1 : 2;
          const render::Camera cam =
              render::frame_camera(preset, renderer->framing_box(o), static_cast<double>(w) / h, o.margin);
          render::Image img = renderer->render(cam, w, h, o);
          preview_camera = cam, preview_w = w, preview_h = h;
          if (map) {
            const auto m = static_cast<render::FitMap>(fit_map - 1);
            render::draw_legend(img, m, render::default_scale(m));
          }
          if (restore) restore();
          texture = gl::upload_texture(img, texture);
          ++pictures;
        }
        if (!fabric_problem.empty()) say(fabric_problem, true), fabric_problem.clear();
        if (!looks_problem.empty() && !looks_said) say(looks_problem, true), looks_said = true;
        tex_w = w, tex_h = h;
      } catch (const std::exception& e) {
        if (restore) restore();
        say(std::string("The preview cannot be drawn: ") + e.what(), true);
        body.reset();
        cloth = {};
      }
      preview_dirty = false;
      last_preview = now;
    }
    if ((view ? view_texture : texture) && (body || !cloth.positions.empty())) {
      // An invisible button under the picture: ImGui::Image takes no input.
      const ImVec2 size{static_cast<float>(tex_w), static_cast<float>(tex_h)};
      ImGui::InvisibleButton("preview", size);
      track("preview");
      const ImVec2 a = ImGui::GetItemRectMin(), b{a.x + size.x, a.y + size.y};
      const auto id = [](unsigned t) { return reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(t)); };
      if (view) {
        ImGui::GetWindowDrawList()->AddImage(id(view_texture), a, b, {0, 1}, {1, 0});  // its rows go up
        if (legend_shown) ImGui::GetWindowDrawList()->AddImage(id(legend_texture), a, b);
      } else {
        ImGui::GetWindowDrawList()->AddImage(id(texture), a, b);
      }
      const ImVec2 mouse = ImGui::GetIO().MousePos;
      const bool pullable = job == &here && running && !cloth.positions.empty() && preview_camera;
      if (arranging && !running && preview_camera) {
        arrange_overlay(a, mouse, ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenBlockedByActiveItem));
        if (ImGui::IsItemActivated() && !ImGui::GetIO().KeyCtrl) lift_piece({mouse.x - a.x, mouse.y - a.y}, mouse);
        if (lifting) {
          if (ImGui::IsItemActive())
            follow_lift(mouse, a);
          else
            drop_lift();
        }
      }
      if (ImGui::IsItemActivated() && ImGui::GetIO().KeyCtrl && pullable) grab_cloth({mouse.x - a.x, mouse.y - a.y});
      if (ImGui::IsItemActivated() && ImGui::GetIO().KeyAlt && !ImGui::GetIO().KeyCtrl && pullable)
        pin_at({mouse.x - a.x, mouse.y - a.y}, ImGui::GetIO().KeyShift);
      if (pullable) draw_pins(a);
      if (pulling && (!ImGui::IsItemActive() || !pullable)) release_hand();
      if (!ImGui::IsItemActive()) turning = false;
      if (pulling) {
        // The held particle is pulled to the point under the mouse at its depth.
        const auto p = render::unproject(*preview_camera, preview_w, preview_h, mouse.x - a.x, mouse.y - a.y, pull_depth);
        hand->move(sim::Vec3(p[0], p[1], p[2]));
        if (const auto q = particle_screen(*pulling)) {
          ImDrawList* dl = ImGui::GetWindowDrawList();
          const ImVec2 from{a.x + static_cast<float>(q->x), a.y + static_cast<float>(q->y)};
          dl->AddLine(from, mouse, rgb(230, 60, 20), 2.0f);
          dl->AddCircleFilled(from, 4.0f, rgb(230, 60, 20));
        }
      } else if (ImGui::IsItemActive() && !lifting && !ImGui::GetIO().KeyAlt && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 0)) {
        turning = true;
        const ImVec2 d = ImGui::GetIO().MouseDelta;
        azimuth -= 0.4 * d.x;
        elevation = std::clamp(elevation + 0.3 * d.y, -60.0, 80.0);
        preview_dirty = true;
      }
      if (ImGui::IsItemHovered() && pullable && !pulling)
        ImGui::SetTooltip("Drag to turn the view; while it drapes, Ctrl+drag pulls the cloth, Alt+click pins it "
                          "there (again: unpins), Alt+Shift+click freezes the piece (again: frees it)");
    } else {
      ImGui::TextDisabled("Drape the garment to see it on the body, or Arrange to place its pieces.");
      ImGui::TextDisabled("Drag the picture to turn it.");
    }
  }

  // A piece dragged in the pattern view: how far it has gone (px) while the
  // mouse is still over the view and more than 3 px from where it started.
  std::optional<ImVec2> piece_drag_offset(const ImVec2& mouse) const {
    if (!piece_drag) return std::nullopt;
    const ImVec2 d{mouse.x - piece_drag_from.x, mouse.y - piece_drag_from.y};
    const bool inside =
        mouse.x >= canvas_lo.x && mouse.x < canvas_hi.x && mouse.y >= canvas_lo.y && mouse.y < canvas_hi.y;
    if (!inside || std::hypot(d.x, d.y) <= 3.0f) return std::nullopt;
    return d;
  }

  // A piece dragged from the pattern view is let go: on an arrangement point
  // of the 3-D view it is put there; in the pattern view it is moved on the
  // sheet (one SetSheetPosition command).
  void end_piece_drag() {
    if (!piece_drag || ImGui::IsMouseDown(ImGuiMouseButton_Left)) return;
    const std::string id = *piece_drag;
    const ImVec2 mouse = ImGui::GetIO().MousePos;
    if (drop_target && *drop_target < arrange_points.size()) {
      put_piece(id, arrange_points[*drop_target]);
    } else if (const auto d = piece_drag_offset(mouse); d && scale > 0) {
      if (const PieceView* pv = piece_view(id)) {
        const pattern::Vec2 at = pv->shift + pattern::Vec2(d->x, -d->y) / scale;
        const std::string name = pv->name;
        run(std::make_unique<xvc::SetSheetPosition>(id, std::array<double, 2>{at.x(), at.y()}));
        say(name + " moved on the sheet by " + format_fixed(100 * d->x / scale, 1) + " cm across and " +
            format_fixed(-100 * d->y / scale, 1) + " cm up.");
      }
    }
    piece_drag.reset();
  }

  void dialogs(Studio& self) {
    struct Dialog {
      const char* title;
      const char* prompt;
      const char* ok;
      bool* want;
    };
    const Dialog all[] = {{"Open document", "XVC document or DXF pattern file to open:", "Open", &want_open},
                          {"Save as", "Save the document as:", "Save", &want_save_as},
                          {"Export VRML", "Write the draped garment and the body as VRML97 (.wrl):", "Export", &want_export}};
    const auto act = [&](const Dialog& d, const fs::path& path) {
      if (d.want == &want_open) self.open(path);
      else if (d.want == &want_save_as) self.save(path);
      else self.export_vrml(path);
    };
    for (const Dialog& d : all) {
      if (*d.want) {
        *d.want = false;
        path_text = d.want == &want_export ? (file.empty() ? fs::path("garment.wrl") : fs::path(file).replace_extension(".wrl")).string()
                                           : file.string();
        // The desktop's own dialog when there is one (set_file_dialog_program).
        bool typed = true;
        if (!dialog_program.empty()) {
          FileDialogRequest rq;
          rq.title = d.title;
          rq.save = d.want != &want_open;
          if (d.want == &want_open) {
            rq.start = file.empty() ? fs::current_path() / "" : file.parent_path() / "";
            rq.filters = {"Documents and patterns (XVC, DXF) | *.xvc *.XVC *.dxf *.DXF", "All files | *"};
          } else {
            rq.start = path_text.empty() ? fs::current_path() / "garment.xvc" : fs::path(path_text);
            rq.filters = d.want == &want_export ? std::vector<std::string>{"VRML97 | *.wrl *.wrl.gz", "All files | *"}
                                                : std::vector<std::string>{"XVC documents | *.xvc", "All files | *"};
          }
          const FileDialogAnswer a = run_file_dialog(dialog_program, rq);
          if (a.kind == FileDialogAnswer::Kind::chosen) act(d, a.path), typed = false;
          else if (a.kind == FileDialogAnswer::Kind::cancelled) say(std::string(d.title) + " cancelled."), typed = false;
          else say("The desktop's file dialog could not be run (" + a.why + "): type the path.");
        }
        if (typed) ImGui::OpenPopup(d.title);
      }
      if (!ImGui::BeginPopupModal(d.title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) continue;
      ImGui::TextUnformatted(d.prompt);
      ImGui::SetNextItemWidth(480);
      if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
      const bool enter = ImGui::InputText("##path", &path_text, ImGuiInputTextFlags_EnterReturnsTrue);
      track("dialog:path");
      const bool ok = ImGui::Button(d.ok) || enter;
      track("dialog:ok");
      ImGui::SameLine();
      if (ImGui::Button("Cancel")) ImGui::CloseCurrentPopup();
      track("dialog:cancel");
      if (ok) {
        ImGui::CloseCurrentPopup();
        act(d, path_text);
      }
      ImGui::EndPopup();
    }
    suggestions_dialog();
    if (want_import) ImGui::OpenPopup("Import DXF"), want_import = false;
    if (ImGui::BeginPopupModal("Import DXF", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
      ImGui::Text("%s: a pattern file (AAMA/ASTM DXF)", import_path.filename().string().c_str());
      static const char* const kDxfUnits[] = {"auto", "mm", "cm", "in"};
      ImGui::SetNextItemWidth(120);
      if (ImGui::BeginCombo("units", import_options.units.c_str())) {
        for (const char* u : kDxfUnits) {
          if (ImGui::Selectable(u, import_options.units == u)) import_options.units = u;
          track(std::string("import:units:") + u);
        }
        ImGui::EndCombo();
      }
      track("import:units");
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("auto: as the file states them (mm when it states none, as Valentina writes)");
      ImGui::Checkbox("unfold mirrored halves", &import_options.unfold_mirrored);
      track("import:unfold");
      ImGui::Checkbox("join pieces written per side", &import_options.join_per_side);
      track("import:join");
      ImGui::Checkbox("sew on sew lines (cut the allowance off)", &import_options.sew_on_sew_lines);
      track("import:sew-lines");
      if (ImGui::Button("Import")) {
        ImGui::CloseCurrentPopup();
        self.import_dxf(import_path, import_options);
      }
      track("import:ok");
      ImGui::SameLine();
      if (ImGui::Button("Cancel")) ImGui::CloseCurrentPopup(), say("Import of " + import_path.filename().string() + " cancelled.");
      track("import:cancel");
      ImGui::EndPopup();
    }
    if (want_import_report) ImGui::OpenPopup("Imported"), want_import_report = false;
    if (ImGui::BeginPopupModal("Imported", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
      // A long report scrolls: at most about 24 lines on screen.
      const float line = ImGui::GetTextLineHeightWithSpacing();
      const float height = std::min(24.0f, static_cast<float>(import_report.size()) * 1.6f + 1.0f) * line;
      ImGui::BeginChild("import report", {720, height}, false);
      ImGui::PushTextWrapPos(700);
      for (const auto& l : import_report) ImGui::TextUnformatted(l.c_str());
      ImGui::PopTextWrapPos();
      ImGui::EndChild();
      if (ImGui::Button("OK") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) ImGui::CloseCurrentPopup();
      track("imported:ok");
      ImGui::EndPopup();
    }
    if (want_unsaved) ImGui::OpenPopup("Unsaved changes"), want_unsaved = false;
    if (ImGui::BeginPopupModal("Unsaved changes", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
      ImGui::Text("%s has unsaved changes.", file.empty() ? "The document" : file.filename().string().c_str());
      const bool save = ImGui::Button("Save");
      track("unsaved:save");
      ImGui::SameLine();
      const bool discard = ImGui::Button("Discard");
      track("unsaved:discard");
      ImGui::SameLine();
      const bool cancel = ImGui::Button("Cancel");
      track("unsaved:cancel");
      if (save || discard || cancel) {
        ImGui::CloseCurrentPopup();
        // Saving needs a file name: without one, Save as comes first and the
        // pending action is dropped (nothing is lost; the user repeats it).
        const bool go = discard || (save && !file.empty() && self.save());
        if (save && file.empty()) want_save_as = true;
        if (go && pending == Pending::open) self.open(pending_file, true);
        if (go && pending == Pending::quit) quit_ok = true;
        if (cancel) say("Kept the document open, with its changes.");
        pending = Pending::none;
      }
      ImGui::EndPopup();
    }
    if (want_recovery) ImGui::OpenPopup("Recover unsaved changes"), want_recovery = false;
    if (ImGui::BeginPopupModal("Recover unsaved changes", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
      ImGui::PushTextWrapPos(560);
      ImGui::Text("%s has changes from %s that were never saved: the studio did not close normally.",
                  file.filename().string().c_str(), recovery_when.c_str());
      ImGui::TextDisabled("Recover opens them as unsaved changes; Discard deletes them.");
      ImGui::PopTextWrapPos();
      if (ImGui::Button("Recover")) recover(true), ImGui::CloseCurrentPopup();
      track("recover:yes");
      ImGui::SameLine();
      if (ImGui::Button("Discard")) recover(false), ImGui::CloseCurrentPopup();
      track("recover:no");
      ImGui::EndPopup();
    }
    if (error_pending) ImGui::OpenPopup("Error"), error_pending = false;
    if (ImGui::BeginPopupModal("Error", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
      ImGui::PushTextWrapPos(560);
      ImGui::TextUnformatted(error_text.c_str());
      ImGui::PopTextWrapPos();
      if (ImGui::Button("OK") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) ImGui::CloseCurrentPopup();
      track("error:ok");
      ImGui::EndPopup();
    }
  }

  void shortcuts(Studio& self) {
    const ImGuiIO& io = ImGui::GetIO();
    if (io.WantTextInput) return;
    auto pressed = [](ImGuiKey k) { return ImGui::IsKeyPressed(ImGui::GetKeyIndex(k), false); };
    if (io.KeyCtrl && pressed(ImGuiKey_Z)) io.KeyShift ? do_redo() : do_undo();
    if (io.KeyCtrl && pressed(ImGuiKey_Y)) do_redo();
    // S, O and F5 are not among ImGui 1.86's named keys: hosts put letters at
    // their ASCII codes and F5 at kF5Key (GLFW's own key codes).
    if (io.KeyCtrl && ImGui::IsKeyPressed('S', false)) file.empty() ? void(want_save_as = true) : void(self.save());
    if (io.KeyCtrl && ImGui::IsKeyPressed('O', false)) want_open = true;
    if (pressed(ImGuiKey_Delete)) {
      if (point_sel && point_sel->pattern_id == selected) delete_point();
      else delete_selected();
    }
    if (ImGui::IsKeyPressed(kF5Key, false)) start_drape();
    if (pressed(ImGuiKey_Space) && job->running() && job->pausable()) toggle_pause();  // held or let run on
    if (drawing != Drawing::none && pressed(ImGuiKey_Enter)) finish_drawing();
    if (drawing != Drawing::none && pressed(ImGuiKey_Escape))
      drawing = Drawing::none, drawn_points.clear(), drawn_curve.clear(), say("Drawing dropped.");
  }
};

Studio::Studio() : impl_(std::make_unique<Impl>()) {}
Studio::~Studio() = default;

bool Studio::open(const fs::path& path, bool discard_changes) {
  Impl& I = *impl_;
  if (I.job->running()) {
    I.say("Stop the drape before opening another document.", true);
    return false;
  }
  if (!discard_changes && I.is_modified()) {
    I.ask_unsaved(Impl::Pending::open, path);
    return false;
  }
  if (iequals(path.extension().string(), ".dxf")) {
    I.import_path = path;
    I.want_import = true;
    I.say("Import " + path.filename().string() + ": choose its units and options.");
    return true;
  }
  try {
    xvc::Document d = xvc::load_file(path);
    xvc::Document as_saved = d;
    I.replace_document(std::move(d), fs::absolute(path), std::move(as_saved));
    I.say("Opened " + path.string() + ": " + std::to_string(I.doc.patterns().size()) + " patterns, " +
          std::to_string(xvc::list_seams(I.doc).size()) + " seams.");
    I.autosaved_rev = -1;
    I.remember(I.file);
    I.look_for_autosave();
    return true;
  } catch (const std::exception& e) {
    I.say("Cannot open " + path.string() + ": " + e.what(), true);
    return false;
  }
}

bool Studio::import_dxf(const fs::path& path, const DxfImport& options) {
  Impl& I = *impl_;
  if (I.job->running()) {
    I.say("Stop the drape before importing another document.", true);
    return false;
  }
  try {
    dxf::ImportOptions io;
    if (options.units != "auto") {
      const auto u = parse_length_unit(options.units);
      if (!u) throw Error(path.string(), "", "unknown units '" + options.units + "' (auto, mm, cm, in)");
      io.units = *u;
    }
    io.unfold_mirrored = options.unfold_mirrored;
    io.join_per_side = options.join_per_side;
    io.sew_on_sew_lines = options.sew_on_sew_lines;
    const dxf::ImportResult r = dxf::import_file(path, io);
    xvc::Document d = xvc::from_style(r.style);
    // Its name beside the DXF, never over a file that exists.
    fs::path target = fs::absolute(path).replace_extension(".xvc");
    for (int k = 2; fs::exists(target) || fs::exists(Impl::autosave_path(target)); ++k)
      target = fs::absolute(path).parent_path() / (path.stem().string() + "-" + std::to_string(k) + ".xvc");
    I.replace_document(std::move(d), target, xvc::Document{});  // never saved: the title shows it
    const auto& s = r.summary;
    I.import_report.clear();
    I.import_report.push_back(path.filename().string() + ": " + std::to_string(s.pieces) + " pieces in " +
                              std::to_string(s.sizes.size()) + " sizes (sample " + s.sample_size + "), " +
                              std::to_string(s.blocks) + " blocks; units " + s.units + "; " + s.producer);
    for (const auto& note : dxf::import_notes(r)) I.import_report.push_back(note);
    for (const auto& diag : r.diagnostics.items())  // about this file: its name left out
      I.import_report.push_back(diag.entity.empty() ? diag.message : diag.entity + ": " + diag.message);
    I.import_report.push_back("Save writes it as " + target.filename().string() + " beside the DXF.");
    I.want_import_report = true;
    I.remember(path);
    I.say("Imported " + path.filename().string() + ": " + std::to_string(s.pieces) + " pieces, " +
          std::to_string(r.diagnostics.items().size()) + " notes; unsaved (" + target.filename().string() + ").");
    return true;
  } catch (const std::exception& e) {
    I.say("Cannot import " + path.string() + ": " + e.what(), true);
    return false;
  }
}

const std::vector<std::string>& Studio::import_report() const { return impl_->import_report; }

bool Studio::request_close() {
  Impl& I = *impl_;
  if (I.quit_ok || !I.is_modified()) return true;
  I.ask_unsaved(Impl::Pending::quit, {});
  return false;
}

bool Studio::quit_confirmed() const { return impl_->quit_ok; }

bool Studio::save(const fs::path& path) {
  Impl& I = *impl_;
  const fs::path target = path.empty() ? I.file : path;
  if (target.empty()) {
    I.want_save_as = true;
    return false;
  }
  try {
    xvc::save_file(I.doc, target);
    I.drop_autosave();  // of the file it came from
    I.file = fs::absolute(target);
    I.drop_autosave();
    I.saved = I.doc;
    I.modified_rev = -1;
    I.say("Saved " + target.string() + ".");
    I.remember(I.file);
    return true;
  } catch (const std::exception& e) {
    I.say("Cannot save " + target.string() + ": " + e.what(), true);
    return false;
  }
}

bool Studio::export_vrml(const fs::path& path) {
  Impl& I = *impl_;
  if (I.cloth.positions.empty() || I.job->running()) {
    I.say("Nothing to export: drape the garment first, and let the drape finish.", true);
    return false;
  }
  try {
    io::vrml::Garment g;
    g.name = I.file.empty() ? "garment" : I.file.stem().string();
    g.cloth.triangles = I.cloth.triangles;
    g.cloth.triangle_piece = I.cloth.triangle_piece;
    g.cloth.pieces = I.cloth.pieces;
    g.cloth.uv = I.cloth.uv;
    g.cloth.representative = I.cloth.representative;
    g.frames.times = {I.cloth.t};
    std::vector<float> x;
    for (const auto& p : I.cloth.positions) x.insert(x.end(), p.begin(), p.end());
    g.frames.positions = {std::move(x)};
    g.looks = io::vrml::looks_from_xvc(I.doc, I.cloth.pieces);
    if (I.body) {
      io::vrml::Body b;
      b.name = "body";
      for (const auto& v : I.body->vertices) b.vertices.push_back({v.x(), v.y(), v.z()});
      b.triangles = I.body->triangles;
      g.body = std::move(b);
    }
    g.validate();
    write_file_atomic(path, io::vrml::static_vrml(g));
    I.say("Exported " + path.string() + " (VRML97: " + std::to_string(I.cloth.pieces.size()) + " pieces" +
          (I.body ? " and the body" : "") + ").");
    return true;
  } catch (const std::exception& e) {
    I.say("Cannot export " + path.string() + ": " + e.what(), true);
    return false;
  }
}

void Studio::draw() {
  Impl& I = *impl_;
  I.widgets.clear();
  I.poll_job();
  I.shortcuts(*this);
  I.autosave(false);

  const ImGuiViewport* vp = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(vp->WorkPos);
  ImGui::SetNextWindowSize(vp->WorkSize);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                 ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_MenuBar |
                                 ImGuiWindowFlags_NoSavedSettings;
  // The window's background is the frame's clear (render_gl_if_changed):
  // a software GL clears a tile at a time, and fills a 1280 x 800 quad
  // pixel by pixel.
  ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(0, 0, 0, 0));
  ImGui::Begin("vgd studio", nullptr, flags);
  ImGui::PopStyleColor();
  I.menu_bar(*this);

  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const float status_h = ImGui::GetFrameHeightWithSpacing();
  const float body_h = avail.y - status_h;
  const float left_w = std::round(avail.x * 0.24f), right_w = std::round(avail.x * 0.36f);
  const float centre_w = avail.x - left_w - right_w - 2 * ImGui::GetStyle().ItemSpacing.x;

  ImGui::BeginChild("left", {left_w, body_h});
  ImGui::BeginChild("tree", {0, std::round(body_h * 0.6f)}, true);
  I.tree_node(I.doc.root(), 0);
  ImGui::EndChild();
  ImGui::BeginChild("inspector", {0, 0}, true);
  I.inspector();
  ImGui::EndChild();
  ImGui::EndChild();

  ImGui::SameLine();
  ImGui::BeginChild("patterns", {centre_w, body_h}, true);
  I.pattern_panel();
  ImGui::EndChild();

  ImGui::SameLine();
  ImGui::BeginChild("right", {right_w, body_h});
  // Rows: size and quality; self-collision, spacing, limit; fabric; body; its
  // unit, up, facing; garments worn with it, one row each; server; Drape,
  // Simulate on server, Stop; progress; the certificate; the body's notes.
  const float sim_rows = 9.5f + static_cast<float>(I.body_text.empty() ? 0 : 1 + I.body_notes.size()) +
                         static_cast<float>(I.under.size() + I.over.size());
  ImGui::BeginChild("simulate", {0, sim_rows * ImGui::GetFrameHeightWithSpacing() + 8}, true);
  I.simulate_panel();
  ImGui::EndChild();
  ImGui::BeginChild("preview", {0, 0}, true, ImGuiWindowFlags_NoScrollbar);
  I.preview_panel();
  ImGui::EndChild();
  ImGui::EndChild();
  I.end_piece_drag();

  if (I.status_error) ImGui::PushStyleColor(ImGuiCol_Text, IM_COL32(190, 30, 30, 255));
  ImGui::TextUnformatted(I.status.c_str());
  if (I.status_error) ImGui::PopStyleColor();
  I.dialogs(*this);
  ImGui::End();
}

const xvc::Document& Studio::document() const { return impl_->doc; }
const fs::path& Studio::file() const { return impl_->file; }
bool Studio::modified() const { return impl_->is_modified(); }
const std::string& Studio::status() const { return impl_->status; }
void Studio::set_file_dialog_program(const std::filesystem::path& program) { impl_->dialog_program = program; }
bool Studio::status_is_error() const { return impl_->status_error; }
dress::DrapeOptions& Studio::drape_options() { return impl_->drape; }
void Studio::set_body(const std::filesystem::path& file, const std::string& unit, const std::string& up,
                      const std::string& facing) {
  impl_->body_text = file.string();
  impl_->body_notes.clear();
  if (file.empty()) {
    impl_->drape.avatar.reset();
    return;
  }
  scene::AvatarDef a;
  a.kind = scene::AvatarDef::Kind::file;
  a.file = file, a.unit = unit, a.up = up, a.facing = facing;
  impl_->drape.avatar = a;
}
void Studio::set_recent_store(const fs::path& file) {
  impl_->recent_store = file;
  impl_->recent.clear();
  try {
    for (const auto& line : split(read_file(file), '\n'))
      if (!trim(line).empty() && impl_->recent.size() < 10) impl_->recent.emplace_back(std::string(trim(line)));
  } catch (const Error&) {
    // None yet.
  }
}
const std::vector<fs::path>& Studio::recent_files() const { return impl_->recent; }
void Studio::set_autosave_seconds(double seconds) { impl_->autosave_s = std::max(0.0, seconds); }
bool Studio::recovery_offered() const { return impl_->recovered.has_value(); }
void Studio::set_server(const std::string& url, const std::string& token) {
  impl_->server_url = url;
  impl_->server_token = token;
}
const std::string& Studio::server() const { return impl_->server_url; }
std::string Studio::server_job() const { return impl_->job == &impl_->on_server ? impl_->on_server.id() : ""; }
DrapeStatus Studio::drape_status() const { return impl_->job->status(); }
const std::optional<dress::Certificate>& Studio::certificate() const { return impl_->cert; }
const std::vector<std::string>& Studio::preparation() const { return impl_->preparation; }
void Studio::wait_for_drape() { impl_->job->wait(); }
const std::string& Studio::selected() const { return impl_->selected; }
const std::vector<std::pair<std::string, std::string>>& Studio::picked() const { return impl_->picked; }
std::size_t Studio::picked_first_side() const { return impl_->picked_a; }
void Studio::set_restore_context(std::function<void()> restore) { impl_->restore = std::move(restore); }

std::optional<Rect> Studio::widget(std::string_view name) const {
  const auto it = impl_->widgets.find(name);
  if (it == impl_->widgets.end()) return std::nullopt;
  return it->second;
}

std::optional<Rect> Studio::point_on_screen(const xvc::OutlinePoint& point) const {
  if (point.pattern_id != impl_->selected) return std::nullopt;  // points show on the selected piece
  const auto at = impl_->laid_out(point);
  if (!at) return std::nullopt;
  const ImVec2 q = impl_->to_screen(*at);
  return Rect{q.x, q.y, q.x, q.y};
}
std::optional<Rect> Studio::piece_on_screen(std::string_view pattern_id) const {
  const PieceView* pv = impl_->piece_view(pattern_id);
  if (!pv) return std::nullopt;
  const ImVec2 q = impl_->to_screen(pv->centre);
  return Rect{q.x, q.y, q.x, q.y};
}
float Studio::pattern_scale() const { return impl_->scale; }
std::optional<Rect> Studio::notch_on_screen(std::string_view pattern_id, std::string_view notch_id) const {
  const PieceView* pv = impl_->piece_view(pattern_id);
  if (!pv) return std::nullopt;
  for (const auto& nv : pv->notches)
    if (nv.id == notch_id) {
      const ImVec2 q = impl_->notch_handle(nv);
      return Rect{q.x, q.y, q.x, q.y};
    }
  return std::nullopt;
}
std::optional<Rect> Studio::grain_end_on_screen(std::string_view pattern_id, int end) const {
  const PieceView* pv = impl_->piece_view(pattern_id);
  if (!pv || !pv->grain || end < 0 || end > 1) return std::nullopt;
  const ImVec2 q = impl_->to_screen((*pv->grain)[static_cast<std::size_t>(end)]);
  return Rect{q.x, q.y, q.x, q.y};
}
std::optional<double> Studio::measured() const { return impl_->measured; }
std::optional<int> Studio::held_particle() const { return impl_->pulling; }
bool Studio::view_in_window_context() const { return impl_->view != nullptr; }
bool Studio::arranging() const { return impl_->arranging; }
std::vector<sim::HandControl::Pin> Studio::pins() const { return impl_->hand->pins(); }
std::optional<Rect> Studio::arrangement_point_on_screen(std::string_view label) const {
  const auto r = widget("preview");
  if (!impl_->preview_camera || !r) return std::nullopt;
  for (const auto& p : impl_->arrange_points)
    if (p.label == label)
      if (const auto q = render::project(*impl_->preview_camera, impl_->preview_w, impl_->preview_h, {p.at.x(), p.at.y(), p.at.z()})) {
        const float x = r->x0 + static_cast<float>(q->x), y = r->y0 + static_cast<float>(q->y);
        return Rect{x, y, x, y};
      }
  return std::nullopt;
}
std::vector<std::array<float, 3>> Studio::arranged_piece(std::string_view pattern_id, int copy) const {
  const auto& I = *impl_;
  std::vector<std::array<float, 3>> out;
  for (std::size_t k = 0; k < I.arranged_pieces.size(); ++k)
    if (I.arranged_pieces[k].first == pattern_id && I.arranged_pieces[k].second == copy)
      for (std::size_t i = 0; i < I.particle_piece.size() && i < I.cloth.positions.size(); ++i)
        if (I.particle_piece[i] == static_cast<int>(k)) out.push_back(I.cloth.positions[i]);
  return out;
}
std::optional<Rect> Studio::arranged_piece_on_screen(std::string_view pattern_id, int copy) const {
  const auto& I = *impl_;
  std::optional<std::size_t> piece;
  for (std::size_t k = 0; k < I.arranged_pieces.size(); ++k)
    if (I.arranged_pieces[k].first == pattern_id && I.arranged_pieces[k].second == copy) piece = k;
  if (!piece) return std::nullopt;
  // Its particle nearest its mean.
  std::vector<int> mine;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < I.particle_piece.size() && i < I.cloth.positions.size(); ++i)
    if (I.particle_piece[i] == static_cast<int>(*piece)) {
      mine.push_back(static_cast<int>(i));
      mean += Eigen::Vector3f(I.cloth.positions[i].data()).cast<double>();
    }
  if (mine.empty()) return std::nullopt;
  mean /= static_cast<double>(mine.size());
  const auto dist = [&](int i) {
    return (Eigen::Vector3f(I.cloth.positions[static_cast<std::size_t>(i)].data()).cast<double>() - mean).squaredNorm();
  };
  std::sort(mine.begin(), mine.end(), [&](int a, int b) { return dist(a) < dist(b); });
  // A press takes the particle nearest the eye within 12 px (lift_piece): the
  // first for which that is one of this piece's (a back behind the front
  // shows at its sides only).
  for (std::size_t j = 0; j < mine.size(); ++j) {
    const auto q = I.particle_screen(mine[j]);
    if (!q) continue;
    const auto hit = I.particle_under(ImVec2(static_cast<float>(q->x), static_cast<float>(q->y)), 12);
    if (hit && static_cast<std::size_t>(hit->first) < I.particle_piece.size() &&
        I.particle_piece[static_cast<std::size_t>(hit->first)] == static_cast<int>(*piece))
      return particle_on_screen(mine[j]);
  }
  return std::nullopt;  // covered by other pieces from this view
}
std::vector<std::array<float, 3>> Studio::cloth_positions() const { return impl_->cloth.positions; }
std::uint64_t Studio::picture_count() const { return impl_->pictures; }
std::optional<Rect> Studio::particle_on_screen(int particle) const {
  const auto q = impl_->particle_screen(particle);
  const auto r = widget("preview");
  if (!q || !r) return std::nullopt;
  const float x = r->x0 + static_cast<float>(q->x), y = r->y0 + static_cast<float>(q->y);
  return Rect{x, y, x, y};
}

std::optional<xvc::OutlinePoint> Studio::selected_point() const {
  if (impl_->point_sel && impl_->point_sel->pattern_id == impl_->selected) return impl_->point_sel;
  return std::nullopt;
}

std::optional<Rect> Studio::stretch_on_screen(std::string_view pattern_id, std::string_view stretch_id) const {
  const auto it = impl_->stretch_rects.find({std::string(pattern_id), std::string(stretch_id)});
  if (it == impl_->stretch_rects.end()) return std::nullopt;
  return it->second;
}

}  // namespace vgd::studio
