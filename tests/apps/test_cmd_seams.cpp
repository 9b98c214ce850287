// vgd draft tshirt (DXF and XVC), vgd seams (suggest, apply, list, add, delete) and
// vgd place (--auto, --set), run as a user would.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "support/run_vgd.hpp"
#include "support/test_paths.hpp"
#include "vgd/xvc/arrangement.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/seams.hpp"

namespace fs = std::filesystem;

TEST(CliDraft, TShirtAsDxfAndAsXvcWithSeamsAndArrangements) {
  const auto dir = vgd::test::scratch_dir("cli_draft_tshirt");
  auto r = vgd::test::run_vgd("draft tshirt -o t.dxf --sizes 38", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "t.dxf"));
  r = vgd::test::run_vgd("draft tshirt -o t.xvc --sizes 38,40", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto doc = vgd::xvc::load_file(dir / "t.xvc");
  EXPECT_EQ(vgd::xvc::list_seams(doc).size(), 16u);  // 8 seams × 2 sizes
  for (const auto* p : doc.patterns()) EXPECT_EQ(vgd::xvc::arrangements_of(*p).size(), 1u);
  r = vgd::test::run_vgd("validate t.xvc", dir);
  EXPECT_EQ(r.code, 0) << r.out << r.err;
}

TEST(CliSeams, SuggestApplyListAddDelete) {
  const auto dir = vgd::test::scratch_dir("cli_seams");
  ASSERT_EQ(vgd::test::run_vgd("draft skirt -o s.dxf --sizes 38", dir).code, 0);
  ASSERT_EQ(vgd::test::run_vgd("import s.dxf -o s.xvc", dir).code, 0);
  auto r = vgd::test::run_vgd("seams suggest s.xvc --json", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j.size(), 3u);
  r = vgd::test::run_vgd("seams suggest s.xvc", dir);
  EXPECT_NE(r.out.find("waist seam"), std::string::npos) << r.out;
  ASSERT_EQ(vgd::test::run_vgd("seams suggest s.xvc --apply -o with.xvc", dir).code, 0);
  r = vgd::test::run_vgd("seams list with.xvc --json", dir);
  const auto listed = nlohmann::json::parse(r.out);
  ASSERT_EQ(listed.size(), 3u);
  const std::string first = listed[0]["id"];
  ASSERT_EQ(vgd::test::run_vgd("seams delete with.xvc " + first + " -o fewer.xvc", dir).code, 0);
  EXPECT_EQ(vgd::xvc::list_seams(vgd::xvc::load_file(dir / "fewer.xvc")).size(), 2u);
  // By hand: the front's left side (stretch 3) to the back's right side (stretch 1), reversed.
  r = vgd::test::run_vgd("seams add fewer.xvc --from pattern1:3 --to pattern2:1 --reverse --name again -o again.xvc", dir);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(vgd::xvc::list_seams(vgd::xvc::load_file(dir / "again.xvc")).size(), 3u);
  r = vgd::test::run_vgd("seams add fewer.xvc --from pattern1:99 --to pattern2:1 -o x.xvc", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("no stretch 99"), std::string::npos) << r.err;
}

TEST(CliPlace, AutoAndSet) {
  const auto dir = vgd::test::scratch_dir("cli_place");
  ASSERT_EQ(vgd::test::run_vgd("draft tshirt -o t.dxf --sizes 38", dir).code, 0);
  ASSERT_EQ(vgd::test::run_vgd("import t.dxf -o t.xvc", dir).code, 0);
  auto r = vgd::test::run_vgd("place t.xvc --auto -o placed.xvc", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  r = vgd::test::run_vgd("place placed.xvc --set FRONT=torso:front:1.25:0.02 -o moved.xvc --list", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("torso:front:1.25:0.02"), std::string::npos) << r.out;
  r = vgd::test::run_vgd("place placed.xvc --set FRONT=torso:up:1.25 -o bad.xvc", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("unknown side"), std::string::npos) << r.err;
  // A turn past the side, and a pin: both listed.
  r = vgd::test::run_vgd("place placed.xvc --set FRONT=torso:left-20:1.25 -o turned.xvc", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  std::string front;
  const auto turned = vgd::xvc::load_file(dir / "turned.xvc");
  for (const auto* p : turned.patterns())
    if (p->attribute("piece") == "FRONT") front = std::string(p->id());
  ASSERT_FALSE(front.empty());
  ASSERT_EQ(vgd::test::run_vgd("edit turned.xvc -o pinned.xvc --pin " + front + "=0,0.3", dir).code, 0);
  r = vgd::test::run_vgd("place pinned.xvc --list", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("torso:left-20:1.25"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("pin pos"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("at (0, 0.3) m"), std::string::npos) << r.out;
}
