// Getting a pattern document ready to drape: seams suggested when it has
// none, pieces no seam sews left out, the body's size table from the style.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "support/test_paths.hpp"
#include "support/trousers.hpp"
#include "vgd/dress/garment.hpp"
#include "vgd/io/dxf/import.hpp"
#include "vgd/xvc/arrangement.hpp"
#include "vgd/body/sizes.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/dress/prepare.hpp"
#include "vgd/xvc/commands.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/seams.hpp"
#include "vgd/xvc/validate.hpp"
#include "vgd/xvc/style.hpp"

namespace vgd::dress {
namespace {

using pattern::PointKind;
using pattern::Vec2;

pattern::Piece panel(const std::string& name, double x0, double w, double h, const std::string& size = "M") {
  pattern::Piece p;
  p.block = name + "_" + size;
  p.name = name;
  p.size = size;
  for (const auto& q : std::vector<Vec2>{{x0, 0}, {x0 + w, 0}, {x0 + w, h}, {x0, h}})
    p.boundary.push_back({q, PointKind::turn});
  p.grain_line = pattern::Segment{Vec2(x0 + w / 2, 0.1), Vec2(x0 + w / 2, h - 0.1)};
  return p;
}

// A style of one size holding these pieces.
pattern::Style one_size(const std::string& name, const std::string& size,
                        std::vector<pattern::Piece> pieces) {
  pattern::Style s;
  s.name = name;
  s.sample_size = size;
  s.sizes = {size};
  s.pieces = std::move(pieces);
  return s;
}

// A style smaller round the body than its body: prepared with no fabric it
// is cut from the shipped knit, said (knit_says) and not warned; in a fabric
// the caller gives it is warned (warning_says).
void expect_knit_or_warned(const pattern::Style& s, const std::string& knit_says, const std::string& warning_says) {
  xvc::Document doc = xvc::from_style(s);
  const Preparation p = prepare_garment(doc);
  EXPECT_TRUE(p.warnings.empty()) << ::testing::PrintToString(p.warnings);
  EXPECT_EQ(p.fabric, "cotton-jersey") << ::testing::PrintToString(p.decisions);
  EXPECT_NE(xvc::garment_material(doc), "") << "written in the document";
  EXPECT_TRUE(std::any_of(p.decisions.begin(), p.decisions.end(),
                          [&](const std::string& d) { return d.find(knit_says) != std::string::npos; }))
      << ::testing::PrintToString(p.decisions);
  xvc::Document given = xvc::from_style(s);
  PrepareOptions o;
  o.fabric_given = true;
  const Preparation w = prepare_garment(given, o);
  EXPECT_EQ(w.fabric, "");
  ASSERT_EQ(w.warnings.size(), 1u) << ::testing::PrintToString(w.decisions);
  EXPECT_NE(w.warnings[0].find(warning_says), std::string::npos) << w.warnings[0];
}

// A shared DXF file, imported with its mirrored pieces unfolded (as vgd dress does).
xvc::Document shared_document(const std::string& file) {
  dxf::ImportOptions unfold;
  unfold.unfold_mirrored = true;
  return xvc::from_style(dxf::import_file(vgd::test::shared_dxf(file), unfold).style);
}

// A whole bodice of size 50, 50 cm wide, centred on x0: armholes from 0.40
// to 0.52 m, shoulders to 0.58 m, its neckline 0.53 m high at the centre.
pattern::Piece bodice(const std::string& name, double x0) {
  pattern::Piece p;
  p.block = name + "_50";
  p.name = name;
  p.size = "50";
  for (const auto& q : std::vector<Vec2>{{-0.25, 0},  {0.25, 0},     {0.25, 0.40},  {0.18, 0.52}, {0.07, 0.58},
                                         {0.0, 0.53}, {-0.07, 0.58}, {-0.18, 0.52}, {-0.25, 0.40}})
    p.boundary.push_back({Vec2(q.x() + x0, q.y()), PointKind::turn});
  p.grain_line = pattern::Segment{Vec2(x0, 0.1), Vec2(x0, 0.4)};
  return p;
}

}  // namespace

TEST(SizeTableFromName, MenOrWomenFromTheStyleName) {
  EXPECT_EQ(size_table_from_name("MEN CLASSIC TEE"), "en13402-men");
  EXPECT_EQ(size_table_from_name("SS17_M POLO REG"), "en13402-men");
  EXPECT_EQ(size_table_from_name("Valentina_MaleShirt_AAMA_R12"), "en13402-men");
  EXPECT_EQ(size_table_from_name("WM_SLIM_TANK"), "en13402-women");
  EXPECT_EQ(size_table_from_name("Womens basic top"), "en13402-women");
  EXPECT_EQ(size_table_from_name("FEMALE blouse"), "en13402-women");
  EXPECT_EQ(size_table_from_name("clo-pattern"), "");
  EXPECT_EQ(size_table_from_name("MEDIUM SKIRT"), "") << "a word that only starts with M says nothing";
  EXPECT_EQ(size_table_from_name("MEN AND WOMEN TEE"), "") << "both: neither";
}

TEST(PrepareGarment, SuggestsSeamsAndLeavesOutWhatNoSeamSews) {
  pattern::Style s = one_size(
      "WM TOP", "M",
      {panel("FRONT", 0.0, 0.30, 0.50), panel("BACK", 1.0, 0.30, 0.50), panel("LABEL", 2.0, 0.04, 0.02)});
  xvc::Document doc = xvc::from_style(s);
  ASSERT_TRUE(xvc::list_seams(doc).empty());
  const Preparation p = prepare_garment(doc);
  EXPECT_EQ(p.size, "M");
  EXPECT_GE(p.seams_added, 2);
  EXPECT_EQ(static_cast<int>(xvc::list_seams(doc).size()), p.seams_added) << "the seams are in the document";
  EXPECT_EQ(p.pieces, (std::vector<std::string>{"FRONT", "BACK"}));
  EXPECT_EQ(p.left_out, (std::vector<std::string>{"LABEL"}));
  EXPECT_EQ(p.body_table, "en13402-women");
  bool label = false, body = false, seam = false;
  for (const auto& d : p.decisions) {
    label =
        label ||
        d == "piece LABEL (label) left out: it is bonded to its host and does not hang as cloth of its own";
    body = body ||
           d.find("from en13402-women (nearest the pattern: its bust girth is 60 cm") != std::string::npos;
    seam = seam || d.find("suggested at size M: FRONT to BACK") != std::string::npos;
  }
  EXPECT_TRUE(label && body && seam);
  // The nearest body (the women's 32, 76 cm) is still 16 cm larger round the
  // bust than the pattern: cut from the shipped knit, or warned in a fabric given.
  expect_knit_or_warned(s,
                        "fabric: the shipped knit cotton-jersey (written in the document): the pattern's bust girth "
                        "is 60 cm, 16 cm less than the body's 76 cm",
                        "the pattern's bust girth is 60 cm, 16 cm less than the body's 76 cm (women's 32)");
  // A top a quarter smaller than the body (a file's halves cut once, not
  // unfolded, say) gets no knit: it is warned.
  {
    pattern::Style narrow = one_size("WM TOP", "M", {panel("FRONT", 0.0, 0.20, 0.50), panel("BACK", 1.0, 0.20, 0.50)});
    xvc::Document d = xvc::from_style(narrow);
    const Preparation w = prepare_garment(d);
    EXPECT_EQ(w.fabric, "");
    ASSERT_EQ(w.warnings.size(), 1u) << ::testing::PrintToString(w.decisions);
    EXPECT_NE(w.warnings[0].find("the pattern's bust girth is 40 cm, 36 cm less"), std::string::npos) << w.warnings[0];
  }

  // Run again on the document it wrote: its seams are kept, nothing added.
  const Preparation again = prepare_garment(doc);
  EXPECT_EQ(again.seams_added, 0);
  EXPECT_EQ(again.pieces, p.pieces);
}

// A skirt smaller round the hip than the body (a jersey tube skirt): cut
// from the shipped knit as a top is, or warned in a fabric given.
TEST(PrepareGarment, ASkirtSmallerRoundTheHipThanTheBodyIsCutFromTheKnit) {
  pattern::Style s = one_size("WM SKIRT", "40",
                              {panel("FRONT", 0.0, 0.40, 0.60, "40"), panel("BACK", 1.0, 0.40, 0.60, "40"),
                               panel("WAISTBAND", 2.0, 0.80, 0.04, "40")});
  expect_knit_or_warned(s,
                        "the pattern's hip girth is 80 cm, 20 cm less than the body's 100 cm: it is cut for a "
                        "stretch fabric",
                        "too small for the body: the pattern's hip girth is 80 cm, 20 cm less than the body's 100 cm "
                        "(women's 40)");
}

TEST(PrepareGarment, NothingToDrapeIsAnErrorNamingThePieces) {
  pattern::Style s =
      one_size("parts", "M", {panel("PART A", 0.0, 0.30, 0.50), panel("PART B", 1.0, 0.05, 0.07)});
  xvc::Document doc = xvc::from_style(s);
  try {
    prepare_garment(doc);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("nothing to drape"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("PART A (role unknown), PART B (role unknown)"), std::string::npos)
        << e.what();
  }
  // A size the document lacks: the error lists the sizes it has.
  PrepareOptions wrong;
  wrong.size = "XL";
  try {
    prepare_garment(doc, wrong);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no pattern of size 'XL'; its sizes: M"), std::string::npos)
        << e.what();
  }
}

}  // namespace vgd::dress

namespace vgd::dress {

// A style with only a base size (Valentina) drapes on the body nearest the
// pattern: the row of its table whose bust leaves the pattern's chest the
// usual ease (10 cm), and that is said.
TEST(PrepareGarment, ABaseSizeDrapesOnTheBodyNearestThePattern) {
  // Front and back 55 cm wide: a chest of 110 cm round.
  pattern::Style s = one_size(
      "MEN shirt", "base", {panel("FRONT", 0.0, 0.55, 0.7, "base"), panel("BACK", 1.0, 0.55, 0.7, "base")});
  xvc::Document doc = xvc::from_style(s);
  const Preparation p = prepare_garment(doc);
  EXPECT_EQ(p.size, "base");
  EXPECT_EQ(p.body_table, "en13402-men");
  const auto rows = body::load_size_table(body::size_table_file("en13402-men"));
  const body::BodyMeasurements* chosen = nullptr;
  for (const auto& r : rows)
    if (r.label == p.body_size) chosen = &r;
  ASSERT_NE(chosen, nullptr) << p.body_size;
  for (const auto& r : rows)  // no other row leaves an ease nearer 10 cm
    EXPECT_LE(std::abs(1.10 - chosen->bust - 0.10), std::abs(1.10 - r.bust - 0.10) + 1e-12) << r.label;
  EXPECT_GT(chosen->bust, 0.95);
  EXPECT_LT(chosen->bust, 1.05);
  bool said = false;
  for (const auto& d : p.decisions)
    said = said || d.find("nearest the pattern: its bust girth is 110 cm") != std::string::npos;
  EXPECT_TRUE(said);
  PrepareOptions asked;
  asked.body_size = "48";
  EXPECT_EQ(prepare_garment(doc, asked).body_size, "48");
}

// A style whose name says neither men nor women: the table whose body of the
// garment's size leaves the pattern the usual ease (a Gerber shirt of size 50
// with a 110 cm chest: the men's 50, 100 cm; the women's 50 would need 8 cm
// more cloth than the pattern has).
TEST(PrepareGarment, TheBodyTableFollowsThePatternsGirth) {
  pattern::Style s =
      one_size("GMG1016S19", "50", {panel("FR", 0.0, 0.55, 0.7, "50"), panel("BK", 1.0, 0.55, 0.7, "50")});
  s.pieces[0].category = "FRONT";
  s.pieces[1].category = "BACK";
  xvc::Document doc = xvc::from_style(s);
  Preparation p = prepare_garment(doc);
  EXPECT_EQ(p.body_table, "en13402-men");
  EXPECT_EQ(p.body_size, "50");
  // Narrower pieces (a 96 cm chest) fit the women's 50 better than the men's.
  s.pieces = {panel("FR", 0.0, 0.48, 0.7, "50"), panel("BK", 1.0, 0.48, 0.7, "50")};
  s.pieces[0].category = "FRONT";
  s.pieces[1].category = "BACK";
  doc = xvc::from_style(s);
  p = prepare_garment(doc);
  const auto women = body::find_size("50", "en13402-women"), men = body::find_size("50", "en13402-men");
  const bool women_nearer = std::abs(0.96 - women.bust - 0.10) < std::abs(0.96 - men.bust - 0.10);
  EXPECT_EQ(p.body_table, women_nearer ? "en13402-women" : "en13402-men");
}

// A style graded over several sizes and named neither men's nor women's
// takes the table holding most of its sizes, whatever its girth (Gerber's
// GLX4802S19 tights, graded 26-52, went on the men's 46 by girth and hung
// off its legs); a size that table lacks is its row nearest the pattern. A
// tie, or sizes no table holds, leaves the choice to the girth.
TEST(PrepareGarment, TheBodyTableFollowsTheStylesSizes) {
  auto graded = [](const std::string& name, const std::vector<std::string>& sizes, double w) {
    pattern::Style s;
    s.name = name;
    s.sample_size = sizes.front();
    s.sizes = sizes;
    for (const auto& z : sizes) {
      s.pieces.push_back(panel("FR", 0.0, w, 0.7, z));
      s.pieces.back().category = "FRONT";
      s.pieces.push_back(panel("BK", 1.0, w, 0.7, z));
      s.pieces.back().category = "BACK";
    }
    return xvc::from_style(s);
  };
  auto said = [](const Preparation& p, const std::string& what) {
    return std::any_of(p.decisions.begin(), p.decisions.end(),
                       [&](const std::string& d) { return d.find(what) != std::string::npos; });
  };
  std::vector<std::string> women_range, men_range;
  for (int z = 32; z <= 52; z += 2) women_range.push_back(std::to_string(z));
  for (int z = 42; z <= 70; z += 2) men_range.push_back(std::to_string(z));

  // A 110 cm chest in size 50: by girth the men's 50 (100 cm) leaves the usual
  // ease, but 10 of the style's 11 sizes are women's (5 men's).
  xvc::Document doc = graded("GX100", women_range, 0.55);
  PrepareOptions at50;
  at50.size = "50";
  Preparation p = prepare_garment(doc, at50);
  EXPECT_EQ(p.body_table, "en13402-women");
  EXPECT_EQ(p.body_size, "50");
  EXPECT_TRUE(said(p, "body: the mannequin of size 50 from en13402-women (the style's sizes 32 to 52: 10 of its 11 "
                      "are en13402-women sizes; its bust girth is 110 cm, -8 cm of ease over the body's 118 cm)"))
      << ::testing::PrintToString(p.decisions);
  // 8 cm less than the body round the bust: cut from the shipped knit, or,
  // in the caller's fabric, warned before the drape.
  EXPECT_TRUE(p.warnings.empty()) << ::testing::PrintToString(p.warnings);
  EXPECT_TRUE(said(p, "fabric: the shipped knit cotton-jersey (written in the document): the pattern's bust girth is "
                      "110 cm, 8 cm less than the body's 118 cm: it is cut for a stretch fabric"))
      << ::testing::PrintToString(p.decisions);
  doc = graded("GX100", women_range, 0.55);
  at50.fabric_given = true;
  p = prepare_garment(doc, at50);
  ASSERT_EQ(p.warnings.size(), 1u);
  EXPECT_EQ(p.warnings[0],
            "the garment is too small for the body: the pattern's bust girth is 110 cm, 8 cm less than the body's "
            "118 cm (women's 50); a woven cannot close round it: choose the body with --body-size, or a knit with "
            "--material");

  // Graded 42-70: men's (8 of 15 against 5); size 42 is no men's size, so the
  // men's row nearest the pattern (a 96 cm chest, 10 cm of ease wanted).
  doc = graded("GX200", men_range, 0.48);
  PrepareOptions at42;
  at42.size = "42";
  p = prepare_garment(doc, at42);
  EXPECT_EQ(p.body_table, "en13402-men");
  const auto rows = body::load_size_table(body::size_table_file("en13402-men"));
  std::string nearest;
  double miss = 1e300;
  for (const auto& r : rows)
    if (std::abs(0.96 - r.bust - 0.10) < miss) miss = std::abs(0.96 - r.bust - 0.10), nearest = r.label;
  EXPECT_EQ(p.body_size, nearest);
  EXPECT_TRUE(said(p, "(the style's sizes 42 to 70: 8 of its 15 are en13402-men sizes, which has no size 42; "
                      "nearest the pattern: its bust girth is 96 cm"))
      << ::testing::PrintToString(p.decisions);
  EXPECT_TRUE(p.warnings.empty()) << ::testing::PrintToString(p.warnings);

  // Sizes 44 and 46 are in both tables: the girth decides, as for one size.
  doc = graded("GX300", {"44", "46"}, 0.55);
  PrepareOptions at46;
  at46.size = "46";
  p = prepare_garment(doc, at46);
  EXPECT_TRUE(said(p, "(nearest the pattern: its bust girth is 110 cm")) << ::testing::PrintToString(p.decisions);
}

// A size the style's table lacks goes on the body that keeps the ease the
// style is cut with in the nearest size the table has, not the usual 10 cm:
// a top graded 32-52 (4 cm a size) 14 cm smaller round the bust than the
// women's 50 in size 50 goes in size 52 (no women's size) on the women's 50
// (with 10 cm of ease wanted, the women's 44).
TEST(PrepareGarment, ASizeTheTableLacksKeepsTheStylesEase) {
  pattern::Style s;
  s.name = "GX400";
  for (int z = 32; z <= 52; z += 2) s.sizes.push_back(std::to_string(z));
  s.sample_size = "40";
  const auto rows = body::load_size_table(body::size_table_file("en13402-women"));
  double bust50 = 0;
  for (const auto& r : rows)
    if (r.label == "50") bust50 = r.bust;
  ASSERT_GT(bust50, 0.0);
  for (int z = 32; z <= 52; z += 2) {
    const double girth = bust50 - 0.14 + 0.04 * (z - 50) / 2;  // m round the bust
    s.pieces.push_back(panel("FR", 0.0, girth / 2, 0.7, std::to_string(z)));
    s.pieces.back().category = "FRONT";
    s.pieces.push_back(panel("BK", 1.0, girth / 2, 0.7, std::to_string(z)));
    s.pieces.back().category = "BACK";
  }
  xvc::Document doc = xvc::from_style(s);
  PrepareOptions at52;
  at52.size = "52";
  const Preparation p = prepare_garment(doc, at52);
  EXPECT_EQ(p.body_table, "en13402-women");
  EXPECT_EQ(p.body_size, "50") << ::testing::PrintToString(p.decisions);
  EXPECT_TRUE(std::any_of(p.decisions.begin(), p.decisions.end(), [](const std::string& d) {
    return d.find("which has no size 52; nearest the pattern: its bust girth is") != std::string::npos &&
           d.find("(-14 cm wanted: the style's in size 50, the table's nearest)") != std::string::npos;
  })) << ::testing::PrintToString(p.decisions);
}

// A shirt's pocket and its flap on a whole front with armholes (FRONT, 50 cm
// wide, its side seams 40 cm up to the armholes' bottom at x = ±0.25): the
// pocket, 10 × 12 cm, on the wearer's left (+x), its top 4 cm above the
// armhole's bottom (y = 0.44), its middle 10 cm from centre front (40 % of
// 25 cm); the flap whose name says what the pocket's does beyond POCKET
// (POCKET FLAP ROUND for POCKET ROUND) over it, its top 1.5 cm above the
// pocket's; the other flap its alternative. Both POSITIONs written, and the
// document valid.
TEST(PrepareGarment, APocketAndItsFlapGoOnAWholeFrontsLeftChest) {
  pattern::Piece pocket = panel("POCKET ROUND", 2.0, 0.10, 0.12, "50");
  pattern::Piece flap = panel("POCKET FLAP", 3.0, 0.10, 0.05, "50");
  pattern::Piece round_flap = panel("POCKET FLAP ROUND", 4.0, 0.10, 0.05, "50");
  xvc::Document doc = xvc::from_style(
      one_size("MEN shirt", "50", {bodice("FRONT", 0.0), bodice("BACK", 1.0), pocket, flap, round_flap}));
  const Preparation p = prepare_garment(doc);
  EXPECT_NE(std::find(p.pieces.begin(), p.pieces.end(), "POCKET ROUND"), p.pieces.end());
  EXPECT_NE(std::find(p.pieces.begin(), p.pieces.end(), "POCKET FLAP ROUND"), p.pieces.end());
  EXPECT_EQ(std::find(p.pieces.begin(), p.pieces.end(), "POCKET FLAP"), p.pieces.end());
  const std::vector<std::string> want = {
      "piece POCKET ROUND (pocket) sewn onto the face of FRONT, its top 4.0 cm above the bottom of the armhole, "
      "its middle 10.0 cm from centre front on the wearer's left (POSITION type=\"placement\" written in the "
      "document: move it there)",
      "piece POCKET FLAP (pocket flap) left out: an alternative to the pocket flap POCKET FLAP ROUND",
      "piece POCKET FLAP ROUND (pocket flap) sewn by its top edge onto the face of FRONT, 1.5 cm above the top of "
      "POCKET ROUND, over its mouth (POSITION type=\"placement\" written in the document)"};
  for (const auto& w : want)
    EXPECT_NE(std::find(p.decisions.begin(), p.decisions.end(), w), p.decisions.end())
        << w << "\n" << ::testing::PrintToString(p.decisions);
  std::map<std::string, xvc::FacePlacement> at;
  for (const auto* q : doc.patterns())
    for (const auto& f : xvc::face_placements_of(*q)) at[std::string(q->attribute("piece"))] = f;
  ASSERT_EQ(at.size(), 2u);
  EXPECT_NEAR(at["POCKET ROUND"].x, 0.10, 1e-12);
  EXPECT_NEAR(at["POCKET ROUND"].y, 0.38, 1e-12) << "its top at 0.44";
  EXPECT_NEAR(at["POCKET FLAP ROUND"].x, 0.10, 1e-12);
  EXPECT_NEAR(at["POCKET FLAP ROUND"].y, 0.43, 1e-12) << "its top at 0.455";
  EXPECT_EQ(at["POCKET ROUND"].host, at["POCKET FLAP ROUND"].host);
  const Diagnostics v = xvc::validate_string(xvc::save_string(doc), "shirt.xvc", xvc::default_schema_path());
  for (const auto& d : v.items()) ADD_FAILURE() << d.format();
}

// A polo's plackets: the one not named as the lower one (3 cm wide, drawn
// lying down) is turned upright along centre front of the whole front, its
// top 5 mm below where the neckline crosses centre front (0.53 m), and sewn
// by its two ends; the lower one lies under it, hidden, and is left out, not
// missing, though it is the narrower.
TEST(PrepareGarment, APlacketGoesUprightAlongCentreFrontAndTheOneUnderItIsLeftOut) {
  xvc::Document doc = xvc::from_style(
      one_size("MEN polo", "50",
               {bodice("FRONT", 0.0), bodice("BACK", 1.0), panel("PLACKET LOWER", 2.0, 0.15, 0.02, "50"),
                panel("PLACKET", 3.0, 0.15, 0.03, "50")}));
  const Preparation p = prepare_garment(doc);
  EXPECT_NE(std::find(p.pieces.begin(), p.pieces.end(), "PLACKET"), p.pieces.end());
  EXPECT_EQ(std::find(p.pieces.begin(), p.pieces.end(), "PLACKET LOWER"), p.pieces.end());
  EXPECT_TRUE(p.missing.empty()) << ::testing::PrintToString(p.missing);
  const std::vector<std::string> want = {
      "piece PLACKET (placket) sewn by its two ends onto the face of FRONT, upright along centre front, its "
      "top "
      "0.5 cm below the neckline there (POSITION type=\"placement\" written in the document: move it there)",
      "piece PLACKET LOWER (placket) left out: it lies under the placket PLACKET, hidden by it"};
  for (const auto& w : want)
    EXPECT_NE(std::find(p.decisions.begin(), p.decisions.end(), w), p.decisions.end())
        << w << "\n"
        << ::testing::PrintToString(p.decisions);
  std::vector<xvc::FacePlacement> at;
  for (const auto* q : doc.patterns())
    for (const auto& f : xvc::face_placements_of(*q)) at.push_back(f);
  ASSERT_EQ(at.size(), 1u);
  EXPECT_NEAR(at[0].x, 0.0, 1e-12);
  EXPECT_NEAR(at[0].y, 0.45, 1e-12) << "its top at 0.525";
  EXPECT_NEAR(at[0].angle_deg, 90.0, 1e-12);
  const Diagnostics v = xvc::validate_string(xvc::save_string(doc), "polo.xvc", xvc::default_schema_path());
  for (const auto& d : v.items()) ADD_FAILURE() << d.format();

  // One longer than the front below its neckline (60 cm) is left out, missing, and says so.
  xvc::Document long_one = xvc::from_style(
      one_size("MEN polo", "50",
               {bodice("FRONT", 0.0), bodice("BACK", 1.0), panel("PLACKET", 3.0, 0.60, 0.03, "50")}));
  const Preparation q = prepare_garment(long_one);
  EXPECT_EQ(std::find(q.pieces.begin(), q.pieces.end(), "PLACKET"), q.pieces.end());
  EXPECT_EQ(q.missing, (std::vector<std::string>{"PLACKET (placket)"}));
  bool said = false;
  for (const auto& d : q.decisions)
    said =
        said ||
        d.find("piece PLACKET (placket) left out: it does not fit on FRONT upright along centre front") == 0;
  EXPECT_TRUE(said) << ::testing::PrintToString(q.decisions);
}

// Pieces left out say why, from their role: bonded interfacings, a pocket
// with no room on its front where a chest pocket goes (the 50 × 60 cm
// rectangle has no armhole: its top corner is the armhole's bottom, and the
// pocket would sit 4 cm above it), linings, pieces nobody cuts.
TEST(PrepareGarment, PiecesLeftOutSayWhy) {
  pattern::Style s =
      one_size("WM TOP", "38",
               {panel("FRONT", 0.0, 0.5, 0.6, "38"), panel("BACK", 1.0, 0.5, 0.6, "38"),
                panel("COLLAR INTERFACING", 2.0, 0.4, 0.08, "38"), panel("POCKET", 3.0, 0.15, 0.15, "38"),
                panel("FRONT LINING", 4.0, 0.5, 0.6, "38"), panel("GUIDE", 5.0, 0.2, 0.2, "38")});
  s.pieces[5].quantity = 0;
  xvc::Document doc = xvc::from_style(s);
  const Preparation p = prepare_garment(doc);
  EXPECT_EQ(p.pieces, (std::vector<std::string>{"FRONT", "BACK"}));
  const std::vector<std::string> want = {
      "piece COLLAR INTERFACING (interfacing) left out: it is bonded to its host and does not hang as cloth "
      "of its own",
      "piece POCKET (pocket) left out: it does not fit on FRONT where vgd puts a chest pocket (its top 4.0 cm "
      "above the bottom of the armhole, its middle 10.0 cm from centre front on the wearer's left); place it "
      "with a POSITION type=\"placement\" (docs/xvc.md)",
      "piece FRONT LINING (lining) left out: a lining hangs inside the garment as a garment of its own; "
      "drape it as one",
      "piece GUIDE left out: the file cuts it 0 times (a reference or an alternative)"};
  for (const auto& w : want)
    EXPECT_NE(std::find(p.decisions.begin(), p.decisions.end(), w), p.decisions.end()) << w;
  bool roles = false;
  for (const auto& d : p.decisions)
    roles = roles || d.find("roles from the pieces' names: FRONT front, BACK back") == 0;
  EXPECT_TRUE(roles);
}

}  // namespace vgd::dress

namespace vgd::dress {

// Two sleeve patterns drawn for one sleeve (a short and a full one, as in a
// Valentina shirt) are alternatives: without an armhole seam the first in
// the document is draped and the other left out, said.
TEST(PrepareGarment, AnAlternativeSleeveIsLeftOut) {
  pattern::Style s =
      one_size("MEN shirt", "50",
               {panel("FRONT", 0, 0.3, 0.6, "50"), panel("BACK", 1, 0.3, 0.6, "50"),
                panel("SHORTSLEEVE", 2, 0.4, 0.25, "50"), panel("FULLSLEEVE", 3, 0.4, 0.6, "50")});
  xvc::Document doc = xvc::from_style(s);
  const Preparation p = prepare_garment(doc);
  EXPECT_NE(std::find(p.pieces.begin(), p.pieces.end(), "SHORTSLEEVE"), p.pieces.end());
  EXPECT_EQ(std::find(p.pieces.begin(), p.pieces.end(), "FULLSLEEVE"), p.pieces.end());
  bool said = false;
  for (const auto& d : p.decisions)
    said = said ||
           d.find("piece FULLSLEEVE left out: an alternative to the sleeve SHORTSLEEVE") != std::string::npos;
  EXPECT_TRUE(said);
}

}  // namespace vgd::dress

namespace vgd::dress {

// Legs by elimination: leggings whose leg piece is named by a code (ORILEG's
// "LL", category "LENGTH OPTIONS"): a piece cut twice, of no role, in a
// garment with a waistband and no front, back or leg, is read as a leg,
// said, and written in the document as LEG in its category.
TEST(PrepareGarment, APieceCutTwiceBesideAWaistbandIsALeg) {
  pattern::Style s =
      one_size("ORILEG WB", "36",
               {panel("ORILEG WB WB", 0.0, 0.05, 0.7, "36"), panel("ORILEG WB LL", 1.0, 0.3, 0.9, "36")});
  s.pieces[1].quantity = 2;
  s.pieces[1].category = "LENGTH OPTIONS";
  xvc::Document doc = xvc::from_style(s);
  try {
    prepare_garment(doc);  // rectangles: no seam fits, nothing to drape; the roles are read first
  } catch (const Error&) {
  }
  const auto* leg = doc.patterns().back();
  EXPECT_EQ(leg->attribute("category"), "LENGTH OPTIONS LEG");
  EXPECT_EQ(xvc::piece_role(doc, *leg).role, pattern::Role::leg);
  // With a front in the garment, nothing is read by elimination.
  s.pieces.push_back(panel("FRONT", 2.0, 0.3, 0.5, "36"));
  xvc::Document other = xvc::from_style(s);
  try {
    prepare_garment(other);
  } catch (const Error&) {
  }
  EXPECT_EQ(other.patterns()[1]->attribute("category"), "LENGTH OPTIONS");
}

}  // namespace vgd::dress

namespace vgd::dress {

// A body file given instead of a mannequin: said as the body, no table or
// mannequin size chosen for it.
TEST(PrepareGarment, ABodyFileIsTheBodyNotAMannequin) {
  xvc::Document doc =
      xvc::from_style(one_size("WM TOP", "38", {panel("FRONT", 0.0, 0.5, 0.6, "38"), panel("BACK", 1.0, 0.5, 0.6, "38")}));
  PrepareOptions o;
  o.avatar = "scan.glb";
  const Preparation p = prepare_garment(doc, o);
  EXPECT_EQ(p.body_table, "");
  EXPECT_EQ(p.decisions.back(), "body: scan.glb (as asked), not a mannequin");
  for (const auto& d : p.decisions) EXPECT_EQ(d.find("mannequin of size"), std::string::npos) << d;
}

}  // namespace vgd::dress

namespace vgd::dress {

// Each pattern's role and whether it is draped are written in the document
// (attributes role and drape) where it says nothing yet; a designer's
// correction there is what the next run reads: a full sleeve chosen instead
// of the short one.
TEST(PrepareGarment, RolesAndPiecesToDrapeAreWrittenInTheDocumentAndCorrectedThere) {
  pattern::Style s =
      one_size("MEN shirt", "50",
               {panel("FRONT", 0, 0.3, 0.6, "50"), panel("BACK", 1, 0.3, 0.6, "50"),
                panel("SHORTSLEEVE", 2, 0.4, 0.25, "50"), panel("FULLSLEEVE", 3, 0.4, 0.6, "50"),
                panel("POCKET", 4, 0.15, 0.15, "50")});
  xvc::Document doc = xvc::from_style(s);
  const Preparation first = prepare_garment(doc);
  std::map<std::string, std::pair<std::string, std::string>> written;  // piece -> role, drape
  for (const auto* p : doc.patterns())
    written[std::string(p->attribute("piece"))] = {std::string(p->attribute("role")), std::string(p->attribute("drape"))};
  using RD = std::pair<std::string, std::string>;
  EXPECT_EQ(written["FRONT"], RD("front", "true"));
  EXPECT_EQ(written["BACK"], RD("back", "true"));
  EXPECT_EQ(written["SHORTSLEEVE"], RD("sleeve", "true"));
  EXPECT_EQ(written["FULLSLEEVE"], RD("sleeve", "false"));
  EXPECT_EQ(written["POCKET"], RD("pocket", "false"));
  const Diagnostics v = xvc::validate_string(xvc::save_string(doc), "shirt.xvc", xvc::default_schema_path());
  for (const auto& d : v.items()) ADD_FAILURE() << d.format();

  // Run again: the same choice, nothing more written.
  const Preparation same = prepare_garment(doc);
  EXPECT_EQ(same.pieces, first.pieces);
  EXPECT_TRUE(std::none_of(same.decisions.begin(), same.decisions.end(),
                           [](const std::string& d) { return d.find("written in the document") != std::string::npos; }));

  // The designer wants the full sleeve.
  for (const auto* p : doc.patterns()) {
    const std::string id(p->id()), piece(p->attribute("piece"));
    if (piece == "SHORTSLEEVE" || piece == "FULLSLEEVE") {
      xvc::SetAttribute set(id, "drape", piece == "FULLSLEEVE" ? "true" : "false");
      xvc::execute(doc, set);
    }
  }
  const Preparation corrected = prepare_garment(doc);
  EXPECT_NE(std::find(corrected.pieces.begin(), corrected.pieces.end(), "FULLSLEEVE"), corrected.pieces.end());
  EXPECT_EQ(std::find(corrected.pieces.begin(), corrected.pieces.end(), "SHORTSLEEVE"), corrected.pieces.end());
  EXPECT_NE(std::find(corrected.decisions.begin(), corrected.decisions.end(),
                      "piece SHORTSLEEVE (sleeve) left out: the document says drape=\"false\""),
            corrected.decisions.end());
  EXPECT_TRUE(corrected.missing.empty()) << "a piece the designer left out is not missing from the garment";
}

// A role set in the document is read instead of the name's words.
TEST(PrepareGarment, ARoleSetInTheDocumentIsReadInsteadOfTheName) {
  pattern::Style s = one_size("WM top", "38", {panel("PANEL 7", 0, 0.3, 0.6, "38")});
  xvc::Document doc = xvc::from_style(s);
  const std::string id(doc.patterns()[0]->id());
  EXPECT_EQ(xvc::piece_role(doc, *doc.patterns()[0]).role, pattern::Role::unknown);
  xvc::SetAttribute set(id, "role", "collar stand");
  xvc::execute(doc, set);
  EXPECT_EQ(xvc::piece_role(doc, *doc.patterns()[0]).role, pattern::Role::collar_stand);
  EXPECT_EQ(xvc::piece_role(doc, *doc.patterns()[0]).word, "role=\"collar stand\"");
  xvc::SetAttribute wrong(id, "role", "elbow");
  try {
    xvc::execute(doc, wrong);
    FAIL() << "a role that is none was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("role \"elbow\""), std::string::npos) << e.what();
  }

  // Half a sleeve by its name; set to a front, it is no sleeve's half.
  xvc::Document halves = xvc::from_style(one_size("WM top", "38", {panel("SLEEVE FRONT", 0, 0.2, 0.3, "38")}));
  EXPECT_EQ(xvc::piece_role(halves, *halves.patterns()[0]).half, pattern::Half::front);
  xvc::SetAttribute front(std::string(halves.patterns()[0]->id()), "role", "front");
  xvc::execute(halves, front);
  EXPECT_EQ(xvc::piece_role(halves, *halves.patterns()[0]).role, pattern::Role::front);
  EXPECT_EQ(xvc::piece_role(halves, *halves.patterns()[0]).half, pattern::Half::none);
}

// Fronts and backs as long as legs and wider at the waist, in trousers (the
// style's name, or a waistband), are the halves of trouser legs: role="leg"
// written, the half from the name, each cut as a left and a right copy. The
// same pieces in a dress stay a front and a back; a trouser half the file
// already cuts twice keeps its quantity.
TEST(PrepareGarment, FrontsAndBacksAsLongAsLegsAreTheHalvesOfTrouserLegs) {
  xvc::Document doc = xvc::from_style(vgd::test::trousers_in_halves());
  const Preparation p = prepare_garment(doc);
  for (const auto* pat : doc.patterns()) {
    SCOPED_TRACE(std::string(pat->attribute("piece")));
    EXPECT_EQ(pat->attribute("role"), "leg");
    EXPECT_EQ(pat->attribute("quantity"), "2");
    EXPECT_EQ(xvc::piece_role(doc, *pat).half,
              pat->attribute("piece") == "FRONT" ? pattern::Half::front : pattern::Half::back);
  }
  EXPECT_EQ(p.pieces, (std::vector<std::string>{"FRONT", "BACK"}));
  const Diagnostics v = xvc::validate_string(xvc::save_string(doc), "trousers.xvc", xvc::default_schema_path());
  for (const auto& d : v.items()) ADD_FAILURE() << d.format();
  // The body: by hip and crotch height.
  const bool said = std::any_of(p.decisions.begin(), p.decisions.end(),
                                [](const std::string& d) { return d.find("its inseam 62.3 cm") != std::string::npos; });
  EXPECT_TRUE(said) << "the body chosen by the trousers' inseam too";

  pattern::Style dress = vgd::test::trousers_in_halves();
  dress.name = "LONG DRESS";
  doc = xvc::from_style(dress);
  EXPECT_THROW(prepare_garment(doc), Error) << "a front and a back that no seam vgd finds sews";
  for (const auto* pat : doc.patterns()) {
    SCOPED_TRACE(std::string(pat->attribute("piece")));
    EXPECT_NE(xvc::piece_role(doc, *pat).role, pattern::Role::leg);
    EXPECT_EQ(pat->attribute("quantity"), "1");
  }

  doc = xvc::from_style(vgd::test::trousers_in_halves("FRONT", "BACK", 4));
  prepare_garment(doc);
  for (const auto* pat : doc.patterns()) EXPECT_EQ(pat->attribute("quantity"), "4");
}

// Gerber's tank with bindings (simple.DXF, size 36): the neck binding, a
// 3.8 cm strip cut long (67 cm along the edge sewn), is sewn round the
// neckline (58.5 cm), folded lengthwise, arranged round the neck, and
// trimmed square to the neckline when the garment is assembled: its seam as
// long as the neckline, its mesh 1.9 cm wide in two layers, its ends (one
// drawn slanted) both 1.9 cm and sewn to each other, with no warning. The
// armhole binding is left out saying what vgd does not sew yet.
TEST(PrepareGarment, ATanksNeckBindingIsSewnFoldedAndTrimmedToTheNeckline) {
  VGD_REQUIRE_SHARED();
  xvc::Document doc = shared_document("simple.DXF");
  const Preparation p = prepare_garment(doc);
  EXPECT_EQ(p.pieces, (std::vector<std::string>{"C-S1615WWO206-NB", "C-S1615WWO206-B", "C-S1615WWO206-F"}));
  EXPECT_EQ(p.left_out, (std::vector<std::string>{"C-S1615WWO206-AB"}));
  const auto said = [&](const std::string& what) {
    return std::any_of(p.decisions.begin(), p.decisions.end(),
                       [&](const std::string& d) { return d.find(what) != std::string::npos; });
  };
  EXPECT_TRUE(said("piece C-S1615WWO206-AB (binding) left out: no seam sews it: vgd sews a binding round a neckline"))
      << ::testing::PrintToString(p.decisions);
  EXPECT_TRUE(said("piece C-S1615WWO206-NB (binding) read as cut double and folded lengthwise"))
      << ::testing::PrintToString(p.decisions);
  for (const auto& [id, list] : xvc::suggest_arrangements(doc)) {
    const auto piece = doc.find(id)->attribute("piece");
    if (piece == "C-S1615WWO206-NB") {
      ASSERT_EQ(list.size(), 1u);
      EXPECT_EQ(list[0].segment, "neck") << "arranged round the neck";
    }
    if (piece == "C-S1615WWO206-AB") {
      EXPECT_TRUE(list.empty()) << "no seam sews it: not arranged";
    }
  }

  AssemblyOptions o;
  o.pieces = p.pieces;
  Diagnostics diag;
  const Garment g = assemble_garment(doc, o, diag);
  const GarmentPiece* nb = nullptr;
  for (const auto& gp : g.pieces)
    if (gp.name == "C-S1615WWO206-NB") nb = &gp;
  ASSERT_NE(nb, nullptr);
  EXPECT_EQ(nb->layers, 2);
  double x0 = 1e9, x1 = -1e9;
  for (const auto& n : nb->mesh.nodes) x0 = std::min(x0, n.x()), x1 = std::max(x1, n.x());
  EXPECT_NEAR(x1 - x0, 0.019, 0.001) << "half the strip's width";
  bool neck = false, ends = false;
  for (const auto& s : g.seams) {
    if (s.name == "binding ends") {
      ends = true;
      EXPECT_NEAR(s.length_a, 0.019, 1e-6) << "folded, cut square";
      EXPECT_NEAR(s.length_b, 0.019, 1e-6) << "folded, cut square";
    }
    if (s.name != "neck seam") continue;
    neck = true;
    EXPECT_NEAR(s.length_a, s.length_b, 0.002) << "the binding trimmed to the neckline";
    EXPECT_NEAR(s.length_b, 0.585, 0.001);
  }
  EXPECT_TRUE(neck);
  EXPECT_TRUE(ends) << "its ends sewn to each other at centre back";
  bool trimmed = false;
  for (const auto& d : diag.items())
    trimmed = trimmed || d.message.find("binding C-S1615WWO206-NB trimmed by 8.5 cm to the 58.5 cm it binds") !=
                             std::string::npos;
  EXPECT_TRUE(trimmed);
  // The seam sewing its ends to each other is not a seam it binds: no warning
  // that the strip is longer than it and cannot be trimmed.
  for (const auto& d : diag.items())
    EXPECT_EQ(d.message.find("not a straight strip vgd can trim"), std::string::npos) << d.message;
}

}  // namespace vgd::dress


namespace vgd::dress {

// A front drawn again for another version of the style, named as a part
// (Gerber's "FR CO 1", category FRONT HALF CO: the front cut for the half
// collar) is read by its size as a front, written in the document, and left
// out as the front's alternative: not a piece the garment lacks. A piece no
// larger than a collar keeps its name's role.
TEST(PrepareGarment, AFrontNamedAsACollarIsReadByItsSizeAsAnAlternativeFront) {
  pattern::Style s = one_size("WM TOP", "38",
                              {panel("FRONT", 0.0, 0.5, 0.6, "38"), panel("BACK", 1.0, 0.5, 0.6, "38"),
                               panel("FR COLLAR 1", 2.0, 0.5, 0.6, "38"), panel("COLLAR", 3.0, 0.45, 0.08, "38")});
  xvc::Document doc = xvc::from_style(s);
  const Preparation p = prepare_garment(doc);
  EXPECT_EQ(p.pieces, (std::vector<std::string>{"FRONT", "BACK"}));
  const auto said = [&](const std::string& what) {
    return std::any_of(p.decisions.begin(), p.decisions.end(),
                       [&](const std::string& d) { return d.find(what) != std::string::npos; });
  };
  EXPECT_TRUE(said("piece FR COLLAR 1 read as a front, not a collar: its outline is as large as the front FRONT's "
                   "(60.0 x 50.0 cm, 3000 cm²; the front's 60.0 x 50.0 cm, 3000 cm²)"))
      << ::testing::PrintToString(p.decisions);
  EXPECT_TRUE(said("piece FR COLLAR 1 (front) left out: an alternative to the front FRONT"))
      << ::testing::PrintToString(p.decisions);
  EXPECT_FALSE(said("piece COLLAR read as")) << ::testing::PrintToString(p.decisions);
  for (const auto& m : p.missing) EXPECT_EQ(m.find("FR COLLAR 1"), std::string::npos) << m;
  for (const auto* pat : doc.patterns())
    if (pat->attribute("piece") == "FR COLLAR 1") {
      EXPECT_EQ(pat->attribute("role"), "front");
    }
}

// Gerber's GMG1016S19 (mirrored.DXF) is drawn with four finishes of one
// neckline: a rib collar and three collar sets (half, full and self collar:
// lower and upper collars, stands), and with a front for the half collar.
// The rib collar is sewn round the neckline; every other collar and stand is
// its alternative, and the front for the half collar the front's: none is a
// piece the garment is draped without, nor are its plackets (YP sewn onto the
// front, YL under it).
TEST(PrepareGarment, CollarSetsBesideASewnNeckbandAreAlternativeFinishesOfTheNeckline) {
  VGD_REQUIRE_SHARED();
  xvc::Document doc = shared_document("mirrored.DXF");
  const Preparation p = prepare_garment(doc);
  const auto said = [&](const std::string& what) {
    return std::count_if(p.decisions.begin(), p.decisions.end(),
                         [&](const std::string& d) { return d.find(what) != std::string::npos; });
  };
  EXPECT_EQ(said("left out: an alternative finish of the neckline, which the neckband GMG1016S19-CO 3 finishes "
                 "(sewn by the seam 'neck seam')"),
            8)
      << ::testing::PrintToString(p.decisions);
  for (const std::string piece : {"CO L 1", "CO L 2", "CO L 4", "CO U 1", "CO U 2", "CO U 4"})
    EXPECT_EQ(said("piece GMG1016S19-" + piece + " (collar) left out: an alternative finish of the neckline"), 1)
        << piece;
  for (const std::string piece : {"CO ST 1", "CO ST 2"})
    EXPECT_EQ(said("piece GMG1016S19-" + piece + " (collar stand) left out: an alternative finish of the neckline"), 1)
        << piece;
  EXPECT_EQ(said("piece GMG1016S19-FR CO 1 read as a front, not a collar"), 1) << ::testing::PrintToString(p.decisions);
  EXPECT_EQ(said("piece GMG1016S19-FR CO 1 (front) left out: an alternative to the front GMG1016S19-FR"), 1);
  EXPECT_TRUE(p.missing.empty()) << ::testing::PrintToString(p.missing);
  EXPECT_NE(std::find(p.pieces.begin(), p.pieces.end(), "GMG1016S19-YP"), p.pieces.end());
  EXPECT_NE(std::find(p.pieces.begin(), p.pieces.end(), "GMG1016S19-CO 3"), p.pieces.end());
  EXPECT_NE(std::find(p.pieces.begin(), p.pieces.end(), "GMG1016S19-FR"), p.pieces.end());
}

}  // namespace vgd::dress
