// The studio driven as a user drives it: synthetic clicks and keys through
// ImGui, frames drawn off-screen (OSMesa), the document and the pixels checked.
#include <gtest/gtest.h>
#include <omp.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <thread>
#include <chrono>
#include <fcntl.h>

#include "support/textured_skirt.hpp"
#include "vgd/body/mannequin.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/body/sizes.hpp"
#include "vgd/qa/compare.hpp"
#include "vgd/render/image.hpp"
#include "vgd/dress/arrange.hpp"
#include "vgd/dress/drape.hpp"
#include "vgd/pattern/contour.hpp"
#include "vgd/studio/harness.hpp"
#include "vgd/xvc/arrangement.hpp"
#include "vgd/xvc/commands.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/seams.hpp"
#include "vgd/xvc/style.hpp"
#include "vgd/xvc/validate.hpp"

#ifdef VGD_STUDIO_TEST_WINDOW
#include <GLFW/glfw3.h>
#endif

namespace fs = std::filesystem;
using vgd::studio::Harness;

// Where the tests' studio draws: off-screen (vgd_test_studio), or, built with
// VGD_STUDIO_TEST_WINDOW (vgd_test_studio_window, run on Xvfb by
// window_tests.sh), in a GLFW window of its own per test, the same tests
// against the same goldens.
#ifdef VGD_STUDIO_TEST_WINDOW
namespace {
struct TestWindow {
  GLFWwindow* window = nullptr;
  TestWindow(int width, int height) {
    if (!glfwInit()) throw std::runtime_error("no X display for the studio's window (run under xvfb-run)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    window = glfwCreateWindow(width, height, "vgd studio test", nullptr, nullptr);
    if (!window) throw std::runtime_error("cannot open an OpenGL 3.3 window");
    glfwMakeContextCurrent(window);
    glfwSwapInterval(0);
  }
  ~TestWindow() { glfwDestroyWindow(window); }
  vgd::studio::HarnessWindow spec() const {
    vgd::studio::HarnessWindow w;
    w.loader = reinterpret_cast<vgd::studio::GlLoader>(glfwGetProcAddress);
    w.make_current = [win = window] { glfwMakeContextCurrent(win); };
    w.present = [win = window] {
      glfwSwapBuffers(win);
      glfwPollEvents();
    };
    return w;
  }
};
// The window first (a base made before the harness, gone after it).
class TestHarness : private TestWindow, public Harness {
 public:
  explicit TestHarness(int width = 1280, int height = 800)
      : TestWindow(width, height), Harness(spec(), width, height) {}
};
}  // namespace
#else
using TestHarness = Harness;
#endif

namespace {

const fs::path kSource = VGD_SOURCE_DIR;
// The project's garments, opened from this test process's own copies: a test
// that edits one and drapes leaves an autosave beside it, which a test running
// at the same time would otherwise be offered to recover.
struct Copies {
  fs::path root = fs::temp_directory_path() / ("vgd-test-studio-data-" + std::to_string(::getpid()));
  Copies() {
    fs::create_directories(root / "data/garments");
    for (const char* f : {"t-shirt.xvc", "a-line-skirt.xvc"})
      fs::copy_file(kSource / "data/garments" / f, root / "data/garments" / f, fs::copy_options::overwrite_existing);
  }
  ~Copies() {
    std::error_code ec;
    fs::remove_all(root, ec);
  }
};
const Copies kCopies;
const fs::path kTShirt = kCopies.root / "data/garments/t-shirt.xvc";
const fs::path kSkirt = kCopies.root / "data/garments/a-line-skirt.xvc";

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("vgd-test-studio-" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// The PATTERN id of a piece in a size.
std::string pattern_id(const vgd::xvc::Document& doc, const std::string& piece, const std::string& size) {
  for (const auto* p : doc.patterns())
    if (p->attribute("piece") == piece && p->attribute("size") == size) return std::string(p->id());
  return {};
}

std::string stretch_id(const vgd::xvc::Document& doc, const std::string& pattern, std::size_t k) {
  return vgd::xvc::boundary_stretches(*doc.find(pattern)).at(k).id;
}

// Pixels of a region that differ from the region's most common colour.
double non_background_fraction(const vgd::render::Image& img, const vgd::studio::Rect& r) {
  std::map<std::uint32_t, int> counts;
  int total = 0, other = 0;
  auto key = [](const std::uint8_t* p) { return (p[0] << 16) | (p[1] << 8) | p[2]; };
  for (int y = static_cast<int>(r.y0); y < static_cast<int>(r.y1); ++y)
    for (int x = static_cast<int>(r.x0); x < static_cast<int>(r.x1); ++x) ++counts[key(img.pixel(x, y))], ++total;
  std::uint32_t bg = 0;
  int most = 0;
  for (const auto& [k, n] : counts)
    if (n > most) most = n, bg = k;
  for (const auto& [k, n] : counts)
    if (k != bg) other += n;
  return total ? static_cast<double>(other) / total : 0.0;
}

vgd::render::Image crop(const vgd::render::Image& img, const vgd::studio::Rect& r) {
  const int x0 = static_cast<int>(r.x0), y0 = static_cast<int>(r.y0);
  vgd::render::Image out(static_cast<int>(r.x1) - x0, static_cast<int>(r.y1) - y0);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) std::copy_n(img.pixel(x0 + x, y0 + y), 4, out.pixel(x, y));
  return out;
}

}  // namespace

TEST(Studio, OpensADocumentAndShowsItsTreeAndTheSampleSizesPieces) {
  TestHarness h;
  ASSERT_TRUE(h.studio().open(kTShirt)) << h.studio().status();
  h.frame();
  const auto& doc = h.studio().document();
  EXPECT_NE(h.studio().status().find(std::to_string(doc.patterns().size()) + " patterns"), std::string::npos);
  EXPECT_TRUE(h.studio().widget("tree:garment"));
  // Every stretch of every size-38 piece is on screen to pick, and no other size's.
  int shown = 0;
  for (const auto* p : doc.patterns())
    for (const auto& st : vgd::xvc::boundary_stretches(*p)) {
      const bool on = h.studio().stretch_on_screen(p->id(), st.id).has_value();
      EXPECT_EQ(on, p->attribute("size") == "38") << p->id() << " " << st.id;
      shown += on;
    }
  EXPECT_GT(shown, 8);
  EXPECT_EQ(h.studio().drape_options().size, "38");
}

TEST(Studio, TheQualityPresetChosenInItsComboReachesTheDrapesScene) {
  TestHarness h;
  ASSERT_TRUE(h.studio().open(kSkirt));
  h.frame();
  auto& o = h.studio().drape_options();
  EXPECT_EQ(o.quality, vgd::scene::Quality::standard);
  for (const auto& [name, q] : std::vector<std::pair<std::string, vgd::scene::Quality>>{
           {"precise", vgd::scene::Quality::precise},
           {"preview", vgd::scene::Quality::preview},
           {"standard", vgd::scene::Quality::standard}}) {
    h.click("quality");
    h.click("quality:" + name);
    EXPECT_EQ(o.quality, q) << name;
    // Every preset keeps self-collision, as vgd drape does.
    EXPECT_TRUE(o.self_collision) << name;
    vgd::dress::DrapeOptions d = o;
    d.garment = kSkirt;
    const auto def = vgd::dress::drape_scene(d);
    ASSERT_TRUE(def.integrator.preset);
    EXPECT_EQ(*def.integrator.preset, q) << name;
  }
  // The fabric combo: a shipped fabric reaches the drape's scene; "garment's"
  // gives the document's own back.
  h.click("fabric");
  h.click("fabric:denim");
  EXPECT_EQ(o.material_xvc.filename(), "denim.xvc");
  {
    vgd::dress::DrapeOptions d = o;
    d.garment = kSkirt;
    const auto def = vgd::dress::drape_scene(d);
    ASSERT_TRUE(def.materials.count("fabric"));
    EXPECT_EQ(def.materials.at("fabric").xvc.filename(), "denim.xvc");
    EXPECT_EQ(def.materials.at("fabric").id, "denim");
  }
  h.click("fabric");
  h.click("fabric:garment's");
  EXPECT_TRUE(o.material_xvc.empty());
  // Unticking self-collision by hand outlasts a preset change.
  h.click("self-collision");
  EXPECT_FALSE(o.self_collision);
  h.click("quality");
  h.click("quality:preview");
  h.click("quality");
  h.click("quality:precise");
  EXPECT_FALSE(o.self_collision);
}

// Sleeves first (vgd drape --sleeves-first) ticked in the simulate panel
// reaches the drape's scene; unticked, the seams sew all at once again.
TEST(Studio, SleevesFirstTickedReachesTheDrapesScene) {
  TestHarness h;
  ASSERT_TRUE(h.studio().open(kTShirt));
  h.frame();
  auto& o = h.studio().drape_options();
  EXPECT_FALSE(o.sleeves_first);
  for (const bool on : {true, false}) {
    h.click("sleeves first");
    EXPECT_EQ(o.sleeves_first, on);
    vgd::dress::DrapeOptions d = o;
    d.garment = kTShirt;
    const auto def = vgd::dress::drape_scene(d);
    ASSERT_TRUE(def.effects.seams);
    EXPECT_EQ(def.effects.seams->sleeves_first, on);
  }
}

TEST(Studio, TwoPickedStretchesBecomeASeamThatUndoAndRedoTakeBackAndForth) {
  TestHarness h;
  ASSERT_TRUE(h.studio().open(kTShirt));
  h.frame();
  const auto& doc = h.studio().document();
  const std::string front = pattern_id(doc, "FRONT", "38"), back = pattern_id(doc, "BACK", "38");
  ASSERT_FALSE(front.empty());
  ASSERT_FALSE(back.empty());
  const std::string a = stretch_id(doc, front, 0), b = stretch_id(doc, back, 0);
  const std::size_t seams_before = vgd::xvc::list_seams(doc).size();

  for (const auto& [pat, seq] : {std::pair{front, a}, std::pair{back, b}}) {
    const auto r = h.studio().stretch_on_screen(pat, seq);
    ASSERT_TRUE(r) << pat << " " << seq;
    h.click_at(r->cx(), r->cy());
  }
  ASSERT_EQ(h.studio().picked().size(), 2u);
  EXPECT_EQ(h.studio().picked()[0], (std::pair{front, a}));
  EXPECT_EQ(h.studio().picked()[1], (std::pair{back, b}));
  h.click("Add seam");
  auto seams = vgd::xvc::list_seams(h.studio().document());
  ASSERT_EQ(seams.size(), seams_before + 1) << h.studio().status();
  const auto& added = seams.back();
  ASSERT_EQ(added.hems.size(), 2u);
  EXPECT_EQ(added.hems[0].pattern, front);
  EXPECT_EQ(added.hems[0].from, a);
  EXPECT_FALSE(added.hems[0].reverse);
  EXPECT_EQ(added.hems[1].pattern, back);
  EXPECT_EQ(added.hems[1].to, b);
  EXPECT_TRUE(added.hems[1].reverse);
  EXPECT_TRUE(h.studio().picked().empty());
  EXPECT_TRUE(h.studio().modified());

  h.key("ctrl+z");
  EXPECT_EQ(vgd::xvc::list_seams(h.studio().document()).size(), seams_before);
  EXPECT_FALSE(h.studio().modified());
  h.key("ctrl+y");
  EXPECT_EQ(vgd::xvc::list_seams(h.studio().document()).size(), seams_before + 1);
}

TEST(Studio, ThePatternViewZoomsAboutTheMouseAndPans) {
  TestHarness h;
  ASSERT_TRUE(h.studio().open(kTShirt));
  h.frame();
  const auto& doc = h.studio().document();
  const std::string front = pattern_id(doc, "FRONT", "38"), back = pattern_id(doc, "BACK", "38");
  const auto a0 = *h.studio().stretch_on_screen(front, stretch_id(doc, front, 0));
  const auto b0 = *h.studio().stretch_on_screen(back, stretch_id(doc, back, 0));
  // Two notches of the wheel at A: A stays put, B moves 1.2² times as far from it.
  h.scroll(a0.cx(), a0.cy(), 2);
  const auto a1 = *h.studio().stretch_on_screen(front, stretch_id(doc, front, 0));
  const auto b1 = *h.studio().stretch_on_screen(back, stretch_id(doc, back, 0));
  EXPECT_NEAR(a1.cx(), a0.cx(), 0.5);
  EXPECT_NEAR(a1.cy(), a0.cy(), 0.5);
  EXPECT_NEAR(b1.cx() - a1.cx(), 1.44 * (b0.cx() - a0.cx()), 1.0);
  EXPECT_NEAR(b1.cy() - a1.cy(), 1.44 * (b0.cy() - a0.cy()), 1.0);
  // The zoomed view still picks what is under the mouse.
  h.click_at(a1.cx(), a1.cy());
  ASSERT_EQ(h.studio().picked().size(), 1u);
  EXPECT_EQ(h.studio().picked()[0].first, front);
}

TEST(Studio, AnAttributeEditedInTheInspectorIsOneUndoableCommand) {
  TestHarness h;
  ASSERT_TRUE(h.studio().open(kTShirt));
  h.frame();
  const std::string seam = vgd::xvc::list_seams(h.studio().document()).front().id;
  const std::string old_name(h.studio().document().find(seam)->attribute("name"));
  h.click("tree:" + seam);
  EXPECT_EQ(h.studio().selected(), seam);
  // Its size (the first seam sews size 34's pieces) comes into the pattern view.
  const auto hem = vgd::xvc::list_seams(h.studio().document()).front().hems.front();
  EXPECT_EQ(h.studio().drape_options().size, h.studio().document().find(hem.pattern)->attribute("size"));
  EXPECT_NE(h.studio().drape_options().size, "38");
  h.click("attr:name");
  h.key("ctrl+a");
  h.type("front hem to back hem");
  h.key("enter");
  EXPECT_EQ(h.studio().document().find(seam)->attribute("name"), "front hem to back hem") << h.studio().status();
  h.key("ctrl+z");
  EXPECT_EQ(h.studio().document().find(seam)->attribute("name"), old_name);
  // Delete (key) removes the selected element; undo brings it back.
  h.click("tree:" + seam);
  h.key("delete");
  EXPECT_EQ(h.studio().document().find(seam), nullptr);
  h.key("ctrl+z");
  EXPECT_NE(h.studio().document().find(seam), nullptr);
}

TEST(Studio, TheOpenDialogTakesATypedPathAndABadFileKeepsTheOpenDocument) {
  const fs::path dir = temp_dir("open");
  TestHarness h;
  h.frame();
  h.click("File");
  h.click("Open...");
  h.key("ctrl+a");
  h.type(kSkirt.string());
  h.key("enter");
  EXPECT_EQ(h.studio().file(), kSkirt) << h.studio().status();
  const std::size_t patterns = h.studio().document().patterns().size();
  ASSERT_GT(patterns, 0u);

  const fs::path bad = dir / "broken.xvc";
  std::ofstream(bad) << "<GARMENT version=\"1.0\"><PATTERNS><PATTERN id=\"p1\"";
  EXPECT_FALSE(h.studio().open(bad));
  EXPECT_TRUE(h.studio().status_is_error());
  EXPECT_NE(h.studio().status().find("broken.xvc"), std::string::npos) << h.studio().status();
  EXPECT_EQ(h.studio().file(), kSkirt);
  EXPECT_EQ(h.studio().document().patterns().size(), patterns);
  h.frames(2);
  ASSERT_TRUE(h.studio().widget("error:ok")) << "the error is shown in a dialog";
  h.click("error:ok");
  h.frame();
  EXPECT_FALSE(h.studio().widget("error:ok"));
}

TEST(Studio, UnsavedChangesAreNotLostToOpenOrClose) {
  TestHarness h;
  ASSERT_TRUE(h.studio().open(kTShirt));
  h.frame();
  const std::string seam = vgd::xvc::list_seams(h.studio().document()).front().id;
  h.click("tree:" + seam);
  h.key("delete");
  ASSERT_TRUE(h.studio().modified());
  // Opening another document asks first and keeps the edited one until answered.
  EXPECT_FALSE(h.studio().open(kSkirt));
  h.frames(2);
  EXPECT_EQ(h.studio().file(), kTShirt);
  EXPECT_EQ(h.studio().document().find(seam), nullptr) << "the edit is still there";
  h.click("unsaved:cancel");
  EXPECT_EQ(h.studio().file(), kTShirt);
  EXPECT_TRUE(h.studio().modified());
  // Closing asks too; Discard lets it close.
  EXPECT_FALSE(h.studio().request_close());
  h.frames(2);
  EXPECT_FALSE(h.studio().quit_confirmed());
  h.click("unsaved:discard");
  EXPECT_TRUE(h.studio().quit_confirmed());
  // Open, answered with Discard, opens.
  EXPECT_FALSE(h.studio().open(kSkirt));
  h.frames(2);
  h.click("unsaved:discard");
  EXPECT_EQ(h.studio().file(), kSkirt);
  EXPECT_FALSE(h.studio().modified());
}

TEST(Studio, SavingWritesTheEditedDocumentAndClearsTheModifiedMark) {
  const fs::path dir = temp_dir("save");
  TestHarness h;
  ASSERT_TRUE(h.studio().open(kSkirt));
  h.frame();
  h.click("Suggest seams");
  h.frames(2);
  h.click("suggestions:add");
  // The skirt has its seams already: suggestions add them a second time, one undo step.
  const std::size_t seams = vgd::xvc::list_seams(h.studio().document()).size();
  ASSERT_TRUE(h.studio().modified()) << h.studio().status();
  const fs::path out = dir / "skirt-edited.xvc";
  ASSERT_TRUE(h.studio().save(out)) << h.studio().status();
  EXPECT_FALSE(h.studio().modified());
  EXPECT_EQ(h.studio().file(), out);
  const auto reread = vgd::xvc::load_file(out);
  EXPECT_EQ(vgd::xvc::list_seams(reread).size(), seams);
  EXPECT_TRUE(reread == h.studio().document());
  // A save that cannot happen says so and keeps the file name.
  std::ofstream(dir / "a-file") << "not a folder";
  EXPECT_FALSE(h.studio().save(dir / "a-file" / "x.xvc"));
  EXPECT_TRUE(h.studio().status_is_error());
  EXPECT_EQ(h.studio().file(), out);
}

TEST(Studio, DrapesTheSkirtFromTheDrapeButtonAndShowsItOnTheBody) {
  omp_set_num_threads(1);  // the studio drapes with the UI thread's count; ctest runs tests side by side
  TestHarness h(1024, 700);
  ASSERT_TRUE(h.studio().open(kSkirt));
  h.frame();
  auto& o = h.studio().drape_options();
  o.time_limit = 4.0;
  o.spacing = 0.02;  // a coarse mesh (rests in about 2 s): the test is about the studio, not the drape
  h.click("quality");
  h.click("quality:preview");
  const auto preview = h.studio().widget("preview");
  EXPECT_FALSE(preview) << "no picture before the first drape";
  h.click("Drape");
  h.studio().wait_for_drape();
  h.frames(4);
  const auto s = h.studio().drape_status();
  EXPECT_EQ(s.stage, "done") << s.message;
  ASSERT_TRUE(h.studio().certificate());
  const auto& c = *h.studio().certificate();
  int pairs = 0, closed = 0;
  for (const auto& st : c.seams) pairs += st.pairs, closed += st.closed;
  EXPECT_GT(pairs, 0);
  EXPECT_EQ(closed, pairs);
  EXPECT_LT(c.max_penetration, 0.001);
  // The preview shows the body and the skirt: a picture, not a blank panel.
  const auto r = h.studio().widget("preview");
  ASSERT_TRUE(r);
  const auto img = h.screenshot();
  EXPECT_GT(non_background_fraction(img, *r), 0.1);
  // The skirt's blue (render::kFabric family) is in the picture.
  int blue = 0;
  for (int y = static_cast<int>(r->y0); y < static_cast<int>(r->y1); ++y)
    for (int x = static_cast<int>(r->x0); x < static_cast<int>(r->x1); ++x) {
      const auto* p = img.pixel(x, y);
      blue += p[2] > p[0] + 40 && p[2] > p[1] + 20;
    }
  EXPECT_GT(blue, 500);
  EXPECT_NE(h.studio().status().find("rest"), std::string::npos) << h.studio().status();
  // File > Export VRML... writes the drape for a web catalogue.
  const fs::path wrl = temp_dir("export") / "skirt.wrl";
  h.click("File");
  h.click("Export VRML...");
  h.key("ctrl+a");
  h.type(wrl.string());
  h.key("enter");
  ASSERT_TRUE(fs::exists(wrl)) << h.studio().status();
  std::ifstream in(wrl);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.rfind("#VRML V2.0 utf8", 0), 0u);
  for (const char* piece : {"FRONT", "BACK", "WAISTBAND"}) EXPECT_NE(text.find(piece), std::string::npos) << piece;
  EXPECT_GE(std::count(text.begin(), text.end(), '\n'), 1000);
  // Dragging the picture turns the view.
  h.drag(r->cx(), r->cy(), r->cx() + 120, r->cy());
  h.frames(2);
  EXPECT_LT(vgd::qa::ssim(crop(img, *r), crop(h.screenshot(), *r)), 0.9);
  // The map combo: the weft strain's fit map with its legend (the bar's red
  // top, which the skirt itself, blue and little strained, does not have).
  auto reds = [&](const vgd::render::Image& shot) {
    const auto rr = h.studio().widget("preview");
    int n = 0;
    for (int y = static_cast<int>(rr->y0); y < static_cast<int>(rr->y1); ++y)
      for (int x = static_cast<int>(rr->x0); x < static_cast<int>(rr->x1); ++x) {
        const auto* p = shot.pixel(x, y);
        n += p[0] > 180 && p[1] < 90 && p[2] < 80;
      }
    return n;
  };
  const int before = reds(h.screenshot());
  h.click("map");
  h.click("map:weft strain");
  h.frames(4);
  const auto mapped = h.screenshot();
  EXPECT_GT(reds(mapped), before + 40) << "the legend's red end";
  EXPECT_LT(vgd::qa::ssim(crop(h.screenshot(), *h.studio().widget("preview")), crop(img, *r)), 0.95);
  // The contact-pressure map: the finished drape's pressures on the body
  // (its certificate's), a picture of its own, no word of a missing drape.
  ASSERT_EQ(c.contact.particle_pressure.size(), static_cast<std::size_t>(c.particles));
  h.click("map");
  h.click("map:contact pressure");
  h.frames(4);
  EXPECT_EQ(h.studio().status().find("contact-pressure map shows"), std::string::npos) << h.studio().status();
  EXPECT_LT(vgd::qa::ssim(crop(h.screenshot(), *h.studio().widget("preview")), crop(mapped, *h.studio().widget("preview"))),
            0.99);
}

// Frames drawn until `done` (a drape's progress), polled for up to 5 minutes
// of wall time (a sanitizer build places and sews many times slower).
bool frames_until(Harness& h, const std::function<bool()>& done) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (!done() && std::chrono::steady_clock::now() < deadline) {
    h.frame();
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return done();
}

// Opens `file` and starts a quick drape of it (2 cm mesh, 4 s at most).
void start_quick_drape(Harness& h, const fs::path& file) {
  ASSERT_TRUE(h.studio().open(file));
  h.frame();
  auto& o = h.studio().drape_options();
  o.time_limit = 4.0;
  o.spacing = 0.02;
  h.click("Drape");
}

// The preview draws the document's looks as vgd render and the VRML export
// do: the skirt with data/textures/gingham.png (4 cm a repeat) associated
// to every piece comes out red and white, none of it in the pieces' own
// colours (the untextured skirt's blue, above).
TEST(Studio, ThePreviewDrawsTheDocumentsTexture) {
  omp_set_num_threads(1);
  const fs::path dir = temp_dir("textured");
  vgd::test::write_textured_skirt(dir / "skirt.xvc");
  TestHarness h(1024, 700);
  start_quick_drape(h, dir / "skirt.xvc");
  h.studio().wait_for_drape();
  h.frames(4);
  ASSERT_EQ(h.studio().drape_status().stage, "done") << h.studio().drape_status().message;
  const auto r = h.studio().widget("preview");
  ASSERT_TRUE(r);
  const auto img = h.screenshot();
  int red = 0, blue = 0;
  for (int y = static_cast<int>(r->y0); y < static_cast<int>(r->y1); ++y)
    for (int c = static_cast<int>(r->x0); c < static_cast<int>(r->x1); ++c) {
      const auto* p = img.pixel(c, y);
      red += p[0] > p[1] + 70 && p[0] > p[2] + 60;
      blue += p[2] > p[0] + 40 && p[2] > p[1] + 20;
    }
  EXPECT_TRUE(h.studio().view_in_window_context()) << "drawn in the UI's context, not through OSMesa";
  EXPECT_GT(red, 500) << "the gingham's red";
  EXPECT_LT(blue, 50) << "no piece in its own colour";
  EXPECT_EQ(h.studio().status().find("Textures left out"), std::string::npos) << h.studio().status();
}

// A drape run here can be held and run on frame by frame: Pause holds it
// after its current frame (the simulated time stands still, the run goes on
// existing), Step runs exactly one frame more (1/25 s), Resume lets it run
// to rest.
TEST(Studio, ADrapeCanBePausedAndSteppedFrameByFrame) {
  omp_set_num_threads(1);
  TestHarness h(1024, 700);
  start_quick_drape(h, kSkirt);
  const auto wait_until = [&](const std::function<bool()>& done) { return frames_until(h, done); };
  ASSERT_TRUE(wait_until([&] { return h.studio().drape_status().t > 0.0; })) << "the drape never reached a frame";
  h.click("Pause");
  ASSERT_TRUE(h.studio().drape_status().paused);
  // The run finishes the frame it is in, then holds.
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  h.frames(2);
  const double held = h.studio().drape_status().t;
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  h.frames(2);
  EXPECT_EQ(h.studio().drape_status().t, held);
  EXPECT_TRUE(h.studio().drape_status().running);
  EXPECT_NE(h.studio().status().find("Paused"), std::string::npos) << h.studio().status();
  h.click("Step");
  ASSERT_TRUE(wait_until([&] { return h.studio().drape_status().t > held; }));
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  h.frames(2);
  EXPECT_NEAR(h.studio().drape_status().t - held, 1.0 / 25.0, 1e-9) << "one frame, and only one";
  EXPECT_TRUE(h.studio().drape_status().paused);
  h.click("Resume");
  h.studio().wait_for_drape();
  h.frames(2);
  EXPECT_EQ(h.studio().drape_status().stage, "done") << h.studio().drape_status().message;
  EXPECT_FALSE(h.studio().drape_status().paused);
}

namespace {
// The T-shirt opened and Arrange pressed: its FRONT 38's id ("" when it
// did not come to arranging) and the document as opened.
std::pair<std::string, vgd::xvc::Document> arrange_the_tshirt(Harness& h) {
  if (!h.studio().open(kTShirt)) return {};
  h.frame();
  const std::string front = pattern_id(h.studio().document(), "FRONT", "38");
  const auto original = h.studio().document();
  h.click("Arrange");
  h.frames(2);
  if (front.empty() || !h.studio().arranging()) return {};
  return {front, original};
}
}  // namespace

// Arranging in 3-D: Arrange shows where the drape starts, with the body's
// arrangement points. The T-shirt's front dragged from the pattern view onto
// "hips front" hangs from the waist (its POSITION says so, its top at the
// waist in the view); dragged up 30 px in the 3-D view it follows the mouse
// up the hips by 30 px on screen; each one undo step; a drape ends arranging.
TEST(Studio, APieceIsArrangedOnTheBodyByDraggingIt) {
  TestHarness h;
  const auto [front, original] = arrange_the_tshirt(h);
  ASSERT_FALSE(front.empty()) << h.studio().status();
  const auto top_of = [](const std::vector<std::array<float, 3>>& ps) {
    float y = -1e30f;
    for (const auto& p : ps) y = std::max(y, p[1]);
    return y;
  };
  const auto on_torso = h.studio().arranged_piece(front);
  ASSERT_FALSE(on_torso.empty());
  const double waist = vgd::dress::arrangement_options(vgd::body::make_mannequin(vgd::body::find_size("38"))).waist_height;
  EXPECT_GT(top_of(on_torso), waist + 0.3) << "the front starts on the torso";

  const auto from = h.studio().piece_on_screen(front);
  const auto to = h.studio().arrangement_point_on_screen("hips front");
  ASSERT_TRUE(from && to);
  h.drag(from->cx(), from->cy(), to->cx(), to->cy());
  h.frames(2);
  const auto placed = vgd::xvc::arrangements_of(*h.studio().document().find(front));
  ASSERT_EQ(placed.size(), 1u) << h.studio().status();
  EXPECT_EQ(placed[0].segment, "hips");
  EXPECT_EQ(placed[0].side, "front");
  EXPECT_NEAR(placed[0].height, waist, 1e-9);
  const auto on_hips = h.studio().arranged_piece(front);
  ASSERT_EQ(on_hips.size(), on_torso.size());
  EXPECT_NEAR(top_of(on_hips), waist, 0.01) << "its top hangs at the waist";
  EXPECT_NE(h.studio().status().find("FRONT put on the hips front"), std::string::npos) << h.studio().status();

  const auto at = h.studio().arranged_piece_on_screen(front);
  ASSERT_TRUE(at.has_value());
  h.drag(at->cx(), at->cy(), at->cx(), at->cy() - 30);
  h.frames(2);
  const auto lifted = vgd::xvc::arrangements_of(*h.studio().document().find(front));
  ASSERT_EQ(lifted.size(), 1u);
  EXPECT_GT(lifted[0].height, waist + 0.02) << h.studio().status();
  const auto now = h.studio().arranged_piece_on_screen(front);
  ASSERT_TRUE(now.has_value());
  EXPECT_NEAR(now->cy(), at->cy() - 30, 3) << "the piece follows the mouse up";
  EXPECT_NEAR(now->cx(), at->cx(), 3);
  EXPECT_NEAR(top_of(h.studio().arranged_piece(front)) - top_of(on_hips), lifted[0].height - waist, 0.005);

  h.key("ctrl+z");
  h.key("ctrl+z");
  h.frame();
  EXPECT_TRUE(h.studio().document() == original);
  h.click("Drape");
  EXPECT_FALSE(h.studio().arranging());
  h.click("Stop");
  h.studio().wait_for_drape();
}

// Shift+drag turns an arranged piece round the body: the T-shirt's front
// dragged 40 px to the right (about a quarter of the way round the torso on
// screen; the body's left, +x, is to the right seen from the front) goes to
// the torso's left side, and the piece laid out there shows right of where
// it was; Alt+drag 40 px further right moves it off the body (its
// clearance grows, its side stays); each an undo step, undone both.
TEST(Studio, AnArrangedPieceIsTurnedRoundTheBodyAndMovedOffIt) {
  TestHarness h;
  const auto [front, original] = arrange_the_tshirt(h);
  ASSERT_FALSE(front.empty()) << h.studio().status();
  const auto at = h.studio().arranged_piece_on_screen(front);
  ASSERT_TRUE(at.has_value());
  const auto before = vgd::xvc::arrangements_of(*h.studio().document().find(front));
  ASSERT_EQ(before.size(), 1u);
  EXPECT_EQ(before[0].side, "front");

  h.drag(at->cx(), at->cy(), at->cx() + 40, at->cy(), 8, /*shift=*/true);
  h.frames(2);
  const auto turned = vgd::xvc::arrangements_of(*h.studio().document().find(front));
  ASSERT_EQ(turned.size(), 1u);
  EXPECT_EQ(turned[0].side, "left") << h.studio().status();
  EXPECT_EQ(turned[0].segment, "torso");
  EXPECT_DOUBLE_EQ(turned[0].height, before[0].height);
  EXPECT_NE(h.studio().status().find("turned round the torso from its front to its left"), std::string::npos)
      << h.studio().status();
  const auto now = h.studio().arranged_piece_on_screen(front);
  ASSERT_TRUE(now.has_value());
  EXPECT_GT(now->cx(), at->cx() + 20) << "laid out on the body's left, right of the front on screen";

  h.drag(now->cx(), now->cy(), now->cx() + 40, now->cy(), 8, false, /*alt=*/true);
  h.frames(2);
  const auto off = vgd::xvc::arrangements_of(*h.studio().document().find(front));
  ASSERT_EQ(off.size(), 1u);
  EXPECT_EQ(off[0].side, "left");
  EXPECT_GT(off[0].clearance, turned[0].clearance + 0.05) << h.studio().status();
  EXPECT_LE(off[0].clearance, vgd::dress::kMaxClearance);
  EXPECT_NE(h.studio().status().find("moved off the body"), std::string::npos) << h.studio().status();

  h.key("ctrl+z");
  h.key("ctrl+z");
  h.frame();
  EXPECT_TRUE(h.studio().document() == original);

  // A shorter drag turns it part of the way: still on the front, turned
  // towards the left by what the mouse went round (around), and shown there.
  const auto start = h.studio().arranged_piece_on_screen(front);
  ASSERT_TRUE(start.has_value());
  h.drag(start->cx(), start->cy(), start->cx() + 15, start->cy(), 8, /*shift=*/true);
  h.frames(2);
  const auto part = vgd::xvc::arrangements_of(*h.studio().document().find(front));
  ASSERT_EQ(part.size(), 1u);
  EXPECT_EQ(part[0].side, "front") << h.studio().status();
  EXPECT_GT(part[0].around_deg, 5.0) << h.studio().status();
  EXPECT_LT(part[0].around_deg, 45.0);
  EXPECT_NE(h.studio().status().find("from its front to its front turned"), std::string::npos) << h.studio().status();
  const auto shown = h.studio().arranged_piece_on_screen(front);
  ASSERT_TRUE(shown.has_value());
  EXPECT_GT(shown->cx(), start->cx() + 5);
  h.key("ctrl+z");
  h.frame();
  EXPECT_TRUE(h.studio().document() == original);
}

// Pins in the document while arranging: an Alt+click on the arranged front
// (a click, not a drag: the clearance stays) adds a POSITION type="pin" at
// the point of the pattern the click took, inside the front's outline; the
// drape then holds that particle where it is arranged. An Alt+click on the
// pin removes it; each is one undo step.
TEST(Studio, ADocumentPinIsAddedAndRemovedWhileArranging) {
  TestHarness h;
  const auto [front, original] = arrange_the_tshirt(h);
  ASSERT_FALSE(front.empty()) << h.studio().status();
  const auto at = h.studio().arranged_piece_on_screen(front);
  ASSERT_TRUE(at.has_value());
  const auto clearance = vgd::xvc::arrangements_of(*h.studio().document().find(front)).at(0).clearance;

  h.click_at(at->cx(), at->cy(), false, /*alt=*/true);
  h.frames(2);
  const auto pins = vgd::xvc::pins_of(*h.studio().document().find(front));
  ASSERT_EQ(pins.size(), 1u) << h.studio().status();
  EXPECT_NE(h.studio().status().find("pinned at"), std::string::npos) << h.studio().status();
  const auto outline = vgd::xvc::to_piece(h.studio().document(), front).boundary;
  EXPECT_TRUE(vgd::pattern::point_in_outline(outline, {pins[0].x, pins[0].y}));
  EXPECT_DOUBLE_EQ(vgd::xvc::arrangements_of(*h.studio().document().find(front)).at(0).clearance, clearance)
      << "a click is not a move off the body";
  ASSERT_TRUE(h.studio().arranging()) << h.studio().status();

  h.click_at(at->cx(), at->cy(), false, /*alt=*/true);
  h.frames(2);
  EXPECT_TRUE(vgd::xvc::pins_of(*h.studio().document().find(front)).empty()) << h.studio().status();
  EXPECT_NE(h.studio().status().find("removed"), std::string::npos) << h.studio().status();

  h.key("ctrl+z");
  h.frame();
  EXPECT_EQ(vgd::xvc::pins_of(*h.studio().document().find(front)).size(), 1u);
  h.key("ctrl+z");
  h.frame();
  EXPECT_TRUE(h.studio().document() == original);
}

// Pulling the cloth by hand: Ctrl+press on the skirt's front hem in the 3-D
// view while it drapes takes hold of a particle there; the mouse moved 60 px
// to the right and held for half a second of simulated time drags that
// particle more than 5 cm, towards the mouse on screen (more than 10 px to
// the right, more than it goes up or down: the skirt settling by itself
// moves down, not sideways); let go, nothing is held.
TEST(Studio, TheClothIsPulledByHandDuringADrape) {
  omp_set_num_threads(1);
  TestHarness h(1024, 700);
  auto& o = h.studio().drape_options();
  ASSERT_TRUE(h.studio().open(kSkirt));
  h.frame();
  o.time_limit = 6.0;
  o.spacing = 0.02;
  h.click("Drape");
  const auto wait_until = [&](const std::function<bool()>& done) { return frames_until(h, done); };
  ASSERT_TRUE(wait_until([&] {
    return h.studio().drape_status().t > 1.5 && h.studio().particle_on_screen(0).has_value();
  })) << "the drape never showed its cloth";
  // The front hem: of the particles within 5 cm of the lowest, the one facing the view (35° round).
  const auto x = h.studio().cloth_positions();
  float low = 1e9f;
  for (const auto& q : x) low = std::min(low, q[1]);
  int pick = -1;
  double facing = -1e9;
  const double az = 35.0 * M_PI / 180.0;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (x[i][1] < low + 0.05 && x[i][0] * std::sin(az) + x[i][2] * std::cos(az) > facing)
      facing = x[i][0] * std::sin(az) + x[i][2] * std::cos(az), pick = static_cast<int>(i);
  ASSERT_GE(pick, 0);
  const auto at = h.studio().particle_on_screen(pick);
  ASSERT_TRUE(at.has_value());
  h.press(at->cx(), at->cy(), true);
  const auto held = h.studio().held_particle();
  ASSERT_TRUE(held.has_value()) << h.studio().status();
  EXPECT_NE(h.studio().status().find("Pulling the cloth"), std::string::npos) << h.studio().status();
  const auto before = h.studio().cloth_positions()[static_cast<std::size_t>(*held)];
  const auto seen = *h.studio().particle_on_screen(*held);
  for (int k = 1; k <= 6; ++k) h.move_mouse(at->cx() + 10.0f * k, at->cy());
  const double t0 = h.studio().drape_status().t;
  ASSERT_TRUE(wait_until([&] { return h.studio().drape_status().t > t0 + 0.5; }));
  h.frames(20);  // the preview redrawn with the newest frame
  const auto after = h.studio().cloth_positions()[static_cast<std::size_t>(*held)];
  const double moved = std::hypot(after[0] - before[0], after[1] - before[1], after[2] - before[2]);
  EXPECT_GT(moved, 0.05) << "pulled " << moved << " m";
  const auto now = h.studio().particle_on_screen(*held);
  ASSERT_TRUE(now.has_value());
  const float dx = now->cx() - seen.cx(), dy = now->cy() - seen.cy();
  EXPECT_GT(dx, 10.0f) << "to the right on screen";
  EXPECT_LT(std::abs(dy), dx) << "more across than up or down: " << dx << ", " << dy << " px";
  EXPECT_EQ(h.studio().held_particle(), held);
  h.release();
  EXPECT_FALSE(h.studio().held_particle().has_value());
  EXPECT_NE(h.studio().status().find("Let go of the cloth"), std::string::npos) << h.studio().status();
  h.click("Stop");
  h.studio().wait_for_drape();
}

// Pins while the skirt drapes: Alt+click on the cloth pins the particle
// nearest the eye under the mouse, Alt+click again unpins it; Alt+Shift+click
// freezes its whole piece, which then holds still (90 % of its particles
// within 1 mm of where it was frozen over 0.5 s simulated, 98 % within 3 mm:
// its seam edges still merge with the other pieces; 0.5 mm and 1.3 mm
// measured) while the rest of the skirt goes on sewing and falling (3-5 cm); Alt+Shift+click frees it, "Unpin all"
// lets every pin go.
TEST(Studio, TheClothIsPinnedAndAPieceFrozenDuringADrape) {
  omp_set_num_threads(1);
  TestHarness h(1024, 700);
  auto& o = h.studio().drape_options();
  ASSERT_TRUE(h.studio().open(kSkirt));
  h.frame();
  o.time_limit = 6.0;
  o.spacing = 0.02;
  h.click("Drape");
  ASSERT_TRUE(frames_until(h, [&] { return h.studio().drape_status().t > 0.1 && h.studio().particle_on_screen(0).has_value(); }))
      << "the drape never showed its cloth";
  h.click("Pause");
  h.frames(4);
  // A particle in the middle of the picture's cloth: the one drawn nearest the middle of the view.
  const auto x = h.studio().cloth_positions();
  const auto r = h.studio().widget("preview");
  ASSERT_TRUE(r.has_value());
  int pick = -1;
  float best = 1e9f;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (const auto q = h.studio().particle_on_screen(static_cast<int>(i)))
      if (const float d = std::hypot(q->cx() - r->cx(), q->cy() - (r->y0 + 0.45f * (r->y1 - r->y0))); d < best)
        best = d, pick = static_cast<int>(i);
  ASSERT_GE(pick, 0);
  const auto at = *h.studio().particle_on_screen(pick);
  h.click_at(at.cx(), at.cy(), false, true);
  ASSERT_EQ(h.studio().pins().size(), 1u) << h.studio().status();
  EXPECT_NE(h.studio().status().find("pinned where it is"), std::string::npos) << h.studio().status();
  h.click_at(at.cx(), at.cy(), false, true);
  EXPECT_TRUE(h.studio().pins().empty()) << h.studio().status();

  h.click_at(at.cx(), at.cy(), true, true);
  const auto frozen = h.studio().pins();
  ASSERT_GT(frozen.size(), 100u) << h.studio().status();
  EXPECT_NE(h.studio().status().find("frozen where it is"), std::string::npos) << h.studio().status();
  const auto before = h.studio().cloth_positions();
  h.click("Resume");
  const double t0 = h.studio().drape_status().t;
  ASSERT_TRUE(frames_until(h, [&] { return h.studio().drape_status().t > t0 + 0.5; }));
  h.click("Pause");
  h.frames(20);  // the preview redrawn with the newest frame
  const auto after = h.studio().cloth_positions();
  // Where each frozen particle is against where it was frozen; the others against where they were.
  std::vector<double> off;
  std::vector<bool> is_frozen(after.size(), false);
  for (const auto& p : frozen) {
    const auto& q = after[static_cast<std::size_t>(p.particle)];
    off.push_back(std::hypot(q[0] - p.at.x(), q[1] - p.at.y(), q[2] - p.at.z()));
    is_frozen[static_cast<std::size_t>(p.particle)] = true;
  }
  std::sort(off.begin(), off.end());
  EXPECT_LT(off[off.size() * 9 / 10], 0.001) << "the frozen piece holds still";
  EXPECT_LT(off[off.size() * 98 / 100], 0.003) << "its seam edges give a little (merges meet the other pieces)";
  double others_max = 0;
  for (std::size_t i = 0; i < after.size(); ++i)
    if (!is_frozen[i])
      others_max = std::max(others_max, static_cast<double>(std::hypot(after[i][0] - before[i][0], after[i][1] - before[i][1],
                                                                       after[i][2] - before[i][2])));
  EXPECT_GT(others_max, 0.02) << "the rest moved meanwhile";
  h.click_at(at.cx(), at.cy(), true, true);
  EXPECT_TRUE(h.studio().pins().empty()) << h.studio().status();
  EXPECT_NE(h.studio().status().find("freed"), std::string::npos) << h.studio().status();
  h.click_at(at.cx(), at.cy(), false, true);
  ASSERT_EQ(h.studio().pins().size(), 1u);
  h.click("Unpin all");
  EXPECT_TRUE(h.studio().pins().empty());
  h.click("Stop");
  h.studio().wait_for_drape();
}

// The desktop's file dialog (zenity's command line) for File > Open...,
// Save as... and Export VRML...: a stand-in program records its arguments
// and answers as zenity does. A chosen path is opened or saved to; exit 1
// cancels with a word in the status bar; a program that cannot be run falls
// back to the typed path, saying why.
TEST(Studio, FileDialogsAskTheDesktopsDialogProgram) {
  const fs::path dir = temp_dir("file-dialog");
  const fs::path args = dir / "args.txt", answer = dir / "answer.txt", code = dir / "code.txt";
  const fs::path program = dir / "fake-zenity";
  vgd::write_file_atomic(program,
                         "#!/bin/sh\nprintf '%s\\n' \"$@\" > '" + args.string() + "'\necho 'GTK warning' >&2\n"
                         "cat '" + answer.string() + "'\nexit $(cat '" + code.string() + "')\n");
  fs::permissions(program, fs::perms::owner_all);
  fs::copy_file(kSkirt, dir / "skirt.xvc", fs::copy_options::overwrite_existing);
  TestHarness h(1024, 700);
  h.studio().set_file_dialog_program(program);
  const auto ask = [&](const char* item, const fs::path& chosen, int exit_code) {
    vgd::write_file_atomic(answer, chosen.empty() ? std::string() : chosen.string() + "\n");
    vgd::write_file_atomic(code, std::to_string(exit_code) + "\n");
    h.click("File");
    h.click(item);
    h.frames(2);
  };
  ask("Open...", dir / "skirt.xvc", 0);
  EXPECT_EQ(h.studio().file(), dir / "skirt.xvc") << h.studio().status();
  const std::string open_args = vgd::read_file(args);
  EXPECT_NE(open_args.find("--file-selection"), std::string::npos) << open_args;
  EXPECT_NE(open_args.find("--file-filter=Documents and patterns (XVC, DXF) | *.xvc *.XVC *.dxf *.DXF"),
            std::string::npos) << open_args;
  EXPECT_EQ(open_args.find("--save"), std::string::npos) << open_args;
  EXPECT_FALSE(h.studio().widget("dialog:path")) << "no typed-path dialog";
  ask("Save as...", dir / "copy.xvc", 0);
  EXPECT_TRUE(fs::exists(dir / "copy.xvc")) << h.studio().status();
  EXPECT_EQ(h.studio().file(), dir / "copy.xvc");
  const std::string save_args = vgd::read_file(args);
  EXPECT_NE(save_args.find("--save"), std::string::npos) << save_args;
  EXPECT_NE(save_args.find("--confirm-overwrite"), std::string::npos) << save_args;
  EXPECT_NE(save_args.find("--filename=" + (dir / "skirt.xvc").string()), std::string::npos) << "starts at the file" << save_args;
  ask("Open...", dir / "skirt.xvc", 1);
  EXPECT_EQ(h.studio().file(), dir / "copy.xvc") << "cancelled: nothing opened";
  EXPECT_NE(h.studio().status().find("cancelled"), std::string::npos) << h.studio().status();
  h.studio().set_file_dialog_program(dir / "no-such-program");
  ask("Open...", {}, 0);
  EXPECT_NE(h.studio().status().find("could not be run"), std::string::npos) << h.studio().status();
  // The typed-path dialog instead.
  h.key("ctrl+a");
  h.type((dir / "skirt.xvc").string());
  h.key("enter");
  EXPECT_EQ(h.studio().file(), dir / "skirt.xvc") << h.studio().status();
}

// A document with no seams (a pattern file imported as it is) drapes as vgd
// dress drapes it (dress/prepare.hpp): seams suggested for the drape, said
// in the status bar and in preparation(); the studio's document keeps none.
TEST(Studio, ADocumentWithoutSeamsIsPreparedAsVgdDressPreparesIt) {
  omp_set_num_threads(1);
  namespace xvc = vgd::xvc;
  xvc::Document d = xvc::load_file(kSkirt);
  for (const auto& s : xvc::list_seams(d)) xvc::execute(d, *std::make_unique<xvc::DeleteNode>(s.id));
  ASSERT_TRUE(xvc::list_seams(d).empty());
  const fs::path file = temp_dir("unsewn") / "skirt.xvc";
  xvc::save_file(d, file);
  TestHarness h(1024, 700);
  start_quick_drape(h, file);
  EXPECT_NE(h.studio().status().find("seams suggested (not in the document)"), std::string::npos) << h.studio().status();
  h.studio().wait_for_drape();
  h.frames(4);
  EXPECT_EQ(h.studio().drape_status().stage, "done") << h.studio().drape_status().message;
  ASSERT_TRUE(h.studio().certificate());
  int pairs = 0, closed = 0;
  for (const auto& st : h.studio().certificate()->seams) pairs += st.pairs, closed += st.closed;
  EXPECT_GT(pairs, 100);
  EXPECT_EQ(closed, pairs);
  bool said = false;
  for (const auto& line : h.studio().preparation()) said = said || line.find("suggested at size") != std::string::npos;
  EXPECT_TRUE(said);
}

// The body row: a body file typed in, its unit and up axis forced in the
// combos, reaches the drape; the importer's decisions are shown; a unit that
// makes no human of it fails the drape with the file named.
TEST(Studio, DrapesOnABodyFileWithTheUnitAndUpChosenInItsRow) {
  omp_set_num_threads(1);
  const fs::path dir = temp_dir("body");
  // The size-38 mannequin as Blender stores it: centimetres, Z up, front -Y.
  const auto m = vgd::body::make_mannequin(vgd::body::find_size("38"));  // the mannequin a drape of size 38 gets
  const fs::path body = dir / "blender.obj";
  {
    std::ofstream out(body);
    for (const auto& v : m.surface.vertices) out << "v " << 100 * v.x() << ' ' << -100 * v.z() << ' ' << 100 * v.y() << '\n';
    for (const auto& t : m.surface.triangles) out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  }
  TestHarness h(1024, 700);
  ASSERT_TRUE(h.studio().open(kSkirt));
  h.frame();
  auto& o = h.studio().drape_options();
  o.time_limit = 6.0;
  o.spacing = 0.02;  // a coarse mesh, at the standard preset (self-collision on)
  EXPECT_FALSE(o.avatar) << "the mannequin until a body is given";
  h.click("body");
  h.type(body.string());
  h.frames(2);
  ASSERT_TRUE(o.avatar);
  EXPECT_EQ(o.avatar->file, body);
  EXPECT_EQ(o.avatar->unit, "auto");
  h.click("unit");
  h.click("unit:cm");
  h.click("up");
  h.click("up:z");
  EXPECT_EQ(o.avatar->unit, "cm");
  EXPECT_EQ(o.avatar->up, "z");
  EXPECT_EQ(o.avatar->facing, "auto");
  h.click("Drape");
  h.studio().wait_for_drape();
  h.frames(4);
  const auto s = h.studio().drape_status();
  EXPECT_EQ(s.stage, "done") << s.message;
  const auto has = [&](const std::string& note) {
    return std::find(s.body_notes.begin(), s.body_notes.end(), note) != s.body_notes.end();
  };
  EXPECT_TRUE(has("unit cm (given)")) << ::testing::PrintToString(s.body_notes);
  EXPECT_TRUE(has("up z (given)")) << ::testing::PrintToString(s.body_notes);
  EXPECT_TRUE(has("facing +z (the feet point +z)")) << ::testing::PrintToString(s.body_notes);
  ASSERT_TRUE(h.studio().certificate());
  const auto& c = *h.studio().certificate();
  int pairs = 0, closed = 0;
  for (const auto& st : c.seams) pairs += st.pairs, closed += st.closed;
  EXPECT_EQ(closed, pairs) << c.stop_reason << " after " << c.simulated_s;
  EXPECT_LT(c.max_penetration, 0.001);
  // Millimetres make a 1.7 cm body: the drape fails and says why, naming the file.
  h.click("unit");
  h.click("unit:mm");
  h.click("Drape");
  h.studio().wait_for_drape();
  h.frames(2);
  EXPECT_EQ(h.studio().drape_status().stage, "failed");
  EXPECT_TRUE(h.studio().status_is_error());
  EXPECT_NE(h.studio().status().find("blender.obj"), std::string::npos) << h.studio().status();
  EXPECT_NE(h.studio().status().find("not a human body"), std::string::npos) << h.studio().status();
}

TEST(Studio, StopEndsARunningDrape) {
  TestHarness h;
  ASSERT_TRUE(h.studio().open(kSkirt));
  h.frame();
  h.studio().drape_options().time_limit = 60;
  h.click("Drape");
  ASSERT_TRUE(h.studio().drape_status().running);
  h.click("Stop");
  h.studio().wait_for_drape();
  h.frame();
  EXPECT_EQ(h.studio().drape_status().stage, "stopped");
  EXPECT_NE(h.studio().status().find("stopped"), std::string::npos) << h.studio().status();
}

TEST(Studio, ScriptsNameTheLineThatFailed) {
  const fs::path dir = temp_dir("script");
  std::ofstream(dir / "s.txt") << "# a comment\nopen " << kTShirt.string() << "\nclick No such button\n";
  TestHarness h;
  try {
    h.run_script(dir / "s.txt");
    FAIL() << "the script should fail";
  } catch (const vgd::Error& e) {
    EXPECT_EQ(e.diagnostic().line, 3);
    EXPECT_NE(std::string(e.what()).find("No such button"), std::string::npos) << e.what();
  }
}

// QA's snapshot of the studio: the first frame with the T-shirt open.
// VGD_UPDATE_GOLDENS=1 rewrites it (tests/golden/regenerate.sh).
TEST(Studio, TheFirstFrameWithTheTShirtMatchesItsGolden) {
  const fs::path golden = kSource / "tests/golden/studio/t-shirt.png";
  // Opened by a relative path: the status bar says the path it was opened
  // by, which would otherwise differ between machines.
  const fs::path cwd = fs::current_path();
  fs::current_path(kCopies.root);
  TestHarness h;
  const bool opened = h.studio().open("data/garments/t-shirt.xvc");
  h.frames(3);
  fs::current_path(cwd);
  ASSERT_TRUE(opened);
  const auto img = h.screenshot();
  if (std::getenv("VGD_UPDATE_GOLDENS")) {
    fs::create_directories(golden.parent_path());
    vgd::render::write_png(img, golden);
  }
  const auto ref = vgd::render::read_png(golden);
  ASSERT_EQ(ref.width, img.width);
  ASSERT_EQ(ref.height, img.height);
  EXPECT_GT(vgd::qa::colour_ssim(ref, img), 0.99);
  EXPECT_LT(vgd::qa::pixel_stats(ref, img).differing_percent, 1.0);
}

// Never lose work: the studio killed (SIGKILL) after an edit it never saved
// leaves the edit in FILE.autosave; opening the file again offers it, and
// Recover brings it back as unsaved changes; Discard deletes it.
TEST(Studio, AnEditSurvivesTheStudioKilledAndIsOfferedForRecovery) {
  const fs::path dir = temp_dir("recovery");
  const fs::path doc = dir / "skirt.xvc";
  fs::copy_file(kSkirt, doc);
  const std::string seam = vgd::xvc::list_seams(vgd::xvc::load_file(doc)).front().id;
  {
    std::ofstream script(dir / "edit.txt");
    script << "open skirt.xvc\nclick tree:" << seam << "\nclick attr:name\nkey ctrl+a\ntype kept after the crash\n"
           << "key enter\nframes 1000000\n";
  }
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::execl(VGD_STUDIO_EXE, VGD_STUDIO_EXE, "--headless", "--autosave-seconds", "0", "--script",
            (dir / "edit.txt").c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ASSERT_GT(pid, 0);
  const fs::path autosave = dir / "skirt.xvc.autosave";
  for (int i = 0; i < 600 && !fs::exists(autosave); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the studio was still running when killed";
  ASSERT_TRUE(fs::exists(autosave)) << "no autosave written";
  const std::string on_disk = vgd::read_file(doc);
  EXPECT_EQ(on_disk.find("kept after the crash"), std::string::npos) << "the edit was never saved";
  EXPECT_NE(vgd::read_file(autosave).find("kept after the crash"), std::string::npos);
  {
    TestHarness h;
    ASSERT_TRUE(h.studio().open(doc));
    EXPECT_TRUE(h.studio().recovery_offered());
    EXPECT_NE(h.studio().status().find("unsaved changes from"), std::string::npos) << h.studio().status();
    h.frames(2);
    h.click("recover:yes");
    EXPECT_FALSE(h.studio().recovery_offered());
    EXPECT_EQ(h.studio().document().find(seam)->attribute("name"), "kept after the crash");
    EXPECT_TRUE(h.studio().modified());
    ASSERT_TRUE(h.studio().save());
    EXPECT_FALSE(fs::exists(autosave)) << "saved: nothing left to recover";
  }
  EXPECT_NE(vgd::read_file(doc).find("kept after the crash"), std::string::npos);
  // An autosave discarded: deleted, the document as saved.
  auto d = vgd::xvc::load_file(doc);
  vgd::xvc::execute(d, *std::make_unique<vgd::xvc::SetAttribute>(seam, "name", "never wanted"));
  vgd::xvc::save_file(d, autosave);
  {
    TestHarness h;  // closed with the question unanswered: the autosave stays
    ASSERT_TRUE(h.studio().open(doc));
    EXPECT_TRUE(h.studio().recovery_offered());
  }
  ASSERT_TRUE(fs::exists(autosave));
  {
    TestHarness h;
    ASSERT_TRUE(h.studio().open(doc));
    h.frames(2);
    h.click("recover:no");
    EXPECT_FALSE(fs::exists(autosave));
    EXPECT_EQ(h.studio().document().find(seam)->attribute("name"), "kept after the crash");
    EXPECT_FALSE(h.studio().modified());
  }
  // A normal close leaves no autosave, even of changes it was told to discard.
  {
    TestHarness h;
    h.studio().set_autosave_seconds(0);
    ASSERT_TRUE(h.studio().open(doc));
    h.frame();
    h.click("tree:" + seam);
    h.click("attr:name");
    h.key("ctrl+a");
    h.type("changed then discarded");
    h.key("enter");
    h.frames(2);
    EXPECT_TRUE(fs::exists(autosave));
  }
  EXPECT_FALSE(fs::exists(autosave));
}

// A designer's DXF opened in the studio: the import dialog (units, unfold,
// join per side, sew lines), then the report; the document is unsaved and
// named beside the DXF without overwriting anything. CLO's T-shirt, written
// as 9 blocks with its halves per side, comes in as 5 pieces.
TEST(Studio, ADxfOpensThroughTheImportDialogWithItsReport) {
  const fs::path shared = fs::path(VGD_SHARED_DIR) / "data" / "dxf" / "clo-pattern.dxf";
  if (!fs::exists(shared)) GTEST_SKIP() << "shared data absent: " << shared;
  const fs::path dir = temp_dir("import-dxf");
  const fs::path dxf = dir / "clo-pattern.dxf";
  fs::copy_file(shared, dxf);
  std::ofstream(dir / "clo-pattern.xvc") << "<!-- the designer's own file, not to be overwritten -->\n";
  TestHarness h;
  ASSERT_TRUE(h.studio().open(dxf)) << h.studio().status();
  h.frames(2);
  h.click("import:ok");
  h.frames(2);
  ASSERT_FALSE(h.studio().import_report().empty()) << h.studio().status();
  std::string report;
  for (const auto& l : h.studio().import_report()) report += l + "\n";
  EXPECT_NE(report.find("clo-pattern.dxf: "), std::string::npos) << report;
  EXPECT_NE(report.find("joined"), std::string::npos) << report;
  EXPECT_NE(report.find("clo-pattern-2.xvc"), std::string::npos) << report;
  EXPECT_EQ(h.studio().file().filename(), "clo-pattern-2.xvc");
  EXPECT_TRUE(h.studio().modified());
  std::set<std::string> pieces;
  for (const auto* p : h.studio().document().patterns()) pieces.insert(std::string(p->attribute("piece")));
  EXPECT_EQ(pieces.size(), 5u) << report;
  h.click("imported:ok");
  ASSERT_TRUE(h.studio().save());
  EXPECT_TRUE(fs::exists(dir / "clo-pattern-2.xvc"));
  EXPECT_NE(vgd::read_file(dir / "clo-pattern.xvc").find("not to be overwritten"), std::string::npos);
  EXPECT_EQ(vgd::xvc::load_file(dir / "clo-pattern-2.xvc").patterns().size(), h.studio().document().patterns().size());
  // Without joining: the 9 blocks as written.
  h.studio().open(dxf, /*discard_changes=*/true);
  h.frames(2);
  h.click("import:join");
  h.click("import:ok");
  h.frames(2);
  pieces.clear();
  for (const auto* p : h.studio().document().patterns()) pieces.insert(std::string(p->attribute("piece")));
  EXPECT_EQ(pieces.size(), 9u);
  // A file that is not a DXF: the error names it, the document stays.
  std::ofstream(dir / "broken.dxf") << "this is not a DXF\n";
  h.click("imported:ok");
  h.studio().open(dir / "broken.dxf", true);
  h.frames(2);
  h.click("import:ok");
  h.frames(2);
  EXPECT_TRUE(h.studio().status_is_error());
  EXPECT_NE(h.studio().status().find("broken.dxf"), std::string::npos) << h.studio().status();
  std::set<std::string> kept;
  for (const auto* p : h.studio().document().patterns()) kept.insert(std::string(p->attribute("piece")));
  EXPECT_EQ(kept, pieces) << "the document that was open stays";
}

// A top smaller round the bust than the body it goes on, as vgd dress
// prepares it: Gerber's tank with bindings in size 50 (113 cm on the women's
// 50, 118 cm) is cut from the shipped knit, said in the preparation's list;
// in a woven chosen in the studio it is warned, in the status line too, when
// the drape starts. Size 40 (2 cm of ease) is neither.
TEST(Studio, ATopTooSmallForItsBodyIsCutInAKnitOrWarnedWhenTheDrapeStarts) {
  const fs::path shared = fs::path(VGD_SHARED_DIR) / "data" / "dxf" / "simple.DXF";
  if (!fs::exists(shared)) GTEST_SKIP() << "shared data absent: " << shared;
  const fs::path dir = temp_dir("too-small");
  fs::copy_file(shared, dir / "tank.dxf");
  TestHarness h;
  ASSERT_TRUE(h.studio().open(dir / "tank.dxf")) << h.studio().status();
  h.frames(2);
  h.click("import:ok");
  h.frames(2);
  h.click("imported:ok");
  struct Case {
    std::string size, material;
  };
  const std::string woven = (kSource / "data" / "materials" / "shirting.xvc").string();
  for (const Case& c : {Case{"40", ""}, Case{"50", ""}, Case{"50", woven}}) {
    SCOPED_TRACE(c.size + " " + c.material);
    h.studio().drape_options().size = c.size;
    h.studio().drape_options().material_xvc = c.material;
    h.studio().drape_options().time_limit = 60;
    h.click("Drape");
    ASSERT_TRUE(h.studio().drape_status().running) << h.studio().status();
    const std::string status = h.studio().status();
    std::string warned, knit;
    for (const auto& line : h.studio().preparation()) {
      if (line.rfind("warning: ", 0) == 0) warned += line + "\n";
      if (line.rfind("fabric: the shipped knit", 0) == 0) knit += line + "\n";
    }
    h.click("Stop");
    h.studio().wait_for_drape();
    h.frame();
    const bool small = c.size == "50", in_woven = !c.material.empty();
    EXPECT_EQ(status.find("the garment is too small for the body") != std::string::npos, small && in_woven) << status;
    EXPECT_EQ(warned.find("the pattern's bust girth is 113 cm, 5 cm less than the body's 118 cm (women's 50)") !=
                  std::string::npos,
              small && in_woven)
        << warned;
    EXPECT_EQ(knit.find("the pattern's bust girth is 113 cm, 5 cm less than the body's 118 cm") != std::string::npos,
              small && !in_woven)
        << knit;
  }
}

// The studio's drape takes vgd dress's second try: a drape that failed only
// where the cloth is caught in the crease between an arm and the torso is
// draped again holding the touching cloth once sewn, and the status says so.
// The project's T-shirt stopped at 1.2 s (before it rests, at 1.48 s) still
// moves only between its right arm and the torso: such a failure, found in
// seconds. That the second drape then passes, on a real garment that fails
// there at its time limit, is RealGarmentsHoldContacts.ATeesArmpitFailureIsDrapedAgainHeld
// (the same library calls: dress::caught_at_armpit, then dress::run_drape held).
TEST(Studio, ADrapeFailedOnlyAtAnArmpitIsDrapedAgainHeld) {
  omp_set_num_threads(1);  // the studio drapes with the UI thread's count; ctest runs tests side by side
  TestHarness h;
  ASSERT_TRUE(h.studio().open(kTShirt)) << h.studio().status();
  h.frame();
  h.studio().drape_options().time_limit = 1.2;
  h.click("Drape");
  h.studio().wait_for_drape();
  h.frame();
  const std::string message = h.studio().drape_status().message;
  EXPECT_NE(message.find("draped again, the touching cloth held once sewn: the first drape failed only where the "
                         "cloth is caught in the crease between the "),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("right-arm"), std::string::npos) << message;
  ASSERT_TRUE(h.studio().certificate().has_value()) << message;
  const vgd::dress::Certificate& c = *h.studio().certificate();
  bool held = false;
  for (const auto& [k, v] : c.settings) held = held || (k == "hold_contacts" && v == "once sewn");
  EXPECT_TRUE(held) << message;
  EXPECT_EQ(c.stop_reason, "time limit") << message;
}

// File > Open Recent: the documents opened or saved, newest first, kept in
// the store the host gives and read back by the next studio.
TEST(Studio, RecentFilesAreKeptAndReopenFromTheMenu) {
  const fs::path dir = temp_dir("recent");
  const fs::path store = dir / "recent-files";
  {
    TestHarness h;
    h.studio().set_recent_store(store);
    EXPECT_TRUE(h.studio().recent_files().empty());
    ASSERT_TRUE(h.studio().open(kSkirt));
    ASSERT_TRUE(h.studio().open(kTShirt));
    ASSERT_TRUE(h.studio().open(kSkirt));
    ASSERT_EQ(h.studio().recent_files().size(), 2u) << "each file once";
    EXPECT_EQ(h.studio().recent_files()[0], fs::absolute(kSkirt));
    EXPECT_EQ(h.studio().recent_files()[1], fs::absolute(kTShirt));
  }
  EXPECT_EQ(vgd::read_file(store), fs::absolute(kSkirt).string() + "\n" + fs::absolute(kTShirt).string() + "\n");
  TestHarness h;
  h.studio().set_recent_store(store);
  ASSERT_EQ(h.studio().recent_files().size(), 2u);
  h.frame();
  h.click("File");
  h.click("Open Recent");
  h.click("recent:2");
  EXPECT_EQ(h.studio().file(), fs::absolute(kTShirt)) << h.studio().status();
  EXPECT_EQ(h.studio().recent_files()[0], fs::absolute(kTShirt));
}

// Suggested seams are reviewed one by one: the dialog lists each with its
// pieces, ease and score; the ticked ones are added as one undoable step,
// Cancel adds none.
TEST(Studio, SuggestedSeamsAreAcceptedOrRejectedOneByOne) {
  TestHarness h;
  ASSERT_TRUE(h.studio().open(kSkirt));
  h.frame();
  const std::size_t before = vgd::xvc::list_seams(h.studio().document()).size();
  vgd::xvc::SeamOptions o;
  o.size = h.studio().drape_options().size;
  const auto expected = vgd::xvc::suggest_seams(h.studio().document(), o);
  ASSERT_GE(expected.size(), 3u);
  h.click("Suggest seams");
  h.frames(2);
  ASSERT_TRUE(h.studio().widget("suggestion:" + std::to_string(expected.size())));
  EXPECT_FALSE(h.studio().widget("suggestion:" + std::to_string(expected.size() + 1)));
  // Untick the first and the last.
  h.click("suggestion:1");
  h.click("suggestion:" + std::to_string(expected.size()));
  h.click("suggestions:add");
  const auto after = vgd::xvc::list_seams(h.studio().document());
  ASSERT_EQ(after.size(), before + expected.size() - 2);
  EXPECT_EQ(after.back().name, expected[expected.size() - 2].name);
  h.key("ctrl+z");
  EXPECT_EQ(vgd::xvc::list_seams(h.studio().document()).size(), before) << "one undo step";
  // Cancel adds nothing.
  h.click("Suggest seams");
  h.frames(2);
  h.click("suggestions:cancel");
  EXPECT_EQ(vgd::xvc::list_seams(h.studio().document()).size(), before);
  EXPECT_FALSE(h.studio().modified());
}

// A piece selected in the tree is duplicated (a piece of its own) or flipped
// about its grain line, each one undo step.
TEST(Studio, APieceIsDuplicatedAndFlippedFromTheInspector) {
  TestHarness h;
  ASSERT_TRUE(h.studio().open(kSkirt));
  h.frame();
  const std::string front = pattern_id(h.studio().document(), "FRONT", "38");
  ASSERT_FALSE(front.empty());
  const std::size_t before = h.studio().document().patterns().size();
  h.click("tree:" + front);
  h.click("Duplicate");
  ASSERT_EQ(h.studio().document().patterns().size(), before + 1) << h.studio().status();
  EXPECT_EQ(h.studio().document().find(h.studio().selected())->attribute("piece"), "FRONT copy");
  h.key("ctrl+z");
  EXPECT_EQ(h.studio().document().patterns().size(), before);
  const auto original = h.studio().document();
  h.click("tree:" + front);
  h.click("Flip");
  EXPECT_FALSE(h.studio().document() == original) << h.studio().status();
  EXPECT_NE(h.studio().status().find("Mirror"), std::string::npos) << h.studio().status();
  h.key("ctrl+z");
  EXPECT_TRUE(h.studio().document() == original) << "one undo step";
}

// A seam selected in the tree shows its pairing in the pattern view: lines
// from hem A's ends to hem B's ends and dots at their starts (purple), none
// when a piece is selected instead.
TEST(Studio, ASelectedSeamShowsItsPairingInThePatternView) {
  TestHarness h;
  ASSERT_TRUE(h.studio().open(kTShirt));
  h.frame();
  auto purple = [&] {
    const auto shot = h.screenshot();
    int n = 0;
    for (int y = 0; y < shot.height; ++y)
      for (int x = 0; x < shot.width; ++x) {
        const auto* p = shot.pixel(x, y);
        n += std::abs(p[0] - 150) < 12 && std::abs(p[1] - 60) < 12 && std::abs(p[2] - 200) < 12;
      }
    return n;
  };
  const std::string seam = vgd::xvc::list_seams(h.studio().document()).front().id;
  h.click("tree:" + seam);
  h.frames(2);
  EXPECT_GT(purple(), 40) << "the pairing's lines and dots";
  h.click("tree:" + pattern_id(h.studio().document(), "FRONT", "34"));
  h.frames(2);
  EXPECT_EQ(purple(), 0);
}


namespace {
// The outline point's coordinates in the document (m).
vgd::pattern::Vec2 outline_point(const vgd::xvc::Document& doc, const vgd::xvc::OutlinePoint& p) {
  const auto piece = vgd::xvc::to_piece(doc, p.pattern_id);
  for (const auto& st : vgd::xvc::boundary_stretches(*doc.find(p.pattern_id)))
    if (st.id == p.sequence_id) return piece.boundary.at(st.first + p.index).p;
  ADD_FAILURE() << "no stretch " << p.sequence_id;
  return {};
}
}  // namespace

// The skirt opened in `h`: its size-38 front's pattern id ("" when the
// skirt did not open) and outline stretches.
struct SkirtFront {
  std::string id;
  std::vector<vgd::xvc::Stretch> stretches;
};
// A click inside a piece, 40 px right of and below its middle (away from
// its grain line and outline points): whether it is then selected.
bool select_inside(Harness& h, const std::string& pattern) {
  const auto centre = h.studio().piece_on_screen(pattern);
  if (!centre) return false;
  h.click_at(centre->cx() + 40, centre->cy() + 40);
  h.frame();
  return h.studio().selected() == pattern;
}

SkirtFront open_skirt_front(Harness& h) {
  SkirtFront f;
  if (!h.studio().open(kSkirt)) return f;
  h.frame();
  f.id = pattern_id(h.studio().document(), "FRONT", "38");
  if (!f.id.empty()) f.stretches = vgd::xvc::boundary_stretches(*h.studio().document().find(f.id));
  return f;
}

// The measuring tool: Measure, then two clicks on outline points give their
// distance in the pattern, exactly (the points snap), said in the status bar;
// meanwhile clicks pick no stretch and move no point.
TEST(Studio, TheMeasuringToolGivesTheDistanceBetweenTwoOutlinePoints) {
  TestHarness h;
  const auto [front, stretches] = open_skirt_front(h);
  ASSERT_FALSE(front.empty()) << h.studio().status();
  ASSERT_GE(stretches.size(), 3u);
  const auto centre = h.studio().piece_on_screen(front);
  ASSERT_TRUE(centre.has_value());
  h.click_at(centre->cx(), centre->cy());  // selected: its points shown
  h.frame();
  const vgd::xvc::OutlinePoint a{front, stretches[0].id, 0}, b{front, stretches[2].id, 0};
  const auto sa = h.studio().point_on_screen(a), sb = h.studio().point_on_screen(b);
  ASSERT_TRUE(sa && sb);
  const auto original = h.studio().document();
  h.click("Measure");
  // Two pixels off each point: the points snap.
  h.click_at(sa->cx() + 2, sa->cy() - 1);
  h.click_at(sb->cx() - 1, sb->cy() + 2);
  ASSERT_TRUE(h.studio().measured().has_value()) << h.studio().status();
  const double expected = (outline_point(original, a) - outline_point(original, b)).norm();
  EXPECT_NEAR(*h.studio().measured(), expected, 1e-9);
  EXPECT_GT(expected, 0.05);
  EXPECT_NE(h.studio().status().find("Measured " + vgd::format_fixed(100 * expected, 2) + " cm"), std::string::npos)
      << h.studio().status();
  EXPECT_TRUE(h.studio().document() == original) << "nothing moved";
  EXPECT_TRUE(h.studio().picked().empty()) << "nothing picked";
  h.click("Measure");
  EXPECT_NE(h.studio().status().find("Measuring ended"), std::string::npos) << h.studio().status();
}

// Drawing in the pattern view. A line on the selected skirt front: two clicks
// 40 px apart, then Enter: the front gains an internal line 40 px / scale
// long, level, in the piece's own frame (inside it), as one undo step. A
// piece: three corners clicked beside the pieces, then the first again: a new
// pattern of the size shown with three stretches, undone in one step. A
// drawing dropped with Esc changes nothing.
TEST(Studio, ALineAndAPieceAreDrawnInThePatternView) {
  TestHarness h;
  const auto [front, stretches] = open_skirt_front(h);
  ASSERT_FALSE(front.empty()) << h.studio().status();
  const auto centre = h.studio().piece_on_screen(front);
  ASSERT_TRUE(centre.has_value());
  h.click_at(centre->cx(), centre->cy());
  h.frame();
  ASSERT_EQ(h.studio().selected(), front);
  const auto original = h.studio().document();
  const std::size_t lines = vgd::xvc::to_piece(original, front).internal_lines.size();
  const float scale = h.studio().pattern_scale();
  ASSERT_GT(scale, 0.0f);

  h.click("Draw line");
  h.click_at(centre->cx() - 20, centre->cy());
  h.click_at(centre->cx() + 20, centre->cy());
  h.key("enter");
  h.frame();
  const auto piece = vgd::xvc::to_piece(h.studio().document(), front);
  ASSERT_EQ(piece.internal_lines.size(), lines + 1) << h.studio().status();
  const auto& line = piece.internal_lines.back().points;
  ASSERT_EQ(line.size(), 2u);
  EXPECT_NEAR((line[1] - line[0]).norm(), 40.0 / scale, 1.5 / scale);
  EXPECT_NEAR(line[1].y(), line[0].y(), 1e-9) << "level";
  EXPECT_TRUE(vgd::pattern::point_in_outline(piece.boundary, 0.5 * (line[0] + line[1]))) << "in the piece's own frame";
  h.key("ctrl+z");
  h.frame();
  EXPECT_TRUE(h.studio().document() == original) << "one undo step";

  // Escape drops a drawing.
  h.click("Draw line");
  h.click_at(centre->cx(), centre->cy());
  h.key("escape");
  h.frame();
  EXPECT_TRUE(h.studio().document() == original);
  EXPECT_NE(h.studio().status().find("Drawing dropped"), std::string::npos) << "[" << h.studio().status() << "]";

  // A piece: corners to the right of the front, closed on the first.
  const std::size_t patterns = original.patterns().size();
  const float x = centre->x1 + 6, y = centre->cy();
  h.click("Draw piece");
  h.click_at(x, y);
  h.click_at(x + 30, y);
  h.click_at(x + 15, y - 30);
  h.click_at(x + 1, y);
  h.frame();
  const auto& drawn = h.studio().document();
  ASSERT_EQ(drawn.patterns().size(), patterns + 1) << h.studio().status();
  const vgd::xvc::Node* added = drawn.patterns().back();
  EXPECT_EQ(added->attribute("piece"), "drawn piece");
  EXPECT_EQ(added->attribute("size"), "38");
  EXPECT_EQ(vgd::xvc::boundary_stretches(*added).size(), 3u);
  const double area = std::abs(vgd::pattern::signed_area(vgd::xvc::to_piece(drawn, std::string(added->id())).boundary));
  EXPECT_NEAR(area, 0.5 * 30 * 30 / (scale * scale), 0.2 * 30 * 30 / (scale * scale));
  h.key("ctrl+z");
  h.frame();
  EXPECT_TRUE(h.studio().document() == original);

  // Curves: a Shift+click is a point the line or outline passes through
  // smoothly. A piece with two corners and a curve point 30 px above their
  // middle: two stretches, the top an arch through the point (more area
  // than the triangle, less than the box).
  h.click("Draw piece");
  h.click_at(x, y);
  h.click_at(x + 40, y);
  h.click_at(x + 20, y - 30, /*shift=*/true);
  h.click_at(x + 1, y);
  h.frame();
  ASSERT_EQ(h.studio().document().patterns().size(), patterns + 1) << h.studio().status();
  const vgd::xvc::Node* arch = h.studio().document().patterns().back();
  EXPECT_EQ(vgd::xvc::boundary_stretches(*arch).size(), 2u);
  const auto arch_piece = vgd::xvc::to_piece(h.studio().document(), std::string(arch->id()));
  EXPECT_GT(arch_piece.boundary.size(), 10u);
  double top = -1e9, bottom = 1e9;
  for (const auto& c : arch_piece.boundary) top = std::max(top, c.p.y()), bottom = std::min(bottom, c.p.y());
  EXPECT_NEAR(top - bottom, 30 / scale, 1.5 / scale) << "through the curve point";
  const double arch_area = std::abs(vgd::pattern::signed_area(arch_piece.boundary)) * scale * scale;  // px²
  EXPECT_GT(arch_area, 1.1 * 0.5 * 40 * 30);
  EXPECT_LT(arch_area, 40 * 30);
  h.key("ctrl+z");
  h.frame();
  // A line bent through a Shift+clicked point.
  h.click_at(centre->cx(), centre->cy());  // the front selected again (the drawn piece was)
  h.frame();
  ASSERT_EQ(h.studio().selected(), front);
  h.click("Draw line");
  h.click_at(centre->cx() - 20, centre->cy());
  h.click_at(centre->cx(), centre->cy() - 10, /*shift=*/true);
  h.click_at(centre->cx() + 20, centre->cy());
  h.key("enter");
  h.frame();
  const auto bent = vgd::xvc::to_piece(h.studio().document(), front).internal_lines;
  ASSERT_EQ(bent.size(), lines + 1) << h.studio().status();
  EXPECT_GT(bent.back().points.size(), 5u);
  double high = -1e9;
  for (const auto& q : bent.back().points) high = std::max(high, q.y());
  EXPECT_NEAR(high - bent.back().points.front().y(), 10 / scale, 1.5 / scale);
  h.key("ctrl+z");
  h.frame();
  EXPECT_TRUE(h.studio().document() == original);
}

// Notches in the pattern view: the selected piece's are grabbed by the
// inner end of their cut and dropped on the outline point nearest the
// mouse: the skirt front's first notch dragged onto the outline point two
// along from its vertex moves there (its vertex said), one undo step.
TEST(Studio, ANotchIsDraggedToAnotherOutlinePoint) {
  TestHarness h;
  const auto [front, stretches] = open_skirt_front(h);
  ASSERT_FALSE(front.empty()) << h.studio().status();
  const auto original = h.studio().document();
  const vgd::xvc::Node* notch = nullptr;
  for (const auto& c : original.find(front)->children)
    if (c.tag == "POSITION" && c.attribute("type") == "notch" && c.has_attribute("vertex") && !notch) notch = &c;
  ASSERT_NE(notch, nullptr);
  const std::string nid(notch->id());
  const std::size_t v0 = std::stoul(std::string(notch->attribute("vertex")));
  ASSERT_TRUE(select_inside(h, front)) << h.studio().status();
  // The outline point two along from the notch's vertex.
  const std::size_t n = vgd::xvc::to_piece(original, front).boundary.size();
  const std::size_t v1 = (v0 + 2) % n;
  std::optional<vgd::xvc::OutlinePoint> target;
  for (const auto& st : stretches)
    if (v1 >= st.first && v1 < st.first + st.count) target = vgd::xvc::OutlinePoint{front, st.id, v1 - st.first};
  ASSERT_TRUE(target.has_value());
  const auto from = h.studio().notch_on_screen(front, nid), to = h.studio().point_on_screen(*target);
  ASSERT_TRUE(from && to);
  h.drag(from->cx(), from->cy(), to->cx() + 2, to->cy() + 2);
  const vgd::xvc::Node* moved = h.studio().document().find(nid);
  ASSERT_NE(moved, nullptr);
  EXPECT_EQ(moved->attribute("vertex"), std::to_string(v1)) << h.studio().status();
  const auto p = outline_point(h.studio().document(), *target);
  EXPECT_EQ(moved->attribute("x"), vgd::format_double(p.x()));
  h.key("ctrl+z");
  h.frame();
  EXPECT_TRUE(h.studio().document() == original) << "one undo step";
}

// Ctrl+click on an outline point of the selected piece adds a notch there
// (cut into the piece, the document checked), Ctrl+click on a notch removes
// it; the piece stays selected; each one undo step.
TEST(Studio, ANotchIsAddedAndRemovedByCtrlClicks) {
  TestHarness h;
  const auto [front, stretches] = open_skirt_front(h);
  ASSERT_FALSE(front.empty()) << h.studio().status();
  const auto original = h.studio().document();
  const auto notches_of = [&](const vgd::xvc::Document& d) {
    std::map<std::string, std::string> out;  // vertex -> id
    for (const auto& c : d.find(front)->children)
      if (c.tag == "POSITION" && c.attribute("type") == "notch") out[std::string(c.attribute("vertex"))] = std::string(c.id());
    return out;
  };
  const auto before = notches_of(original);
  ASSERT_TRUE(select_inside(h, front)) << h.studio().status();
  // A vertex with no notch: the second point of the first stretch with three or more.
  std::optional<vgd::xvc::OutlinePoint> target;
  std::size_t vertex = 0;
  for (const auto& st : stretches)
    if (!target && st.count >= 3 && !before.count(std::to_string(st.first + 1)))
      target = vgd::xvc::OutlinePoint{front, st.id, 1}, vertex = st.first + 1;
  ASSERT_TRUE(target.has_value());
  const auto at = h.studio().point_on_screen(*target);
  ASSERT_TRUE(at.has_value());
  h.click_at(at->cx(), at->cy(), false, false, /*ctrl=*/true);
  h.frame();
  const auto added = notches_of(h.studio().document());
  ASSERT_EQ(added.size(), before.size() + 1) << h.studio().status();
  ASSERT_EQ(added.count(std::to_string(vertex)), 1u) << h.studio().status();
  const std::string nid = added.at(std::to_string(vertex));
  EXPECT_EQ(h.studio().selected(), front) << "the piece stays selected";
  const auto p = outline_point(h.studio().document(), *target);
  EXPECT_EQ(h.studio().document().find(nid)->attribute("x"), vgd::format_double(p.x())) << "on the point clicked";
  EXPECT_EQ(h.studio().document().find(nid)->attribute("y"), vgd::format_double(p.y()));
  EXPECT_FALSE(vgd::xvc::check(h.studio().document()).has_errors());

  const auto handle = h.studio().notch_on_screen(front, nid);
  ASSERT_TRUE(handle.has_value());
  h.click_at(handle->cx(), handle->cy(), false, false, /*ctrl=*/true);
  h.frame();
  EXPECT_EQ(notches_of(h.studio().document()), before) << h.studio().status();
  h.key("ctrl+z");
  h.frame();
  EXPECT_EQ(notches_of(h.studio().document()).size(), before.size() + 1);
  h.key("ctrl+z");
  h.frame();
  EXPECT_TRUE(h.studio().document() == original) << "one undo step each";
}

// Moving a piece in the pattern view: the skirt's front dragged by (40, 25) px
// from inside it is drawn 40 px right and 25 px lower, the others where they
// were; the document holds its sheet position (checked, validated, saved);
// undo puts it back; let go off the pattern view (nothing arranged there) it
// stays.
TEST(Studio, APieceIsMovedInThePatternView) {
  TestHarness h;
  const auto [front, stretches] = open_skirt_front(h);
  ASSERT_FALSE(front.empty()) << h.studio().status();
  const std::string back = pattern_id(h.studio().document(), "BACK", "38");
  const auto original = h.studio().document();
  const auto at = h.studio().piece_on_screen(front), back_at = h.studio().piece_on_screen(back);
  ASSERT_TRUE(at && back_at);
  h.drag(at->cx(), at->cy(), at->cx() + 40, at->cy() + 25);
  h.frame();
  const auto moved = h.studio().piece_on_screen(front), back_now = h.studio().piece_on_screen(back);
  ASSERT_TRUE(moved && back_now);
  EXPECT_NEAR(moved->cx(), at->cx() + 40, 0.5);
  EXPECT_NEAR(moved->cy(), at->cy() + 25, 0.5);
  EXPECT_NEAR(back_now->cx(), back_at->cx(), 0.5) << "the others stay";
  EXPECT_NEAR(back_now->cy(), back_at->cy(), 0.5);
  const auto sheet = vgd::xvc::sheet_position(*h.studio().document().find(front));
  ASSERT_TRUE(sheet.has_value()) << h.studio().status();
  EXPECT_NE(h.studio().status().find("FRONT moved on the sheet"), std::string::npos) << h.studio().status();
  {
    const auto a = vgd::xvc::to_piece(h.studio().document(), front).boundary, b = vgd::xvc::to_piece(original, front).boundary;
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k) EXPECT_EQ(a[k].p, b[k].p) << "the piece itself is unchanged";
  }
  const fs::path dir = temp_dir("sheet");
  vgd::xvc::save_file(h.studio().document(), dir / "moved.xvc");
  EXPECT_EQ(vgd::xvc::validate_file(dir / "moved.xvc", vgd::xvc::default_schema_path()).count(vgd::Severity::error), 0u);
  EXPECT_EQ(vgd::xvc::sheet_position(*vgd::xvc::load_file(dir / "moved.xvc").find(front)), sheet);
  h.key("ctrl+z");
  h.frame();
  EXPECT_TRUE(h.studio().document() == original);
  const auto back_home = h.studio().piece_on_screen(front);
  ASSERT_TRUE(back_home.has_value());
  EXPECT_NEAR(back_home->cx(), at->cx(), 0.5);
  // Let go over the 3-D view (not arranging): nothing moves.
  const auto preview = h.studio().widget("preview").value_or(vgd::studio::Rect{1000, 400, 1000, 400});
  h.drag(at->cx(), at->cy(), preview.cx(), preview.cy());
  h.frame();
  EXPECT_TRUE(h.studio().document() == original);
}

// The grain line in the pattern view: every piece's drawn, the selected
// piece's ends handles; the front's second end dragged 25 px right moves it
// 25 px / scale in the piece's frame (the first stays), one undo step.
TEST(Studio, AGrainLineIsTurnedByDraggingItsEnd) {
  TestHarness h;
  const auto [front, stretches] = open_skirt_front(h);
  ASSERT_FALSE(front.empty()) << h.studio().status();
  const auto original = h.studio().document();
  const auto g0 = vgd::xvc::to_piece(original, front).grain_line;
  ASSERT_TRUE(g0.has_value());
  ASSERT_TRUE(select_inside(h, front)) << h.studio().status();
  const auto end = h.studio().grain_end_on_screen(front, 1);
  ASSERT_TRUE(end.has_value());
  const float scale = h.studio().pattern_scale();
  h.drag(end->cx(), end->cy(), end->cx() + 25, end->cy());
  const auto g1 = vgd::xvc::to_piece(h.studio().document(), front).grain_line;
  ASSERT_TRUE(g1.has_value()) << h.studio().status();
  EXPECT_LT((g1->a - g0->a).norm(), 1e-12) << "the other end stays";
  EXPECT_NEAR(g1->b.x() - g0->b.x(), 25 / scale, 1e-6) << h.studio().status();
  EXPECT_NEAR(g1->b.y(), g0->b.y(), 1e-6);
  EXPECT_FALSE(vgd::xvc::sheet_position(*h.studio().document().find(front)).has_value()) << "the piece did not move";
  h.key("ctrl+z");
  h.frame();
  EXPECT_TRUE(h.studio().document() == original) << "one undo step";
}

// Outline editing in the pattern view: a click inside a piece selects it and
// shows its points; a point dragged by (30, -12) px moves by that much in the
// piece's frame (y up), as one undo step; a point clicked, a point inserted
// after it and deleted again; the piece rotated 90° about its middle, its
// grain line kept; the saved document validates and holds the edits.
TEST(Studio, AnOutlinePointIsDraggedInsertedAndDeletedAndAPieceRotated) {
  TestHarness h;
  const auto [front, stretches] = open_skirt_front(h);
  ASSERT_FALSE(front.empty()) << h.studio().status();
  ASSERT_GE(stretches.size(), 2u);
  const vgd::xvc::OutlinePoint p{front, stretches[1].id, 3};
  EXPECT_FALSE(h.studio().point_on_screen(p).has_value()) << "points show on the selected piece only";
  const auto centre = h.studio().piece_on_screen(front);
  ASSERT_TRUE(centre.has_value());
  h.click_at(centre->cx(), centre->cy());
  EXPECT_EQ(h.studio().selected(), front) << "a click inside the piece selects it";
  h.frame();
  const auto at = h.studio().point_on_screen(p);
  ASSERT_TRUE(at.has_value());
  const auto original = h.studio().document();
  const vgd::pattern::Vec2 before = outline_point(original, p);
  const float scale = h.studio().pattern_scale();
  h.drag(at->cx(), at->cy(), at->cx() + 30, at->cy() - 12);
  const vgd::pattern::Vec2 after = outline_point(h.studio().document(), p);
  EXPECT_NEAR(after.x() - before.x(), 30 / scale, 1e-6) << h.studio().status();
  EXPECT_NEAR(after.y() - before.y(), 12 / scale, 1e-6);
  ASSERT_TRUE(h.studio().selected_point().has_value());
  EXPECT_EQ(h.studio().selected_point()->index, 3u);
  // Every other point where it was.
  const auto pa = vgd::xvc::to_piece(original, front), pb = vgd::xvc::to_piece(h.studio().document(), front);
  ASSERT_EQ(pa.boundary.size(), pb.boundary.size());
  int moved = 0;
  for (std::size_t i = 0; i < pa.boundary.size(); ++i) moved += pa.boundary[i].p != pb.boundary[i].p;
  EXPECT_EQ(moved, 1);
  h.key("ctrl+z");
  EXPECT_TRUE(h.studio().document() == original) << "one undo step";

  // Insert after the selected point, then delete it (the Delete key).
  h.frame();
  h.click("Insert point");
  EXPECT_EQ(vgd::xvc::to_piece(h.studio().document(), front).boundary.size(), pa.boundary.size() + 1) << h.studio().status();
  EXPECT_EQ(h.studio().selected_point()->index, 4u) << "the new point is selected";
  h.key("delete");
  EXPECT_TRUE(h.studio().document() == original) << h.studio().status();
  EXPECT_EQ(h.studio().selected(), front) << "the piece stays selected";

  // A stretch's first point is not deleted: the status says why.
  const auto first = h.studio().point_on_screen({front, stretches[1].id, 0});
  ASSERT_TRUE(first.has_value());
  h.click_at(first->cx(), first->cy());
  ASSERT_TRUE(h.studio().selected_point().has_value());
  EXPECT_EQ(h.studio().selected_point()->index, 0u) << "a click selects the point";
  h.click("Delete point");
  EXPECT_NE(h.studio().status().find("begins"), std::string::npos) << h.studio().status();
  EXPECT_TRUE(h.studio().document() == original);
  h.frame();
  h.click("error:ok");  // the error's dialog

  // Rotated by 90° counter-clockwise; the grain line kept.
  h.click("Rotate");
  ASSERT_NE(h.studio().status().find("Rotate pattern " + front + " by 90"), std::string::npos) << h.studio().status();
  const auto rotated = vgd::xvc::to_piece(h.studio().document(), front);
  ASSERT_TRUE(rotated.grain_line && pa.grain_line);
  EXPECT_EQ(rotated.grain_line->a, pa.grain_line->a);
  vgd::pattern::Vec2 lo = pa.boundary[0].p, hi = lo;
  for (const auto& c : pa.boundary) lo = lo.cwiseMin(c.p), hi = hi.cwiseMax(c.p);
  const vgd::pattern::Vec2 m = 0.5 * (lo + hi), r = pa.boundary[0].p - m;
  EXPECT_LT((rotated.boundary[0].p - (m + vgd::pattern::Vec2(-r.y(), r.x()))).norm(), 1e-12);
  const fs::path out = fs::temp_directory_path() / ("vgd-studio-edit-" + std::to_string(::getpid()) + ".xvc");
  ASSERT_TRUE(h.studio().save(out)) << h.studio().status();
  const auto v = vgd::xvc::validate_file(out, vgd::xvc::default_schema_path());
  for (const auto& d : v.items()) ADD_FAILURE() << d.format();
  EXPECT_TRUE(vgd::xvc::load_file(out) == h.studio().document());
  fs::remove(out);
}

// A piece's own fabric chosen in the inspector: the skirt's waistband cut from
// the shipped denim (its MATERIAL copied into the document, named by the
// pattern's ASSOCIATION), the piece still selected; one undo takes it back;
// "garment's" again removes the copy.
TEST(Studio, APieceIsCutFromAFabricOfItsOwn) {
  TestHarness h;
  ASSERT_TRUE(h.studio().open(kSkirt));
  h.frame();
  const std::string band = pattern_id(h.studio().document(), "WAISTBAND", "38");
  ASSERT_FALSE(band.empty());
  const auto original = h.studio().document();
  h.click("tree:" + band);
  h.click("piece fabric");
  h.click("piece fabric:denim");
  const auto& doc = h.studio().document();
  const std::string own = vgd::xvc::piece_material(doc, *doc.find(band));
  ASSERT_FALSE(own.empty()) << h.studio().status();
  EXPECT_NE(std::string(doc.find(own)->attribute("name")).find("denim"), std::string::npos);
  EXPECT_EQ(h.studio().selected(), band);
  EXPECT_EQ(vgd::xvc::garment_material(doc), "") << "the skirt's own fabric stays the default";
  h.key("ctrl+z");
  EXPECT_TRUE(h.studio().document() == original);
  h.key("ctrl+y");
  h.frame();
  h.click("piece fabric");
  h.click("piece fabric:garment's");
  EXPECT_TRUE(h.studio().document().container("MATERIALS")->children.empty()) << h.studio().status();
  EXPECT_EQ(vgd::xvc::piece_material(h.studio().document(), *h.studio().document().find(band)), "");
}

// Garments worn with the document: a path that is no file refused; the skirt
// added under the T-shirt, and the drape made of both, each piece named after
// its garment (t-shirt/FRONT_38, a-line-skirt/FRONT_38); taken off, the next
// drape is the T-shirt's alone.
TEST(Studio, AGarmentIsWornUnderTheDocument) {
  TestHarness h;
  ASSERT_TRUE(h.studio().open(kTShirt));
  h.frame();
  h.click("layer");
  h.type("no-such-garment.xvc");
  h.click("Add under");
  EXPECT_NE(h.studio().status().find("No garment document"), std::string::npos) << h.studio().status();
  h.frame();
  h.click("error:ok");
  h.click("layer");
  h.key("ctrl+a");
  h.type(kSkirt.string());
  h.click("Add under");
  h.frame();
  ASSERT_TRUE(h.studio().widget("take off:a-line-skirt.xvc").has_value()) << h.studio().status();
  auto& d = h.studio().drape_options();
  d.spacing = 0.03;
  d.time_limit = 0.2;
  d.quality = vgd::scene::Quality::preview;
  auto pieces = [&] {
    std::set<std::string> names;
    for (const auto& p : h.studio().certificate()->placement) names.insert(p.piece);
    return names;
  };
  h.click("Drape");
  h.studio().wait_for_drape();
  h.frames(3);
  ASSERT_TRUE(h.studio().certificate().has_value()) << h.studio().status();
  auto names = pieces();
  EXPECT_TRUE(names.count("a-line-skirt/FRONT_38")) << h.studio().status();
  EXPECT_TRUE(names.count("t-shirt/FRONT_38"));
  EXPECT_EQ(names.size(), 7u) << "three skirt pieces and four T-shirt pieces";
  h.click("take off:a-line-skirt.xvc");
  h.click("Drape");
  h.studio().wait_for_drape();
  h.frames(3);
  names = pieces();
  EXPECT_TRUE(names.count("FRONT_38")) << h.studio().status();
  EXPECT_EQ(names.size(), 4u);
}

// An M:N seam: two stretches of the front that follow one another picked for
// hem A (the second with Shift), one of the back for hem B: one SEAM whose
// hem A runs from the first to the second, forward, and whose hem B is the
// back's, reversed. Stretches of hem A not in a row are refused with the
// reason. "Flip seam" on the new seam reverses hem B; undo takes it back.
TEST(Studio, AnMToNSeamIsPickedWithShiftAndFlipped) {
  TestHarness h;
  ASSERT_TRUE(h.studio().open(kTShirt));
  h.frame();
  const auto& doc = h.studio().document();
  const std::string front = pattern_id(doc, "FRONT", "38"), back = pattern_id(doc, "BACK", "38");
  const std::string a1 = stretch_id(doc, front, 1), a2 = stretch_id(doc, front, 2), b = stretch_id(doc, back, 0);
  const std::size_t seams_before = vgd::xvc::list_seams(doc).size();
  auto pick = [&](const std::string& pat, const std::string& seq, bool shift) {
    const auto r = h.studio().stretch_on_screen(pat, seq);
    ASSERT_TRUE(r) << pat << " " << seq;
    h.click_at(r->cx(), r->cy(), shift);
  };
  pick(front, a1, false);
  pick(back, b, false);
  pick(front, a2, true);
  ASSERT_EQ(h.studio().picked().size(), 3u);
  EXPECT_EQ(h.studio().picked_first_side(), 2u);
  EXPECT_EQ(h.studio().picked()[1], (std::pair{front, a2})) << "Shift+click joins hem A";
  h.click("Add seam");
  auto seams = vgd::xvc::list_seams(h.studio().document());
  ASSERT_EQ(seams.size(), seams_before + 1) << h.studio().status();
  const auto added = seams.back();
  ASSERT_EQ(added.hems.size(), 2u);
  EXPECT_EQ(added.hems[0].pattern, front);
  EXPECT_EQ(added.hems[0].from, a1);
  EXPECT_EQ(added.hems[0].to, a2);
  EXPECT_FALSE(added.hems[0].reverse);
  EXPECT_EQ(added.hems[1].from, b);
  EXPECT_TRUE(added.hems[1].reverse);
  // Not in a row: refused, nothing added.
  pick(front, stretch_id(doc, front, 0), false);
  pick(front, stretch_id(doc, front, 2), true);
  pick(back, b, false);
  h.click("Add seam");
  EXPECT_NE(h.studio().status().find("follow one another"), std::string::npos) << h.studio().status();
  EXPECT_EQ(vgd::xvc::list_seams(h.studio().document()).size(), seams_before + 1);
  h.frame();
  h.click("error:ok");
  h.click("Clear picks");
  // Flipped from the inspector, then undone.
  const auto before = h.studio().document();
  h.click("tree:" + added.id);
  h.click("Flip seam");
  const auto flipped = vgd::xvc::list_seams(h.studio().document()).back();
  EXPECT_FALSE(flipped.hems[1].reverse) << h.studio().status();
  h.key("ctrl+z");
  EXPECT_TRUE(h.studio().document() == before);
}

// A designer's session on a shared DXF, every step through the studio: the
// racer-back tank imported (size 36, its sample); its front moved on the
// sheet, turned 3° off the grain, a hem corner dragged 12 px down; seams
// suggested and all but the first accepted, that one picked by hand from
// its two stretches; Arrange, the front dragged 15 px up the torso in 3-D;
// a drape started and held at once (Space), the cloth taken by hand, the
// drape let run on for 0.3 s simulated while pulled (it moves, stays
// finite), stopped; draped again to rest on one thread, shown as its
// weft strain map (the 3-D view against tests/golden/studio/session-weft.png,
// colour SSIM > 0.97, looked at); saved: the file validates and holds every
// edit.
TEST(Studio, ASharedDxfIsImportedEditedArrangedDrapedAndSaved) {
  const fs::path shared = fs::path(VGD_SHARED_DIR) / "data" / "dxf" / "WM_SLIM_TANK.DXF";
  if (!fs::exists(shared)) GTEST_SKIP() << "shared data absent: " << shared;
  omp_set_num_threads(1);
  const fs::path dir = temp_dir("session");
  fs::copy_file(shared, dir / "tank.dxf");
  TestHarness h(1280, 800);
  ASSERT_TRUE(h.studio().open(dir / "tank.dxf")) << h.studio().status();
  h.frames(2);
  h.click("import:ok");
  h.frames(2);
  h.click("imported:ok");
  ASSERT_EQ(h.studio().drape_options().size, "36");
  const std::string front = pattern_id(h.studio().document(), "TANK_SR_FR", "36");
  const std::string back = pattern_id(h.studio().document(), "TANK_SR_BK", "36");
  ASSERT_FALSE(front.empty() || back.empty());
  const auto imported = h.studio().document();

  // Moved on the sheet, turned 3°, a hem corner dragged down.
  const auto at = h.studio().piece_on_screen(front);
  ASSERT_TRUE(at.has_value());
  h.drag(at->cx(), at->cy(), at->cx() + 20, at->cy());
  ASSERT_TRUE(vgd::xvc::sheet_position(*h.studio().document().find(front)).has_value()) << h.studio().status();
  h.click_at(at->cx() + 20, at->cy());
  ASSERT_EQ(h.studio().selected(), front);
  h.click("rotate angle");
  h.key("ctrl+a");
  h.type("3");
  h.key("enter");
  h.click("Rotate");
  ASSERT_NE(h.studio().status().find("by 3"), std::string::npos) << h.studio().status();
  h.frame();
  // The front's lowest outline point: a hem corner.
  const auto stretches = vgd::xvc::boundary_stretches(*h.studio().document().find(front));
  std::optional<vgd::xvc::OutlinePoint> corner;
  double lowest = 1e9;
  for (const auto& st : stretches) {
    const vgd::xvc::OutlinePoint p{front, st.id, 0};
    const double y = outline_point(h.studio().document(), p).y();
    if (y < lowest) lowest = y, corner = p;
  }
  ASSERT_TRUE(corner.has_value());
  const auto cs = h.studio().point_on_screen(*corner);
  ASSERT_TRUE(cs.has_value());
  const auto before_drag = outline_point(h.studio().document(), *corner);
  h.drag(cs->cx(), cs->cy(), cs->cx(), cs->cy() + 12);
  const auto after_drag = outline_point(h.studio().document(), *corner);
  EXPECT_NEAR(before_drag.y() - after_drag.y(), 12 / h.studio().pattern_scale(), 1e-6) << h.studio().status();

  // Seams: the suggestions but the first, which is picked by hand.
  vgd::xvc::SeamOptions so;
  so.size = "36";
  const auto suggested = vgd::xvc::suggest_seams(h.studio().document(), so);
  ASSERT_GE(suggested.size(), 3u);
  h.click("Suggest seams");
  h.frames(2);
  h.click("suggestion:1");
  h.click("suggestions:add");
  ASSERT_EQ(vgd::xvc::list_seams(h.studio().document()).size(), suggested.size() - 1) << h.studio().status();
  const auto& first = suggested.front();
  ASSERT_EQ(first.hems.size(), 2u);
  ASSERT_EQ(first.hems[0].from, first.hems[0].to) << "one stretch a side";
  ASSERT_EQ(first.hems[1].from, first.hems[1].to);
  h.click("Clear picks");
  for (const auto& hem : first.hems) {
    const auto r = h.studio().stretch_on_screen(hem.pattern, hem.from);
    ASSERT_TRUE(r.has_value());
    h.click_at(r->cx(), r->cy());
  }
  h.click("Add seam");
  const auto seams = vgd::xvc::list_seams(h.studio().document());
  ASSERT_EQ(seams.size(), suggested.size()) << h.studio().status();
  if (first.hems[0].reverse == first.hems[1].reverse) {
    // Picked, hem B runs against hem A; the suggestion runs both one way.
    h.click("tree:" + seams.back().id);
    h.click("Flip seam");
  }

  // Arranged in 3-D: the front dragged 15 px up its place.
  h.click("Arrange");
  h.frames(2);
  ASSERT_TRUE(h.studio().arranging()) << h.studio().status();
  const auto fa = h.studio().arranged_piece_on_screen(front);
  ASSERT_TRUE(fa.has_value());
  h.drag(fa->cx(), fa->cy(), fa->cx(), fa->cy() - 15);
  const auto arranged = vgd::xvc::arrangements_of(*h.studio().document().find(front));
  ASSERT_EQ(arranged.size(), 1u) << h.studio().status();
  EXPECT_EQ(arranged[0].segment, "torso");

  // A drape, pulled by hand a while, stopped.
  auto& o = h.studio().drape_options();
  o.time_limit = 6.0;
  o.spacing = 0.02;
  h.click("Drape");
  ASSERT_FALSE(h.studio().arranging());
  // Held (Space) from the start, so that however slowly the preview comes,
  // the drape waits for the hand: it holds after its first frame.
  h.key("space");
  ASSERT_TRUE(h.studio().drape_status().paused) << h.studio().status();
  ASSERT_TRUE(frames_until(h, [&] { return h.studio().drape_status().t > 0 && h.studio().particle_on_screen(0).has_value(); }))
      << h.studio().drape_status().message;
  h.frames(20);  // the preview shows the frame it holds
  const auto r = h.studio().widget("preview");
  ASSERT_TRUE(r.has_value());
  int pick = -1;
  float best = 1e9f;
  const auto x0 = h.studio().cloth_positions();
  for (std::size_t i = 0; i < x0.size(); ++i)
    if (const auto q = h.studio().particle_on_screen(static_cast<int>(i)))
      if (const float d = std::hypot(q->cx() - r->cx(), q->cy() - (r->y0 + 0.55f * (r->y1 - r->y0))); d < best)
        best = d, pick = static_cast<int>(i);
  ASSERT_GE(pick, 0);
  const auto ps = *h.studio().particle_on_screen(pick);
  h.press(ps.cx(), ps.cy(), true);
  ASSERT_TRUE(h.studio().held_particle().has_value()) << h.studio().status();
  const int held = *h.studio().held_particle();
  const auto held_before = h.studio().cloth_positions()[static_cast<std::size_t>(held)];
  for (int k = 1; k <= 4; ++k) h.move_mouse(ps.cx() + 10.0f * k, ps.cy());
  const double t0 = h.studio().drape_status().t;
  h.key("space");  // runs on, still held by the hand
  ASSERT_FALSE(h.studio().drape_status().paused);
  ASSERT_TRUE(frames_until(h, [&] { return h.studio().drape_status().t > t0 + 0.3; }));
  h.frames(20);
  const auto pulled = h.studio().cloth_positions();
  const auto& held_after = pulled[static_cast<std::size_t>(held)];
  EXPECT_GT(std::hypot(held_after[0] - held_before[0], held_after[1] - held_before[1], held_after[2] - held_before[2]), 0.01f);
  for (const auto& q : pulled) ASSERT_TRUE(std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2]));
  h.release();
  h.click("Stop");
  h.studio().wait_for_drape();
  h.frames(2);

  // Draped to rest, its weft strain shown.
  h.click("Drape");
  h.studio().wait_for_drape();
  h.frames(4);
  ASSERT_EQ(h.studio().drape_status().stage, "done") << h.studio().drape_status().message;
  ASSERT_TRUE(h.studio().certificate().has_value());
  EXPECT_TRUE(h.studio().certificate()->passed()) << h.studio().status();
  h.click("map");
  h.click("map:weft strain");
  h.frames(4);
  const auto view = crop(h.screenshot(), *h.studio().widget("preview"));
  const fs::path golden = kSource / "tests/golden/studio/session-weft.png";
  if (std::getenv("VGD_UPDATE_GOLDENS")) {
    fs::create_directories(golden.parent_path());
    vgd::render::write_png(view, golden);
  }
  const auto ref = vgd::render::read_png(golden);
  ASSERT_EQ(ref.width, view.width);
  ASSERT_EQ(ref.height, view.height);
  EXPECT_GT(vgd::qa::colour_ssim(ref, view), 0.97);

  // Saved: valid, every edit in it.
  const fs::path out = dir / "tank-session.xvc";
  ASSERT_TRUE(h.studio().save(out)) << h.studio().status();
  const auto v = vgd::xvc::validate_file(out, vgd::xvc::default_schema_path());
  for (const auto& d : v.items())
    if (d.severity == vgd::Severity::error) ADD_FAILURE() << d.format();
  const auto saved = vgd::xvc::load_file(out);
  EXPECT_TRUE(saved == h.studio().document());
  EXPECT_EQ(vgd::xvc::sheet_position(*saved.find(front)), vgd::xvc::sheet_position(*h.studio().document().find(front)));
  EXPECT_NEAR(outline_point(saved, *corner).y(), after_drag.y(), 1e-9);
  EXPECT_EQ(vgd::xvc::list_seams(saved).size(), suggested.size());
  EXPECT_EQ(vgd::xvc::arrangements_of(*saved.find(front)).size(), 1u);
  EXPECT_FALSE(saved == imported);
}
