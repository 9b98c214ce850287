// Arrangements: suggested from piece names, stored as POSITION type="arrangement",
// valid against the schema and vgd's rules, editable and undoable.
#include <gtest/gtest.h>

#include "vgd/core/diagnostics.hpp"
#include "vgd/pattern/draft.hpp"
#include "vgd/xvc/arrangement.hpp"
#include "vgd/xvc/commands.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/style.hpp"
#include "vgd/xvc/validate.hpp"

using namespace vgd;
using namespace vgd::xvc;

TEST(Arrangement, SuggestedFromNames) {
  const auto tee = pattern::draft_tshirt(pattern::TShirtMeasurements{});
  const auto f = suggest_arrangement(tee[0], false), b = suggest_arrangement(tee[1], false);
  const auto l = suggest_arrangement(tee[2], false), r = suggest_arrangement(tee[3], false);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].segment, "torso");
  EXPECT_EQ(f[0].side, "front");
  EXPECT_EQ(b[0].side, "back");
  EXPECT_EQ(l[0].segment, "left-arm");
  EXPECT_EQ(r[0].segment, "right-arm");
  EXPECT_FALSE(l[0].flip);
  // The reference point is the top centre of the piece: the front's neck-point level.
  EXPECT_NEAR(f[0].x, 0.0, 1e-12);
  EXPECT_NEAR(f[0].y, pattern::TShirtMeasurements{}.length, 1e-12);
  EXPECT_EQ(f[0].angle_deg, 0.0);
  const auto skirt = pattern::draft_skirt(pattern::SkirtMeasurements{});
  EXPECT_EQ(suggest_arrangement(skirt[0], true)[0].segment, "hips");
  EXPECT_EQ(suggest_arrangement(skirt[2], true)[0].segment, "hips");
  // One sleeve cut twice: right arm, and the left arm mirrored.
  pattern::Piece sleeve = tee[2];
  sleeve.name = "SLEEVE";
  sleeve.quantity = 2;
  const auto two = suggest_arrangement(sleeve, false);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[0].segment, "right-arm");
  EXPECT_EQ(two[1].segment, "left-arm");
  EXPECT_TRUE(two[1].flip);
  // A piece lying sideways (grain along +x) is turned upright by 90°.
  pattern::Piece side = tee[0];
  side.grain_line = pattern::Segment{pattern::Vec2(0, 0), pattern::Vec2(1, 0)};
  EXPECT_NEAR(suggest_arrangement(side, false)[0].angle_deg, 90.0, 1e-12);
}

TEST(Arrangement, StoredValidatedEditedAndUndone) {
  Document doc = from_style(pattern::draft_tshirt_style({pattern::TShirtMeasurements{}}));
  const Document before = doc;
  UndoStack stack(doc);
  for (const auto& [id, list] : suggest_arrangements(doc)) stack.execute(std::make_unique<SetArrangements>(id, list));
  EXPECT_FALSE(check(doc).has_errors());
  const auto text = save_string(doc);
  EXPECT_EQ(validate_string(text, "tee.xvc", default_schema_path()).count(vgd::Severity::error), 0u) << text.substr(0, 2000);
  const Node* front = doc.patterns()[0];
  auto a = arrangements_of(*front);
  ASSERT_EQ(a.size(), 1u);
  EXPECT_EQ(a[0].side, "front");
  // Edit: move the front 5 cm lower; undo restores it.
  a[0].height -= 0.05;
  stack.execute(std::make_unique<SetArrangements>(std::string(front->id()), a));
  EXPECT_NEAR(arrangements_of(*doc.patterns()[0])[0].height, a[0].height, 1e-15);
  stack.undo();
  EXPECT_NEAR(arrangements_of(*doc.patterns()[0])[0].height, a[0].height + 0.05, 1e-15);
  while (stack.can_undo()) stack.undo();
  EXPECT_EQ(doc, before);
  // The round trip through text keeps every attribute.
  const Document again = load_string(text, "tee.xvc");
  EXPECT_EQ(arrangements_of(*again.patterns()[2])[0].segment, "left-arm");
}

TEST(Arrangement, RulesRefuseIncompleteOrMisplacedArrangements) {
  Document doc = from_style(pattern::draft_tshirt_style({pattern::TShirtMeasurements{}}));
  Node bad{"POSITION", {{"type", "arrangement"}, {"x", "0"}, {"y", "0"}, {"segment", "torso"}}, {}};
  EXPECT_THROW(execute(doc, *std::make_unique<AddNode>(std::string(doc.patterns()[0]->id()), bad)), Error);
  Node notch{"POSITION", {{"type", "notch"}, {"x", "0"}, {"y", "0"}, {"height", "1"}}, {}};
  EXPECT_THROW(execute(doc, *std::make_unique<AddNode>(std::string(doc.patterns()[0]->id()), notch)), Error);
  const auto piece = to_piece(doc, doc.patterns()[0]->id());
  EXPECT_THROW(parse_arrangement("torso:up:1.2", piece), Error);
  EXPECT_THROW(parse_arrangement("torso:front", piece), Error);
  const auto a = parse_arrangement("torso:front:1.25:0.02:0:flip", piece);
  EXPECT_EQ(a.height, 1.25);
  EXPECT_EQ(a.clearance, 0.02);
  EXPECT_TRUE(a.flip);
}
