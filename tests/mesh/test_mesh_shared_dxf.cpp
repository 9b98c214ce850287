// Meshing every piece of every shared real DXF file at 1 cm: the bounds hold on
// real outlines (Gerber AAMA/ASTM, CLO, Valentina), not just on test shapes.
// Built only with the importer (vgd_io_dxf); skipped without ../shared.
#include <gtest/gtest.h>

#include <cctype>

#include "support/test_paths.hpp"
#include "vgd/io/dxf/import.hpp"
#include "vgd/mesh/mesh.hpp"
#include "vgd/mesh/quality.hpp"
#include "vgd/mesh/triangle_io.hpp"

using namespace vgd;
using namespace vgd::mesh;

namespace {

class MeshSharedDxf : public ::testing::TestWithParam<std::string> {};

// Meshes the given sizes (empty = the sample size) and checks every piece.
void mesh_and_check(const std::string& file, const std::vector<std::string>& sizes) {
  const auto imported = dxf::import_file(test::shared_dxf(file));
  const pattern::Style& style = imported.style;
  MeshOptions o;  // 1 cm spacing, 25°, default area bound
  const double bound = effective_max_area(o);
  for (const std::string& size : sizes) {
    Diagnostics d;
    const auto meshes = mesh_style(style, size, o, d);
    EXPECT_FALSE(d.has_errors()) << file << " size " << size << ": " << d.items().front().format();

    // Every closed, non-crossing piece of the size is meshed; the others are warned about.
    std::size_t meshable = 0, blocks = 0;
    for (const pattern::Piece* p : style.pieces_of_size(size.empty() ? style.sample_size : size)) {
      ++blocks;
      meshable += p->closed && !p->self_intersecting;
    }
    EXPECT_EQ(meshes.size(), meshable) << file << " size " << size;
    EXPECT_GE(d.count(Severity::warning), blocks - meshable) << file;

    for (const PieceMesh& m : meshes) {
      const QualityReport q = check_mesh(m, o.min_angle_deg);
      EXPECT_TRUE(q.valid()) << file << " " << m.piece << ": " << q.problems.front();
      EXPECT_LE(q.area_rel_error, 1e-9) << file << " " << m.piece;
      EXPECT_EQ(q.missing_contour_vertices, 0) << file << " " << m.piece;
      EXPECT_LE(q.max_area_m2, bound * (1 + 1e-12)) << file << " " << m.piece;
      EXPECT_GE(q.min_angle_away_from_sharp_deg, 20.7) << file << " " << m.piece;
      EXPECT_GE(q.min_angle_away_from_sharp_deg, o.min_angle_deg) << file << " " << m.piece;
    }
  }
}

}  // namespace

TEST_P(MeshSharedDxf, SampleSizeMeetsTheBounds) {
  VGD_REQUIRE_SHARED();
  mesh_and_check(GetParam(), {""});
}

TEST_P(MeshSharedDxf, EverySizeMeetsTheBounds) {
  VGD_REQUIRE_SHARED();
  const auto imported = dxf::import_file(test::shared_dxf(GetParam()));
  mesh_and_check(GetParam(), imported.style.sizes);
}

INSTANTIATE_TEST_SUITE_P(Files, MeshSharedDxf,
                         ::testing::ValuesIn(test::shared_dxf_files()), test::FileParamName());

TEST(MeshSharedDxfFiles, TriangleFilesOfARealPieceRoundTrip) {
  VGD_REQUIRE_SHARED();
  const auto imported = dxf::import_file(test::shared_dxf("drill-holes.DXF"));
  Diagnostics d;
  const auto meshes = mesh_style(imported.style, "", MeshOptions{}, d);
  ASSERT_FALSE(meshes.empty());
  const auto dir = test::scratch_dir("mesh_shared_triangle");
  write_triangle_files(meshes.front(), dir / "piece.1");
  const TriangleData back = read_triangle_files(dir / "piece.1");
  const TriangleData want = to_triangle_data(meshes.front());
  EXPECT_EQ(back.nodes, want.nodes);
  EXPECT_EQ(back.triangles, want.triangles);
  EXPECT_EQ(back.segments, want.segments);
  EXPECT_EQ(back.segment_markers, want.segment_markers);
}
