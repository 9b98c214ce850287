// Careless and hostile input, end to end: each input is generated here (no
// large files in the repository) and must be refused with exit 1 and a
// message naming the file, the entity and the problem in words — never an
// internal error (exit 4), a crash, a hang or a clobbered file.
#include <gtest/gtest.h>

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/run_vgd.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/io/trj/trj.hpp"

using namespace vgd;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// No raw byte from the input: what is printed is valid UTF-8 without control bytes but line breaks.
bool clean(const std::string& text) { return printable(text) == text; }

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  if (p != std::string::npos) s.replace(p, from.size(), to);
  return s;
}

void put_u32(std::string& s, std::uint32_t v) {
  for (int k = 3; k >= 0; --k) s += static_cast<char>((v >> (8 * k)) & 0xFF);
}

std::string png_chunk(const std::string& type, const std::string& data) {
  std::string c;
  put_u32(c, static_cast<std::uint32_t>(data.size()));
  c += type + data;
  const std::string crc_of = type + data;
  put_u32(c, static_cast<std::uint32_t>(
                 ::crc32(0, reinterpret_cast<const Bytef*>(crc_of.data()), static_cast<uInt>(crc_of.size()))));
  return c;
}

// A PNG of under 80 bytes whose header claims width x height RGBA pixels.
std::string png_claiming(std::uint32_t width, std::uint32_t height) {
  std::string ihdr;
  put_u32(ihdr, width);
  put_u32(ihdr, height);
  ihdr += std::string("\x08\x06\x00\x00\x00", 5);
  const std::string zeros(std::min<std::uint64_t>(1000, std::uint64_t{height} * (1 + 4ull * width)), '\0');
  std::string idat(compressBound(zeros.size()), '\0');
  uLongf n = idat.size();
  ::compress(reinterpret_cast<Bytef*>(idat.data()), &n, reinterpret_cast<const Bytef*>(zeros.data()), zeros.size());
  idat.resize(n);
  return std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk("IHDR", ihdr) + png_chunk("IDAT", idat) +
         png_chunk("IEND", "");
}

std::string skirt_xvc() { return read_file(test::source_dir() / "data" / "garments" / "a-line-skirt.xvc"); }

// A 5 x 5 sheet falling free for 1 s at 100 fps; with max_speed 1 m/s it stops after 11 frames.
json falling_sheet(bool stops) {
  json j = json::parse(R"({
    "name": "sheet",
    "materials": { "cloth": { "particle_mass": 0.01, "density": 0.1, "spring.warp": 100, "spring.weft": 100,
                              "spring.shear": 20, "spring.bend_warp": 5, "spring.bend_weft": 5 } },
    "cloth": [ { "name": "sheet", "grid": { "particles": [5, 5], "size": [0.4, 0.4] }, "model": "mass-spring",
                 "placement": { "origin": [0, 1, 0], "u": [1, 0, 0], "v": [0, 0, 1] }, "material": "cloth" } ],
    "effects": { "gravity": {} },
    "integrator": { "method": "euler", "step": "1 ms" },
    "frames": { "fps": 100, "duration": 0.3 }
  })");
  if (stops) j["integrator"]["max_speed"] = "1 m/s";
  return j;
}

}  // namespace

TEST(HostileInput, TextThatIsNotUtf8IsAnErrorInValidJson) {
  const auto dir = test::scratch_dir("hostile_utf8");
  write_file_atomic(dir / "ff.xvc", replaced(skirt_xvc(), "name=\"VGD A-LINE SKIRT\"", "name=\"VGD \xff SKIRT\""));
  const auto r = test::run_vgd({"validate", (dir / "ff.xvc").string(), "--json"});
  EXPECT_EQ(r.code, 3) << r.err;
  const json j = json::parse(r.out);  // throws on invalid UTF-8
  EXPECT_FALSE(j["valid"].get<bool>());
  EXPECT_TRUE(has(j["diagnostics"][0]["message"].get<std::string>(), "not UTF-8")) << r.out;
  EXPECT_EQ(j["diagnostics"][0]["line"].get<int>(), 2);
}

TEST(HostileInput, APngClaimingTenBillionPixelsIsRefusedBeforeDecoding) {
  const auto dir = test::scratch_dir("hostile_png");
  const auto huge = dir / "huge.png";
  write_file_atomic(huge, png_claiming(100000, 100000));
  ASSERT_LT(fs::file_size(huge), 80u);
  const auto r = test::run_vgd({"compare", huge.string(), huge.string()});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_TRUE(has(r.err, huge.string() + ": 100000 x 100000 pixels is more than")) << r.err;
  EXPECT_TRUE(has(r.err, "--max-pixels")) << r.err;
  // The limit is the user's to raise or lower: 8 x 8 is refused under 63 pixels.
  write_file_atomic(dir / "small.png", png_claiming(8, 8));
  const auto small = (dir / "small.png").string();
  EXPECT_EQ(test::run_vgd({"compare", small, small, "--max-pixels", "63"}).code, 1);
  EXPECT_NE(test::run_vgd({"compare", small, small, "--max-pixels", "64"}).code, 1);
}

TEST(HostileInput, AnOutlineTouchingItselfIsRefusedNotMeshedWithoutEnd) {
  // The front's second point moved onto its hem (y = 1e-300): a spike 1e-300 m wide.
  const auto dir = test::scratch_dir("hostile_touch");
  const auto file = dir / "tiny.xvc";
  write_file_atomic(file, replaced(skirt_xvc(), "<C2D x=\"0.2933333333333334\" y=\"0.06583333333333333\"/>",
                                   "<C2D x=\"0.2933333333333334\" y=\"1e-300\"/>"));
  const auto r = test::run_vgd({"mesh", file.string(), "--size", "34"});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_TRUE(has(r.err, file.string() + ": FRONT_34: the outline or a cutout touches itself at (0.2933, 0.0000) m"))
      << r.err;
  EXPECT_TRUE(has(r.out, "BACK_34")) << r.out;  // the other pieces are meshed
}

TEST(HostileInput, ASceneCannotPlanMillionsOfFramesOrSteps) {
  const auto dir = test::scratch_dir("hostile_frames");
  json j = falling_sheet(false);
  j["frames"]["fps"] = 1e9;
  write_file_atomic(dir / "fps.json", j.dump());
  auto r = test::run_vgd({"simulate", (dir / "fps.json").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(has(r.err, "fps.json: frames.fps: 1e+09 frames per second is more than the 10000")) << r.err;

  write_file_atomic(dir / "ok.json", falling_sheet(false).dump());
  r = test::run_vgd({"simulate", (dir / "ok.json").string(), "--duration", "1e6"});
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(has(r.err, "frames.duration:") && has(r.err, "100000000 frames, more than the 1000000")) << r.err;
  r = test::run_vgd({"simulate", (dir / "ok.json").string(), "--step", "1e-15"});
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(has(r.err, "integrator.step:") && has(r.err, "steps, more than the 1000000000")) << r.err;
}

TEST(HostileInput, AnObjFaceWithAMillionCornersIsRefusedAtItsLine) {
  const auto dir = test::scratch_dir("hostile_face");
  std::string obj;
  for (int i = 0; i < 3000; ++i)
    obj += "v " + std::to_string(i % 100 * 0.01) + " " + std::to_string(i / 100 * 0.01) + " 0\n";
  obj += "f";
  for (int i = 0; i < 1000000; ++i) obj += " " + std::to_string(1 + i % 3000);
  obj += "\n";
  write_file_atomic(dir / "face.obj", obj);
  const auto r = test::run_vgd({"avatar", "convert", (dir / "face.obj").string(), "-o", (dir / "out.obj").string()});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_TRUE(has(r.err, "face.obj:3001: face: a face with 1000000 corners, more than the 1024")) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out.obj"));
}

TEST(HostileInput, LabFitRefusesMoreMeasurementsThanItsLimit) {
  const auto dir = test::scratch_dir("hostile_lab");
  std::string csv = "quantity,direction,x,value,unit\nweight,,,120,g/m2\nshear_rigidity,,,395,N/m\n"
                    "bending_rigidity,warp,,1e-5,N.m\nbending_rigidity,weft,,8e-6,N.m\n";
  for (int i = 1; i <= 4999; ++i) {
    const std::string e = format_double(i * 1e-5);
    csv += "tensile,warp," + e + "," + format_double(i * 1e-5 * 500) + ",N/m\n";
    csv += "tensile,weft," + e + "," + format_double(i * 1e-5 * 300) + ",N/m\n";
  }
  write_file_atomic(dir / "m.csv", csv);  // 10 002 measurements
  auto r = test::run_vgd({"lab", "fit", (dir / "m.csv").string(), "-o", (dir / "out").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(has(r.err, "m.csv:10002: more than 10000 measurements (--max-rows)")) << r.err;
  r = test::run_vgd({"lab", "fit", (dir / "m.csv").string(), "--max-rows", "10002", "-o", (dir / "out").string()});
  EXPECT_EQ(r.code, 0) << r.err;
}

TEST(HostileInput, ADxfLineLongerThanDxflibReadsIsRefused) {
  const auto dir = test::scratch_dir("hostile_dxf_line");
  std::string dxf = "  0\nSECTION\n  2\nENTITIES\n  0\nLINE\n" + std::string(100000, ' ') + "8\n0\n 10\n0\n 20\n0\n"
                    " 11\n1\n 21\n1\n  0\nENDSEC\n  0\nEOF\n";
  write_file_atomic(dir / "long.dxf", dxf);
  const auto r = test::run_vgd({"import", (dir / "long.dxf").string(), "--unfold-mirrored", "-o",
                                (dir / "out.xvc").string()});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_TRUE(has(r.err, "long.dxf:7: a line of 100001 characters; a DXF line holds at most 1022")) << r.err;
}

TEST(HostileInput, ARunThatStopsEarlyLeavesTheCompleteTrajectoryAsItWas) {
  const auto dir = test::scratch_dir("hostile_trj");
  write_file_atomic(dir / "ok.json", falling_sheet(false).dump());
  write_file_atomic(dir / "stops.json", falling_sheet(true).dump());
  const auto trj = (dir / "out.trj").string();
  ASSERT_EQ(test::run_vgd({"simulate", (dir / "ok.json").string(), "--trj", trj}).code, 0);
  const int complete = io::trj::TrjReader(trj).frame_count();
  EXPECT_EQ(complete, 31);

  const auto r = test::run_vgd({"simulate", (dir / "stops.json").string(), "--trj", trj});
  EXPECT_EQ(r.code, 1);
  const auto failed = dir / "out.failed.trj";
  EXPECT_TRUE(has(r.err, "its 11 frames are in " + failed.string() + "; " + trj + " is unchanged")) << r.err;
  const io::trj::TrjReader kept(trj);
  EXPECT_TRUE(kept.run_ok());
  EXPECT_EQ(kept.frame_count(), complete);
  const io::trj::TrjReader partial(failed);
  EXPECT_FALSE(partial.run_ok());
  EXPECT_EQ(partial.frame_count(), 11);
}

TEST(HostileInput, JsonMistakesAreSaidInWords) {
  const auto dir = test::scratch_dir("hostile_json");
  write_file_atomic(dir / "bad.json", "{\"version\": 1, \"di");
  auto r = test::run_vgd({"simulate", (dir / "bad.json").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(has(r.err, "bad.json:1: not valid JSON at line 1, column 19: invalid string: missing closing quote"))
      << r.err;
  EXPECT_FALSE(has(r.err, "json.exception")) << r.err;

  write_file_atomic(dir / "skirt.xvc", skirt_xvc());
  write_file_atomic(dir / "bad.seams.json", "{\"seams\": [ {\"pieces\": 1e999 } ] }");
  r = test::run_vgd({"seams", "apply", (dir / "skirt.xvc").string(), (dir / "bad.seams.json").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(has(r.err, "bad.seams.json: not valid JSON") && has(r.err, "a number too large for a double: 1e999"))
      << r.err;
  EXPECT_FALSE(has(r.err, "json.exception")) << r.err;
}

TEST(HostileInput, BinaryBytesAndEntityTricksAreRefusedInWords) {
  const auto dir = test::scratch_dir("hostile_bytes");
  // Bytes that are not UTF-8 in a scene's string: the parser's account quotes them, escaped.
  write_file_atomic(dir / "bytes.json", "{\"name\": \"\xfe\xff\"}");
  auto r = test::run_vgd({"simulate", (dir / "bytes.json").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(has(r.err, "bytes.json:1: not valid JSON at line 1, column")) << r.err;
  EXPECT_TRUE(clean(r.err)) << r.err;
  EXPECT_TRUE(has(r.err, "ill-formed UTF-8 byte (read up to: \"\\xFE)")) << r.err;

  // Entities expanding a billion times, and one referring to itself.
  std::string bomb = "<?xml version=\"1.0\"?>\n<!DOCTYPE g [<!ENTITY a \"aaaaaaaaaa\">";
  for (char e = 'b'; e <= 'j'; ++e) {
    bomb += std::string("<!ENTITY ") + e + " \"";
    for (int k = 0; k < 10; ++k) bomb += std::string("&") + static_cast<char>(e - 1) + ";";
    bomb += "\">";
  }
  bomb += "]>\n<GARMENT id=\"g\" name=\"&j;\"/>\n";
  write_file_atomic(dir / "bomb.xvc", bomb);
  write_file_atomic(dir / "loop.xvc",
                    "<?xml version=\"1.0\"?>\n<!DOCTYPE g [<!ENTITY a \"&b;\"><!ENTITY b \"&a;\">]>\n"
                    "<GARMENT id=\"g\" name=\"&a;\"/>\n");
  for (const char* f : {"bomb.xvc", "loop.xvc"}) {
    r = test::run_vgd({"validate", (dir / f).string()});
    EXPECT_EQ(r.code, 3) << f;
    EXPECT_TRUE(has(r.out, "an entity refers to itself or expands into too much text")) << r.out;
    EXPECT_FALSE(has(r.out, "entity reference loop")) << r.out;
    EXPECT_EQ(r.err, "vgd: " + (dir / f).string() + ": 1 error(s)\n") << f;
  }
}

TEST(HostileInput, ACompressedTrajectoryIsExportedOrNamedAsOne) {
  const auto dir = test::scratch_dir("hostile_wvt");
  write_file_atomic(dir / "ok.json", falling_sheet(false).dump());
  const auto trj = (dir / "s.trj").string(), wvt = (dir / "s.wvt").string();
  ASSERT_EQ(test::run_vgd({"simulate", (dir / "ok.json").string(), "--trj", trj}).code, 0);
  ASSERT_EQ(test::run_vgd({"compress", trj, "-o", wvt}).code, 0);
  auto r = test::run_vgd({"export", wvt, "-o", (dir / "s.wrl").string()});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(dir / "s.wrl"));
  r = test::run_vgd({"render", wvt, "-o", (dir / "s.png").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(has(r.err, wvt + ": a compressed trajectory (.wvt): vgd decompress turns it into a .trj")) << r.err;
  // Under a name that does not say so, the trajectory reader knows it by its first bytes.
  fs::copy_file(wvt, dir / "s2.trj");
  r = test::run_vgd({"render", (dir / "s2.trj").string(), "-o", (dir / "s.png").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(has(r.err, "s2.trj: header: a compressed trajectory (.wvt), not a .trj: vgd decompress")) << r.err;
}

TEST(HostileInput, TrajectoryMistakesNameTheFileByItsPath) {
  const auto dir = test::scratch_dir("hostile_trj_names");
  io::trj::Topology topo;
  topo.num_particles = 3;
  topo.triangles = {{0, 1, 2}};
  topo.uv = {{0, 0}, {1, 0}, {0, 1}};
  {  // no frame at all
    io::trj::TrjWriter w(dir / "empty.trj");
    w.begin(topo);
    w.end(true);
  }
  auto r = test::run_vgd({"export", (dir / "empty.trj").string(), "-o", (dir / "e.wrl").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(has(r.err, (dir / "empty.trj").string() + ": the trajectory has no frame")) << r.err;
  {  // 3e38 m across: no error bound of 1 mm fits a 2^30-step grid
    io::trj::TrjWriter w(dir / "wide.trj");
    w.begin(topo);
    w.add_frame(0.0, std::vector<float>{0, 0, 0, 3e38f, 0, 0, 0, 1, 0});
    w.end(true);
  }
  r = test::run_vgd({"compress", (dir / "wide.trj").string(), "-o", (dir / "w.wvt").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(has(r.err, (dir / "wide.trj").string() + ": an error bound of 1 mm is too fine for a trajectory 3"))
      << r.err;
  EXPECT_FALSE(has(r.err, "<trajectory>")) << r.err;
  EXPECT_FALSE(fs::exists(dir / "w.wvt"));
}

TEST(HostileInput, LibraryMessagesAreSaidInWords) {
  const auto dir = test::scratch_dir("hostile_words");
  // assimp's "Cannot parse string \"a\" as a real number: ..."
  write_file_atomic(dir / "p.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn a b c\nf 1 2 3\n");
  auto r = test::run_vgd({"avatar", "report", (dir / "p.obj").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(has(r.err, "p.obj: not a 3-D model vgd can read") && has(r.err, "a number was expected, found \"a\""))
      << r.err;
  EXPECT_FALSE(has(r.err, "Cannot parse string")) << r.err;
  // A fit driven to infinity names the measurements and the parameter.
  write_file_atomic(dir / "over.csv",
                    "quantity,direction,x,value,unit\nweight,,,120,g/m2\ntensile,warp,1e-300,1e300,N/m\n"
                    "tensile,weft,1e-300,1e300,N/m\nshear_rigidity,,,395,N/m\nbending_rigidity,warp,,1e-5,N.m\n"
                    "bending_rigidity,weft,,1e-5,N.m\n");
  r = test::run_vgd({"lab", "fit", (dir / "over.csv").string(), "--model", "mass-spring", "-o",
                     (dir / "out").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(has(r.err, (dir / "over.csv").string() + ": spring.warp: the fit drove it to a value that is not a "
                                                       "finite number"))
      << r.err;
}

TEST(HostileInput, ABodyFileAssimpLoopsOnIsRefusedAtALimitScaledToItsSize) {
  // Found by fuzzing: 922 bytes of PLY whose header assimp never finishes (the
  // corpus file's first byte picks the format for the fuzz target).
  const auto dir = test::scratch_dir("hostile_ply_loop");
  const std::string corpus = read_file(test::source_dir() / "tests" / "fuzz" / "corpus" / "avatar" / "assimp-loops.ply");
  write_file_atomic(dir / "loop.ply", corpus.substr(1));
  const auto r = test::run_vgd({"avatar", "report", (dir / "loop.ply").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(has(r.err, "loop.ply: not read: assimp had not finished reading it after 5.0 s, the limit for a file of "
                         "its size"))
      << r.err;
}
