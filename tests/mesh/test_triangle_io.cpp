// Triangle's .node/.ele/.poly files: exact round trip, and files written by hand.
#include <gtest/gtest.h>

#include <fstream>

#include "support/test_paths.hpp"
#include "synthetic.hpp"
#include "vgd/core/file.hpp"
#include "vgd/mesh/triangle_io.hpp"

using namespace vgd;
using namespace vgd::mesh;

namespace {

void write(const std::filesystem::path& p, const std::string& text) {
  std::ofstream out(p);
  out << text;
}

}  // namespace

TEST(TriangleFiles, RoundTripIsExact) {
  auto p = test::piece("FRONT", test::sleeve());
  p.cutouts.push_back({test::circle({0.2, 0.2}, 0.05, 30), true});
  Diagnostics d;
  MeshOptions o;
  o.resample.spacing_m = 0.02;
  const PieceMesh m = mesh_piece(p, o, d);
  const auto dir = test::scratch_dir("triangle_round_trip");
  write_triangle_files(m, dir / "FRONT.1");
  for (const char* ext : {".node", ".ele", ".poly"}) EXPECT_TRUE(std::filesystem::exists(dir / (std::string("FRONT.1") + ext)));

  const TriangleData in = read_triangle_files(dir / "FRONT.1");
  const TriangleData out = to_triangle_data(m);
  EXPECT_EQ(in.nodes, out.nodes);  // bit for bit
  EXPECT_EQ(in.node_markers, out.node_markers);
  EXPECT_EQ(in.triangles, out.triangles);
  EXPECT_EQ(in.segments, out.segments);
  EXPECT_EQ(in.segment_markers, out.segment_markers);
  ASSERT_EQ(in.holes.size(), 1u);
  EXPECT_EQ(in.holes, out.holes);
  EXPECT_LT((in.holes[0] - Vec2(0.2, 0.2)).norm(), 0.05);  // inside the cutout
  EXPECT_EQ(in.segments.size(), m.boundary.size());
  EXPECT_EQ(in.node_markers[m.contour_nodes[1][0]], kFirstCutoutMarker);
}

TEST(TriangleFiles, ReadsZeroBasedFilesWithCommentsAndAttributes) {
  const auto dir = test::scratch_dir("triangle_hand_written");
  write(dir / "box.node",
        "# a unit square\n"
        "4 2 1 1\n"
        "0 0.0 0.0 7.5 1\n"
        "1 1.0 0.0 7.5 1   # attribute 7.5 ignored\n"
        "2 1.0 1.0 7.5 1\n"
        "\n"
        "3 0.0 1.0 7.5 1\n");
  write(dir / "box.ele", "2 3 0\n0 0 1 2\n1 0 2 3\n");
  const TriangleData d = read_triangle_files(dir / "box");
  ASSERT_EQ(d.nodes.size(), 4u);
  EXPECT_EQ(d.nodes[2], Vec2(1, 1));
  EXPECT_EQ(d.node_markers, (std::vector<int>{1, 1, 1, 1}));
  EXPECT_EQ(d.triangles[1], (std::array<int, 3>{0, 2, 3}));
  EXPECT_TRUE(d.segments.empty());  // no .poly
}

TEST(TriangleFiles, ReadsVerticesFromAPolyFile) {
  // Triangle's input form: vertices in the .poly, no .node.
  const auto dir = test::scratch_dir("triangle_poly_vertices");
  write(dir / "t.poly", "3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n3 1\n1 1 2 5\n2 2 3 5\n3 3 1 5\n0\n");
  write(dir / "t.ele", "1 3 0\n1 1 2 3\n");
  const TriangleData d = read_triangle_files(dir / "t");
  EXPECT_EQ(d.nodes.size(), 3u);
  EXPECT_EQ(d.segments[2], (std::array<int, 2>{2, 0}));
  EXPECT_EQ(d.segment_markers, (std::vector<int>{5, 5, 5}));
}

TEST(TriangleFiles, ErrorsNameFileAndLine) {
  const auto dir = test::scratch_dir("triangle_errors");
  write(dir / "bad.node", "3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n");
  write(dir / "bad.ele", "1 3 0\n1 1 2 9\n");
  try {
    read_triangle_files(dir / "bad");
    FAIL() << "expected vgd::Error";
  } catch (const Error& e) {
    EXPECT_NE(e.diagnostic().file.find("bad.ele"), std::string::npos);
    EXPECT_EQ(e.diagnostic().line, 2);
  }
  write(dir / "num.node", "2 2 0 0\n1 0 zero\n2 1 0\n");
  write(dir / "num.ele", "0 3 0\n");
  try {
    read_triangle_files(dir / "num");
    FAIL() << "expected vgd::Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.diagnostic().line, 2);
  }
  EXPECT_THROW(read_triangle_files(dir / "missing"), Error);
}
