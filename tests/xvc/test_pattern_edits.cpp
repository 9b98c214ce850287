#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <set>

#include "fixtures.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/pattern/contour.hpp"
#include "vgd/xvc/arrangement.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/validate.hpp"

using namespace vgd::xvc;
using namespace vgd::xvc::test;
using vgd::pattern::Piece;

namespace {
// Boundary points of each stretch plus the point its edge runs to (next stretch's first).
std::map<std::string, std::vector<Vec2>> stretch_edges(const Document& doc, const std::string& pattern_id) {
  const Piece pc = to_piece(doc, pattern_id);
  const auto st = boundary_stretches(*doc.find(pattern_id));
  std::map<std::string, std::vector<Vec2>> out;
  for (std::size_t k = 0; k < st.size(); ++k) {
    auto& pts = out[st[k].id];
    for (std::size_t i = 0; i <= st[k].count; ++i) pts.push_back(pc.boundary[(st[k].first + i) % pc.boundary.size()].p);
  }
  return out;
}

// Same points in any order, within `tol`.
bool same_point_set(std::vector<Vec2> a, std::vector<Vec2> b, double tol = 1e-12) {
  if (a.size() != b.size()) return false;
  for (const auto& p : a) {
    const auto it = std::find_if(b.begin(), b.end(), [&](const Vec2& q) { return (p - q).norm() <= tol; });
    if (it == b.end()) return false;
    b.erase(it);
  }
  return true;
}

// A document whose pattern1 has a diagonal grain line through the origin.
Document diagonal_grain_document() {
  auto style = full_style();
  style.pieces[0].grain_line = vgd::pattern::Segment{Vec2(0, 0), Vec2(0.2, 0.2)};
  return from_style(style);
}
}  // namespace

TEST(DeletePattern, RemovesThePatternAndEverythingNamingIt) {
  Document doc = full_document();
  DeletePattern del("pattern1");
  execute(doc, del);
  EXPECT_EQ(doc.find("pattern1"), nullptr);
  EXPECT_EQ(doc.find("seq1"), nullptr) << "its stretches go with it";
  EXPECT_EQ(doc.find("hem1"), nullptr) << "a hem along it goes";
  EXPECT_EQ(doc.find("seam1"), nullptr) << "the seam, left with one hem, goes";
  EXPECT_EQ(doc.find("hem2"), nullptr);
  for (const auto& g : doc.container("GRADATIONS")->children)
    for (const auto& s : g.children) EXPECT_NE(s.attribute("pattern"), "pattern1");
  const Node& accessory = doc.container("ACCESSORIES")->children.at(0);
  for (const auto& c : accessory.children) EXPECT_NE(c.attribute("pattern"), "pattern1") << "placement on it goes";
  EXPECT_NE(doc.find("pattern2"), nullptr);
  EXPECT_NE(doc.find("material1"), nullptr) << "a material it used stays";
  EXPECT_FALSE(check(doc).has_errors()) << dump(check(doc));
}

TEST(DeletePattern, LastSizeOfAPieceTakesItsGradation) {
  Document doc = from_style(full_style());
  DeletePattern del("pattern5");  // the only POCKET
  execute(doc, del);
  for (const auto& g : doc.container("GRADATIONS")->children) EXPECT_NE(g.attribute("piece"), "POCKET");
  EXPECT_EQ(to_style(doc).pieces.size(), 4u);
}

TEST(CopyPattern, MakesAnIndependentPieceRightAfterTheOriginal) {
  Document doc = full_document();
  CopyPattern copy("pattern1");
  const std::string id = execute(doc, copy);
  ASSERT_EQ(doc.patterns()[1]->id(), id);
  const Node& c = *doc.find(id);
  EXPECT_EQ(c.attribute("block"), "FRONT_36_copy");
  EXPECT_EQ(c.attribute("piece"), "FRONT copy");
  EXPECT_EQ(c.attribute("size"), "36");
  // Same geometry, new ids for it and every stretch, notch and association.
  const Piece a = to_piece(doc, "pattern1"), b = to_piece(doc, id);
  ASSERT_EQ(a.boundary.size(), b.boundary.size());
  for (std::size_t i = 0; i < a.boundary.size(); ++i) EXPECT_EQ(a.boundary[i].p, b.boundary[i].p);
  for (const auto& s : boundary_stretches(c)) EXPECT_EQ(doc.path_of(s.id)->at(1), 1u) << s.id << " lives in the copy";
  // Its own gradation names it.
  bool listed = false;
  for (const auto& g : doc.container("GRADATIONS")->children)
    if (g.attribute("piece") == "FRONT copy") listed = g.children.size() == 1 && g.children[0].attribute("pattern") == id;
  EXPECT_TRUE(listed);
  EXPECT_FALSE(check(doc).has_errors()) << dump(check(doc));
}

TEST(CopyPattern, SecondCopyGetsNumberedNames) {
  Document doc = from_style(full_style());
  CopyPattern copy("pattern1");
  execute(doc, copy);
  const std::string id = execute(doc, copy);
  EXPECT_EQ(doc.find(id)->attribute("block"), "FRONT_36_copy2");
  EXPECT_EQ(doc.find(id)->attribute("piece"), "FRONT copy 2");
}

TEST(CopyPattern, CopyOfTheSampleSizeIsMarkedSample) {
  Document doc = from_style(full_style());
  CopyPattern copy("pattern3");  // FRONT 38, the sample size
  const std::string id = execute(doc, copy);
  for (const auto& g : doc.container("GRADATIONS")->children)
    for (const auto& s : g.children)
      if (s.attribute("pattern") == id) {
        EXPECT_EQ(s.attribute("sample"), "true");
      }
}

TEST(MirrorPattern, KeepsTheOutlineCounterClockwise) {
  Document doc = full_document();
  const double area = vgd::pattern::signed_area(to_piece(doc, "pattern1").boundary);
  ASSERT_GT(area, 0);
  MirrorPattern mirror("pattern1", MirrorAxis::vertical);
  execute(doc, mirror);
  EXPECT_NEAR(vgd::pattern::signed_area(to_piece(doc, "pattern1").boundary), area, 1e-12);
}

TEST(MirrorPattern, VerticalAxisReflectsAboutTheBoxMiddle) {
  Document doc = from_style(full_style());
  const Piece before = to_piece(doc, "pattern2");  // x in [0.5, 0.8]
  MirrorPattern mirror("pattern2", MirrorAxis::vertical);
  execute(doc, mirror);
  const Piece after = to_piece(doc, "pattern2");
  ASSERT_EQ(after.boundary.size(), before.boundary.size());
  const std::size_t n = before.boundary.size();
  for (std::size_t i = 0; i < n; ++i) {
    // New vertex j holds old vertex (n - j) % n, reflected: x -> 1.3 - x.
    const auto& old = before.boundary[(n - i) % n];
    EXPECT_NEAR(after.boundary[i].p.x(), 1.3 - old.p.x(), 1e-12) << i;
    EXPECT_EQ(after.boundary[i].p.y(), old.p.y()) << i;
    EXPECT_EQ(after.boundary[i].kind, old.kind) << i;
  }
}

TEST(MirrorPattern, EachStretchStillCoversItsEdgeSoHemsStayRight) {
  Document doc = full_document();
  const auto before = stretch_edges(doc, "pattern1");
  const Node hem = *doc.find("hem1");
  MirrorPattern mirror("pattern1", MirrorAxis::vertical);
  execute(doc, mirror);
  const auto after = stretch_edges(doc, "pattern1");
  ASSERT_EQ(before.size(), after.size());
  for (const auto& [id, pts] : before) {
    std::vector<Vec2> reflected;
    for (const auto& p : pts) reflected.emplace_back(0.3 - p.x(), p.y());
    EXPECT_TRUE(same_point_set(reflected, after.at(id))) << id;
  }
  // Contour order reversed: the hem's ends swap and it runs the other way.
  const Node& h = *doc.find("hem1");
  EXPECT_EQ(h.attribute("from"), hem.attribute("to"));
  EXPECT_EQ(h.attribute("to"), hem.attribute("from"));
  EXPECT_EQ(h.attribute("direction"), "reverse");
  EXPECT_EQ(doc.find("hem2")->attribute("direction"), "reverse") << "a hem on another pattern is untouched";
}

TEST(MirrorPattern, NotchesFollowTheirVertexAndAngle) {
  Document doc = from_style(full_style());
  MirrorPattern mirror("pattern1", MirrorAxis::vertical);
  execute(doc, mirror);
  const Piece after = to_piece(doc, "pattern1");
  const auto& notch = after.notches[0];  // was on vertex 2 at (0.3, 0.15), cutting at 180 deg
  ASSERT_GE(notch.boundary_index, 0);
  EXPECT_NEAR((after.boundary[static_cast<std::size_t>(notch.boundary_index)].p - notch.position).norm(), 0, 1e-12);
  EXPECT_NEAR(notch.position.x(), 0.0, 1e-12);
  EXPECT_NEAR(notch.angle_deg, 0.0, 1e-12) << "a cut pointing -x now points +x";
  EXPECT_NEAR(after.notches[1].angle_deg, 90.0, 1e-12) << "a cut along the axis keeps its angle";
}

TEST(MirrorPattern, GrainLineAxisReflectsAcrossTheGrain) {
  Document doc = diagonal_grain_document();
  MirrorPattern mirror("pattern1", MirrorAxis::grain_line);
  execute(doc, mirror);
  // Across y = x: (0.3, 0) -> (0, 0.3), which was vertex 1 and is now vertex n - 1.
  const Piece after = to_piece(doc, "pattern1");
  const auto& p = after.boundary[after.boundary.size() - 1].p;
  EXPECT_NEAR(p.x(), 0.0, 1e-12);
  EXPECT_NEAR(p.y(), 0.3, 1e-12);
  EXPECT_GT(vgd::pattern::signed_area(after.boundary), 0);
}

TEST(MirrorPattern, AutomaticAxisUsesTheGrainLineWhenThereIsOne) {
  Document a = diagonal_grain_document(), b = diagonal_grain_document();
  MirrorPattern automatic("pattern1"), grain("pattern1", MirrorAxis::grain_line);
  execute(a, automatic);
  execute(b, grain);
  EXPECT_EQ(save_string(a), save_string(b));
  Document c = from_style(full_style());
  MirrorPattern no_grain("pattern5");  // POCKET has no grain line: vertical
  execute(c, no_grain);
  EXPECT_NEAR(to_piece(c, "pattern5").boundary[1].p.x(), 3.0, 1e-12);
}

TEST(MirrorPattern, AutomaticAxisIgnoresAZeroLengthGrainLine) {
  auto style = full_style();
  style.pieces[1].grain_line = vgd::pattern::Segment{Vec2(0.6, 0.1), Vec2(0.6, 0.1)};
  Document doc = from_style(style);
  MirrorPattern automatic("pattern2");
  execute(doc, automatic);
  EXPECT_NEAR(to_piece(doc, "pattern2").boundary[0].p.x(), 1.3 - 0.6, 1e-12) << "vertical about x = 0.65";
  MirrorPattern grain("pattern2", MirrorAxis::grain_line);
  EXPECT_THROW(execute(doc, grain), vgd::Error);
}

TEST(MirrorPattern, GrainAxisWithoutGrainLineIsRefused) {
  Document doc = from_style(full_style());
  const std::string before = save_string(doc);
  MirrorPattern mirror("pattern5", MirrorAxis::grain_line);
  try {
    execute(doc, mirror);
    FAIL() << "expected an error";
  } catch (const vgd::Error& e) {
    EXPECT_NE(std::string(e.what()).find("pattern5 has no grain line"), std::string::npos) << e.what();
  }
  EXPECT_EQ(save_string(doc), before);
}

TEST(MirrorPattern, TwiceGivesBackTheOriginal) {
  Document doc = full_document();
  const Piece before = to_piece(doc, "pattern1");
  MirrorPattern mirror("pattern1", MirrorAxis::vertical);
  execute(doc, mirror);
  execute(doc, mirror);
  const Piece after = to_piece(doc, "pattern1");
  ASSERT_EQ(after.boundary.size(), before.boundary.size());
  for (std::size_t i = 0; i < after.boundary.size(); ++i) {
    EXPECT_NEAR((after.boundary[i].p - before.boundary[i].p).norm(), 0, 1e-12) << i;
    EXPECT_EQ(after.boundary[i].kind, before.boundary[i].kind) << i;
  }
  EXPECT_EQ(stretch_ids(doc, "pattern1"), stretch_ids(from_style(full_style()), "pattern1"));
  EXPECT_EQ(after.cutouts[0].points.size(), before.cutouts[0].points.size());
  EXPECT_NEAR((after.cutouts[0].points[1] - before.cutouts[0].points[1]).norm(), 0, 1e-12) << "closed loops restored";
  EXPECT_EQ(doc.find("hem1")->attribute("from"), "seq2");
  EXPECT_EQ(doc.find("hem1")->attribute("direction"), "forward");
}

TEST(PatternEdits, EveryEditedDocumentIsValidAgainstTheSchema) {
  Document doc = full_document();
  UndoStack stack(doc);
  stack.execute(std::make_unique<CopyPattern>("pattern1"));
  stack.execute(std::make_unique<MirrorPattern>("pattern1"));
  stack.execute(std::make_unique<MirrorPattern>("pattern2", MirrorAxis::vertical));
  stack.execute(std::make_unique<DeletePattern>("pattern4"));
  stack.execute(std::make_unique<DeleteNode>("seq3"));
  stack.execute(std::make_unique<PasteNode>("patterns", copy_node(doc, "pattern3")));
  const auto d = validate_string(save_string(doc), "edited.xvc", schema());
  EXPECT_FALSE(d.has_errors()) << dump(d);
  EXPECT_EQ(d.count(vgd::Severity::warning), 1u) << "the pasted pattern repeats its block name: " << dump(d);
}

namespace {
// The outline point at boundary vertex v of a pattern: its stretch and index in it.
OutlinePoint point_at(const Document& doc, const std::string& pattern_id, std::size_t v) {
  for (const auto& st : boundary_stretches(*doc.find(pattern_id)))
    if (v >= st.first && v < st.first + st.count) return {pattern_id, st.id, v - st.first};
  ADD_FAILURE() << "no vertex " << v;
  return {};
}

const Node* notch_of(const Document& doc, const std::string& pattern_id) {
  for (const auto& c : doc.find(pattern_id)->children)
    if (c.tag == "POSITION" && c.attribute("type") == "notch" && c.has_attribute("vertex")) return &c;
  return nullptr;
}

Vec2 xy(const Node& n) { return {std::stod(std::string(n.attribute("x"))), std::stod(std::string(n.attribute("y")))}; }
}  // namespace

// A point dragged in the pattern view: the outline point moves, the notch on it
// with it, nothing else; one undo gives the document back as it was.
TEST(MovePoint, MovesThePointAndTheNotchOnIt) {
  Document doc = full_document();
  const Document before = doc;
  const Piece a = to_piece(doc, "pattern1");
  const Node* notch = notch_of(doc, "pattern1");
  ASSERT_NE(notch, nullptr);
  const std::size_t v = std::stoul(std::string(notch->attribute("vertex")));
  ASSERT_LT((xy(*notch) - a.boundary[v].p).norm(), 1e-12) << "the fixture's notch sits on its vertex";
  UndoStack stack(doc);
  stack.execute(std::make_unique<MovePoint>(point_at(doc, "pattern1", v), 0.33, 0.16));
  const Piece b = to_piece(doc, "pattern1");
  ASSERT_EQ(b.boundary.size(), a.boundary.size());
  for (std::size_t i = 0; i < a.boundary.size(); ++i)
    if (i == v) EXPECT_EQ(b.boundary[i].p, Vec2(0.33, 0.16));
    else EXPECT_EQ(b.boundary[i].p, a.boundary[i].p) << i;
  EXPECT_LT((xy(*notch_of(doc, "pattern1")) - Vec2(0.33, 0.16)).norm(), 1e-12);
  EXPECT_FALSE(check(doc).has_errors()) << dump(check(doc));
  stack.undo();
  EXPECT_EQ(doc.root(), before.root());
}

// A point added after vertex 1: the edge to vertex 2 split at its middle, the
// notch on vertex 2 renumbered to 3 and still on its point; deleting it again
// gives the outline back.
TEST(InsertPoint, SplitsTheEdgeAndRenumbersTheNotches) {
  Document doc = full_document();
  const Piece a = to_piece(doc, "pattern1");
  const std::size_t v = std::stoul(std::string(notch_of(doc, "pattern1")->attribute("vertex")));
  ASSERT_GE(v, 2u);
  InsertPoint ins(point_at(doc, "pattern1", v - 1), "curve");
  execute(doc, ins);
  const Piece b = to_piece(doc, "pattern1");
  ASSERT_EQ(b.boundary.size(), a.boundary.size() + 1);
  EXPECT_LT((b.boundary[v].p - 0.5 * (a.boundary[v - 1].p + a.boundary[v].p)).norm(), 1e-12);
  EXPECT_EQ(b.boundary[v].kind, vgd::pattern::PointKind::curve);
  const Node* notch = notch_of(doc, "pattern1");
  ASSERT_NE(notch, nullptr);
  EXPECT_EQ(notch->attribute("vertex"), std::to_string(v + 1));
  EXPECT_LT((xy(*notch) - b.boundary[v + 1].p).norm(), 1e-12);
  EXPECT_FALSE(check(doc).has_errors()) << dump(check(doc));
  DeletePoint del(point_at(doc, "pattern1", v));
  execute(doc, del);
  const Piece c = to_piece(doc, "pattern1");
  ASSERT_EQ(c.boundary.size(), a.boundary.size());
  for (std::size_t i = 0; i < a.boundary.size(); ++i) EXPECT_EQ(c.boundary[i].p, a.boundary[i].p) << i;
  EXPECT_EQ(notch_of(doc, "pattern1")->attribute("vertex"), std::to_string(v));
}

// What a deletion may not do: take the point a stretch (and its seams) begins
// at, or leave an outline of fewer than three points; an unknown stretch or
// point is named.
TEST(DeletePoint, RefusesAStretchesFirstPointAndTooSmallAnOutline) {
  Document doc = full_document();
  const auto st = boundary_stretches(*doc.find("pattern1"));
  DeletePoint first({"pattern1", st[1].id, 0});
  try {
    execute(doc, first);
    ADD_FAILURE() << "deleted where a stretch begins";
  } catch (const vgd::Error& e) {
    EXPECT_NE(std::string(e.what()).find("is where the stretch " + st[1].id + " begins"), std::string::npos) << e.what();
  }
  DeletePoint nowhere({"pattern1", st[0].id, 99});
  try {
    execute(doc, nowhere);
    ADD_FAILURE();
  } catch (const vgd::Error& e) {
    EXPECT_NE(std::string(e.what()).find("no point 99"), std::string::npos) << e.what();
  }
  // Down to three points, then refused.
  // A square with one turn point: one stretch of four points.
  auto style = full_style();
  style.pieces[0].boundary = {{Vec2(0, 0), vgd::pattern::PointKind::turn},
                              {Vec2(0.2, 0), vgd::pattern::PointKind::plain},
                              {Vec2(0.2, 0.2), vgd::pattern::PointKind::plain},
                              {Vec2(0, 0.2), vgd::pattern::PointKind::plain}};
  style.pieces[0].notches.clear();
  Document tri = from_style(style);
  ASSERT_EQ(boundary_stretches(*tri.find("pattern1")).size(), 1u);
  bool refused = false;
  for (;;) {
    const auto s = boundary_stretches(*tri.find("pattern1"));
    const auto it = std::find_if(s.begin(), s.end(), [](const Stretch& x) { return x.count > 1; });
    ASSERT_NE(it, s.end()) << "a stretch with a point to delete";
    DeletePoint d({"pattern1", it->id, it->count - 1});
    if (to_piece(tri, "pattern1").boundary.size() == 3) {
      try {
        execute(tri, d);
      } catch (const vgd::Error& e) {
        refused = std::string(e.what()).find("at least three points") != std::string::npos;
      }
      break;
    }
    execute(tri, d);
  }
  EXPECT_TRUE(refused);
  EXPECT_EQ(to_piece(tri, "pattern1").boundary.size(), 3u);
  EXPECT_FALSE(check(tri).has_errors()) << dump(check(tri));
}

TEST(SetPointKind, MakesATurnPointACurvePointAndBack) {
  Document doc = full_document();
  const OutlinePoint p = point_at(doc, "pattern1", 2);
  ASSERT_EQ(to_piece(doc, "pattern1").boundary[2].kind, vgd::pattern::PointKind::plain);
  SetPointKind turn(p, "turn");
  execute(doc, turn);
  EXPECT_EQ(to_piece(doc, "pattern1").boundary[2].kind, vgd::pattern::PointKind::turn);
  SetPointKind plain(p, "plain");
  execute(doc, plain);
  EXPECT_EQ(to_piece(doc, "pattern1").boundary[2].kind, vgd::pattern::PointKind::plain);
  SetPointKind bad(p, "corner");
  EXPECT_THROW(execute(doc, bad), vgd::Error);
}

// A quarter turn about the outline's box middle: every outline point turned,
// the notch's direction with it, the grain line kept (the piece now cut across
// the warp); counter-clockwise still; turned back, the document is as before.
TEST(RotatePattern, TurnsTheOutlineAndNotchesButNotTheGrain) {
  Document doc = full_document();
  const Document before = doc;
  const Piece a = to_piece(doc, "pattern1");
  Vec2 lo = a.boundary[0].p, hi = lo;
  for (const auto& c : a.boundary) lo = lo.cwiseMin(c.p), hi = hi.cwiseMax(c.p);
  const Vec2 m = 0.5 * (lo + hi);
  const double notch_angle = std::stod(std::string(notch_of(doc, "pattern1")->attribute("angle")));
  RotatePattern turn("pattern1", 90);
  execute(doc, turn);
  const Piece b = to_piece(doc, "pattern1");
  ASSERT_EQ(b.boundary.size(), a.boundary.size());
  for (std::size_t i = 0; i < a.boundary.size(); ++i) {
    const Vec2 r = a.boundary[i].p - m;
    EXPECT_LT((b.boundary[i].p - (m + Vec2(-r.y(), r.x()))).norm(), 1e-12) << i;
  }
  ASSERT_TRUE(b.grain_line.has_value());
  EXPECT_EQ(b.grain_line->a, a.grain_line->a);
  EXPECT_EQ(b.grain_line->b, a.grain_line->b);
  EXPECT_NEAR(std::stod(std::string(notch_of(doc, "pattern1")->attribute("angle"))), notch_angle + 90 > 180 ? notch_angle - 270 : notch_angle + 90, 1e-9);
  EXPECT_NEAR(vgd::pattern::signed_area(b.boundary), vgd::pattern::signed_area(a.boundary), 1e-12);
  EXPECT_FALSE(check(doc).has_errors()) << dump(check(doc));
  RotatePattern back("pattern1", -90);
  execute(doc, back);
  const Piece c = to_piece(doc, "pattern1");
  for (std::size_t i = 0; i < a.boundary.size(); ++i) EXPECT_LT((c.boundary[i].p - a.boundary[i].p).norm(), 1e-15) << i;
}

// A piece cut from a fabric of its own: the MATERIAL copied in once, with scope
// "piece" (a second piece cut from the same fabric shares it), named by an
// ASSOCIATION; the garment's fabric stays the garment's. Cut from the garment's
// fabric again, the association goes, and the piece MATERIAL with the last one.
// The fixture's pattern1 names the garment's own MATERIAL: cut from another
// fabric, that MATERIAL stays (it is the garment's); undo restores everything.
TEST(SetPieceMaterial, CopiesTheFabricOnceAndDropsItWhenNoPieceNamesIt) {
  Document doc = full_document();
  const std::string garment = garment_material(doc);
  ASSERT_FALSE(garment.empty());
  ASSERT_EQ(piece_material(doc, *doc.find("pattern1")), garment);
  const std::size_t materials = doc.container("MATERIALS")->children.size();
  Node denim{"MATERIAL", {{"id", "denim"}, {"name", "denim 12 oz"}},
             {Node{"PARAMETER", {{"id", "p1"}, {"name", "density"}, {"value", "0.42"}, {"unit", "kg/m2"}}, {}}}};
  SetPieceMaterial a("pattern2", denim);
  const std::string id = execute(doc, a);
  EXPECT_EQ(piece_material(doc, *doc.find("pattern2")), id);
  EXPECT_EQ(doc.find(id)->attribute("scope"), "piece");
  EXPECT_EQ(doc.container("MATERIALS")->children.size(), materials + 1);
  SetPieceMaterial b("pattern3", denim);
  EXPECT_EQ(execute(doc, b), id) << "the same fabric is not copied twice";
  EXPECT_EQ(doc.container("MATERIALS")->children.size(), materials + 1);
  EXPECT_EQ(garment_material(doc), garment);
  EXPECT_FALSE(check(doc).has_errors()) << dump(check(doc));
  SetPieceMaterial back2("pattern2", std::nullopt);
  execute(doc, back2);
  EXPECT_EQ(piece_material(doc, *doc.find("pattern2")), "");
  EXPECT_NE(doc.find(id), nullptr) << "pattern3 still names it";
  SetPieceMaterial back3("pattern3", std::nullopt);
  execute(doc, back3);
  EXPECT_EQ(doc.find(id), nullptr);
  EXPECT_EQ(doc.container("MATERIALS")->children.size(), materials);
  const Document before = doc;
  UndoStack stack(doc);
  stack.execute(std::make_unique<SetPieceMaterial>("pattern1", denim));
  EXPECT_EQ(doc.find(piece_material(doc, *doc.find("pattern1")))->attribute("name"), "denim 12 oz");
  EXPECT_NE(doc.find(garment), nullptr) << "the garment's MATERIAL stays";
  EXPECT_EQ(garment_material(doc), garment);
  EXPECT_FALSE(check(doc).has_errors()) << dump(check(doc));
  stack.undo();
  EXPECT_EQ(doc.root(), before.root());
  SetPieceMaterial notes("pattern1", Node{"PARAMETER", {{"id", "x"}}, {}});
  EXPECT_THROW(execute(doc, notes), vgd::Error);
}

// An internal line drawn on a piece: read back as the piece's internal line,
// point for point; the document still checks and validates; undo removes it.
// Refused: one point, a point 2 mm outside the outline, a NaN, a pattern
// that is not one.
TEST(AddInternalLine, DrawsALineInsideAPieceAndRefusesOneOutside) {
  Document doc = full_document();
  const Piece before = to_piece(doc, "pattern1");
  Vec2 lo = before.boundary[0].p, hi = lo;
  for (const auto& c : before.boundary) lo = lo.cwiseMin(c.p), hi = hi.cwiseMax(c.p);
  const Vec2 m = 0.5 * (lo + hi);
  const std::vector<std::array<double, 2>> pts = {{m.x() - 0.02, m.y()}, {m.x() + 0.02, m.y() + 0.01}, {m.x(), m.y() - 0.03}};
  UndoStack stack(doc);
  const std::string id = stack.execute(std::make_unique<AddInternalLine>("pattern1", pts));
  const Piece after = to_piece(doc, "pattern1");
  ASSERT_EQ(after.internal_lines.size(), before.internal_lines.size() + 1);
  const auto& line = after.internal_lines.back();
  EXPECT_FALSE(line.closed);
  ASSERT_EQ(line.points.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(line.points[i], Vec2(pts[i][0], pts[i][1])) << i;
  EXPECT_EQ(id, "pattern1");
  const Node* seq = nullptr;
  for (const auto& c : doc.find(id)->children)
    if (c.tag == "C2DSEQ" && c.attribute("role") == "internal") seq = &c;
  ASSERT_NE(seq, nullptr);
  EXPECT_EQ(seq->children.size(), 3u);
  EXPECT_EQ(after.boundary.size(), before.boundary.size());
  EXPECT_FALSE(check(doc).has_errors()) << dump(check(doc));
  EXPECT_EQ(vgd::xvc::validate_string(save_string(doc), "t.xvc", vgd::xvc::default_schema_path()).count(vgd::Severity::error), 0u);
  stack.undo();
  EXPECT_EQ(to_piece(doc, "pattern1").internal_lines.size(), before.internal_lines.size());

  Document d = full_document();
  EXPECT_THROW(execute(d, *std::make_unique<AddInternalLine>("pattern1", std::vector<std::array<double, 2>>{{m.x(), m.y()}})),
               vgd::Error);
  const Vec2 out = Vec2(hi.x() + 0.002, m.y());
  try {
    execute(d, *std::make_unique<AddInternalLine>("pattern1", std::vector<std::array<double, 2>>{{m.x(), m.y()}, {out.x(), out.y()}}));
    ADD_FAILURE() << "a point outside was drawn";
  } catch (const vgd::Error& e) {
    EXPECT_NE(std::string(e.what()).find("point 2 of the line"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("lies outside the piece"), std::string::npos) << e.what();
  }
  // An outline vertex, and a point 0.5 mm outside the outline beyond it: on the outline, drawn.
  const Vec2 corner = before.boundary.front().p;
  const Vec2 beyond = corner + 0.0005 * (corner - m).normalized();
  ASSERT_LE(vgd::pattern::nearest_edge(before.boundary, beyond).distance, 0.001);
  EXPECT_NO_THROW(execute(d, *std::make_unique<AddInternalLine>(
                                 "pattern1", std::vector<std::array<double, 2>>{{m.x(), m.y()}, {corner.x(), corner.y()},
                                                                                {beyond.x(), beyond.y()}})));
  EXPECT_THROW(execute(d, *std::make_unique<AddInternalLine>(
                              "pattern1", std::vector<std::array<double, 2>>{{m.x(), m.y()}, {std::nan(""), m.y()}})),
               vgd::Error);
  EXPECT_THROW(execute(d, *std::make_unique<AddInternalLine>("seam1", pts)), vgd::Error);
}

// A piece drawn as a polygon (clockwise here): a new PATTERN of the sample
// size, counter-clockwise, one stretch per side, cut once, with a GRADATION
// naming it; a second one of the same name is numbered; the document checks
// and validates. Refused: two points, crossing sides, a sliver under 1 cm².
TEST(AddDrawnPattern, AddsAPolygonAsAPieceWithAStretchPerSide) {
  Document doc = full_document();
  const std::size_t n = doc.patterns().size();
  const std::vector<std::array<double, 2>> square = {{2.0, 0.0}, {2.0, 0.1}, {2.2, 0.1}, {2.2, 0.0}};
  const std::string id = execute(doc, *std::make_unique<AddDrawnPattern>("PATCH", "", square));
  ASSERT_EQ(doc.patterns().size(), n + 1);
  const Node* p = doc.find(id);
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->attribute("piece"), "PATCH");
  EXPECT_EQ(p->attribute("quantity"), "1");
  const auto* grads = doc.container("GRADATIONS");
  ASSERT_NE(grads, nullptr);
  EXPECT_EQ(p->attribute("size"), grads->attribute("sample_size"));
  bool graded = false;
  for (const auto& g : grads->children)
    for (const auto& s : g.children) graded = graded || s.attribute("pattern") == id;
  EXPECT_TRUE(graded);
  const Piece pc = to_piece(doc, id);
  EXPECT_NEAR(vgd::pattern::signed_area(pc.boundary), 0.02, 1e-12);  // counter-clockwise
  EXPECT_EQ(boundary_stretches(*p).size(), 4u);
  EXPECT_FALSE(check(doc).has_errors()) << dump(check(doc));
  EXPECT_EQ(vgd::xvc::validate_string(save_string(doc), "t.xvc", vgd::xvc::default_schema_path()).count(vgd::Severity::error), 0u);
  const std::string again = execute(doc, *std::make_unique<AddDrawnPattern>("PATCH", "", square));
  EXPECT_EQ(doc.find(again)->attribute("piece"), "PATCH 2");

  using Pts = std::vector<std::array<double, 2>>;
  EXPECT_THROW(execute(doc, *std::make_unique<AddDrawnPattern>("X", "", Pts{{0, 0}, {1, 0}})), vgd::Error);
  EXPECT_THROW(execute(doc, *std::make_unique<AddDrawnPattern>("X", "", Pts{{0, 0}, {0.1, 0.1}, {0.1, 0}, {0, 0.1}})),
               vgd::Error);
  EXPECT_THROW(execute(doc, *std::make_unique<AddDrawnPattern>("X", "", Pts{{0, 0}, {0.5, 0}, {0.5, 0.0001}})), vgd::Error);
  EXPECT_EQ(doc.patterns().size(), n + 2);
}

// A drawn piece with curve points (a smoothed outline): stretches begin at
// its corners only, the first at a corner, the points keep their kinds; a
// curve mark per point or none, else refused.
TEST(AddDrawnPattern, CurvePointsJoinTheStretchesBetweenCorners) {
  Document doc = full_document();
  // A 20 x 20 cm piece whose top bulges through four curve points.
  const std::vector<std::array<double, 2>> pts = {{2.2, 0.2}, {2.15, 0.22}, {2.1, 0.23}, {2.05, 0.22}, {2.0, 0.2}, {2.0, 0.0}, {2.2, 0.0}};
  const std::vector<bool> curve = {true, true, true, true, false, false, false};
  const std::string id = execute(doc, *std::make_unique<AddDrawnPattern>("CURVED", "", pts, curve));
  const Piece pc = to_piece(doc, id);
  ASSERT_EQ(pc.boundary.size(), pts.size());
  EXPECT_EQ(pc.boundary.front().kind, vgd::pattern::PointKind::turn) << "it starts at a corner";
  int turns = 0, curves = 0;
  for (const auto& c : pc.boundary) turns += c.kind == vgd::pattern::PointKind::turn, curves += c.kind == vgd::pattern::PointKind::curve;
  EXPECT_EQ(turns, 3);
  EXPECT_EQ(curves, 4);
  EXPECT_EQ(boundary_stretches(*doc.find(id)).size(), 3u) << "a stretch from each corner";
  EXPECT_GT(vgd::pattern::signed_area(pc.boundary), 0.0);
  EXPECT_FALSE(check(doc).has_errors()) << dump(check(doc));
  EXPECT_EQ(vgd::xvc::validate_string(save_string(doc), "t.xvc", vgd::xvc::default_schema_path()).count(vgd::Severity::error), 0u);
  EXPECT_THROW(execute(doc, *std::make_unique<AddDrawnPattern>("X", "", pts, std::vector<bool>{true, false})), vgd::Error);
}

// A piece's place on the sheet: set (one POSITION type="sheet", the document
// checks and validates), set again (still one, the new place), kept by a
// rotation and a mirroring (the piece is not moved on the sheet by them),
// absent from a copy, refused when not finite, removed; undo restores; two in
// one PATTERN are an error of the check.
TEST(SetSheetPosition, PlacesThePieceOnTheSheetOnceAndRotationKeepsIt) {
  Document doc = full_document();
  const Document before = doc;
  UndoStack stack(doc);
  EXPECT_FALSE(sheet_position(*doc.find("pattern1")).has_value());
  stack.execute(std::make_unique<SetSheetPosition>("pattern1", std::array<double, 2>{0.25, -0.5}));
  ASSERT_TRUE(sheet_position(*doc.find("pattern1")).has_value());
  EXPECT_EQ(*sheet_position(*doc.find("pattern1")), (std::array<double, 2>{0.25, -0.5}));
  stack.execute(std::make_unique<SetSheetPosition>("pattern1", std::array<double, 2>{-0.125, 0.75}));
  int sheets = 0;
  for (const auto& c : doc.find("pattern1")->children) sheets += c.tag == "POSITION" && c.attribute("type") == "sheet";
  EXPECT_EQ(sheets, 1);
  EXPECT_EQ(*sheet_position(*doc.find("pattern1")), (std::array<double, 2>{-0.125, 0.75}));
  EXPECT_FALSE(check(doc).has_errors()) << dump(check(doc));
  const auto valid = validate_string(save_string(doc), "sheet.xvc", schema());
  EXPECT_FALSE(valid.has_errors()) << dump(valid);
  stack.execute(std::make_unique<RotatePattern>("pattern1", 30));
  stack.execute(std::make_unique<MirrorPattern>("pattern1"));
  EXPECT_EQ(*sheet_position(*doc.find("pattern1")), (std::array<double, 2>{-0.125, 0.75}));
  const std::string copy = stack.execute(std::make_unique<CopyPattern>("pattern1"));
  EXPECT_FALSE(sheet_position(*doc.find(copy)).has_value()) << "a copy is laid out by the view";
  EXPECT_THROW(stack.execute(std::make_unique<SetSheetPosition>("pattern1", std::array<double, 2>{NAN, 0.0})), vgd::Error);
  EXPECT_THROW(stack.execute(std::make_unique<SetSheetPosition>("seq3", std::array<double, 2>{0.0, 0.0})), vgd::Error);
  stack.execute(std::make_unique<SetSheetPosition>("pattern1", std::nullopt));
  EXPECT_FALSE(sheet_position(*doc.find("pattern1")).has_value());
  while (stack.can_undo()) stack.undo();
  EXPECT_EQ(doc.root(), before.root());
  // A second sheet position in one PATTERN: refused by the check, said so.
  stack.execute(std::make_unique<SetSheetPosition>("pattern1", std::array<double, 2>{0.0, 0.0}));
  try {
    stack.execute(std::make_unique<AddNode>("pattern1", Node{"POSITION", {{"type", "sheet"}, {"x", "1"}, {"y", "1"}}, {}}));
    ADD_FAILURE() << "a second sheet position was added";
  } catch (const vgd::Error& e) {
    EXPECT_NE(std::string(e.what()).find("one sheet position, not 2"), std::string::npos) << e.what();
  }
  // In an ACCESSORY (which holds POSITIONs): refused too.
  std::string accessory;
  for (const auto& c : doc.container("ACCESSORIES")->children) accessory = std::string(c.id());
  ASSERT_FALSE(accessory.empty());
  try {
    stack.execute(std::make_unique<AddNode>(accessory, Node{"POSITION", {{"type", "sheet"}, {"x", "1"}, {"y", "1"}}, {}}));
    ADD_FAILURE() << "a sheet position was added outside a PATTERN";
  } catch (const vgd::Error& e) {
    EXPECT_NE(std::string(e.what()).find("belongs inside a PATTERN"), std::string::npos) << e.what();
  }
}

// A grain line set: the piece's grain line runs between the new ends (its
// sequence keeps its id), one is added to a piece without, the document
// checks and validates; refused under 1 cm or not finite; undo restores.
TEST(SetGrainLine, MovesTheGrainLineOrAddsOne) {
  Document doc = full_document();
  const Document before = doc;
  UndoStack stack(doc);
  const Piece a = to_piece(doc, "pattern1");
  ASSERT_TRUE(a.grain_line.has_value());
  stack.execute(std::make_unique<SetGrainLine>("pattern1", std::array<double, 2>{0.1, 0.1}, std::array<double, 2>{0.2, 0.3}));
  const Piece b = to_piece(doc, "pattern1");
  ASSERT_TRUE(b.grain_line.has_value());
  EXPECT_EQ(b.grain_line->a, Vec2(0.1, 0.1));
  EXPECT_EQ(b.grain_line->b, Vec2(0.2, 0.3));
  int grains = 0;
  for (const auto& c : doc.find("pattern1")->children) grains += c.tag == "C2DSEQ" && c.attribute("role") == "grain";
  EXPECT_EQ(grains, 1);
  EXPECT_FALSE(check(doc).has_errors()) << dump(check(doc));
  // A drawn piece has none: one is added.
  const std::string drawn = stack.execute(std::make_unique<AddDrawnPattern>(
      "PATCH", "", std::vector<std::array<double, 2>>{{2.0, 0.0}, {2.2, 0.0}, {2.2, 0.1}, {2.0, 0.1}}));
  EXPECT_FALSE(to_piece(doc, drawn).grain_line.has_value());
  stack.execute(std::make_unique<SetGrainLine>(drawn, std::array<double, 2>{2.1, 0.02}, std::array<double, 2>{2.1, 0.08}));
  ASSERT_TRUE(to_piece(doc, drawn).grain_line.has_value());
  EXPECT_EQ(to_piece(doc, drawn).grain_line->b, Vec2(2.1, 0.08));
  EXPECT_FALSE(check(doc).has_errors()) << dump(check(doc));
  const auto valid = validate_string(save_string(doc), "grain.xvc", schema());
  EXPECT_FALSE(valid.has_errors()) << dump(valid);
  EXPECT_THROW(stack.execute(std::make_unique<SetGrainLine>("pattern1", std::array<double, 2>{0.1, 0.1},
                                                            std::array<double, 2>{0.1, 0.105})),
               vgd::Error);
  EXPECT_THROW(stack.execute(std::make_unique<SetGrainLine>("pattern1", std::array<double, 2>{NAN, 0.1},
                                                            std::array<double, 2>{0.1, 0.3})),
               vgd::Error);
  while (stack.can_undo()) stack.undo();
  EXPECT_EQ(doc.root(), before.root());
}

// A notch moved to another boundary vertex: its point is that vertex, its
// vertex attribute says so, its cut points into the piece (square to the
// outline there: along the inward normal from the neighbours); the document
// checks; refused beyond the boundary or for what is not a notch; undo
// restores.
TEST(MoveNotch, PutsTheNotchOnAnotherVertexCuttingInwards) {
  Document doc = full_document();
  const Document before = doc;
  const Node* notch = notch_of(doc, "pattern1");
  ASSERT_NE(notch, nullptr);
  const std::string id(notch->id());
  const Piece a = to_piece(doc, "pattern1");
  const std::size_t n = a.boundary.size();
  const std::size_t v = (std::stoul(std::string(notch->attribute("vertex"))) + 2) % n;
  UndoStack stack(doc);
  EXPECT_EQ(stack.execute(std::make_unique<MoveNotch>("pattern1", id, v)), id);
  const Node* moved = doc.find(id);
  EXPECT_EQ(xy(*moved), a.boundary[v].p);
  EXPECT_EQ(moved->attribute("vertex"), std::to_string(v));
  const double ang = std::stod(std::string(moved->attribute("angle"))) * std::numbers::pi / 180.0;
  const Vec2 cut(std::cos(ang), std::sin(ang));
  const Vec2 t = a.boundary[(v + 1) % n].p - a.boundary[(v + n - 1) % n].p;
  EXPECT_NEAR(cut.dot(t.normalized()), 0.0, 1e-9) << "square to the outline";
  EXPECT_TRUE(vgd::pattern::point_in_outline(a.boundary, a.boundary[v].p + 0.002 * cut)) << "into the piece";
  EXPECT_FALSE(check(doc).has_errors()) << dump(check(doc));
  EXPECT_THROW(stack.execute(std::make_unique<MoveNotch>("pattern1", id, n)), vgd::Error);
  std::string drill;
  for (const auto& c : doc.find("pattern1")->children)
    if (c.tag == "POSITION" && c.attribute("type") == "drill") drill = std::string(c.id());
  if (!drill.empty()) {
    EXPECT_THROW(stack.execute(std::make_unique<MoveNotch>("pattern1", drill, 0)), vgd::Error);
  }
  EXPECT_THROW(stack.execute(std::make_unique<MoveNotch>("pattern1", "no-such", 0)), vgd::Error);
  stack.undo();
  EXPECT_EQ(doc.root(), before.root());
}

// A notch added on a boundary vertex: a new POSITION type="notch" there, its
// cut square into the piece, 5 mm deep; read back by to_piece as a notch; the
// document checks and validates; refused on a vertex that has one and beyond
// the boundary; DeleteNode removes it; undo restores.
TEST(AddNotch, PutsANewNotchOnAVertexCuttingInwards) {
  Document doc = full_document();
  const Document before = doc;
  const Piece a = to_piece(doc, "pattern1");
  const std::size_t n = a.boundary.size();
  const std::size_t notches = a.notches.size();
  const Node* old = notch_of(doc, "pattern1");
  ASSERT_NE(old, nullptr);
  const std::size_t taken = std::stoul(std::string(old->attribute("vertex")));
  const std::size_t v = (taken + 1) % n;
  UndoStack stack(doc);
  const std::string id = stack.execute(std::make_unique<AddNotch>("pattern1", v));
  const Node* added = doc.find(id);
  ASSERT_NE(added, nullptr);
  EXPECT_EQ(added->tag, "POSITION");
  EXPECT_EQ(added->attribute("type"), "notch");
  EXPECT_EQ(xy(*added), a.boundary[v].p);
  EXPECT_EQ(added->attribute("vertex"), std::to_string(v));
  EXPECT_EQ(added->attribute("length"), "0.005");
  const double ang = std::stod(std::string(added->attribute("angle"))) * std::numbers::pi / 180.0;
  const Vec2 cut(std::cos(ang), std::sin(ang));
  const Vec2 t = a.boundary[(v + 1) % n].p - a.boundary[(v + n - 1) % n].p;
  EXPECT_NEAR(cut.dot(t.normalized()), 0.0, 1e-9) << "square to the outline";
  EXPECT_TRUE(vgd::pattern::point_in_outline(a.boundary, a.boundary[v].p + 0.002 * cut)) << "into the piece";
  EXPECT_EQ(to_piece(doc, "pattern1").notches.size(), notches + 1);
  EXPECT_FALSE(check(doc).has_errors()) << dump(check(doc));
  const auto valid = validate_string(save_string(doc), "notch.xvc", schema());
  EXPECT_FALSE(valid.has_errors()) << dump(valid);
  EXPECT_THROW(stack.execute(std::make_unique<AddNotch>("pattern1", v)), vgd::Error) << "one there already";
  EXPECT_THROW(stack.execute(std::make_unique<AddNotch>("pattern1", taken)), vgd::Error);
  EXPECT_THROW(stack.execute(std::make_unique<AddNotch>("pattern1", n)), vgd::Error);
  stack.execute(std::make_unique<DeleteNode>(id));
  EXPECT_EQ(doc.find(id), nullptr);
  EXPECT_EQ(to_piece(doc, "pattern1").notches.size(), notches);
  while (stack.can_undo()) stack.undo();
  EXPECT_EQ(doc.root(), before.root());
}

// A pin (POSITION type="pin"): written at its point inside the piece, read
// back by pins_of, valid against the schema and the rules, kept where the
// piece's cloth is when the pattern turns; refused off the piece (naming the
// pattern and how far off) and for a non-finite point; removed by DeleteNode.
TEST(AddPin, HoldsAPointOfThePieceAndRefusesOneOffIt) {
  Document doc = full_document();
  const Document before = doc;
  const Piece a = to_piece(doc, "pattern1");
  Vec2 centre = Vec2::Zero();
  for (const auto& c : a.boundary) centre += c.p;
  centre /= static_cast<double>(a.boundary.size());
  ASSERT_TRUE(vgd::pattern::point_in_outline(a.boundary, centre));
  UndoStack stack(doc);
  const std::string id = stack.execute(std::make_unique<AddPin>("pattern1", std::array{centre.x(), centre.y()}));
  const Node* added = doc.find(id);
  ASSERT_NE(added, nullptr);
  EXPECT_EQ(added->attribute("type"), "pin");
  EXPECT_NEAR((xy(*added) - centre).norm(), 0.0, 1e-12);
  const auto pins = pins_of(*doc.find("pattern1"));
  ASSERT_EQ(pins.size(), 1u);
  EXPECT_EQ(pins[0].id, id);
  EXPECT_NEAR(pins[0].x, centre.x(), 1e-12);
  EXPECT_FALSE(check(doc).has_errors()) << dump(check(doc));
  const auto valid = validate_string(save_string(doc), "pin.xvc", schema());
  EXPECT_FALSE(valid.has_errors()) << dump(valid);
  EXPECT_EQ(to_piece(doc, "pattern1").boundary.size(), a.boundary.size()) << "the outline is untouched";

  // The point on an outline vertex is taken; 1 cm outside it is not.
  const Vec2 v = a.boundary[0].p;
  EXPECT_NO_THROW(stack.execute(std::make_unique<AddPin>("pattern1", std::array{v.x(), v.y()})));
  const Vec2 out = v + 0.01 * (v - centre).normalized();
  ASSERT_FALSE(vgd::pattern::point_in_outline(a.boundary, out));
  try {
    stack.execute(std::make_unique<AddPin>("pattern1", std::array{out.x(), out.y()}));
    ADD_FAILURE() << "a pin off the piece was added";
  } catch (const vgd::Error& e) {
    EXPECT_NE(std::string(e.what()).find("pattern1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("mm outside the piece"), std::string::npos) << e.what();
  }
  EXPECT_THROW(stack.execute(std::make_unique<AddPin>("pattern1", std::array{std::nan(""), 0.0})), vgd::Error);

  // A quarter turn of the pattern turns its pin with it: still inside.
  stack.execute(std::make_unique<RotatePattern>("pattern1", 90.0));
  const Node* turned = doc.find(id);
  ASSERT_NE(turned, nullptr);
  EXPECT_TRUE(vgd::pattern::point_in_outline(to_piece(doc, "pattern1").boundary, xy(*turned)));
  EXPECT_GT((xy(*turned) - centre).norm(), 1e-4) << "moved with the piece";

  stack.execute(std::make_unique<DeleteNode>(id));
  EXPECT_EQ(doc.find(id), nullptr);
  while (stack.can_undo()) stack.undo();
  EXPECT_EQ(doc.root(), before.root());
}
