// The VRML flavours on a two-piece tube skirt (tube_skirt.hpp): what each
// file holds (shapes, shared coordinates, counts, texture coordinates equal
// to the material coordinates, welded seams, normals), the seed's creaseAngle
// rule, decimation and precision, the live flavour's PROTOs and engine, the
// seed's flag in a few kilobytes, looks from the XVC document, atomic writes.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <filesystem>
#include <set>

#include "support/test_paths.hpp"
#include "tube_skirt.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/io/vrml/looks.hpp"
#include "vgd/io/vrml/vrml.hpp"
#include "vgd/xvc/io.hpp"
#include "vrml_tokens.hpp"

using namespace vgd;
namespace fs = std::filesystem;
namespace vrml = vgd::io::vrml;

namespace {

// Welded vertices of the default tube skirt: 2 pieces × 9 × 7 particles, less one side column per seam.
constexpr int kParticles = 2 * 9 * 7, kWelded = kParticles - 2 * 9, kFaces = 2 * 8 * 6 * 2;

std::size_t at(const std::vector<std::string>& t, const std::vector<std::string>& seq, std::size_t from = 0) {
  const auto i = test::find_seq(t, seq, from);
  EXPECT_NE(i, std::string::npos) << "not found: " << seq.front() << " " << seq.back();
  return i;
}

}  // namespace

TEST(VrmlStatic, FileStartsWithTheVrml97Header) {
  const std::string s = vrml::static_vrml(test::tube_skirt());
  EXPECT_EQ(s.rfind("#VRML V2.0 utf8\n", 0), 0u);
}

TEST(VrmlStatic, PiecesShareOneCoordinateWithSeamsWelded) {
  const auto g = test::tube_skirt();
  const auto t = test::vrml_tokens(vrml::static_vrml(g));
  EXPECT_TRUE(test::balanced(t));
  EXPECT_EQ(test::count_token(t, "Shape"), 3);  // FRONT, BACK, the body
  EXPECT_NE(test::find_seq(t, {"DEF", "Piece_FRONT", "Shape"}), std::string::npos);
  EXPECT_NE(test::find_seq(t, {"DEF", "Piece_BACK", "Shape"}), std::string::npos);
  EXPECT_NE(test::find_seq(t, {"DEF", "avatar", "Shape"}), std::string::npos);
  EXPECT_EQ(test::count_token(t, "GarmentCoord"), 2);  // DEF once, USE once
  const auto points = test::numbers_after(t, at(t, {"DEF", "GarmentCoord", "Coordinate", "{", "point"}));
  EXPECT_EQ(points.size(), 3u * kWelded);
  // Faces: every triangle once over the two pieces, coordIndex within the welded vertices.
  const auto ci = test::all_fields(t, "coordIndex");
  ASSERT_EQ(ci.size(), 3u);  // two pieces and the body
  EXPECT_EQ(ci[0].size() + ci[1].size(), 4u * kFaces);
  for (int k = 0; k < 2; ++k)
    for (std::size_t i = 0; i < ci[k].size(); ++i) {
      if (i % 4 == 3) EXPECT_EQ(ci[k][i], -1);
      else EXPECT_TRUE(ci[k][i] >= 0 && ci[k][i] < kWelded);
    }
  EXPECT_EQ(ci[2].size(), 4u * g.body->triangles.size());  // the body
  // Double-sided cloth, one normal per welded vertex.
  EXPECT_EQ(test::count_token(t, "solid"), 3);
  EXPECT_EQ(test::find_seq(t, {"solid", "TRUE"}), std::string::npos);
  const auto normals = test::numbers_after(t, at(t, {"DEF", "GarmentNormal", "Normal", "{", "vector"}));
  ASSERT_EQ(normals.size(), 3u * kWelded);
  for (std::size_t v = 0; v < normals.size(); v += 3)
    EXPECT_NEAR(std::hypot(normals[v], normals[v + 1], normals[v + 2]), 1.0, 2e-3);
}

TEST(VrmlStatic, WritesTheLastFrameByDefault) {
  auto g = test::tube_skirt();
  const auto t = test::vrml_tokens(vrml::static_vrml(g));
  const auto points = test::numbers_after(t, at(t, {"DEF", "GarmentCoord", "Coordinate", "{", "point"}));
  const auto mesh = vrml::output_mesh(g.cloth, true);
  const auto& last = g.frames.positions.back();
  for (int v = 0; v < kWelded; ++v)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(points[3 * v + c], last[3 * mesh.vertex_particle[v] + c], 5.1e-5);
}

TEST(VrmlStatic, TexCoordsAreTheMaterialCoordinatesOfEveryParticle) {
  const auto g = test::tube_skirt();
  const auto t = test::vrml_tokens(vrml::static_vrml(g));
  const auto tc = test::numbers_after(t, at(t, {"DEF", "GarmentTexCoord", "TextureCoordinate", "{", "point"}));
  ASSERT_EQ(tc.size(), 2u * g.cloth.uv.size());
  for (std::size_t i = 0; i < g.cloth.uv.size(); ++i) {
    EXPECT_NEAR(tc[2 * i], g.cloth.uv[i][0], 5e-5);
    EXPECT_NEAR(tc[2 * i + 1], g.cloth.uv[i][1], 5e-5);
  }
  // texCoordIndex names each triangle's own particles (so each piece keeps its pattern coordinates at a seam).
  const auto ti = test::all_fields(t, "texCoordIndex");
  ASSERT_EQ(ti.size(), 2u);
  std::size_t tri = 0;
  for (const auto& piece : ti)
    for (std::size_t i = 0; i < piece.size(); i += 4, ++tri)
      for (int k = 0; k < 3; ++k) EXPECT_EQ(piece[i + k], g.cloth.triangles[tri][k]);
  EXPECT_EQ(tri, g.cloth.triangles.size());
}

TEST(VrmlCreaseAngle, FollowsTheMeshResolutionAsTheSeedSays) {
  // Coarse meshes get a large threshold (smooth), fine ones a small one (real creases stay sharp).
  EXPECT_DOUBLE_EQ(vrml::crease_angle(0.05), 3.14);
  EXPECT_NEAR(vrml::crease_angle(0.01), 0.01 / vrml::kCreaseRadius, 1e-12);
  EXPECT_DOUBLE_EQ(vrml::crease_angle(0.001), 0.5);
  for (double h = 0.001; h < 0.05; h *= 1.3) EXPECT_LE(vrml::crease_angle(h), vrml::crease_angle(h * 1.3));
  // The file states the rule's value for its mesh: 5 mm edges -> 0.833 rad; the coarse skirt -> 3.14.
  test::TubeSkirtSpec fine;
  fine.nu = 13, fine.nv = 11, fine.length = 0.06, fine.width = 0.05;
  const auto gf = test::tube_skirt(fine);
  EXPECT_NEAR(vrml::median_edge_length(gf.cloth), 0.005, 1e-9);
  const auto tf = test::vrml_tokens(vrml::static_vrml(gf));
  EXPECT_NEAR(test::numbers_after(tf, at(tf, {"creaseAngle"}))[0], 0.833, 1e-3);
  const auto tc = test::vrml_tokens(vrml::static_vrml(test::tube_skirt()));
  EXPECT_NEAR(test::numbers_after(tc, at(tc, {"creaseAngle"}))[0], 3.14, 1e-9);
  // An explicit value wins.
  vrml::StaticOptions o;
  o.crease_angle = 1.25;
  const auto te = test::vrml_tokens(vrml::static_vrml(gf, o));
  EXPECT_NEAR(test::numbers_after(te, at(te, {"creaseAngle"}))[0], 1.25, 1e-9);
}

TEST(VrmlAnimated, AnInterpolatorOverEveryFrameDrivesTheSharedCoordinate) {
  const auto g = test::tube_skirt();
  const auto t = test::vrml_tokens(vrml::animated_vrml(g));
  EXPECT_TRUE(test::balanced(t));
  // One vertex per particle (seams close during a run), every frame a key.
  const auto points = test::numbers_after(t, at(t, {"DEF", "GarmentCoord", "Coordinate", "{", "point"}));
  EXPECT_EQ(points.size(), 3u * kParticles);
  const auto key = test::numbers_after(t, at(t, {"DEF", "Motion", "CoordinateInterpolator", "{", "key"}));
  ASSERT_EQ(key.size(), 11u);
  EXPECT_DOUBLE_EQ(key.front(), 0.0);
  EXPECT_DOUBLE_EQ(key.back(), 1.0);
  for (std::size_t k = 1; k < key.size(); ++k) EXPECT_GT(key[k], key[k - 1]);
  const auto values = test::numbers_after(t, at(t, {"keyValue"}));
  EXPECT_EQ(values.size(), 11u * 3 * kParticles);
  EXPECT_NEAR(values[3 * kParticles * 4], g.frames.positions[4][0], 6e-4);  // frame 4, particle 0, x
  EXPECT_NEAR(test::numbers_after(t, at(t, {"DEF", "Clock", "TimeSensor", "{", "cycleInterval"}))[0], 1.0, 1e-9);
  EXPECT_NE(test::find_seq(t, {"ROUTE", "Clock.fraction_changed", "TO", "Motion.set_fraction"}), std::string::npos);
  EXPECT_NE(test::find_seq(t, {"ROUTE", "Motion.value_changed", "TO", "GarmentCoord.set_point"}), std::string::npos);
  // No fixed normals: the viewer recomputes them every frame with the creaseAngle.
  EXPECT_EQ(test::count_token(t, "Normal"), 0);
}

TEST(VrmlAnimated, DecimationAndPrecisionShrinkTheFile) {
  test::TubeSkirtSpec s;
  s.frames = 31;
  s.body = false;
  const auto g = test::tube_skirt(s);
  vrml::AnimatedOptions full;
  full.precision = 5;
  vrml::AnimatedOptions every3 = full;
  every3.decimate = 3;
  vrml::AnimatedOptions coarse = every3;
  coarse.precision = 2;
  const auto a = vrml::animated_vrml(g, full), b = vrml::animated_vrml(g, every3), c = vrml::animated_vrml(g, coarse);
  EXPECT_LT(b.size(), 0.45 * a.size());
  EXPECT_LT(c.size(), 0.8 * b.size());
  // Frames 0, 3, ..., 30 kept: 11 keys; the last frame always kept.
  const auto tb = test::vrml_tokens(b);
  EXPECT_EQ(test::numbers_after(tb, at(tb, {"key"})).size(), 11u);
  s.frames = 30;  // 0 .. 27 every 3 and the last (29)
  const auto tl = test::vrml_tokens(vrml::animated_vrml(test::tube_skirt(s), every3));
  const auto key = test::numbers_after(tl, at(tl, {"key"}));
  EXPECT_EQ(key.size(), 11u);
  EXPECT_DOUBLE_EQ(key.back(), 1.0);
  // Two decimals: every coordinate is a multiple of 1 cm.
  const auto tc = test::vrml_tokens(c);
  for (double v : test::numbers_after(tc, at(tc, {"keyValue"}))) EXPECT_NEAR(v * 100, std::round(v * 100), 1e-9);
}

TEST(VrmlNumbers, FixedDecimalsWithoutTrailingZeros) {
  auto f = [](double v, int d) {
    std::string s;
    vrml::append_number(s, v, d);
    return s;
  };
  EXPECT_EQ(f(1.25, 4), "1.25");
  EXPECT_EQ(f(2.0, 3), "2");
  EXPECT_EQ(f(-0.00001, 3), "0");
  EXPECT_EQ(f(-0.1234567, 3), "-0.123");
  EXPECT_EQ(f(1234.6, 0), "1235");
}

TEST(VrmlLive, TheFileCarriesTheSeedsThreeProtosAndAnEcmascriptEngine) {
  auto g = test::tube_skirt();
  vrml::LiveOptions o;
  o.pinned = vrml::top_particles(g, 0.01);
  o.colliders = vrml::body_colliders(g, 4);
  const std::string s = vrml::live_vrml(g, o);
  const auto t = test::vrml_tokens(s);
  EXPECT_TRUE(test::balanced(t));
  for (const char* proto : {"Garment", "ObjectCollider", "SimulationScript"})
    EXPECT_NE(test::find_seq(t, {"PROTO", proto, "["}), std::string::npos) << proto;
  EXPECT_NE(test::find_seq(t, {"DEF", "Cloth", "Garment", "{"}), std::string::npos);
  EXPECT_NE(test::find_seq(t, {"DEF", "Simulation", "SimulationScript", "{", "garment", "USE", "Cloth"}),
            std::string::npos);
  EXPECT_NE(s.find("url \"javascript:"), std::string::npos);
  // The waist row is pinned: 7 + 7 particles less the 2 welded at the seams = 12 vertices.
  const auto pinned = test::numbers_after(t, at(t, {"pinned"}, at(t, {"DEF", "Cloth", "Garment"})));
  EXPECT_EQ(pinned.size(), 12u);
  EXPECT_EQ(o.pinned.size(), 14u);
  // Colliders stand in for the body, inside it.
  ASSERT_FALSE(o.colliders.empty());
  for (const auto& c : o.colliders) {
    EXPECT_NEAR(c.size[0], 0.123, 1e-9);  // the body's half width and the clearance
    EXPECT_NEAR(c.size[2], 0.083, 1e-9);
  }
  EXPECT_EQ(test::count_token(t, "ObjectCollider"), 1 + static_cast<int>(o.colliders.size()));
  // The garment's geometry in the Garment node: welded particles, uv of every particle.
  const auto cloth = at(t, {"DEF", "Cloth", "Garment"});
  EXPECT_EQ(test::numbers_after(t, at(t, {"coordinate"}, cloth)).size(), 3u * kWelded);
  EXPECT_EQ(test::numbers_after(t, at(t, {"texCoord"}, cloth)).size(), 2u * kParticles);
  EXPECT_EQ(test::numbers_after(t, at(t, {"index"}, cloth)).size(), 4u * kFaces);
  // The seed's event sequence: the script's outputs drive the garment.
  EXPECT_NE(test::find_seq(t, {"ROUTE", "Simulation.coord_changed", "TO", "Cloth.set_coordinate"}), std::string::npos);
  EXPECT_NE(test::find_seq(t, {"ROUTE", "Clock.time", "TO", "Engine.tick"}), std::string::npos);
}

TEST(VrmlLive, TheSeedsFlagIsAFewKilobytesAndItsScriptHasEveryEffect) {
  const std::string s = vrml::live_flag_vrml();
  EXPECT_LT(s.size(), 12000u) << "the flag should take about 11 kB, not " << s.size() << " bytes";
  EXPECT_GT(s.size(), 3000u);
  const auto t = test::vrml_tokens(s);
  EXPECT_TRUE(test::balanced(t));
  // The seed's flag: 30 x 30, pinned at the two staff corners, the seed's wind and constants.
  EXPECT_NE(test::find_seq(t, {"warpParticles", "30"}), std::string::npos);
  EXPECT_NE(test::find_seq(t, {"pinned", "[", "0", "870", "]"}), std::string::npos);
  EXPECT_NE(test::find_seq(t, {"wind", "10", "10", "-100"}), std::string::npos);
  EXPECT_NE(test::find_seq(t, {"warpElasticConst", "1800"}), std::string::npos);
  // The staff (a box) and the ball on top (a sphere) are colliders.
  EXPECT_NE(test::find_seq(t, {"ObjectCollider", "{", "shape", "1"}), std::string::npos);
  EXPECT_NE(test::find_seq(t, {"ObjectCollider", "{", "shape", "0"}), std::string::npos);
  // No coordinates in the file: the script generates the grid.
  EXPECT_EQ(test::find_seq(t, {"coordinate"}, at(t, {"DEF", "Flag", "Garment"})), std::string::npos);
  // The engine: gravity, viscosity, springs, wind, pins, collisions, integration.
  const std::string js(vrml::live_script_source());
  for (const char* word : {"gravity", "viscosity", "wind", "windTurbulence", "pin", "collide", "function step",
                           "function tick", "SK[k]*(L-SR[k])", "integrationStep"})
    EXPECT_NE(js.find(word), std::string::npos) << word;
  EXPECT_EQ(js.find('"'), std::string::npos) << "the script sits in a VRML string";
  EXPECT_EQ(js.find('\\'), std::string::npos);
}

TEST(VrmlLooks, ColoursAndTexturesComeFromTheDocumentsAssociations) {
  // The example of docs/xvc.md: FRONT has material1 (0.9 0.9 0.85); we give it texture1 too.
  const std::string md = read_file(test::source_dir() / "docs" / "xvc.md");
  const auto b = md.find("```xml\n") + 7;
  std::string xml = md.substr(b, md.find("```", b) - b);
  const std::string assoc = "<ASSOCIATION id=\"assoc1\" ref=\"material1\" role=\"material\"/>";
  ASSERT_NE(xml.find(assoc), std::string::npos);
  xml.replace(xml.find(assoc), assoc.size(), assoc + "<ASSOCIATION id=\"assoc9\" ref=\"texture1\" role=\"texture\"/>");
  const auto doc = xvc::load_string(xml, "example.xvc");
  Diagnostics diag;
  const auto looks = vrml::looks_from_xvc(doc, {"FRONT", "BACK", "SLEEVE"}, &diag);
  ASSERT_EQ(looks.size(), 3u);
  EXPECT_DOUBLE_EQ(looks[0].colour.r, 0.9);
  EXPECT_DOUBLE_EQ(looks[0].colour.b, 0.85);
  EXPECT_EQ(looks[0].texture, "textures/stripes.png");
  EXPECT_DOUBLE_EQ(looks[0].repeat_u, 0.05);
  EXPECT_DOUBLE_EQ(looks[0].rotation_deg, 90);
  // BACK has no association: the document's only material. SLEEVE matches no pattern: the same, said.
  EXPECT_DOUBLE_EQ(looks[1].colour.b, 0.85);
  EXPECT_TRUE(looks[1].texture.empty());
  EXPECT_EQ(diag.items().size(), 1u);
  // In the file: an ImageTexture and a TextureTransform turning metres into repeats.
  auto g = test::tube_skirt();
  g.looks = {looks[0], looks[1]};
  const auto t = test::vrml_tokens(vrml::static_vrml(g));
  EXPECT_NE(test::find_seq(t, {"ImageTexture", "{", "url", "\"textures/stripes.png\""}), std::string::npos);
  EXPECT_NE(test::find_seq(t, {"TextureTransform", "{", "scale", "20", "20", "rotation", "1.5708"}), std::string::npos);
  EXPECT_NE(test::find_seq(t, {"diffuseColor", "0.9", "0.9", "0.85"}), std::string::npos);
}

TEST(VrmlLooks, AGarmentWithoutColoursGetsTheDefaultFabric) {
  auto g = test::tube_skirt();
  g.looks.clear();
  const auto t = test::vrml_tokens(vrml::static_vrml(g));
  EXPECT_EQ(test::count_token(t, "diffuseColor"), 3);
  EXPECT_NE(test::find_seq(t, {"diffuseColor", "0.18", "0.3", "0.62"}), std::string::npos);
  EXPECT_NE(test::find_seq(t, {"diffuseColor", "0.82", "0.78", "0.72"}), std::string::npos);  // the body
  // An empty document: every piece the default.
  const auto looks = vrml::looks_from_xvc(xvc::Document{}, {"FRONT"});
  EXPECT_DOUBLE_EQ(looks[0].colour.b, vrml::kDefaultFabric.b);
  EXPECT_EQ(looks[0].source, "default");
}

TEST(VrmlWrite, FilesAreWrittenAtomicallyAndBadGarmentsAreRefused) {
  const auto dir = test::scratch_dir("vrml_write");
  vrml::write_vrml(dir / "a.wrl", vrml::static_vrml(test::tube_skirt()));
  EXPECT_EQ(read_file(dir / "a.wrl").rfind("#VRML V2.0 utf8", 0), 0u);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
  auto g = test::tube_skirt();
  g.frames.positions[3].pop_back();
  try {
    (void)vrml::static_vrml(g);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("frame 3"), std::string::npos) << e.what();
  }
  g = test::tube_skirt();
  g.cloth.triangles[5][1] = 9999;
  EXPECT_THROW((void)vrml::static_vrml(g), Error);
}

TEST(VrmlWrite, AGzPathIsGzipCompressedAndTheFlagThenTakesAFewKilobytes) {
  const auto dir = test::scratch_dir("vrml_gzip");
  const std::string text = vrml::live_flag_vrml();
  vrml::write_vrml(dir / "flag.wrl.gz", text);
  const std::string gz = read_file(dir / "flag.wrl.gz");
  ASSERT_GT(gz.size(), 2u);
  EXPECT_EQ(static_cast<unsigned char>(gz[0]), 0x1f);  // the gzip magic
  EXPECT_EQ(static_cast<unsigned char>(gz[1]), 0x8b);
  EXPECT_LT(gz.size(), 6000u) << "the live flag, compressed";
  // zlib inflates it back to the same text.
  std::string back(text.size() + 16, '\0');
  z_stream z{};
  ASSERT_EQ(inflateInit2(&z, 15 + 16), Z_OK);
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(gz.data()));
  z.avail_in = static_cast<uInt>(gz.size());
  z.next_out = reinterpret_cast<Bytef*>(back.data());
  z.avail_out = static_cast<uInt>(back.size());
  EXPECT_EQ(inflate(&z, Z_FINISH), Z_STREAM_END);
  back.resize(z.total_out);
  inflateEnd(&z);
  EXPECT_EQ(back, text);
}
