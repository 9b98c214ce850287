// `vgd render` with the garment document's looks: a drape folder whose
// certificate names a document with a TEXTURE draws the pieces textured (the
// gingham's red and white where the garment is, every other pixel as before),
// --no-texture and --colour draw flat colours, a missing texture file is an
// error naming it, a document that cannot be read is a warning, and the same
// input gives the same bytes.
#include <gtest/gtest.h>

#include <cmath>

#include "render/synthetic_scene.hpp"
#include "support/run_vgd.hpp"
#include "support/textured_skirt.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/file.hpp"
#include "vgd/render/image.hpp"

using namespace vgd;
namespace fs = std::filesystem;

namespace {

// OBJ text of one mesh as `vgd drape` writes garment.obj: `v`, `vt` (pattern
// metres: arc length from the front, height), then `g` and `f a/a b/b c/c`.
std::string garment_obj(const render::Mesh& m, float radius) {
  std::string s;
  for (const auto& p : m.positions)
    s += "v " + std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + "\n";
  for (const auto& p : m.positions)
    s += "vt " + std::to_string(radius * std::atan2(p[0], p[2])) + " " + std::to_string(p[1]) + "\n";
  s += "g " + m.name + "\n";
  for (const auto& t : m.triangles) {
    s += "f";
    for (int k = 0; k < 3; ++k) s += " " + std::to_string(t[k] + 1) + "/" + std::to_string(t[k] + 1);
    s += "\n";
  }
  return s;
}

std::string body_obj(const render::Mesh& m) {
  std::string s = "g body\n";
  for (const auto& p : m.positions)
    s += "v " + std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + "\n";
  for (const auto& t : m.triangles)
    s += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + "\n";
  return s;
}

// A drape folder: garment.obj (the piece FRONT_38, a tube round the body, with
// vt), avatar.obj, and a certificate naming `document`.
fs::path drape_folder(const std::string& name, const fs::path& document) {
  const auto dir = test::scratch_dir(name);
  render::Mesh front = test::tube(0.2f, 0.6f, 1.0f);
  front.name = "FRONT_38";
  write_file_atomic(dir / "garment.obj", garment_obj(front, 0.2f));
  write_file_atomic(dir / "avatar.obj", body_obj(test::dressed_cylinder().meshes[0]));
  write_file_atomic(dir / "certificate.json",
                    "{\n  \"inputs\": {\n    \"garment\": \"" + document.string() + "\"\n  }\n}\n");
  return dir;
}

fs::path textured_folder(const std::string& name) {
  const auto doc_dir = test::scratch_dir(name + "_doc");
  test::write_textured_skirt(doc_dir / "skirt.xvc");
  return drape_folder(name, doc_dir / "skirt.xvc");
}

test::CliResult run_render(const fs::path& input, const fs::path& out, std::vector<std::string> extra = {}) {
  std::vector<std::string> args{"render", input.string(), "--views", "front", "--size", "128", "-o", out.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  return test::run_vgd(args);
}

bool same_pixel(const render::Image& a, const render::Image& b, int x, int y) {
  return std::equal(a.pixel(x, y), a.pixel(x, y) + 4, b.pixel(x, y));
}

}  // namespace

TEST(CmdRenderTexture, ADrapeFolderIsDrawnWithItsDocumentsTexture) {
  const auto dir = textured_folder("cmd_render_tex");
  for (auto [out, extra] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {"tex", {}}, {"flat", {"--no-texture"}}, {"red", {"--colour", "#c02020"}}, {"blue", {"--colour", "#2020c0"}}}) {
    extra.insert(extra.end(), {"--fit", "garment"});  // close enough to see the 2 cm checks
    const auto r = run_render(dir, dir / out, extra);
    ASSERT_EQ(r.code, 0) << out << ": " << r.err;
  }
  const auto tex = render::read_png(dir / "tex/front.png"), flat = render::read_png(dir / "flat/front.png");
  const auto red = render::read_png(dir / "red/front.png"), blue = render::read_png(dir / "blue/front.png");
  int garment = 0, changed = 0, checks_red = 0, checks_white = 0, outside_changed = 0;
  for (int y = 0; y < tex.height; ++y)
    for (int x = 0; x < tex.width; ++x) {
      if (same_pixel(red, blue, x, y)) {  // not the garment
        outside_changed += !same_pixel(flat, tex, x, y);
        continue;
      }
      ++garment;
      changed += !same_pixel(flat, tex, x, y);
      const auto* p = tex.pixel(x, y);
      checks_red += p[0] > p[1] + 70 && p[0] > p[2] + 60;
      checks_white += p[0] > 150 && std::abs(p[0] - p[1]) < 25 && std::abs(p[1] - p[2]) < 25;
    }
  ASSERT_GT(garment, 128 * 128 / 5) << "the garment fills the view";
  EXPECT_EQ(outside_changed, 0) << "only the garment's pixels change";
  EXPECT_GT(changed, garment * 9 / 10);
  EXPECT_GT(checks_red, garment / 10) << "the gingham's red";
  EXPECT_GT(checks_white, garment / 10) << "the gingham's white";
  // The flat render of a document without colours is the default fabric blue, as before looks were read.
  const auto* mid = flat.pixel(64, 64);
  EXPECT_GT(mid[2], mid[0] + 40) << "default fabric blue";
}

TEST(CmdRenderTexture, TheSameInputGivesTheSameBytes) {
  const auto dir = textured_folder("cmd_render_tex_same");
  ASSERT_EQ(run_render(dir, dir / "a").code, 0);
  ASSERT_EQ(run_render(dir, dir / "b").code, 0);
  EXPECT_TRUE(read_file(dir / "a/front.png") == read_file(dir / "b/front.png"));
}

TEST(CmdRenderTexture, AMissingTextureFileIsAnErrorNamingIt) {
  const auto dir = textured_folder("cmd_render_tex_missing");
  fs::remove(test::binary_dir() / "test-scratch" / "cmd_render_tex_missing_doc" / "gingham.png");
  const auto r = run_render(dir, dir / "out");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("gingham.png"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--no-texture"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out/front.png"));
  EXPECT_EQ(run_render(dir, dir / "flat", {"--no-texture"}).code, 0) << "flat colours need no texture file";
}

TEST(CmdRenderTexture, AnUnreadableDocumentIsAWarningAndFlatColour) {
  const auto dir = drape_folder("cmd_render_tex_nodoc", "/nonexistent/skirt.xvc");
  const auto r = run_render(dir, dir / "out");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("warning"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("skirt.xvc"), std::string::npos) << r.err;
  // As without a certificate: the default fabric colour.
  fs::remove(dir / "certificate.json");
  ASSERT_EQ(run_render(dir, dir / "plain").code, 0);
  EXPECT_TRUE(read_file(dir / "out/front.png") == read_file(dir / "plain/front.png"));
}

TEST(CmdRenderTexture, LookGivesTheDocumentForAnObj) {
  const auto doc_dir = test::scratch_dir("cmd_render_tex_look_doc");
  test::write_textured_skirt(doc_dir / "skirt.xvc");
  const auto dir = drape_folder("cmd_render_tex_look", "/nonexistent/skirt.xvc");
  const std::vector<std::string> common{"--avatar", (dir / "avatar.obj").string()};
  auto with = common, without = common;
  with.insert(with.end(), {"--look", (doc_dir / "skirt.xvc").string()});
  ASSERT_EQ(run_render(dir / "garment.obj", dir / "look", with).code, 0);
  ASSERT_EQ(run_render(dir / "garment.obj", dir / "none", without).code, 0);
  EXPECT_TRUE(read_file(dir / "look/front.png") != read_file(dir / "none/front.png"));
  EXPECT_EQ(run_render(dir / "garment.obj", dir / "bad", {"--look", (doc_dir / "nothing.xvc").string()}).code, 1)
      << "an explicit --look must be readable";
}
