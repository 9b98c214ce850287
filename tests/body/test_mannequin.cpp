// The parametric mannequin: watertight, sized, and measuring what it was asked
// to measure. Girths are taken the way a tape takes them: a horizontal slice of
// the generated mesh, the loop around the trunk's centre line, its convex hull.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <unistd.h>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/mesh/surface.hpp"
#include "vgd/body/mannequin.hpp"
#include "support/test_paths.hpp"

using namespace vgd;
using namespace vgd::body;

namespace {

BodyMeasurements women38() {
  BodyMeasurements m;  // defaults: EN 13402-3 women's 38 on a 1.68 m body
  m.label = "38";
  return m;
}

BodyMeasurements men50() {
  BodyMeasurements m;
  m.label = "50";
  m.sex = "male";
  m.height = 1.80;
  m.bust = 1.00;
  m.under_bust = 1.00;
  m.waist = 0.88;
  m.hip = 1.02;
  m.shoulder_width = 0.44;
  m.neck = 0.40;
  m.arm_length = 0.64;
  m.inseam = 0.84;
  return m;
}

// A larger women's size (EN 13402-3 46-like proportions).
BodyMeasurements women46() {
  BodyMeasurements m;
  m.label = "46";
  m.height = 1.70;
  m.bust = 1.06;
  m.under_bust = 0.92;
  m.waist = 0.91;
  m.hip = 1.12;
  m.shoulder_width = 0.43;
  m.neck = 0.38;
  m.arm_length = 0.60;
  m.inseam = 0.785;
  return m;
}

// The slice loop around (x, z) = centre at height y, or empty.
std::vector<mesh::Vec2d> loop_around(const mesh::SurfaceMesh& s, double y, const mesh::Vec2d& centre) {
  for (auto& loop : mesh::slice_horizontal(s, y))
    if (loop.size() > 2 && mesh::point_in_polygon(loop, centre)) return loop;
  return {};
}

// Lowest point of the surface on the vertical line through (x, z), above y_min.
double lowest_hit(const mesh::SurfaceMesh& s, double x, double z, double y_min) {
  double best = 1e9;
  for (const auto& t : s.triangles) {
    const Vec3 &a = s.vertices[t[0]], &b = s.vertices[t[1]], &c = s.vertices[t[2]];
    // Barycentric coordinates of (x, z) in the triangle's projection on the xz plane.
    const double d = (b.x() - a.x()) * (c.z() - a.z()) - (c.x() - a.x()) * (b.z() - a.z());
    if (std::abs(d) < 1e-15) continue;
    const double u = ((x - a.x()) * (c.z() - a.z()) - (c.x() - a.x()) * (z - a.z())) / d;
    const double v = ((b.x() - a.x()) * (z - a.z()) - (x - a.x()) * (b.z() - a.z())) / d;
    if (u < 0 || v < 0 || u + v > 1) continue;
    const double y = a.y() + u * (b.y() - a.y()) + v * (c.y() - a.y());
    if (y > y_min) best = std::min(best, y);
  }
  return best;
}

struct Generated {
  Avatar avatar;
  double seconds = 0;
};

const Generated& generated(const BodyMeasurements& m) {
  static std::map<std::string, Generated> cache;
  const std::string key = m.sex + m.label;
  auto it = cache.find(key);
  if (it == cache.end()) {
    const auto t0 = std::chrono::steady_clock::now();
    Generated g{make_mannequin(m), 0};
    g.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    it = cache.emplace(key, std::move(g)).first;
  }
  return it->second;
}

class Mannequin : public ::testing::TestWithParam<BodyMeasurements> {};

}  // namespace

TEST_P(Mannequin, IsWatertightWithTheTriangleBudget) {
  const auto& g = generated(GetParam());
  const auto check = mesh::check_surface(g.avatar.surface);
  EXPECT_TRUE(check.watertight()) << "boundary " << check.boundary_edges << ", non-manifold " << check.non_manifold_edges
                                  << ", inconsistent " << check.inconsistent_edges << ", volume " << check.volume;
  EXPECT_EQ(check.degenerate_triangles, 0);
  EXPECT_GE(check.triangles, 5000);
  EXPECT_LE(check.triangles, 20000);
  std::printf("[ figures  ] %s %s: %d triangles, %d vertices, edges %.1f–%.1f mm (mean %.1f), %.2f s\n",
              GetParam().sex.c_str(), GetParam().label.c_str(), check.triangles, check.vertices, 1e3 * check.min_edge,
              1e3 * check.max_edge, 1e3 * check.mean_edge, g.seconds);
  // Speed is not asserted here (a timed test failed under the sanitizers on
  // a loaded machine: 12 s); it is measured in docs/performance.md (0.6–0.9 s
  // per body, Release). A mesher that ran away would break the triangle budget.
}

TEST_P(Mannequin, MeasuresWhatItWasAskedFor) {
  const BodyMeasurements& m = GetParam();
  const auto& av = generated(m).avatar;
  const MannequinLandmarks lm = mannequin_landmarks(m);
  const auto* torso = av.segment("torso");
  const auto* hips = av.segment("hips");
  ASSERT_TRUE(torso && hips);
  auto girth = [&](const BodySegment& seg, double y) {
    const SegmentRing r = ring_at(seg, y - seg.start.y());
    const auto loop = loop_around(av.surface, y, {r.centre.x(), r.centre.z()});
    EXPECT_FALSE(loop.empty()) << "no trunk loop at y = " << y;
    return mesh::convex_hull_perimeter(loop);
  };
  const double bust = girth(*torso, lm.bust), waist = girth(*torso, lm.waist), hip = girth(*hips, lm.hip);
  std::printf("[ figures  ] %s %s: bust %.4f (%+.2f %%), waist %.4f (%+.2f %%), hip %.4f (%+.2f %%)\n", m.sex.c_str(),
              m.label.c_str(), bust, 100 * (bust / m.bust - 1), waist, 100 * (waist / m.waist - 1), hip,
              100 * (hip / m.hip - 1));
  EXPECT_NEAR(bust / m.bust, 1.0, 0.02);
  EXPECT_NEAR(waist / m.waist, 1.0, 0.02);
  EXPECT_NEAR(hip / m.hip, 1.0, 0.02);

  const auto box = mesh::bounding_box(av.surface);
  EXPECT_NEAR(box.max.y() / m.height, 1.0, 0.01);
  EXPECT_NEAR(box.min.y(), 0.0, 1e-9);
  EXPECT_NEAR(box.centre().x(), 0.0, 1e-9);
  EXPECT_NEAR(box.centre().z(), 0.0, 1e-9);

  const double crotch = lowest_hit(av.surface, 0.0, hips->start.z(), 0.2 * m.height);
  EXPECT_NEAR(crotch / m.inseam, 1.0, 0.02) << "crotch at " << crotch;

  // Shoulder width: the body's width at the shoulder joints' height.
  double lo = 1e9, hi = -1e9;
  for (const auto& loop : mesh::slice_horizontal(av.surface, av.segment("left-arm")->start.y()))
    for (const auto& p : loop) lo = std::min(lo, p.x()), hi = std::max(hi, p.x());
  EXPECT_NEAR((hi - lo) / m.shoulder_width, 1.0, 0.05);
  std::printf("[ figures  ] %s %s: height %.4f, crotch %.4f (%+.2f %%), shoulders %.4f (%+.2f %%)\n", m.sex.c_str(),
              m.label.c_str(), box.max.y(), crotch, 100 * (crotch / m.inseam - 1), hi - lo,
              100 * ((hi - lo) / m.shoulder_width - 1));
}

TEST_P(Mannequin, SegmentsFollowTheBody) {
  const auto& av = generated(GetParam()).avatar;
  for (const char* name : {"neck", "torso", "hips", "left-arm", "right-arm", "left-leg", "right-leg"}) {
    const auto* s = av.segment(name);
    ASSERT_NE(s, nullptr) << name;
    EXPECT_GT(s->length, 0.05) << name;
    ASSERT_GE(s->rings.size(), 2u) << name;
    EXPECT_DOUBLE_EQ(s->rings.front().s, 0.0);
    EXPECT_NEAR(s->rings.back().s, s->length, 1e-12);
    EXPECT_NEAR(s->axis.norm(), 1.0, 1e-12);
    EXPECT_NEAR(s->front.dot(s->axis), 0.0, 1e-12) << name;
  }
  EXPECT_GT(av.segment("torso")->front.z(), 0.99);
  EXPECT_GT(av.segment("torso")->axis.y(), 0.99);
  EXPECT_GT(av.segment("left-arm")->rings.back().centre.x(), 0.2);
  EXPECT_LT(av.segment("right-arm")->rings.back().centre.x(), -0.2);
  EXPECT_GT(av.segment("left-leg")->start.x(), 0.0);
  EXPECT_LT(av.segment("left-leg")->axis.y(), -0.99);
  EXPECT_GT(av.segment("torso")->side().x(), 0.99) << "the body's left is +X";

  // Trunk rings are the mesh's cross-sections away from the joins: the hips
  // between crotch and waist, the torso from the waist to the bust (above it the
  // arms hang within a centimetre of the flanks and join them at the armpit).
  const double bust_height = mannequin_landmarks(GetParam()).bust;
  for (const char* name : {"torso", "hips"}) {
    const auto& s = *av.segment(name);
    const double s_max = std::string(name) == "torso" ? bust_height - s.start.y() : 0.75 * s.length;
    for (const auto& r : s.rings) {
      if (r.s < 0.25 * s.length || r.s > s_max) continue;
      const auto loop = loop_around(av.surface, r.centre.y(), {r.centre.x(), r.centre.z()});
      ASSERT_FALSE(loop.empty()) << name << " at s = " << r.s;
      double x0 = 1e9, x1 = -1e9, z0 = 1e9, z1 = -1e9;
      for (const auto& p : loop) x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x()), z0 = std::min(z0, p.y()), z1 = std::max(z1, p.y());
      EXPECT_NEAR(0.5 * (x1 - x0), r.half_width, 0.005) << name << " at s = " << r.s;
      EXPECT_NEAR(0.5 * (z1 - z0), r.half_depth, 0.005) << name << " at s = " << r.s;
    }
  }
  // Leg rings: the horizontal slice's loop around the ring centre has the ring's size.
  for (const char* name : {"left-leg", "right-leg"}) {
    const auto& s = *av.segment(name);
    for (const auto& r : s.rings) {
      if (r.s < 0.3 * s.length || r.s > 0.9 * s.length) continue;
      const auto loop = loop_around(av.surface, r.centre.y(), {r.centre.x(), r.centre.z()});
      ASSERT_FALSE(loop.empty()) << name << " at s = " << r.s;
      const double radius = mesh::convex_hull_perimeter(loop) / (2 * M_PI);
      EXPECT_NEAR(radius, r.half_width, 0.005) << name << " at s = " << r.s;
    }
  }
  // Triangles are labelled with their nearest segment.
  ASSERT_EQ(av.triangle_segment.size(), av.surface.triangles.size());
  std::size_t labelled = 0, left_arm_ok = 0, left_arm_far = 0;
  const int left_arm = static_cast<int>(av.segment("left-arm") - av.segments.data());
  const double wrist_y = av.segment("left-arm")->rings.back().centre.y();
  for (std::size_t t = 0; t < av.triangle_segment.size(); ++t) {
    labelled += av.triangle_segment[t] >= 0;
    const auto& tri = av.surface.triangles[t];
    const double x = (av.surface.vertices[tri[0]].x() + av.surface.vertices[tri[1]].x() + av.surface.vertices[tri[2]].x()) / 3;
    const double y = (av.surface.vertices[tri[0]].y() + av.surface.vertices[tri[1]].y() + av.surface.vertices[tri[2]].y()) / 3;
    if (x > 0.5 * GetParam().shoulder_width && y > wrist_y) {  // the arm, not the hand
      ++left_arm_far;
      left_arm_ok += av.triangle_segment[t] == left_arm;
    }
  }
  EXPECT_GT(labelled, 0.75 * av.triangle_segment.size());  // head, hands and feet may stay unlabelled
  EXPECT_GT(left_arm_ok, 0.9 * left_arm_far);
}

INSTANTIATE_TEST_SUITE_P(Bodies, Mannequin, ::testing::Values(women38(), men50(), women46()),
                         [](const auto& p) { return p.param.sex + "_" + p.param.label; });

TEST(MannequinGeneration, IsDeterministic) {
  MannequinOptions o;
  o.target_triangles = 5000;
  const Avatar a = make_mannequin(women38(), o), b = make_mannequin(women38(), o);
  ASSERT_EQ(a.surface.vertices.size(), b.surface.vertices.size());
  ASSERT_EQ(a.surface.triangles, b.surface.triangles);
  for (std::size_t i = 0; i < a.surface.vertices.size(); ++i) ASSERT_EQ(a.surface.vertices[i], b.surface.vertices[i]);
}

// The body's value skips the neck with the head and each limb where a lower
// bound shows the part cannot change it: the skipping must give the value of
// every part evaluated, bit for bit, anywhere round the body (near the
// surface, where the mesher and the calibration look, and away from it), in
// every pose the options allow.
TEST(MannequinGeneration, SkippingFarPartsLeavesTheValueBitForBit) {
  std::vector<std::pair<BodyMeasurements, MannequinOptions>> bodies;
  for (const auto& m : {women38(), men50(), women46()}) bodies.push_back({m, {}});
  MannequinOptions t_pose, forward;
  t_pose.arm_angle_deg = 90;
  forward.arm_forward_deg = 45;
  bodies.push_back({women38(), t_pose});
  bodies.push_back({men50(), forward});
  std::uint64_t state = 12345;
  auto uniform = [&] {  // xorshift64*: the same points on every machine
    state ^= state >> 12, state ^= state << 25, state ^= state >> 27;
    return static_cast<double>((state * 2685821657736338717ull) >> 11) * 0x1.0p-53;
  };
  for (const auto& [m, o] : bodies) {
    const MannequinSdf sdf(m, o);
    int near = 0;
    for (int i = 0; i < 20000; ++i) {
      const Vec3 p(-0.9 + 1.8 * uniform(), -0.05 + 2.0 * uniform(), -0.4 + 0.8 * uniform());
      const double v = sdf(p), all = sdf.every_part(p);
      ASSERT_EQ(v, all) << m.sex << " " << m.label << " at (" << p.x() << ", " << p.y() << ", " << p.z() << ")";
      near += std::abs(v) < 0.03;
    }
    EXPECT_GT(near, 200) << "points near the surface were tried";
  }
}

// The cache (docs/avatar.md, "The cache"): a mannequin made again for the
// same measurements and options takes its surface from the file the first
// one left, the same bit for bit and without meshing; a file that does not
// read back whole is meshed again and replaced; "off" keeps nothing.
class MannequinCache : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("vgd-mannequin-cache-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    ::setenv("VGD_CACHE_DIR", dir_.c_str(), 1);
    o_.target_triangles = 5000;
  }
  void TearDown() override {
    ::unsetenv("VGD_CACHE_DIR");
    std::filesystem::remove_all(dir_);
  }
  std::vector<std::filesystem::path> files() const {
    std::vector<std::filesystem::path> out;
    if (std::filesystem::exists(dir_))
      for (const auto& e : std::filesystem::directory_iterator(dir_)) out.push_back(e.path());
    return out;
  }
  static void expect_same(const Avatar& a, const Avatar& b) {
    ASSERT_EQ(a.surface.triangles, b.surface.triangles);
    ASSERT_EQ(a.surface.vertices.size(), b.surface.vertices.size());
    for (std::size_t i = 0; i < a.surface.vertices.size(); ++i) ASSERT_EQ(a.surface.vertices[i], b.surface.vertices[i]);
    ASSERT_EQ(a.triangle_segment, b.triangle_segment);
    ASSERT_EQ(a.segments.size(), b.segments.size());
    for (std::size_t s = 0; s < a.segments.size(); ++s) EXPECT_EQ(a.segments[s].start, b.segments[s].start);
  }
  std::filesystem::path dir_;
  MannequinOptions o_;
};

TEST_F(MannequinCache, ASecondMannequinComesFromTheCacheBitForBit) {
  ASSERT_EQ(mannequin_cache_dir(), dir_);
  const long before = mannequin_meshings();
  const Avatar first = make_mannequin(women38(), o_);
  EXPECT_EQ(mannequin_meshings(), before + 1);
  ASSERT_EQ(files().size(), 1u) << "the surface kept";
  const Avatar second = make_mannequin(women38(), o_);
  EXPECT_EQ(mannequin_meshings(), before + 1) << "taken from the cache, not meshed";
  expect_same(first, second);
  // Not asked to use it: meshed, the same.
  MannequinOptions fresh = o_;
  fresh.cache = false;
  expect_same(first, make_mannequin(women38(), fresh));
  EXPECT_EQ(mannequin_meshings(), before + 2);
  // Another body, or the same one in another pose, is another file.
  MannequinOptions t_pose = o_;
  t_pose.arm_angle_deg = 90;
  make_mannequin(women38(), t_pose);
  make_mannequin(men50(), o_);
  EXPECT_EQ(files().size(), 3u);
  EXPECT_EQ(mannequin_meshings(), before + 4);
}

TEST_F(MannequinCache, AFileThatDoesNotReadBackWholeIsMeshedAgainAndReplaced) {
  const Avatar made = make_mannequin(women38(), o_);
  ASSERT_EQ(files().size(), 1u);
  const auto file = files().front();
  const std::string whole = vgd::read_file(file);
  auto flipped = [&](std::size_t at) {
    std::string b = whole;
    b[at] = static_cast<char>(b[at] ^ 0x10);
    return b;
  };
  const std::vector<std::string> damaged = {whole.substr(0, whole.size() / 2),  // cut short
                                            flipped(40),                        // its key changed
                                            flipped(whole.size() / 2),          // a coordinate changed
                                            ""};
  for (const auto& bad : damaged) {
    vgd::write_file_atomic(file, bad);
    const long before = mannequin_meshings();
    expect_same(made, make_mannequin(women38(), o_));
    EXPECT_EQ(mannequin_meshings(), before + 1) << "meshed again";
    EXPECT_EQ(vgd::read_file(file), whole) << "and the file replaced";
  }
}

TEST_F(MannequinCache, OffKeepsNothing) {
  ::setenv("VGD_CACHE_DIR", "off", 1);
  EXPECT_TRUE(mannequin_cache_dir().empty());
  const long before = mannequin_meshings();
  make_mannequin(women38(), o_);
  make_mannequin(women38(), o_);
  EXPECT_EQ(mannequin_meshings(), before + 2);
  EXPECT_TRUE(files().empty());
}

// The cache keeps 64 surfaces at most: writing one removes the oldest of
// its own files beyond that, never the one just written, and never a file
// it did not write (another name, or a cache-like name without its format).
TEST_F(MannequinCache, KeepsTheNewestSurfacesOnlyAndNothingElseIsRemoved) {
  std::filesystem::create_directories(dir_);
  const auto old = std::filesystem::file_time_type::clock::now() - std::chrono::hours(24);
  mesh::SurfaceMesh tiny;
  tiny.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  tiny.triangles = {{0, 1, 2}};
  auto name = [](int i) {
    char n[40];
    std::snprintf(n, sizeof n, "mannequin-%016x.bin", 0xabc000 + i);
    return std::string(n);
  };
  for (int i = 0; i < 70; ++i) {
    const auto f = dir_ / name(i);
    vgd::write_file_atomic(f, mannequin_cache_file(tiny, "old " + std::to_string(i) + "\n"));
    std::filesystem::last_write_time(f, old + std::chrono::seconds(i));
  }
  // Older than all of them, but not the cache's: kept.
  const auto mine = dir_ / name(999), notes = dir_ / "notes.txt";
  vgd::write_file_atomic(mine, "a file of the user's own, named like the cache's");
  vgd::write_file_atomic(notes, "not the cache's");
  std::filesystem::last_write_time(mine, old - std::chrono::hours(1));
  std::filesystem::last_write_time(notes, old - std::chrono::hours(1));
  make_mannequin(women38(), o_);
  EXPECT_EQ(files().size(), 66u) << "64 surfaces and the two files that are not the cache's";
  for (int i = 0; i < 70; ++i) EXPECT_EQ(std::filesystem::exists(dir_ / name(i)), i >= 7) << i;
  EXPECT_EQ(vgd::read_file(mine), "a file of the user's own, named like the cache's");
  EXPECT_TRUE(std::filesystem::exists(notes));
}

// The file format on its own: a surface written reads back the same; any
// byte cut off or changed, or another key, reads back nothing.
TEST(MannequinCacheFile, ReadsBackWhatWasWrittenAndNothingElse) {
  mesh::SurfaceMesh s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  s.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const std::string bytes = mannequin_cache_file(s, "key 1\n");
  const auto back = read_mannequin_cache_file(bytes, "key 1\n");
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->vertices, s.vertices);
  EXPECT_EQ(back->triangles, s.triangles);
  EXPECT_FALSE(read_mannequin_cache_file(bytes, "key 2\n").has_value());
  for (std::size_t cut = 0; cut < bytes.size(); ++cut)
    EXPECT_FALSE(read_mannequin_cache_file(bytes.substr(0, cut), "key 1\n").has_value()) << cut;
  for (std::size_t at = 0; at < bytes.size(); ++at) {
    std::string changed = bytes;
    changed[at] = static_cast<char>(changed[at] ^ 0x10);
    EXPECT_FALSE(read_mannequin_cache_file(changed, "key 1\n").has_value()) << at;
  }
  // The fuzz target's seed of a whole file (after its mode byte) is this tetrahedron.
  const std::string seed = vgd::read_file(vgd::test::source_dir() / "tests/fuzz/corpus/mannequin/raw-tetrahedron.bin");
  const auto tetra = read_mannequin_cache_file(std::string_view(seed).substr(1), "fuzz\n");
  ASSERT_TRUE(tetra.has_value());
  EXPECT_EQ(tetra->vertices, s.vertices);
  EXPECT_EQ(tetra->triangles, s.triangles);
}

TEST(MannequinGeneration, TriangleTargetIsFollowed) {
  for (int target : {5000, 20000}) {
    MannequinOptions o;
    o.target_triangles = target;
    const Avatar a = make_mannequin(women38(), o);
    EXPECT_NEAR(a.surface.num_triangles(), target, 0.2 * target);
    EXPECT_GE(a.surface.num_triangles(), 5000);
    EXPECT_LE(a.surface.num_triangles(), 20000);
  }
}

TEST(MannequinGeneration, RefusesImplausibleMeasurements) {
  BodyMeasurements m = women38();
  m.height = 168;  // centimetres given as metres
  try {
    make_mannequin(m);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("height"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1.68, not 168"), std::string::npos) << e.what();
  }
  m = women38();
  m.under_bust = 0.95;
  EXPECT_THROW(make_mannequin(m), Error);
  m = women38();
  m.waist = -1;
  EXPECT_THROW(make_mannequin(m), Error);
}
