// Arrangements: suggested from piece names, stored as POSITION type="arrangement",
// valid against the schema and vgd's rules, editable and undoable.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "shared_style.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/pattern/draft.hpp"
#include "vgd/xvc/arrangement.hpp"
#include "vgd/xvc/commands.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/seams.hpp"
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

// A piece turned part of the way round its segment: SIDE±DEG on the command
// line is `around`, written and read back, valid against the schema and the
// rules; on a notch it is refused like every arrangement attribute; a turn
// that is not a number is refused naming it.
TEST(Arrangement, APieceTurnedPastItsSideKeepsTheTurn) {
  Document doc = from_style(pattern::draft_tshirt_style({pattern::TShirtMeasurements{}}));
  const std::string id(doc.patterns()[0]->id());
  const auto piece = to_piece(doc, id);
  const auto a = parse_arrangement("torso:left-20:1.3", piece);
  EXPECT_EQ(a.side, "left");
  EXPECT_DOUBLE_EQ(a.around_deg, -20.0);
  EXPECT_DOUBLE_EQ(parse_arrangement("torso:front+32.5:1.3", piece).around_deg, 32.5);
  EXPECT_DOUBLE_EQ(parse_arrangement("torso:front:1.3", piece).around_deg, 0.0);
  EXPECT_THROW(parse_arrangement("torso:front+x:1.3", piece), Error);
  execute(doc, *std::make_unique<SetArrangements>(id, std::vector{a}));
  EXPECT_FALSE(check(doc).has_errors());
  const auto text = save_string(doc);
  EXPECT_EQ(validate_string(text, "turned.xvc", default_schema_path()).count(vgd::Severity::error), 0u);
  const auto back = arrangements_of(*load_string(text, "turned.xvc").find(id));
  ASSERT_EQ(back.size(), 1u);
  EXPECT_DOUBLE_EQ(back[0].around_deg, -20.0);
  EXPECT_EQ(back[0].side, "left");
  Node notch{"POSITION", {{"type", "notch"}, {"x", "0"}, {"y", "0"}, {"around", "10"}}, {}};
  EXPECT_THROW(execute(doc, *std::make_unique<AddNode>(id, notch)), Error);
}

// A sleeve cut in two: each half on its own side of each arm, and a back half
// that reaches 5 cm above the top of the seam it shares with the front half
// (a tab past the shoulder point, as in MEN_CLASSIC_TEE) goes 5 cm further up
// the arm, so that the seam's two tops start level.
TEST(Arrangement, SleeveHalvesOnTheirSidesAndLevelAlongTheirSeam) {
  pattern::Style s;
  s.name = "halves";
  s.sample_size = "M";
  s.sizes = {"M"};
  const auto half = [](const std::string& name, std::vector<pattern::Vec2> pts) {
    pattern::Piece p;
    p.name = name;
    p.block = name + "_M";
    p.size = "M";
    p.quantity = 2;
    for (const auto& q : pts) p.boundary.push_back({q, pattern::PointKind::turn});
    p.grain_line = pattern::Segment{pattern::Vec2(0, 0.05), pattern::Vec2(0, 0.25)};
    return p;
  };
  // Front: its over-arm edge (0,0)->(0,0.30) on the right, the top of the piece.
  s.pieces.push_back(half("SLEEVE FRONT", {{-0.15, 0}, {0, 0}, {0, 0.30}, {-0.15, 0.20}}));
  // Back: its over-arm edge (0,0.30)->(0,0) on the left, a tab up to 0.35 beside it.
  s.pieces.push_back(half("SLEEVE BACK", {{0, 0}, {0.15, 0}, {0.15, 0.20}, {0.02, 0.35}, {0, 0.30}}));
  // A graded size L with no seams of its own: 10 % longer, its tab as high.
  s.sizes.push_back("L");
  for (int k = 0; k < 2; ++k) {
    pattern::Piece l = s.pieces[k];
    l.size = "L";
    l.block = l.name + "_L";
    for (auto& c : l.boundary) c.p.y() *= 1.1;
    s.pieces.push_back(l);
  }
  Document doc = from_style(s);
  const auto f = doc.patterns()[0], b = doc.patterns()[1];
  const auto fs = boundary_stretches(*f), bs = boundary_stretches(*b);
  HemRef fh{std::string(f->id()), fs[1].id, fs[1].id, false, 0.30, 0};
  HemRef bh{std::string(b->id()), bs[4].id, bs[4].id, true, 0.30, 0};

  // Without the seam, both hang by their tops.
  auto arranged = suggest_arrangements(doc);
  ASSERT_EQ(arranged.size(), 4u);
  ASSERT_EQ(arranged[0].second.size(), 2u);
  ASSERT_EQ(arranged[1].second.size(), 2u);
  const double top = arranged[0].second[0].height;
  EXPECT_EQ(arranged[1].second[0].height, top);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(arranged[0].second[k].side, "front");
    EXPECT_EQ(arranged[1].second[k].side, "back");
  }
  EXPECT_EQ(arranged[0].second[0].segment, "right-arm");
  EXPECT_EQ(arranged[0].second[1].segment, "left-arm");
  // The over-arm edge (from the piece's highest point) outside the arm: at the
  // front of the right arm the pattern's +u runs to the body's left, inside,
  // so the front half (over-arm on +u) is flipped there; at the back +u runs
  // outside, so the back half (over-arm on -u) is flipped too; each left copy
  // is the mirror.
  EXPECT_TRUE(arranged[0].second[0].flip);
  EXPECT_FALSE(arranged[0].second[1].flip);
  EXPECT_TRUE(arranged[1].second[0].flip);
  EXPECT_FALSE(arranged[1].second[1].flip);

  execute(doc, *std::make_unique<AddSeams>(std::vector<Node>{seam_node("over-arm seam", {fh, bh})}));
  arranged = suggest_arrangements(doc);
  EXPECT_EQ(arranged[0].second[0].height, top);
  EXPECT_NEAR(arranged[1].second[0].height, top - 0.05, 1e-12) << "5 cm further up the arm";
  EXPECT_NEAR(arranged[1].second[1].height, top - 0.05, 1e-12);
  EXPECT_EQ(arranged[2].second[0].height, top) << "size L's front half";
  EXPECT_NEAR(arranged[3].second[0].height, top - 0.055, 1e-12) << "size L's back half, by the sample's seam";
}

// A shirt's yoke hangs on the torso's back like a back, its top at the neck
// point's height (with the bodice lift); the back sewn below it hangs from
// the yoke's lowest point: as much lower as the yoke is high (12 cm here).
// In a lower-body garment a yoke is not placed by rule.
TEST(Arrangement, ABackHangsBelowItsSizesYoke) {
  auto style = pattern::draft_tshirt_style({pattern::TShirtMeasurements{}});
  const std::string size = style.pieces[0].size;
  pattern::Piece yoke;
  yoke.block = "YOKE_" + size;
  yoke.name = "YOKE";
  yoke.size = size;
  yoke.quantity = 1;
  yoke.boundary = {{pattern::Vec2(2.0, 0)}, {pattern::Vec2(2.4, 0)}, {pattern::Vec2(2.4, 0.10)},
                   {pattern::Vec2(2.25, 0.12)}, {pattern::Vec2(2.15, 0.12)}, {pattern::Vec2(2.0, 0.10)}};
  const Document plain = from_style(style);
  style.pieces.push_back(yoke);
  const Document doc = from_style(style);
  const auto heights = [](const Document& d) {
    std::map<std::string, Arrangement> by_piece;
    for (const auto& [id, list] : suggest_arrangements(d))
      if (!list.empty()) by_piece[std::string(d.find(id)->attribute("piece"))] = list.front();
    return by_piece;
  };
  const auto before = heights(plain), after = heights(doc);
  ASSERT_TRUE(after.count("YOKE"));
  const Arrangement& y = after.at("YOKE");
  EXPECT_EQ(y.segment, "torso");
  EXPECT_EQ(y.side, "back");
  const ArrangementOptions o;
  EXPECT_NEAR(y.height, o.neck_point_height + o.bodice_lift, 1e-12);
  std::string back;
  for (const auto& [name, a] : before)
    if (a.side == "back" && a.segment == "torso") back = name;
  ASSERT_FALSE(back.empty());
  EXPECT_NEAR(after.at(back).height, before.at(back).height - 0.12, 1e-12);
  for (const auto& [name, a] : before)
    if (name != back) {
      EXPECT_NEAR(after.at(name).height, a.height, 1e-12) << name;
    }
  EXPECT_TRUE(suggest_arrangement(yoke, true).empty());
}

// A rib cuff cut twice beside a sleeve cut twice: sewn by its long edge to
// each copy's hem (the right sleeve's first), its ends under the arm, and
// arranged on each arm at the sleeve's hem: the sleeve's own height down the
// arm plus its length. A cuff no seam sews is not placed.
TEST(Arrangement, ACuffGoesOnAtItsSleevesHem) {
  auto style = pattern::draft_tshirt_style({pattern::TShirtMeasurements{}});
  std::vector<pattern::Piece> kept;
  for (auto& p : style.pieces) {
    if (p.name == "RIGHT SLEEVE") continue;
    if (p.name == "LEFT SLEEVE") p.name = "SLEEVE", p.block = "SLEEVE_" + p.size, p.quantity = 2;
    kept.push_back(p);
  }
  pattern::Piece cuff;
  cuff.name = "CUFF";
  cuff.size = kept.front().size;
  cuff.block = "CUFF_" + cuff.size;
  cuff.quantity = 2;
  for (const auto& q : {pattern::Vec2(3.0, 0), pattern::Vec2(3.05, 0), pattern::Vec2(3.05, 0.25), pattern::Vec2(3.0, 0.25)})
    cuff.boundary.push_back({q, pattern::PointKind::turn});
  kept.push_back(cuff);
  style.pieces = kept;
  const Document bare = from_style(style);
  std::vector<Node> seams;
  std::vector<std::string> names;
  for (const auto& x : suggest_seams(bare)) {
    seams.push_back(seam_node(x));
    names.push_back(x.name);
  }
  const auto at = [&](const std::string& n) { return std::find(names.begin(), names.end(), n) - names.begin(); };
  ASSERT_LT(at("right cuff"), static_cast<long>(names.size()));
  EXPECT_LT(at("right cuff"), at("left cuff"));
  EXPECT_LT(at("right cuff ends"), at("left cuff ends"));
  ASSERT_LT(at("left cuff ends"), static_cast<long>(names.size()));
  Document doc = bare;
  execute(doc, *std::make_unique<AddSeams>(std::move(seams)));
  std::map<std::string, std::vector<Arrangement>> by_piece;
  for (const auto& [id, list] : suggest_arrangements(doc)) by_piece[std::string(doc.find(id)->attribute("piece"))] = list;
  const auto& sl = by_piece.at("SLEEVE");
  const auto& cf = by_piece.at("CUFF");
  ASSERT_EQ(cf.size(), 2u);
  ASSERT_EQ(sl.size(), 2u);
  EXPECT_EQ(cf[0].segment, "right-arm");
  EXPECT_EQ(cf[1].segment, "left-arm");
  EXPECT_FALSE(cf[0].flip);
  EXPECT_TRUE(cf[1].flip);
  EXPECT_NEAR(cf[0].angle_deg, -90.0, 1e-12);  // drawn upright: turned to go round the arm
  std::string sleeve_id;
  for (const Node* p : doc.patterns())
    if (p->attribute("piece") == "SLEEVE") sleeve_id = std::string(p->id());
  ASSERT_FALSE(sleeve_id.empty());
  const pattern::Piece sleeve = to_piece(doc, sleeve_id);
  double lo = 1e300, hi = -1e300;
  const double a = sl[0].angle_deg * M_PI / 180.0;
  for (const auto& c : sleeve.boundary) {
    const double y = std::sin(a) * c.p.x() + std::cos(a) * c.p.y();
    lo = std::min(lo, y), hi = std::max(hi, y);
  }
  EXPECT_NEAR(cf[0].height, sl[0].height + (hi - lo), 1e-9);
  EXPECT_NEAR(cf[1].height, cf[0].height, 1e-12);
  for (const auto& [id, list] : suggest_arrangements(bare)) {
    if (bare.find(id)->attribute("piece") == "CUFF") {
      EXPECT_TRUE(list.empty());
    }
  }
}


// A polo's collar goes round the neck centred at the back (its ends at
// centre front), by the edge its seam sews to the neckline: the collar is
// drawn with that edge (the curved, notched one) on the left, which turning
// a band a quarter clockwise would put at the top, so it is turned half
// round; with no seam it is turned as any band.
TEST(Arrangement, APolosCollarGoesOnByTheEdgeSewnToTheNeckline) {
  VGD_REQUIRE_SHARED();
  const auto [bare, sample] = vgd::test::shared_style("drill-holes.DXF");
  std::vector<Node> seams;
  std::optional<SeamSuggestion> collar;
  for (const auto& s : suggest_seams(bare, sample)) {
    seams.push_back(seam_node(s));
    if (s.name == "collar seam") collar = s;
  }
  ASSERT_TRUE(collar);
  Document doc = bare;
  execute(doc, *std::make_unique<AddSeams>(std::move(seams)));
  const auto arranged = [](const Document& d) {
    std::map<std::string, std::vector<Arrangement>> out;
    for (const auto& [id, list] : suggest_arrangements(d))
      if (d.find(id)->attribute("size") == "50") out[std::string(d.find(id)->attribute("piece"))] = list;
    return out;
  };
  const auto unsewn = arranged(bare).at("SS17_M POLO REG CO");
  ASSERT_EQ(unsewn.size(), 1u);
  EXPECT_NEAR(unsewn[0].angle_deg, -90.0, 1e-12);
  const auto sewn = arranged(doc).at("SS17_M POLO REG CO");
  ASSERT_EQ(sewn.size(), 1u);
  EXPECT_EQ(sewn[0].segment, "neck");
  EXPECT_EQ(sewn[0].side, "back");
  EXPECT_NEAR(sewn[0].angle_deg, 90.0, 1e-12);
  // The sewn edge is now the bottom: its points lie lowest as arranged.
  const std::string id = collar->hems[0].pattern;
  const pattern::Piece piece = to_piece(doc, id);
  const auto st = boundary_stretches(*doc.find(id));
  std::size_t from = 0, to = 0;
  for (std::size_t k = 0; k < st.size(); ++k) {
    if (st[k].id == collar->hems[0].from) from = st[k].first;
    if (st[k].id == collar->hems[0].to) to = k + 1 < st.size() ? st[k + 1].first : 0;
  }
  const double a = sewn[0].angle_deg * M_PI / 180.0;
  const auto up = [&](const pattern::Vec2& p) { return std::sin(a) * p.x() + std::cos(a) * p.y(); };
  double lo = 1e300, hi = -1e300, edge = 0;
  int n = 0;
  for (const auto& c : piece.boundary) lo = std::min(lo, up(c.p)), hi = std::max(hi, up(c.p));
  for (std::size_t i = from;; i = (i + 1) % piece.boundary.size()) {
    edge += up(piece.boundary[i].p), ++n;
    if (i == to) break;
  }
  EXPECT_LT(edge / n - lo, 0.1 * (hi - lo)) << "the sewn edge lies in the bottom tenth of the collar's height";
  // Its reference point is the top's middle: the edge sewn sits a whole collar below it.
  EXPECT_NEAR(up(pattern::Vec2(sewn[0].x, sewn[0].y)), hi, 1e-9);
}

// A shirt's stand goes round the neck as a collar does (centred at the back,
// its sewn lower edge at the neck point); the collar sewn to the stand's top
// is turned down over it: reflected top to bottom (its sewn edge at the top,
// its drawing's left end on the stand's left, as the seam pairs them), its
// top at the stand's, 1 cm further out. Valentina's shirt, its halves unfolded.
TEST(Arrangement, AShirtsCollarIsTurnedDownOverItsStand) {
  VGD_REQUIRE_SHARED();
  auto [doc, at_base] = vgd::test::shared_style_halves_unfolded("Valentina_MaleShirt_AAMA_R12.dxf");
  std::vector<Node> seams;
  std::optional<SeamSuggestion> collar;
  for (const auto& s : suggest_seams(doc, at_base)) {
    seams.push_back(seam_node(s));
    if (s.name == "collar seam") collar = s;
  }
  ASSERT_TRUE(collar);
  execute(doc, *std::make_unique<AddSeams>(std::move(seams)));
  std::map<std::string, std::vector<Arrangement>> arranged;
  for (const auto& [id, list] : suggest_arrangements(doc)) arranged[std::string(doc.find(id)->attribute("piece"))] = list;
  const ArrangementOptions defaults;
  const auto& stand = arranged.at("COLLARBASE");
  ASSERT_EQ(stand.size(), 1u);
  EXPECT_EQ(stand[0].segment, "neck");
  EXPECT_EQ(stand[0].side, "back");
  EXPECT_FALSE(stand[0].flip);
  const pattern::Piece sp = to_piece(doc, collar->hems[1].pattern), cp = to_piece(doc, collar->hems[0].pattern);
  const auto height_of = [](const pattern::Piece& p, double angle_deg) {
    const double a = angle_deg * M_PI / 180.0;
    double lo = 1e300, hi = -1e300;
    for (const auto& c : p.boundary) {
      const double y = std::sin(a) * c.p.x() + std::cos(a) * c.p.y();
      lo = std::min(lo, y), hi = std::max(hi, y);
    }
    return hi - lo;
  };
  EXPECT_NEAR(stand[0].height, defaults.neck_point_height + height_of(sp, stand[0].angle_deg), 1e-9);
  const auto& top = arranged.at("COLLARTOP");
  ASSERT_EQ(top.size(), 1u);
  EXPECT_EQ(top[0].segment, "neck");
  EXPECT_EQ(top[0].side, "back");
  EXPECT_TRUE(top[0].flip);
  EXPECT_NEAR(std::abs(top[0].angle_deg), 180.0, 1e-12) << "drawn with its neck edge at the bottom";
  EXPECT_NEAR(top[0].height, stand[0].height, 1e-12);
  EXPECT_NEAR(top[0].clearance, stand[0].clearance + 0.01, 1e-12);
  // The sewn edge is at the top as arranged: on average in the top fifth of
  // the collar's height (the collar's up is -y once turned; the edge curves).
  double lo = 1e300, hi = -1e300;
  for (const auto& c : cp.boundary) lo = std::min(lo, -c.p.y()), hi = std::max(hi, -c.p.y());
  const auto st = boundary_stretches(*doc.find(collar->hems[0].pattern));
  std::size_t from = 0, to = 0;
  for (std::size_t k = 0; k < st.size(); ++k) {
    if (st[k].id == collar->hems[0].from) from = st[k].first;
    if (st[k].id == collar->hems[0].to) to = k + 1 < st.size() ? st[k + 1].first : 0;
  }
  double edge = 0;
  int n = 0;
  for (std::size_t i = from;; i = (i + 1) % cp.boundary.size()) {
    edge += -cp.boundary[i].p.y(), ++n;
    if (i == to) break;
  }
  EXPECT_GT(edge / n - lo, 0.8 * (hi - lo)) << "the sewn edge lies in the collar's top fifth as arranged";
}
