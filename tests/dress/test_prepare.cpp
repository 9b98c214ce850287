// Getting a pattern document ready to drape: seams suggested when it has
// none, pieces no seam sews left out, the body's size table from the style.
#include <gtest/gtest.h>

#include "vgd/core/diagnostics.hpp"
#include "vgd/dress/prepare.hpp"
#include "vgd/xvc/seams.hpp"
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
  for (const auto& q : std::vector<Vec2>{{x0, 0}, {x0 + w, 0}, {x0 + w, h}, {x0, h}}) p.boundary.push_back({q, PointKind::turn});
  p.grain_line = pattern::Segment{Vec2(x0 + w / 2, 0.1), Vec2(x0 + w / 2, h - 0.1)};
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
  pattern::Style s;
  s.name = "WM TOP";
  s.sample_size = "M";
  s.sizes = {"M"};
  s.pieces = {panel("FRONT", 0.0, 0.30, 0.50), panel("BACK", 1.0, 0.30, 0.50), panel("LABEL", 2.0, 0.04, 0.02)};
  xvc::Document doc = xvc::from_style(s);
  ASSERT_TRUE(xvc::list_seams(doc).empty());
  const Preparation p = prepare_garment(doc);
  EXPECT_EQ(p.size, "M");
  EXPECT_GE(p.seams_added, 2);
  EXPECT_EQ(static_cast<int>(xvc::list_seams(doc).size()), p.seams_added) << "the seams are in the document";
  EXPECT_EQ(p.pieces, (std::vector<std::string>{"FRONT", "BACK"}));
  EXPECT_EQ(p.left_out, (std::vector<std::string>{"LABEL"}));
  EXPECT_EQ(p.body_table, "en13402-women");
  EXPECT_EQ(p.body_size, "42") << "a letter size the table lacks: its middle row (32 to 50: the sixth of ten)";
  bool label = false, body = false, seam = false;
  for (const auto& d : p.decisions) {
    label = label || d == "piece LABEL left out: no seam sews it";
    body = body || d.find("from en13402-women (the style's name 'WM TOP'; the table has no size 'M'") != std::string::npos;
    seam = seam || d.find("suggested at size M: FRONT to BACK") != std::string::npos;
  }
  EXPECT_TRUE(label && body && seam);

  // Run again on the document it wrote: its seams are kept, nothing added.
  const Preparation again = prepare_garment(doc);
  EXPECT_EQ(again.seams_added, 0);
  EXPECT_EQ(again.pieces, p.pieces);
}

TEST(PrepareGarment, NothingToDrapeIsAnErrorNamingThePieces) {
  pattern::Style s;
  s.name = "parts";
  s.sample_size = "M";
  s.sizes = {"M"};
  s.pieces = {panel("PART A", 0.0, 0.30, 0.50), panel("PART B", 1.0, 0.05, 0.07)};
  xvc::Document doc = xvc::from_style(s);
  try {
    prepare_garment(doc);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("nothing to drape"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("PART A, PART B"), std::string::npos) << e.what();
  }
  PrepareOptions wrong;
  wrong.size = "XL";
  EXPECT_THROW(prepare_garment(doc, wrong), Error);
}

}  // namespace vgd::dress

namespace vgd::dress {

// A style with only a base size (Valentina): the men's table has no size
// "base", so the mannequin is the table's middle size, and that is said.
TEST(PrepareGarment, ABaseSizeDrapesOnTheTablesMiddleSize) {
  pattern::Style s;
  s.name = "MEN shirt";
  s.sample_size = "base";
  s.sizes = {"base"};
  s.pieces = {panel("FRONT", 0.0, 0.3, 0.5, "base"), panel("BACK", 1.0, 0.3, 0.5, "base")};
  xvc::Document doc = xvc::from_style(s);
  const Preparation p = prepare_garment(doc);
  EXPECT_EQ(p.size, "base");
  EXPECT_EQ(p.body_table, "en13402-men");
  EXPECT_EQ(p.body_size, "52") << "en13402-men has 44 to 58: its middle row";
  bool said = false;
  for (const auto& d : p.decisions) said = said || d.find("the table has no size 'base': its middle size") != std::string::npos;
  EXPECT_TRUE(said);
  PrepareOptions asked;
  asked.body_size = "48";
  EXPECT_EQ(prepare_garment(doc, asked).body_size, "48");
}

}  // namespace vgd::dress

namespace vgd::dress {

// Two sleeve patterns drawn for one sleeve (a short and a full one, as in a
// Valentina shirt) are alternatives: without an armhole seam the first in
// the document is draped and the other left out, said.
TEST(PrepareGarment, AnAlternativeSleeveIsLeftOut) {
  pattern::Style s;
  s.name = "MEN shirt";
  s.sample_size = "50";
  s.sizes = {"50"};
  s.pieces = {panel("FRONT", 0, 0.3, 0.6, "50"), panel("BACK", 1, 0.3, 0.6, "50"), panel("SHORTSLEEVE", 2, 0.4, 0.25, "50"),
              panel("FULLSLEEVE", 3, 0.4, 0.6, "50")};
  xvc::Document doc = xvc::from_style(s);
  const Preparation p = prepare_garment(doc);
  EXPECT_NE(std::find(p.pieces.begin(), p.pieces.end(), "SHORTSLEEVE"), p.pieces.end());
  EXPECT_EQ(std::find(p.pieces.begin(), p.pieces.end(), "FULLSLEEVE"), p.pieces.end());
  bool said = false;
  for (const auto& d : p.decisions)
    said = said || d.find("piece FULLSLEEVE left out: an alternative to the sleeve SHORTSLEEVE") != std::string::npos;
  EXPECT_TRUE(said);
}

}  // namespace vgd::dress
