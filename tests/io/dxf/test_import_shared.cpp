// The importer against figures computed independently (ezdxf + a raw tag reader,
// exact arithmetic; tests/io/dxf/reference/README.md) for every block of every
// shared real DXF file: Gerber AAMA and ASTM, CLO, Valentina AAMA and ASTM.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/test_paths.hpp"
#include "vgd/io/dxf/import.hpp"
#include "vgd/pattern/roles.hpp"
#include "vgd/pattern/shape_roles.hpp"

using nlohmann::json;

namespace {

const json& reference() {
  static const json j = [] {
    std::ifstream in(vgd::test::source_dir() / "tests/io/dxf/reference/expected.json");
    return json::parse(in);
  }();
  return j;
}

// "2", "1,1" -> 2; null (no quantity anywhere) -> the importer's default 1.
int reference_quantity(const json& q) {
  if (q.is_null()) return 1;
  int total = 0;
  std::string s = q.get<std::string>();
  std::size_t pos = 0;
  while (pos <= s.size()) {
    const auto comma = s.find(',', pos);
    total += std::stoi(s.substr(pos, comma - pos));
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  return total;
}

bool near_rel(double a, double b, double rel) { return std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b)); }

class SharedDxf : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(SharedDxf, MatchesIndependentReference) {
  VGD_REQUIRE_SHARED();
  const std::string file = GetParam();
  const json& ref = reference().at("files").at(file);
  const json& rs = ref.at("summary");
  const auto result = vgd::dxf::import_file(vgd::test::shared_dxf(file));
  const auto& s = result.summary;

  // File level: pieces, blocks, sizes, units, flavour.
  EXPECT_EQ(s.pieces, rs.at("pieces").get<int>());
  EXPECT_EQ(s.blocks, rs.at("blocks").get<int>());
  ASSERT_EQ(s.sizes.size(), rs.at("sizes").size());
  for (std::size_t i = 0; i < s.sizes.size(); ++i) {
    const auto want = rs.at("sizes")[i].get<std::string>();
    EXPECT_EQ(s.sizes[i], want.empty() ? "base" : want);  // no size stated anywhere -> "base"
  }
  EXPECT_EQ(vgd::parse_length_unit(s.units), vgd::parse_length_unit(rs.at("units").get<std::string>()));
  EXPECT_EQ(s.flavour, rs.at("flavour").get<std::string>());
  if (!rs.at("sample_size").is_null() && !rs.at("sample_size").get<std::string>().empty()) {
    EXPECT_EQ(s.sample_size, rs.at("sample_size").get<std::string>());
  }

  // Block level: one record per block, in file order.
  const json& rb = ref.at("blocks");
  ASSERT_EQ(result.blocks.size(), rb.size());
  for (std::size_t i = 0; i < rb.size(); ++i) {
    const auto& mine = result.blocks[i];
    const json& want = rb[i];
    SCOPED_TRACE(file + " block " + mine.block);
    EXPECT_EQ(mine.block, want.at("block").get<std::string>());
    EXPECT_EQ(mine.piece, want.at("piece").get<std::string>());
    EXPECT_EQ(mine.quantity, reference_quantity(want.at("quantity")));
    EXPECT_EQ(mine.boundary_vertices, want.at("boundary_vertices").get<int>());
    EXPECT_EQ(mine.closed, want.at("closed").get<bool>());
    EXPECT_TRUE(near_rel(mine.area_m2, want.at("area_m2").get<double>(), 2e-9))
        << mine.area_m2 << " vs " << want.at("area_m2");
    EXPECT_TRUE(near_rel(mine.perimeter_m, want.at("perimeter_m").get<double>(), 2e-9))
        << mine.perimeter_m << " vs " << want.at("perimeter_m");
    const double grain = want.at("grain_angle_deg").is_null() ? 0.0 : want.at("grain_angle_deg").get<double>();
    EXPECT_NEAR(mine.grain_angle_deg, grain, 1e-7);
    EXPECT_EQ(mine.notches, want.at("notches").get<int>());
    EXPECT_EQ(mine.drill_holes, want.at("drill_holes").get<int>());
    EXPECT_EQ(mine.internal_lines, want.at("internal_lines").at("total").get<int>());
    EXPECT_EQ(mine.mirror_line, !want.at("mirror_line").is_null());
    EXPECT_EQ(mine.self_intersecting, want.at("self_intersecting").get<bool>());
    EXPECT_TRUE(mine.imported);
  }
}

INSTANTIATE_TEST_SUITE_P(AllFiles, SharedDxf,
                         ::testing::ValuesIn(vgd::test::shared_dxf_files()), vgd::test::FileParamName());

// Hand-checked figures (tests/io/dxf/reference/README.md, "Hand checks").
TEST(SharedDxfByHand, CloBoxIsThreeByTwoMetres) {
  VGD_REQUIRE_SHARED();
  const auto r = vgd::dxf::import_file(vgd::test::shared_dxf("clo-box.dxf"));
  ASSERT_EQ(r.blocks.size(), 1u);
  EXPECT_NEAR(r.blocks[0].area_m2, 5.999971674, 1e-9);
  EXPECT_NEAR(r.blocks[0].perimeter_m, 9.999976831, 1e-9);
  EXPECT_NEAR(r.blocks[0].grain_angle_deg, 90.0, 1e-9);
}

TEST(SharedDxfByHand, SimpleTrapezoid) {
  VGD_REQUIRE_SHARED();
  const auto r = vgd::dxf::import_file(vgd::test::shared_dxf("simple.DXF"));
  EXPECT_NEAR(r.blocks[0].area_m2, 0.02521377486, 1e-11);
  EXPECT_NEAR(r.blocks[0].perimeter_m, 1.427895286, 1e-9);
}

TEST(SharedDxf, MirroredFileUnfoldsEveryHalfPiece) {
  VGD_REQUIRE_SHARED();
  vgd::dxf::ImportOptions o;
  o.unfold_mirrored = true;
  const auto r = vgd::dxf::import_file(vgd::test::shared_dxf("mirrored.DXF"), o);
  int halves = 0;
  for (std::size_t i = 0; i < r.blocks.size(); ++i) {
    if (!r.blocks[i].mirror_line) continue;
    ++halves;
    const auto& p = r.style.pieces[i];
    EXPECT_FALSE(p.mirror_line.has_value()) << p.block << " was not unfolded";
    EXPECT_NEAR(std::abs(vgd::pattern::signed_area(p.boundary)), 2 * r.blocks[i].area_m2,
                1e-9 * r.blocks[i].area_m2)
        << p.block;
    EXPECT_FALSE(vgd::pattern::is_self_intersecting(p.boundary)) << p.block;
  }
  EXPECT_EQ(halves, 195);  // 13 half pieces x 15 sizes (195 layer-6 lines)
}

// CLO writes its T-shirt's front and back as left and right halves (blocks
// 11/37 and 7/38), its sleeve twice (36, 39) and a neck binding in two
// halves: joined, 9 blocks are 5 pieces, each half pair twice the area of
// its half, and no other shared file has a piece joined.
TEST(SharedDxf, CloHalvesWrittenPerSideAreJoined) {
  VGD_REQUIRE_SHARED();
  vgd::dxf::ImportOptions o;
  o.unfold_mirrored = true;
  o.join_per_side = true;
  const auto r = vgd::dxf::import_file(vgd::test::shared_dxf("clo-pattern.dxf"), o);
  EXPECT_EQ(r.blocks.size(), 9u);
  ASSERT_EQ(r.joined.size(), 4u);
  EXPECT_EQ(r.style.pieces.size(), 5u);
  int halves = 0;
  for (const auto& j : r.joined) {
    if (!j.halves) {
      EXPECT_EQ(j.kept, "36_M");
      continue;
    }
    ++halves;
    const auto kept = std::find_if(r.blocks.begin(), r.blocks.end(), [&](const auto& b) { return b.block == j.kept; });
    const auto piece = std::find_if(r.style.pieces.begin(), r.style.pieces.end(), [&](const auto& p) { return p.block == j.kept; });
    ASSERT_NE(kept, r.blocks.end());
    ASSERT_NE(piece, r.style.pieces.end());
    EXPECT_NEAR(std::abs(vgd::pattern::signed_area(piece->boundary)), 2 * kept->area_m2, 1e-4 * kept->area_m2) << j.kept;
    EXPECT_FALSE(vgd::pattern::is_self_intersecting(piece->boundary)) << j.kept;
  }
  EXPECT_EQ(halves, 3);
  for (const auto& file : vgd::test::shared_dxf_files()) {
    if (file == "clo-pattern.dxf") continue;
    EXPECT_TRUE(vgd::dxf::import_file(vgd::test::shared_dxf(file), o).joined.empty()) << file;
  }
}

// Valentina's trousers (ASTM) have a closed sew line in every block: sewn on
// them, every block is smaller than as cut, the allowance between 2 mm and
// 8 cm; no other shared file has a sew line.
TEST(SharedDxf, ValentinaTrousersAreSewnOnTheirSewLines) {
  VGD_REQUIRE_SHARED();
  vgd::dxf::ImportOptions o;
  o.sew_on_sew_lines = true;
  const auto cut = vgd::dxf::import_file(vgd::test::shared_dxf("Valentina_Trousers_ASTM_R12.dxf"));
  const auto sewn = vgd::dxf::import_file(vgd::test::shared_dxf("Valentina_Trousers_ASTM_R12.dxf"), o);
  EXPECT_EQ(sewn.sewn_on_sew_lines, 11);
  EXPECT_GE(sewn.allowance_min, 0.002);
  EXPECT_LE(sewn.allowance_max, 0.08);
  ASSERT_EQ(sewn.style.pieces.size(), cut.style.pieces.size());
  for (std::size_t i = 0; i < cut.style.pieces.size(); ++i) {
    EXPECT_LT(std::abs(vgd::pattern::signed_area(sewn.style.pieces[i].boundary)),
              std::abs(vgd::pattern::signed_area(cut.style.pieces[i].boundary)))
        << cut.style.pieces[i].block;
    EXPECT_FALSE(vgd::pattern::is_self_intersecting(sewn.style.pieces[i].boundary)) << cut.style.pieces[i].block;
  }
  for (const auto& file : vgd::test::shared_dxf_files())
    if (file != "Valentina_Trousers_ASTM_R12.dxf") {
      EXPECT_EQ(vgd::dxf::import_file(vgd::test::shared_dxf(file), o).sewn_on_sew_lines, 0) << file;
    }
}

// Roles from shapes on pieces whose names do give a role: over the sample
// size of every shared file, each front, back and sleeve (whole pieces: not
// halves of a sleeve or leg) whose shape gives a role gets the one its name
// gives. Printed: how many of them the shapes recognise.
TEST(SharedDxf, RolesFromShapesAgreeWithTheNamesOfTheSharedFiles) {
  VGD_REQUIRE_SHARED();
  vgd::dxf::ImportOptions o;
  o.unfold_mirrored = true;
  int named = 0, recognised = 0;
  for (const auto& file : vgd::test::shared_dxf_files()) {
    const auto r = vgd::dxf::import_file(vgd::test::shared_dxf(file), o);
    std::vector<const vgd::pattern::Piece*> pieces;
    std::vector<vgd::pattern::Role> by_name;
    for (const auto* p : r.style.pieces_of_size(r.style.sample_size)) {
      const auto g = vgd::pattern::piece_role(p->name, p->category, p->annotation);
      if (g.half != vgd::pattern::Half::none || p->quantity == 0) continue;
      pieces.push_back(p);
      by_name.push_back(g.role);
    }
    const auto shapes = vgd::pattern::roles_from_shapes(pieces);
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      const auto n = by_name[i];
      if (n != vgd::pattern::Role::front && n != vgd::pattern::Role::back && n != vgd::pattern::Role::sleeve) continue;
      ++named;
      if (shapes[i].role == vgd::pattern::Role::unknown) {
        std::printf("not recognised: %s %s (%s)\n", file.c_str(), pieces[i]->name.c_str(),
                    std::string(vgd::pattern::role_name(n)).c_str());
        continue;
      }
      ++recognised;
      EXPECT_EQ(vgd::pattern::role_name(shapes[i].role), vgd::pattern::role_name(n))
          << file << ": " << pieces[i]->name << ": " << shapes[i].why;
    }
  }
  std::printf("roles from shapes: %d of %d named fronts, backs and sleeves recognised\n", recognised, named);
  EXPECT_EQ(named, 20);       // the tops' fronts, backs and sleeves and the trousers' four halves
  EXPECT_EQ(recognised, 16);  // all but the trousers' halves (four body-sized pieces, not two)
}

// Valentina marks no turn points: corners come from the outline. Every
// piece gets at least three, at least 5 mm of arc apart (one per corner), and
// a polygon drawn with few vertices (a collar, a pocket flap: 4 to 7) has a
// corner at every vertex where it turns by 30 degrees or more.
TEST(SharedDxf, FilesWithoutTurnPointsGetTheirCornersFromTheOutline) {
  VGD_REQUIRE_SHARED();
  for (const std::string file : {"Valentina_MaleShirt_AAMA_R12.dxf", "Valentina_Trousers_ASTM_R12.dxf"}) {
    SCOPED_TRACE(file);
    const auto r = vgd::dxf::import_file(vgd::test::shared_dxf(file));
    int said = 0;
    for (const auto& d : r.diagnostics.items()) said += d.message.find("corners found from the outline") != std::string::npos;
    EXPECT_EQ(said, static_cast<int>(r.style.pieces.size()));
    for (const auto& p : r.style.pieces) {
      const auto& b = p.boundary;
      const int n = static_cast<int>(b.size());
      std::vector<int> turns;
      for (int i = 0; i < n; ++i)
        if (b[i].kind == vgd::pattern::PointKind::turn) turns.push_back(i);
      EXPECT_GE(turns.size(), 3u) << p.block;
      for (std::size_t k = 0; k < turns.size(); ++k) {
        const auto& a = b[turns[k]].p;
        const auto& c = b[turns[(k + 1) % turns.size()]].p;
        EXPECT_GT((a - c).norm(), 0.005) << p.block << " vertex " << turns[k];
      }
      if (n <= 7) {
        for (int i = 0; i < n; ++i) {
          const auto u = b[i].p - b[(i + n - 1) % n].p, v = b[(i + 1) % n].p - b[i].p;
          const double turn = std::abs(std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v))) * 180 / M_PI;
          if (turn >= 30 && u.norm() > 0.005 && v.norm() > 0.005) {
            EXPECT_EQ(b[i].kind, vgd::pattern::PointKind::turn) << p.block << " vertex " << i << ", " << turn << " deg";
          }
        }
      }
    }
  }
}
