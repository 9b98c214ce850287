// Meshing synthetic pieces: the bounds hold, the contour survives, the area is exact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "synthetic.hpp"
#include "vgd/mesh/mesh.hpp"
#include "vgd/mesh/quality.hpp"

using namespace vgd;
using namespace vgd::mesh;
using vgd::test::piece;

namespace {

// CGAL's proven bound; every non-exempt triangle must reach it.
constexpr double kProvenAngle = 20.7;

bool is_node(const PieceMesh& m, const Vec2& p) {
  return std::find(m.nodes.begin(), m.nodes.end(), p) != m.nodes.end();
}

// What every mesh must satisfy: valid, area exact, contour vertices present, the
// size bound everywhere and the angle bound away from sharp corners.
QualityReport expect_good(const PieceMesh& m, const MeshOptions& o) {
  const QualityReport q = check_mesh(m, o.min_angle_deg);
  EXPECT_TRUE(q.valid()) << m.piece << ": " << (q.problems.empty() ? "" : q.problems.front());
  EXPECT_LE(q.area_rel_error, 1e-9) << m.piece;
  EXPECT_EQ(q.missing_contour_vertices, 0) << m.piece;
  const double bound = effective_max_area(o);
  if (bound > 0) {
    EXPECT_LE(q.max_area_m2, bound * (1 + 1e-12)) << m.piece;
  }
  EXPECT_GE(q.min_angle_away_from_sharp_deg, kProvenAngle) << m.piece;
  EXPECT_EQ(q.boundary_steiner_nodes, m.boundary_steiner_nodes) << m.piece;
  return q;
}

// Boundary edges lie on the contour edge they name, follow each other along every
// contour, and carry that contour's marker and side.
void expect_boundary_attributed(const PieceMesh& m) {
  for (std::size_t k = 0; k < m.boundary.size(); ++k) {
    const BoundaryEdge& e = m.boundary[k];
    ASSERT_GE(e.contour, 0);
    ASSERT_LT(static_cast<std::size_t>(e.contour), m.contours.size());
    const auto& pts = m.contours[e.contour].points;
    ASSERT_GE(e.contour_edge, 0);
    const Vec2 p = pts[e.contour_edge], q = pts[(e.contour_edge + 1) % pts.size()];
    for (int v : {e.a, e.b}) {
      const Vec2 r = m.nodes[v] - p, d = q - p;
      EXPECT_LE(std::abs(d.x() * r.y() - d.y() * r.x()), 1e-12 * d.squaredNorm()) << "edge " << k;
    }
    EXPECT_EQ(e.marker, e.contour == 0 ? kOutlineMarker : kFirstCutoutMarker + e.contour - 1);
    if (!m.contours[e.contour].sides.empty()) {
      EXPECT_EQ(e.side, m.contours[e.contour].sides[e.contour_edge]);
    }
    const BoundaryEdge& next = m.boundary[(k + 1) % m.boundary.size()];
    if (next.contour == e.contour) {
      EXPECT_EQ(next.a, e.b) << "edge " << k;
    }
  }
}

MeshOptions opts(double spacing = 0.01, double min_angle = 25.0) {
  MeshOptions o;
  o.resample.spacing_m = spacing;
  o.min_angle_deg = min_angle;
  return o;
}

}  // namespace

TEST(MeshPiece, SquareMeetsBoundsAndKeepsCorners) {
  Diagnostics d;
  const auto o = opts();
  const PieceMesh m = mesh_piece(piece("SQUARE", test::square()), o, d);
  const QualityReport q = expect_good(m, o);
  EXPECT_GE(q.min_angle_deg, o.min_angle_deg);
  EXPECT_NEAR(q.mesh_area_m2, 0.25, 0.25 * 1e-9);
  for (const Vec2& c : test::square()) EXPECT_TRUE(is_node(m, c));
  // 1 cm spacing, 200 contour vertices, no Steiner point needed on a straight boundary.
  EXPECT_EQ(m.contours[0].points.size(), 200u);
  EXPECT_EQ(m.boundary_steiner_nodes, 0);
  EXPECT_TRUE(d.empty());
  expect_boundary_attributed(m);
}

TEST(MeshPiece, LShapeAreaIsExact) {
  Diagnostics d;
  const auto o = opts(0.02);
  const PieceMesh m = mesh_piece(piece("L", test::l_shape()), o, d);
  const QualityReport q = expect_good(m, o);
  EXPECT_GE(q.min_angle_deg, o.min_angle_deg);
  EXPECT_NEAR(q.mesh_area_m2, std::abs(pattern::signed_area(test::l_shape())), 1e-9 * q.mesh_area_m2);
  for (const Vec2& c : test::l_shape()) EXPECT_TRUE(is_node(m, c));
  expect_boundary_attributed(m);
}

TEST(MeshPiece, SharpSpikeIsTheOnlyPlaceBelowTheAngleBound) {
  Diagnostics d;
  const auto o = opts();
  const PieceMesh m = mesh_piece(piece("SPIKE", test::spiked()), o, d);
  const QualityReport q = expect_good(m, o);
  EXPECT_EQ(q.sharp_corners, 1);                // the 10° tip
  EXPECT_NEAR(q.min_angle_deg, 10.0, 1e-6);     // the tip triangle cannot do better
  EXPECT_GE(q.min_angle_away_from_sharp_deg, o.min_angle_deg);
  for (const Vec2& c : test::spiked()) EXPECT_TRUE(is_node(m, c));
  expect_boundary_attributed(m);
}

TEST(MeshPiece, HolesAreCutOutInEitherOrientation) {
  auto p = piece("HOLES", test::square());
  p.cutouts.push_back({test::circle({0.3, 0.3}, 0.1, 64, /*ccw=*/false), true});
  p.cutouts.push_back({{{0.05, 0.05}, {0.15, 0.05}, {0.15, 0.1}, {0.05, 0.1}}, true});
  Diagnostics d;
  const auto o = opts();
  const PieceMesh m = mesh_piece(p, o, d);
  const QualityReport q = expect_good(m, o);
  EXPECT_TRUE(d.empty());
  ASSERT_EQ(m.contours.size(), 3u);
  EXPECT_EQ(m.contours[1].cutout, 0);
  EXPECT_EQ(m.contours[2].cutout, 1);
  // Polygon area of the (resampled) contours: the square minus both holes.
  const double expected = 0.25 - std::abs(pattern::signed_area(m.contours[1].points)) - 0.005;
  EXPECT_NEAR(q.mesh_area_m2, expected, 1e-9 * expected);
  // No triangle inside a hole.
  for (const auto& t : m.triangles) {
    const Vec2 c = (m.nodes[t[0]] + m.nodes[t[1]] + m.nodes[t[2]]) / 3;
    EXPECT_GT((c - Vec2(0.3, 0.3)).norm(), 0.09);
    EXPECT_FALSE(c.x() > 0.05 && c.x() < 0.15 && c.y() > 0.05 && c.y() < 0.1);
  }
  // Hole nodes carry their hole's marker.
  for (int v : m.contour_nodes[1]) EXPECT_EQ(m.node_markers[v], kFirstCutoutMarker);
  for (int v : m.contour_nodes[2]) EXPECT_EQ(m.node_markers[v], kFirstCutoutMarker + 1);
  expect_boundary_attributed(m);
}

TEST(MeshPiece, PatternCurveWith500Vertices) {
  const auto outline = test::sleeve(500);
  ASSERT_EQ(outline.size(), 500u);
  Diagnostics d;
  const auto o = opts();
  // Hem corners and underarm points are AAMA turn points, as a CAD system marks them.
  auto p = piece("SLEEVE", outline);
  for (int i : {0, 1, 2, 499}) p.boundary[i].kind = pattern::PointKind::turn;
  const PieceMesh m = mesh_piece(p, o, d);
  const QualityReport q = expect_good(m, o);
  EXPECT_GE(q.min_angle_deg, o.min_angle_deg);
  // The turn points are side ends: kept exactly.
  for (int i : {0, 1, 2, 499}) EXPECT_TRUE(is_node(m, outline[i])) << i;
  expect_boundary_attributed(m);
}

TEST(MeshPiece, WithoutResamplingEveryInputVertexIsANode) {
  const auto outline = test::sleeve(500);
  auto o = opts();
  o.resample_contour = false;
  o.max_area_m2 = 6e-5;
  Diagnostics d;
  const PieceMesh m = mesh_piece(piece("SLEEVE", outline), o, d);
  expect_good(m, o);
  // Contour vertices come first, in order.
  for (std::size_t i = 0; i < outline.size(); ++i) {
    ASSERT_EQ(m.contour_nodes[0][i], static_cast<int>(i));
    EXPECT_EQ(m.nodes[i], outline[i]);
  }
  // The 0.35 m straight edges need Steiner points; they are counted and attributed.
  EXPECT_GT(m.boundary_steiner_nodes, 0);
  EXPECT_EQ(m.boundary.size(), outline.size() + m.boundary_steiner_nodes);
  expect_boundary_attributed(m);
}

TEST(MeshPiece, ForbiddingBoundarySplitsKeepsTheContourAsIs) {
  auto p = piece("HOLED", test::l_shape());
  p.cutouts.push_back({test::circle({0.07, 0.4}, 0.04, 40), true});
  auto o = opts();
  o.split_boundary = false;
  Diagnostics d;
  const PieceMesh m = mesh_piece(p, o, d);
  const QualityReport q = check_mesh(m, o.min_angle_deg);
  EXPECT_TRUE(q.valid());
  EXPECT_EQ(m.boundary_steiner_nodes, 0);
  EXPECT_EQ(m.boundary.size(), m.contours[0].points.size() + m.contours[1].points.size());
  // With the default size bound no boundary triangle is too big either.
  EXPECT_LE(q.max_area_m2, effective_max_area(o) * (1 + 1e-12));
  expect_boundary_attributed(m);
}

// A line inside the piece (where a pocket is sewn onto it): its points are
// nodes bit for bit, in order, and each of its edges is an edge of the mesh
// with triangles on both sides; the piece is whole (area exact, the
// boundary the outline's). Two lines on the 0.5 m square, a U and a
// straight one; with the boundary kept as drawn no node is added on them.
// A line leaving the piece, or crossing another, is refused naming it.
TEST(MeshPiece, LinesInsideThePieceAreEdgesOfTheMesh) {
  const std::vector<std::vector<Vec2>> lines = {
      {{0.1, 0.4}, {0.1, 0.25}, {0.13, 0.2}, {0.22, 0.2}, {0.25, 0.25}, {0.25, 0.4}},
      {{0.3, 0.1}, {0.35, 0.12}, {0.4, 0.14}}};
  for (const bool split : {true, false}) {
    auto o = opts(0.02);
    o.split_boundary = split;
    o.lines = lines;
    Diagnostics d;
    const PieceMesh m = mesh_piece(piece("FRONT", test::square()), o, d);
    const QualityReport q = check_mesh(m, o.min_angle_deg);
    EXPECT_TRUE(q.valid()) << (q.problems.empty() ? "" : q.problems.front());
    EXPECT_LE(q.area_rel_error, 1e-9);
    ASSERT_EQ(m.line_nodes.size(), 2u);
    for (std::size_t k = 0; k < lines.size(); ++k) {
      ASSERT_EQ(m.line_nodes[k].size(), lines[k].size());
      for (std::size_t i = 0; i < lines[k].size(); ++i) EXPECT_EQ(m.nodes[m.line_nodes[k][i]], lines[k][i]);
      for (std::size_t i = 0; !split && i + 1 < lines[k].size(); ++i) {
        const int a = m.line_nodes[k][i], b = m.line_nodes[k][i + 1];
        int left = 0, right = 0;  // triangles with a -> b, and with b -> a
        for (const auto& t : m.triangles)
          for (int j = 0; j < 3; ++j) {
            left += t[j] == a && t[(j + 1) % 3] == b;
            right += t[j] == b && t[(j + 1) % 3] == a;
          }
        EXPECT_EQ(left, 1) << "line " << k << " edge " << i;
        EXPECT_EQ(right, 1) << "line " << k << " edge " << i;
      }
    }
    EXPECT_EQ(m.boundary.size(), m.contours[0].points.size() + m.boundary_steiner_nodes) << "the outline's";
    expect_boundary_attributed(m);
  }
  auto o = opts(0.02);
  o.lines = {{{0.1, 0.1}, {0.6, 0.1}}};
  Diagnostics d;
  try {
    mesh_piece(piece("FRONT", test::square()), o, d);
    FAIL() << "a line leaving the piece was meshed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("FRONT: line 1 leaves the piece at (0.6000, 0.1000) m"), std::string::npos)
        << e.what();
  }
  o.lines = {{{0.1, 0.1}, {0.4, 0.4}}, {{0.1, 0.4}, {0.4, 0.1}}};
  try {
    mesh_piece(piece("FRONT", test::square()), o, d);
    FAIL() << "crossing lines were meshed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("crosses itself or another contour near (0.2500, 0.2500) m"), std::string::npos)
        << e.what();
  }
}

TEST(MeshPiece, AngleBoundsFrom20_7To30) {
  for (double angle : {20.7, 25.0, 30.0}) {
    Diagnostics d;
    const auto o = opts(0.02, angle);
    const PieceMesh m = mesh_piece(piece("SLEEVE", test::sleeve()), o, d);
    const QualityReport q = expect_good(m, o);
    EXPECT_GE(q.min_angle_deg, angle) << angle;
  }
}

TEST(MeshPiece, EdgeLengthBound) {
  auto o = opts(0.02);
  o.max_area_m2 = 1.0;  // out of the way
  o.max_edge_m = 0.015;
  Diagnostics d;
  const PieceMesh m = mesh_piece(piece("SQUARE", test::square(0.2)), o, d);
  expect_good(m, o);
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) EXPECT_LE((m.nodes[t[k]] - m.nodes[t[(k + 1) % 3]]).norm(), 0.015 * (1 + 1e-12));
}

TEST(MeshPiece, FarFromTheOriginLikeCadFiles) {
  auto outline = test::sleeve();
  for (auto& p : outline) p += Vec2(152.4, -87.3);
  Diagnostics d;
  const auto o = opts();
  const PieceMesh m = mesh_piece(piece("FAR", outline), o, d);
  expect_good(m, o);
}

TEST(MeshPiece, IsDeterministic) {
  Diagnostics d;
  const auto o = opts(0.02);
  const PieceMesh a = mesh_piece(piece("L", test::l_shape()), o, d);
  const PieceMesh b = mesh_piece(piece("L", test::l_shape()), o, d);
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_EQ(a.triangles, b.triangles);
}

TEST(MeshPiece, MaterialFrameFollowsTheGrainLine) {
  auto p = piece("GRAIN", test::square(0.2));
  p.grain_line = pattern::Segment{Vec2(0.1, 0.02), Vec2(0.1, 0.18)};  // vertical grain
  Diagnostics d;
  const PieceMesh m = mesh_piece(p, opts(0.05), d);
  EXPECT_TRUE(m.frame.warp.isApprox(Vec2(0, 1)));
  EXPECT_TRUE(m.frame.weft.isApprox(Vec2(-1, 0)));
  const auto uv = material_coordinates(m);
  ASSERT_EQ(uv.size(), m.nodes.size());
  for (std::size_t i = 0; i < uv.size(); ++i) {
    EXPECT_NEAR(uv[i].x(), m.nodes[i].y() - 0.02, 1e-15);  // along the warp
    EXPECT_NEAR(uv[i].y(), 0.1 - m.nodes[i].x(), 1e-15);   // along the weft
  }
  // No grain line: the pattern's own axes.
  EXPECT_TRUE(material_frame(piece("NONE", test::square())).warp.isApprox(Vec2(1, 0)));
}

TEST(MeshPiece, BadCutoutsAreSkippedWithAWarning) {
  auto p = piece("CUTS", test::square());
  p.cutouts.push_back({{{0.6, 0.1}, {0.7, 0.1}, {0.7, 0.2}}, true});             // outside
  p.cutouts.push_back({{{0.45, 0.2}, {0.55, 0.2}, {0.55, 0.3}, {0.45, 0.3}}, true});  // crosses the outline
  p.cutouts.push_back({{{0.1, 0.1}, {0.2, 0.1}}, false});                        // open
  p.cutouts.push_back({{{0.2, 0.2}, {0.3, 0.2}, {0.3, 0.3}, {0.2, 0.3}}, true});  // fine
  Diagnostics d;
  const PieceMesh m = mesh_piece(p, opts(), d);
  EXPECT_EQ(d.count(Severity::warning), 3u);
  for (const auto& item : d.items()) EXPECT_EQ(item.entity, "CUTS");
  ASSERT_EQ(m.contours.size(), 2u);
  EXPECT_EQ(m.contours[1].cutout, 3);
  expect_good(m, opts());
}

TEST(MeshPiece, UnmeshablePiecesThrowNamingThePiece) {
  Diagnostics d;
  auto open = piece("OPEN_38", test::square());
  open.closed = false;
  try {
    mesh_piece(open, opts(), d);
    FAIL() << "expected vgd::Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.diagnostic().entity, "OPEN_38");
  }
  auto crossed = piece("CROSSED_38", test::square());
  crossed.self_intersecting = true;
  EXPECT_THROW(mesh_piece(crossed, opts(), d), Error);
  auto cw = test::square();
  std::reverse(cw.begin(), cw.end());
  EXPECT_THROW(mesh_piece(piece("CW", cw), opts(), d), Error);
  EXPECT_THROW(mesh_piece(piece("TINY", {{0, 0}, {1, 0}}), opts(), d), Error);
}

TEST(MeshPiece, AnOutlineTouchingItselfIsRefusedAndAFewMicrometresApartMeshes) {
  // A spike back along the bottom edge, 1e-300 m above it: refinement would not end.
  Diagnostics d;
  const std::vector<Vec2> touching{{0, 0}, {0.5, 0}, {0.45, 1e-300}, {0.5, 0.01}, {0.5, 0.5}, {0, 0.5}};
  try {
    mesh_piece(piece("TOUCH", touching), opts(), d);
    FAIL() << "expected vgd::Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.diagnostic().entity, "TOUCH");
    EXPECT_NE(e.diagnostic().message.find("touches itself at (0.4500, 0.0000) m"), std::string::npos)
        << e.diagnostic().message;
  }
  // A notch whose tip comes within 5 micrometres of the opposite edge (a real
  // graded sleeve does): above the 0.1 micrometre tolerance, it meshes.
  MeshOptions o = opts();
  o.resample_contour = false;
  const std::vector<Vec2> close{{0, 0}, {0.5, 0}, {0.5, 0.2}, {0.25, 0.2}, {0.25, 5e-6}, {0.2, 0.2}, {0, 0.2}};
  EXPECT_NO_THROW(mesh_piece(piece("CLOSE", close), o, d));
}

TEST(Triangulate, CrossingContoursAreReportedWithTheirPlace) {
  // A bow tie drawn as one outline (positive net area so the orientation check passes).
  const std::vector<Vec2> bow = {{0, 0}, {1, 0}, {1, 0.5}, {0.4, -0.2}, {0, 0.5}};
  MeshOptions o;
  o.resample_contour = false;
  try {
    triangulate({Contour{bow, {}, -1}}, o, "BOWTIE");
    FAIL() << "expected vgd::Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.diagnostic().entity, "BOWTIE");
    EXPECT_NE(e.diagnostic().message.find("crosses"), std::string::npos) << e.what();
  }
  // A hole outside the outline makes the domain wrong: refused.
  EXPECT_THROW(triangulate({Contour{test::square(), {}, -1}, Contour{test::circle({2, 2}, 0.1, 8), {}, 0}}, o, "X"),
               Error);
}

TEST(Triangulate, RefusesBadOptions) {
  MeshOptions o;
  o.min_angle_deg = 40;
  EXPECT_THROW(triangulate({Contour{test::square(), {}, -1}}, o), Error);
  o = MeshOptions{};
  o.resample.spacing_m = 0;
  Diagnostics d;
  EXPECT_THROW(mesh_piece(piece("S", test::square()), o, d), Error);
  o = MeshOptions{};
  o.max_area_m2 = -1;
  EXPECT_THROW(triangulate({Contour{test::square(), {}, -1}}, o), Error);
}

TEST(Triangulate, NodeGuardStopsRunawayRefinement) {
  MeshOptions o;
  o.resample_contour = false;
  o.max_area_m2 = 1e-10;
  o.max_nodes = 5000;
  try {
    triangulate({Contour{test::square(), {}, -1}}, o, "HUGE");
    FAIL() << "expected vgd::Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.diagnostic().entity, "HUGE");
  }
}

TEST(Triangulate, DefaultAreaBoundFollowsTheSpacing) {
  MeshOptions o;
  o.resample.spacing_m = 0.02;
  EXPECT_NEAR(effective_max_area(o), (1 + std::sqrt(2.0)) / 4 * 4e-4, 1e-18);
  o.max_area_m2 = 1e-3;
  EXPECT_EQ(effective_max_area(o), 1e-3);
  o.max_area_m2 = 0;
  o.resample_contour = false;
  EXPECT_EQ(effective_max_area(o), 0.0);
}

TEST(MeshStyle, SkipsOpenAndCrossingPiecesAndMeshesOneSize) {
  pattern::Style s;
  s.name = "TEST";
  s.sample_size = "M";
  s.sizes = {"S", "M"};
  s.pieces.push_back(piece("FRONT_M", test::l_shape()));
  s.pieces.push_back(piece("BACK_M", test::square(0.3)));
  s.pieces.back().closed = false;
  s.pieces.push_back(piece("SLEEVE_M", test::sleeve()));
  s.pieces.back().self_intersecting = true;
  s.pieces.push_back(piece("FRONT_S", test::l_shape()));
  s.pieces.back().size = "S";
  Diagnostics d;
  const auto meshes = mesh_style(s, "", opts(0.02), d);
  ASSERT_EQ(meshes.size(), 1u);
  EXPECT_EQ(meshes[0].piece, "FRONT_M");
  EXPECT_EQ(d.count(Severity::warning), 2u);
  EXPECT_EQ(mesh_style(s, "S", opts(0.02), d).size(), 1u);
  EXPECT_THROW(mesh_style(s, "XL", opts(0.02), d), Error);
}

TEST(InteriorPoint, IsInsideConcavePolygons) {
  // A C shape whose centroid is outside it.
  const std::vector<Vec2> c = {{0, 0}, {1, 0}, {1, 0.2}, {0.2, 0.2}, {0.2, 0.8}, {1, 0.8}, {1, 1}, {0, 1}};
  const Vec2 p = interior_point(c);
  const bool in_bar = p.x() > 0 && p.x() < 0.2 && p.y() > 0 && p.y() < 1;
  const bool in_arms = p.x() > 0 && p.x() < 1 && ((p.y() > 0 && p.y() < 0.2) || (p.y() > 0.8 && p.y() < 1));
  EXPECT_TRUE(in_bar || in_arms) << p.transpose();
}
