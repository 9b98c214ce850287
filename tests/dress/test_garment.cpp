// Garment assembly: hems of one seam get the same number of vertices, and the
// seam pairs sit on the hems in sewing order.
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "vgd/dress/garment.hpp"
#include "vgd/xvc/arrangement.hpp"
#include "vgd/xvc/style.hpp"
#include "vgd/xvc/xvc.hpp"

namespace vgd::dress {
namespace {

using pattern::ContourPoint;
using pattern::PointKind;
using pattern::Vec2;

pattern::Piece rectangle(const std::string& name, double x0, double w, double h) {
  pattern::Piece p;
  p.block = name + "_38";
  p.name = name;
  p.size = "38";
  p.boundary = {{Vec2(x0, 0), PointKind::turn},
                {Vec2(x0 + w, 0), PointKind::turn},
                {Vec2(x0 + w, h), PointKind::turn},
                {Vec2(x0, h), PointKind::turn}};
  p.grain_line = pattern::Segment{Vec2(x0 + w / 2, 0.1), Vec2(x0 + w / 2, h - 0.1)};
  return p;
}

// A piece of size 38 drawn with this outline.
pattern::Piece drawn(const std::string& name, std::vector<ContourPoint> outline) {
  pattern::Piece p;
  p.block = name + "_38";
  p.name = name;
  p.size = "38";
  p.boundary = std::move(outline);
  return p;
}

// A style of one size, 38, of these pieces.
pattern::Style one_size(const std::string& name, std::vector<pattern::Piece> pieces) {
  pattern::Style s;
  s.name = name;
  s.sample_size = "38";
  s.sizes = {"38"};
  s.pieces = std::move(pieces);
  return s;
}

xvc::Node hem(const std::string& id, const std::string& from, const std::string& to, const std::string& dir) {
  return {"HEM", {{"id", id}, {"from", from}, {"to", to}, {"direction", dir}, {"type", "plain"}}, {}};
}

// FRONT 0.30 x 0.50 and BACK 0.34 x 0.53: the front's right side (stretch 2,
// from (0.3,0) up) sewn to the back's left side (stretch 4, from (x0,h) down,
// so reverse runs it upwards too).
xvc::Document two_panels(std::vector<xvc::Node> seams) {
  xvc::Node root =
      xvc::from_style(one_size("panels", {rectangle("FRONT", 0.0, 0.30, 0.50), rectangle("BACK", 1.0, 0.34, 0.53)}))
          .root();
  for (auto& c : root.children)
    if (c.tag == "SEAMS") c.children = std::move(seams);
  return xvc::Document(std::move(root), "panels.xvc");
}

std::vector<std::string> stretch_ids(const xvc::Document& d, int pattern) {
  std::vector<std::string> ids;
  for (const auto& st : xvc::boundary_stretches(*d.patterns()[pattern])) ids.push_back(st.id);
  return ids;
}

TEST(Garment, SeamHemsGetEqualVertexCountsAndPairsFollowTheSewingDirection) {
  const xvc::Document probe = two_panels({});
  const auto f = stretch_ids(probe, 0), b = stretch_ids(probe, 1);
  ASSERT_EQ(f.size(), 4u);
  ASSERT_EQ(b.size(), 4u);
  xvc::Node seam{"SEAM", {{"id", "seam1"}, {"name", "side"}, {"type", "plain"}},
                 {hem("hem1", f[1], f[1], "forward"), hem("hem2", b[3], b[3], "reverse")}};
  const xvc::Document doc = two_panels({seam});
  Diagnostics diag;
  AssemblyOptions opt;
  opt.spacing = 0.02;
  const Garment g = assemble_garment(doc, opt, diag);
  ASSERT_EQ(g.pieces.size(), 2u);
  ASSERT_EQ(g.seams.size(), 1u);
  const GarmentSeam& sm = g.seams[0];
  EXPECT_NEAR(sm.length_a, 0.50, 1e-12);
  EXPECT_NEAR(sm.length_b, 0.53, 1e-12);
  // ceil(0.53 / 0.02) = 27 segments: 28 pairs.
  ASSERT_EQ(sm.pairs.size(), 28u);
  for (std::size_t k = 0; k < sm.pairs.size(); ++k) {
    const auto& [a, bnode] = sm.pairs[k];
    EXPECT_EQ(a.piece, 0);
    EXPECT_EQ(bnode.piece, 1);
    const Vec2 pa = g.pieces[0].mesh.nodes[a.node], pb = g.pieces[1].mesh.nodes[bnode.node];
    // Proportional positions along the two hems, both running upwards.
    const double t = static_cast<double>(k) / 27.0;
    EXPECT_NEAR(pa.x(), 0.30, 1e-12);
    EXPECT_NEAR(pa.y(), 0.50 * t, 1e-9);
    EXPECT_NEAR(pb.x(), 1.0, 1e-12);
    EXPECT_NEAR(pb.y(), 0.53 * t, 1e-9);
  }
  // No Steiner point was added on the boundary, and the mesh covers the piece.
  for (const auto& p : g.pieces) {
    EXPECT_EQ(p.mesh.boundary_steiner_nodes, 0);
    double area = 0;
    for (const auto& t : p.mesh.triangles) {
      const Vec2 e1 = p.mesh.nodes[t[1]] - p.mesh.nodes[t[0]], e2 = p.mesh.nodes[t[2]] - p.mesh.nodes[t[0]];
      area += 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
    }
    EXPECT_NEAR(area, pattern::signed_area(p.piece.boundary), 1e-12);
  }
}

TEST(Garment, ThreeHemSeamSewsTheFirstToTheOthersInTurn) {
  const xvc::Document probe = two_panels({});
  const auto f = stretch_ids(probe, 0), b = stretch_ids(probe, 1);
  // The front's bottom (0.30) sewn to the back's right side (0.53) then its top (0.34).
  xvc::Node seam{"SEAM", {{"id", "seam1"}, {"name", "cap"}, {"type", "plain"}},
                 {hem("hem1", f[0], f[0], "forward"), hem("hem2", b[1], b[1], "forward"),
                  hem("hem3", b[2], b[2], "forward")}};
  Diagnostics diag;
  AssemblyOptions opt;
  opt.spacing = 0.02;
  const Garment g = assemble_garment(two_panels({seam}), opt, diag);
  ASSERT_EQ(g.seams.size(), 1u);
  const auto& pairs = g.seams[0].pairs;
  const int n = static_cast<int>(std::ceil(0.87 / 0.02 - 1e-9));  // 44 segments on the first hem
  EXPECT_EQ(pairs.size(), static_cast<std::size_t>(n + 2));       // the corner of the back is sewn twice
  // The first hem's ends meet the back's corners (1.34, 0) and (1.0, 0.53).
  EXPECT_LT((g.pieces[1].mesh.nodes[pairs.front()[1].node] - Vec2(1.34, 0.0)).norm(), 1e-12);
  EXPECT_LT((g.pieces[1].mesh.nodes[pairs.back()[1].node] - Vec2(1.0, 0.53)).norm(), 1e-12);
  EXPECT_EQ(pairs.front()[0].node, g.pieces[0].mesh.contour_nodes[0][0]);
}

TEST(Garment, OverlappingHemsAreRefusedNamingTheHem) {
  const xvc::Document probe = two_panels({});
  const auto f = stretch_ids(probe, 0), b = stretch_ids(probe, 1);
  xvc::Node s1{"SEAM", {{"id", "seam1"}}, {hem("hem1", f[1], f[2], "forward"), hem("hem2", b[3], b[3], "reverse")}};
  xvc::Node s2{"SEAM", {{"id", "seam2"}}, {hem("hem3", f[2], f[2], "forward"), hem("hem4", b[1], b[1], "reverse")}};
  Diagnostics diag;
  try {
    assemble_garment(two_panels({s1, s2}), {}, diag);
    FAIL() << "overlapping hems were accepted";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("panels.xvc"), std::string::npos) << m;
    EXPECT_NE(m.find("hem3"), std::string::npos) << m;
    EXPECT_NE(m.find("overlaps hem hem1"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace vgd::dress

namespace vgd::dress {
namespace {

// FRONT and BACK in sizes 38 and 40 (each 2 cm wider and taller); the side
// seam is written for size 38 only, as a seam file applied at the sample
// size leaves a graded document.
xvc::Document graded_panels(bool back_40_has_a_fifth_corner) {
  pattern::Style s;
  s.name = "graded panels";
  s.sample_size = "38";
  s.sizes = {"38", "40"};
  s.pieces = {rectangle("FRONT", 0.0, 0.30, 0.50), rectangle("BACK", 1.0, 0.34, 0.53)};
  for (auto p : {rectangle("FRONT", 0.0, 0.32, 0.52), rectangle("BACK", 1.0, 0.36, 0.55)}) {
    p.size = "40";
    p.block = p.name + "_40";
    if (back_40_has_a_fifth_corner && p.name == "BACK")
      p.boundary.insert(p.boundary.begin() + 1, ContourPoint{Vec2(1.18, 0), PointKind::turn});
    s.pieces.push_back(p);
  }
  xvc::Document doc = xvc::from_style(s);
  const auto f = stretch_ids(doc, 0), b = stretch_ids(doc, 1);
  xvc::Node root = doc.root();
  for (auto& c : root.children)
    if (c.tag == "SEAMS")
      c.children = {xvc::Node{"SEAM", {{"id", "seam1"}, {"name", "side"}, {"type", "plain"}},
                              {hem("hem1", f[1], f[1], "forward"), hem("hem2", b[3], b[3], "reverse")}}};
  return xvc::Document(std::move(root), "graded.xvc");
}

}  // namespace

TEST(Garment, ASizeWithoutSeamsIsSewnAsTheSizeThatHasThem) {
  const xvc::Document doc = graded_panels(false);
  Diagnostics diag;
  AssemblyOptions opt;
  opt.spacing = 0.02;
  opt.size = "40";
  const Garment g = assemble_garment(doc, opt, diag);
  ASSERT_EQ(g.seams.size(), 1u);
  EXPECT_EQ(g.seams[0].name, "side");
  EXPECT_NEAR(g.seams[0].length_a, 0.52, 1e-12) << "sewn on size 40's own front";
  EXPECT_NEAR(g.seams[0].length_b, 0.55, 1e-12);
  bool said = false;
  for (const auto& d : diag.items())
    said = said || (d.severity == Severity::warning && d.entity == "size 40" &&
                    d.message.find("the 1 seams of size 38 are sewn at the same stretches") != std::string::npos);
  EXPECT_TRUE(said) << "the choice is said";

  // Size 38 is sewn as written, with nothing to say.
  Diagnostics quiet;
  opt.size = "38";
  EXPECT_EQ(assemble_garment(doc, opt, quiet).seams.size(), 1u);
  EXPECT_EQ(quiet.count(Severity::warning), 0u);
}

TEST(Garment, SeamsThatDoNotFitAnotherSizeAreAnErrorNamingTheSize) {
  const xvc::Document doc = graded_panels(true);
  Diagnostics diag;
  AssemblyOptions opt;
  opt.spacing = 0.02;
  opt.size = "40";
  try {
    assemble_garment(doc, opt, diag);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.diagnostic().entity, "size 40");
    EXPECT_NE(std::string(e.what()).find("vgd seams suggest --apply --size 40"), std::string::npos) << e.what();
  }
}

TEST(Garment, PiecesWithNoSeamAtAllAreSaid) {
  const xvc::Document doc = two_panels({});
  Diagnostics diag;
  AssemblyOptions opt;
  opt.spacing = 0.02;
  const Garment g = assemble_garment(doc, opt, diag);
  EXPECT_TRUE(g.seams.empty());
  bool said = false;
  for (const auto& d : diag.items()) said = said || d.message.find("no SEAM sews the 2 pieces") != std::string::npos;
  EXPECT_TRUE(said);
}

}  // namespace vgd::dress

namespace vgd::dress {

// A piece cut twice (a sleeve) sewn to each side of a piece cut once: the
// SEAM sewing the body's x = 0.4 side comes first in the document, and the
// copy placed beside that side is copy 1. Copies in document order give it
// copy 0; placed, each seam takes the copy beside its own side.
TEST(Garment, EachSeamSewsTheCopyPlacedNearItsOtherPieces) {
  pattern::Style s = one_size("cut twice", {rectangle("BODY", 0.0, 0.40, 0.50), rectangle("SLEEVE", 1.0, 0.20, 0.50)});
  s.pieces[1].quantity = 2;
  xvc::Document probe = xvc::from_style(s);
  const auto body = stretch_ids(probe, 0), sleeve = stretch_ids(probe, 1);
  xvc::Node root = probe.root();
  for (auto& c : root.children)
    if (c.tag == "SEAMS")
      c.children = {
          xvc::Node{"SEAM", {{"id", "seam1"}, {"name", "at x = 0.4"}, {"type", "plain"}},
                    {hem("hem1", sleeve[3], sleeve[3], "forward"), hem("hem2", body[1], body[1], "reverse")}},
          xvc::Node{"SEAM", {{"id", "seam2"}, {"name", "at x = 0"}, {"type", "plain"}},
                    {hem("hem3", sleeve[3], sleeve[3], "forward"), hem("hem4", body[3], body[3], "reverse")}}};
  const xvc::Document doc(std::move(root), "cut-twice.xvc");
  const std::string sleeve_id(doc.patterns()[1]->id());
  AssemblyOptions opt;
  opt.spacing = 0.05;
  opt.copies[sleeve_id] = 2;
  auto sleeve_piece_of = [](const Garment& g, const GarmentSeam& seam) {
    const int p = seam.pairs.front()[0].piece;
    return g.pieces[p].copy;
  };
  Diagnostics d1;
  const Garment in_order = assemble_garment(doc, opt, d1);
  ASSERT_EQ(in_order.seams.size(), 2u);
  EXPECT_EQ(sleeve_piece_of(in_order, in_order.seams[0]), 0);
  EXPECT_EQ(sleeve_piece_of(in_order, in_order.seams[1]), 1);

  // Copy 0 of the sleeve lies left of the body (its left edge at x = -0.5),
  // copy 1 right of it (at x = 0.6); the body where it is.
  opt.place = [&](const std::string& id, int copy, const std::vector<pattern::Vec2>& pts) {
    std::vector<Eigen::Vector3d> out;
    for (const auto& p : pts) {
      const double x = id == sleeve_id ? p.x() - 1.0 + (copy == 0 ? -0.5 : 0.6) : p.x();
      out.emplace_back(x, p.y(), 0.0);
    }
    return out;
  };
  Diagnostics d2;
  const Garment placed = assemble_garment(doc, opt, d2);
  ASSERT_EQ(placed.seams.size(), 2u);
  EXPECT_EQ(sleeve_piece_of(placed, placed.seams[0]), 1) << "the x = 0.4 side takes the copy beside it";
  EXPECT_EQ(sleeve_piece_of(placed, placed.seams[1]), 0);
}

}  // namespace vgd::dress

namespace vgd::dress {

// A pattern the document marks drape="false" (vgd dress left it out; the
// designer can flip it) is not assembled when no piece list is given, and
// its seams are not sewn, with a warning; a piece list overrides the mark.
TEST(Garment, APatternMarkedNotToDrapeIsLeftOut) {
  const xvc::Document probe = two_panels({});
  const auto f = stretch_ids(probe, 0), b = stretch_ids(probe, 1);
  xvc::Node seam{"SEAM", {{"id", "seam1"}, {"name", "side"}, {"type", "plain"}},
                 {hem("hem1", f[1], f[1], "forward"), hem("hem2", b[3], b[3], "reverse")}};
  xvc::Node root = two_panels({seam}).root();
  for (auto& c : root.children)
    if (c.tag == "PATTERNS") c.children[1].set_attribute("drape", "false");
  const xvc::Document doc(std::move(root), "panels.xvc");
  Diagnostics diag;
  AssemblyOptions opt;
  opt.spacing = 0.03;
  const Garment g = assemble_garment(doc, opt, diag);
  ASSERT_EQ(g.pieces.size(), 1u);
  EXPECT_EQ(g.pieces[0].name, "FRONT");
  EXPECT_TRUE(g.seams.empty());
  ASSERT_FALSE(diag.items().empty());
  EXPECT_EQ(diag.items().front().message, "seam 'side' is not sewn: one of its pieces is left out");
  opt.pieces = {"FRONT", "BACK"};
  Diagnostics listed;
  EXPECT_EQ(assemble_garment(doc, opt, listed).pieces.size(), 2u);
}

// A piece marked folded (cut double and folded lengthwise, a rib) hangs as
// the half beside the longest edge a seam sews, in two layers: BACK (0.34 m
// wide) sewn by its left side is meshed 0.17 m wide, from x = 1.0 to 1.17,
// its seam as long as before. Folded with no seam on it, it is refused
// naming the piece.
TEST(Garment, AFoldedPieceHangsAsTheHalfBesideItsSeamInTwoLayers) {
  const xvc::Document probe = two_panels({});
  const auto f = stretch_ids(probe, 0), b = stretch_ids(probe, 1);
  xvc::Node seam{"SEAM", {{"id", "seam1"}, {"name", "side"}, {"type", "plain"}},
                 {hem("hem1", f[1], f[1], "forward"), hem("hem2", b[3], b[3], "reverse")}};
  const auto folded = [](xvc::Node root) {
    for (auto& c : root.children)
      if (c.tag == "PATTERNS") c.children[1].set_attribute("folded", "true");
    return xvc::Document(std::move(root), "panels.xvc");
  };
  Diagnostics diag;
  AssemblyOptions opt;
  opt.spacing = 0.02;
  const Garment plain = assemble_garment(two_panels({seam}), opt, diag);
  const Garment g = assemble_garment(folded(two_panels({seam}).root()), opt, diag);
  ASSERT_EQ(g.pieces.size(), 2u);
  EXPECT_EQ(plain.pieces[1].layers, 1);
  EXPECT_EQ(g.pieces[0].layers, 1);
  EXPECT_EQ(g.pieces[1].layers, 2);
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
  for (const auto& n : g.pieces[1].mesh.nodes)
    x0 = std::min(x0, n.x()), x1 = std::max(x1, n.x()), y0 = std::min(y0, n.y()), y1 = std::max(y1, n.y());
  EXPECT_NEAR(x0, 1.0, 1e-12);
  EXPECT_NEAR(x1, 1.17, 1e-12);
  EXPECT_NEAR(y1 - y0, 0.53, 1e-12);
  ASSERT_EQ(g.seams.size(), 1u);
  EXPECT_NEAR(g.seams[0].length_b, 0.53, 1e-12);
  EXPECT_EQ(g.seams[0].pairs.size(), plain.seams[0].pairs.size());
  try {
    assemble_garment(folded(two_panels({}).root()), opt, diag);
    FAIL() << "a folded piece no seam sews was assembled";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("piece BACK is folded (folded=\"true\"), but no seam sews it"), std::string::npos)
        << e.what();
  }
}

// A binding sewn to an edge shorter than itself is trimmed to it: a
// 2 × 40 cm strip with a slanted end (43 cm along its other edge) sewn by
// its 40 cm edge to FRONT's 30 cm top is cut short, square, by 10 cm at the
// end its sewn edge ends, and said. One that is not a straight strip (a
// curved one) is not trimmed: eased in, with a warning naming it.
TEST(Garment, ABindingLongerThanItsEdgeIsTrimmedSquareToIt) {
  // The binding's stretch `edge` (its long edge) sewn to FRONT's top.
  const auto document = [](std::vector<ContourPoint> binding, int edge) {
    xvc::Node root =
        xvc::from_style(one_size("bound", {rectangle("FRONT", 0.0, 0.30, 0.50), drawn("BINDING", std::move(binding))})).root();
    xvc::Document d(std::move(root), "bound.xvc");
    const auto f = stretch_ids(d, 0), k = stretch_ids(d, 1);
    xvc::Node seam{"SEAM", {{"id", "seam1"}, {"name", "neck seam"}, {"type", "plain"}},
                   {hem("hem1", k[edge], k[edge], "forward"), hem("hem2", f[2], f[2], "reverse")}};
    root = d.root();
    for (auto& c : root.children)
      if (c.tag == "SEAMS") c.children = {seam};
    return xvc::Document(std::move(root), "bound.xvc");
  };
  AssemblyOptions opt;
  opt.spacing = 0.02;
  {
    Diagnostics diag;
    const Garment g = assemble_garment(document({{Vec2(2.0, 0), PointKind::turn},
                                                 {Vec2(2.02, 0), PointKind::turn},
                                                 {Vec2(2.02, 0.40), PointKind::turn},
                                                 {Vec2(2.0, 0.43), PointKind::turn}},
                                                1),
                                       opt, diag);
    ASSERT_EQ(g.seams.size(), 1u);
    EXPECT_NEAR(g.seams[0].length_a, 0.30, 1e-12);
    EXPECT_NEAR(g.seams[0].length_b, 0.30, 1e-12);
    double y0 = 1e9, y1 = -1e9;
    for (const auto& n : g.pieces[1].mesh.nodes) y0 = std::min(y0, n.y()), y1 = std::max(y1, n.y());
    EXPECT_NEAR(y1 - y0, 0.30, 1e-12) << "cut square: its other edge as long";
    bool said = false;
    for (const auto& d : diag.items())
      said = said || (d.entity == g.pieces[1].pattern_id &&
                      d.message == "binding BINDING trimmed by 10.0 cm to the 30.0 cm it binds");
    EXPECT_TRUE(said);
  }
  {
    std::vector<ContourPoint> arc;  // a quarter ring, 2 cm wide: its outer edge 0.40 m
    const double r = 0.40 / (M_PI / 2);
    for (int k = 0; k <= 8; ++k) {
      const double t = M_PI / 2 * k / 8;
      arc.push_back({Vec2(2.0 + r * std::cos(t), r * std::sin(t)), k == 0 || k == 8 ? PointKind::turn : PointKind::curve});
    }
    for (int k = 8; k >= 0; --k) {
      const double t = M_PI / 2 * k / 8;
      arc.push_back({Vec2(2.0 + (r - 0.02) * std::cos(t), (r - 0.02) * std::sin(t)),
                     k == 0 || k == 8 ? PointKind::turn : PointKind::curve});
    }
    Diagnostics diag;
    const Garment g = assemble_garment(document(arc, 0), opt, diag);
    ASSERT_EQ(g.seams.size(), 1u);
    EXPECT_GT(g.seams[0].length_a, 0.39) << "not trimmed";
    bool warned = false;
    for (const auto& d : diag.items())
      warned = warned || (d.severity == Severity::warning && d.entity == g.pieces[1].pattern_id &&
                          d.message.find("binding BINDING is ") == 0 &&
                          d.message.find("not a straight strip vgd can trim: it is eased in") != std::string::npos);
    EXPECT_TRUE(warned);
  }
}

// An allowance's corner left on a piece (MEN_CLASSIC_TEE's back sleeve
// half): EAR, 20 × 20 cm, has its right side sewn to PANEL's right side and
// its top to PANEL's top; both end at PANEL's corner C. Between those two
// seams EAR's outline runs out to a point 5 cm beyond its corner, from
// (0.20, 0.17) to (0.25, 0.25) and back to (0.17, 0.20): 18.9 cm of cloth
// edge whose ends are sewn to C, the cloth between standing off as a horn.
// It is cut off along its 4.2 cm chord, and said. So it is when PANEL's top
// starts 1.5 cm short of C, the 1.5 cm of it beside C unsewn (the tee's back
// has 2 cm so at its shoulder point): the ends are sewn within 1.5 cm of each
// other, under half the chord. With the top sewn to PANEL's bottom instead,
// the ends go to two points 17 cm apart: the corner stays.
TEST(Garment, AnEarBetweenTwoSeamsSewnToOnePointIsCutOffAlongItsChord) {
  enum Top { at_c, short_of_c, at_bottom };
  const auto document = [](Top top) {
    pattern::Piece e = drawn("EAR", {{Vec2(0, 0), PointKind::turn},
                                     {Vec2(0.20, 0), PointKind::turn},
                                     {Vec2(0.20, 0.17), PointKind::turn},
                                     {Vec2(0.25, 0.25), PointKind::turn},
                                     {Vec2(0.17, 0.20), PointKind::turn},
                                     {Vec2(0, 0.20), PointKind::turn}});
    e.grain_line = pattern::Segment{Vec2(0.1, 0.02), Vec2(0.1, 0.18)};
    pattern::Piece panel = rectangle("PANEL", 1.0, 0.17, 0.17);
    if (top == short_of_c) panel.boundary.insert(panel.boundary.begin() + 3, {Vec2(1.155, 0.17), PointKind::turn});
    xvc::Document d(xvc::from_style(one_size("ear", {panel, e})).root(), "ear.xvc");
    const auto p = stretch_ids(d, 0), k = stretch_ids(d, 1);
    // PANEL: 0 bottom, 1 right (up to C), 2 top (from C; short_of_c: 2 the
    // 1.5 cm beside C, 3 the rest), left. EAR: 1 right side, 4 top.
    const std::string& panel_top = top == at_c ? p[2] : top == short_of_c ? p[3] : p[0];
    std::vector<xvc::Node> seams = {
        {"SEAM", {{"id", "seam1"}, {"name", "side"}, {"type", "plain"}},
         {hem("hem1", k[1], k[1], "forward"), hem("hem2", p[1], p[1], "forward")}},
        {"SEAM", {{"id", "seam2"}, {"name", "top"}, {"type", "plain"}},
         {hem("hem3", k[4], k[4], "forward"), hem("hem4", panel_top, panel_top, top == at_bottom ? "reverse" : "forward")}}};
    xvc::Node root = d.root();
    for (auto& c : root.children)
      if (c.tag == "SEAMS") c.children = seams;
    return xvc::Document(std::move(root), "ear.xvc");
  };
  AssemblyOptions opt;
  opt.spacing = 0.02;
  const auto reach = [](const Garment& g) {  // how far EAR's cloth reaches beyond its corner, along (1, 1)
    double most = -1e9;
    for (const auto& n : g.pieces[1].mesh.nodes) most = std::max(most, n.x() + n.y());
    return most;
  };
  for (const Top top : {at_c, short_of_c}) {
    Diagnostics diag;
    const Garment g = assemble_garment(document(top), opt, diag);
    ASSERT_EQ(g.pieces.size(), 2u);
    EXPECT_NEAR(reach(g), 0.37, 1e-12) << "cut along the chord x + y = 0.37";
    const std::string sewn = top == at_c ? "to one point" : "within 1.5 cm of each other";
    bool said = false;
    for (const auto& d : diag.items())
      said = said || (d.entity == g.pieces[1].pattern_id &&
                      d.message == "EAR: the 18.9 cm of outline between seams 'side' and 'top', whose ends are sewn " +
                                       sewn +
                                       ", cut off along its 4.2 cm chord (19.5 cm² of an allowance's corner, which "
                                       "would stand off the garment)");
    EXPECT_TRUE(said) << sewn;
    ASSERT_EQ(g.seams.size(), 2u);
    EXPECT_NEAR(g.seams[0].length_a, 0.17, 1e-12) << "the seams keep their stretches";
    EXPECT_NEAR(g.seams[1].length_a, 0.17, 1e-12);
  }
  {
    Diagnostics diag;
    const Garment g = assemble_garment(document(at_bottom), opt, diag);
    EXPECT_NEAR(reach(g), 0.50, 1e-12) << "two points: the corner stays";
    for (const auto& d : diag.items()) EXPECT_EQ(d.message.find("cut off along"), std::string::npos) << d.message;
  }
}

// A patch pocket sewn onto a panel's face (POSITION type="placement"): a
// 10 × 12 cm POCKET whose mouth is its top edge, placed with its middle at
// (0.15, 0.30) on the 30 × 50 cm FRONT, turned by 90°. Its outline but the
// mouth (34 cm) is sewn vertex to vertex to a line of FRONT's mesh where it
// lies there: each pair's two nodes at one pattern point. Placed past
// FRONT's edge, it is refused naming the POSITION.
TEST(Garment, APocketIsSewnOntoItsHostsFaceAlongItsOutlineButItsMouth) {
  const auto document = [](double x) {
    xvc::Node root =
        xvc::from_style(one_size("pocketed", {rectangle("FRONT", 0.0, 0.30, 0.50), rectangle("POCKET", 1.0, 0.10, 0.12)}))
            .root();
    for (auto& c : root.children)
      if (c.tag == "PATTERNS")
        for (auto& p : c.children)
          if (p.attribute("piece") == "POCKET") {
            xvc::Node pos = xvc::face_placement_node({"", std::string(c.children[0].id()), x, 0.30, 90.0});
            pos.set_attribute("id", "pos_pocket");
            p.children.push_back(pos);
          }
    return xvc::Document(std::move(root), "pocketed.xvc");
  };
  AssemblyOptions opt;
  opt.spacing = 0.02;
  Diagnostics diag;
  const Garment g = assemble_garment(document(0.15), opt, diag);
  ASSERT_EQ(g.pieces.size(), 2u);
  EXPECT_EQ(g.pieces[1].host, 0);
  EXPECT_EQ(g.pieces[1].face_layer, 1);
  EXPECT_NEAR(g.pieces[1].face_gap, 0.005, 1e-15);
  ASSERT_EQ(g.seams.size(), 1u);
  const GarmentSeam& seam = g.seams[0];
  EXPECT_EQ(seam.name, "POCKET on FRONT");
  EXPECT_NEAR(seam.length_a, 0.34, 1e-12) << "the sides and the bottom, not the mouth";
  ASSERT_EQ(seam.pairs.size(), 18u) << "34 cm at 2 cm: 17 segments";
  const pattern::Vec2 mouth_left(1.0, 0.12), mouth_right(1.10, 0.12);
  for (const auto& [a, b] : seam.pairs) {
    ASSERT_EQ(a.piece, 1);
    ASSERT_EQ(b.piece, 0);
    const pattern::Vec2 p = g.pieces[1].mesh.nodes[a.node], q = g.pieces[0].mesh.nodes[b.node];
    EXPECT_LT((g.pieces[1].on_host(p) - q).norm(), 1e-12) << "the pocket's point where it lies on FRONT";
    EXPECT_FALSE(p.y() > 0.12 - 1e-12 && p.x() > 1.0 + 1e-9 && p.x() < 1.10 - 1e-9) << "no pair inside the mouth";
  }
  // Turned by 90°: the mouth (the pocket's top) lies on FRONT's left, x = 0.15 - 0.06.
  EXPECT_LT((g.pieces[1].on_host(mouth_left) - pattern::Vec2(0.09, 0.25)).norm(), 1e-12);
  EXPECT_LT((g.pieces[1].on_host(mouth_right) - pattern::Vec2(0.09, 0.35)).norm(), 1e-12);
  try {
    assemble_garment(document(0.27), opt, diag);
    FAIL() << "a pocket past its host's edge was assembled";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("pos_pocket: POCKET placed on FRONT reaches past its outline at"),
              std::string::npos)
        << e.what();
  }
}

// A pocket flap (its name says FLAP) is sewn by its top edge only: a
// 10 × 5 cm POCKET FLAP on FRONT, turned by 90° like the pocket above, is
// sewn along its 10 cm top edge, starts 10 mm off the front (a pocket 5 mm)
// and is two faces out from it, over a pocket (GarmentPiece::face_layer).
TEST(Garment, APocketFlapIsSewnOntoItsHostsFaceByItsTopEdge) {
  xvc::Node root = xvc::from_style(one_size("flapped", {rectangle("FRONT", 0.0, 0.30, 0.50),
                                                         rectangle("POCKET FLAP", 1.0, 0.10, 0.05)}))
                       .root();
  for (auto& c : root.children)
    if (c.tag == "PATTERNS") {
      xvc::Node pos = xvc::face_placement_node({"", std::string(c.children[0].id()), 0.15, 0.30, 90.0});
      pos.set_attribute("id", "pos_flap");
      c.children[1].children.push_back(pos);
    }
  AssemblyOptions opt;
  opt.spacing = 0.02;
  Diagnostics diag;
  const Garment g = assemble_garment(xvc::Document(std::move(root), "flapped.xvc"), opt, diag);
  ASSERT_EQ(g.seams.size(), 1u);
  EXPECT_EQ(g.seams[0].name, "POCKET FLAP on FRONT");
  EXPECT_NEAR(g.seams[0].length_a, 0.10, 1e-12) << "its top edge";
  ASSERT_EQ(g.seams[0].pairs.size(), 6u);
  for (const auto& [a, b] : g.seams[0].pairs) EXPECT_NEAR(g.pieces[1].mesh.nodes[a.node].y(), 0.05, 1e-12);
  EXPECT_EQ(g.pieces[1].face_layer, 2);
  EXPECT_NEAR(g.pieces[1].face_gap, 0.010, 1e-15);
  EXPECT_EQ(g.pieces[0].face_layer, 0);
}

// A 15 × 3 cm PLACKET drawn lying down, turned upright (90°) on a 30 × 50 cm
// FRONT, is sewn by its two 3 cm ends only, each a seam of its own: its top
// end (its own right edge) where it lies on the front 7.5 cm above its
// middle, its bottom end 7.5 cm below; a face out from the front.
TEST(Garment, APlacketIsSewnOntoItsHostsFaceByItsTwoEnds) {
  xvc::Node root = xvc::from_style(one_size("polo", {rectangle("FRONT", 0.0, 0.30, 0.50),
                                                     rectangle("PLACKET", 1.0, 0.15, 0.03)}))
                       .root();
  for (auto& c : root.children)
    if (c.tag == "PATTERNS") {
      xvc::Node pos = xvc::face_placement_node({"", std::string(c.children[0].id()), 0.15, 0.30, 90.0});
      pos.set_attribute("id", "pos_placket");
      c.children[1].children.push_back(pos);
    }
  AssemblyOptions opt;
  opt.spacing = 0.02;
  Diagnostics diag;
  const Garment g = assemble_garment(xvc::Document(std::move(root), "polo.xvc"), opt, diag);
  ASSERT_EQ(g.seams.size(), 2u);
  for (const auto& [seam, own_x, host_y] : {std::tuple{0, 1.15, 0.375}, std::tuple{1, 1.0, 0.225}}) {
    const GarmentSeam& s = g.seams[seam];
    EXPECT_EQ(s.name, std::string("PLACKET on FRONT (") + (seam == 0 ? "top" : "bottom") + ")");
    EXPECT_NEAR(s.length_a, 0.03, 1e-12) << s.name;
    ASSERT_EQ(s.pairs.size(), 3u) << s.name;
    for (const auto& [a, b] : s.pairs) {
      EXPECT_EQ(a.piece, 1);
      EXPECT_NEAR(g.pieces[1].mesh.nodes[a.node].x(), own_x, 1e-12) << s.name;
      EXPECT_EQ(b.piece, 0);
      EXPECT_NEAR(g.pieces[0].mesh.nodes[b.node].y(), host_y, 1e-9) << s.name;
    }
  }
  EXPECT_EQ(g.pieces[1].face_layer, 1);
  EXPECT_NEAR(g.pieces[1].face_gap, 0.005, 1e-15);
}

}  // namespace vgd::dress
