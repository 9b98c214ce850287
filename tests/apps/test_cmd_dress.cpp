// vgd dress: a pattern file to a draped garment in one command.
#include <gtest/gtest.h>

#include <array>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <nlohmann/json.hpp>

#include "support/json_file.hpp"
#include "support/split_sleeve.hpp"
#include "support/trousers.hpp"
#include "support/run_vgd.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/file.hpp"
#include "vgd/dress/certificate.hpp"
#include "vgd/xvc/commands.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/seams.hpp"
#include "vgd/xvc/style.hpp"

namespace vgd::test {

using nlohmann::json;

// The Gerber polo straight from its DXF, in a graded size: the importer's
// marks, the suggested seams (at the sample size, carried to 44), its rib
// collar sewn round the neckline and folded over, its placket sewn by its
// two ends onto the front (the under placket left out, hidden), the pieces
// no seam sews left out and said, the men's table chosen from the style's name, both
// sleeves on their own armholes, previews written, the document it draped
// saved beside them.
TEST(CliDress, APoloFromItsDxfDrapesInOneCommand) {
  VGD_REQUIRE_SHARED();
  const auto out = scratch_dir("dress-polo");
  const auto r = run_vgd({"dress", shared_dxf("drill-holes.DXF").string(), "--size", "44", "-o", out.string(),
                          "--views", "front"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("seam 'left armhole' suggested at size 50"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("seam 'collar seam' suggested at size 50"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("piece SS17_M POLO REG CO (collar) read as rolled over at half its width"), std::string::npos)
      << r.err;
  EXPECT_NE(
      r.err.find(
          "piece SS17_M POLO REG YP (placket) sewn by its two ends onto the face of SS17_M POLO REG FR"),
      std::string::npos)
      << r.err;
  EXPECT_NE(
      r.err.find("piece SS17_M POLO REG YL (placket) left out: it lies under the placket SS17_M POLO REG YP"),
      std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("body: the mannequin of size 44 from en13402-men"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no SEAM sews this size: the 9 seams of size 50"), std::string::npos) << r.err;
  const json c = read_json(out / "certificate.json");
  EXPECT_TRUE(c["passed"].get<bool>()) << c["failures"].dump();
  ASSERT_EQ(c["seams"].size(), 11u) << "the 9 SEAMs and the placket's two ends";
  for (const auto& s : c["seams"]) EXPECT_EQ(s["closed"], s["pairs"]) << s.dump();
  EXPECT_EQ(c["placement"].size(), 6u) << "front, back, two sleeves, the collar and the placket";
  EXPECT_TRUE(std::filesystem::exists(out / "previews" / "front.png"));
  // Read back (as the studio reads a server's), it writes the same text.
  const std::string cert_text = vgd::read_file(out / "certificate.json");
  EXPECT_EQ(dress::to_json(dress::certificate_from_json(cert_text, "certificate.json")), cert_text);
  // The document it draped: its seams are in it, and vgd drape runs it again.
  const auto again = run_vgd({"seams", "list", (out / "garment.xvc").string()});
  EXPECT_EQ(again.code, 0) << again.err;
  EXPECT_NE(again.out.find("left armhole"), std::string::npos) << again.out;
  // With each piece's role and whether it is draped, read back when it runs
  // on its own document: the under placket stays out, as the document now says.
  const std::string saved = vgd::read_file(out / "garment.xvc");
  EXPECT_NE(saved.find("role=\"collar\""), std::string::npos);
  EXPECT_NE(saved.find("folded=\"true\""), std::string::npos);
  EXPECT_NE(saved.find("role=\"sleeve\""), std::string::npos);
  const auto rerun = run_vgd({"dress", (out / "garment.xvc").string(), "--size", "44", "-o", out.string(),
                              "--no-previews", "--time-limit", "0.05"});
  EXPECT_TRUE(rerun.code == 0 || rerun.code == 3) << rerun.err;
  EXPECT_NE(rerun.err.find("piece SS17_M POLO REG YL (placket) left out: the document says drape=\"false\""),
            std::string::npos)
      << rerun.err;
  EXPECT_EQ(rerun.err.find("is kept as"), std::string::npos) << "its own input is not moved aside";
}

// CLO's T-shirt imported as the file wrote it (9 blocks, the halves apart):
// vgd dress joins them as it does on a DXF, reads the roles from the shapes
// and sews the same 8 seams. A document that holds more than its style (a
// mesh parameter set) is not written again: its halves stay apart.
TEST(CliDress, ADocumentImportedAsWrittenHasItsHalvesJoined) {
  VGD_REQUIRE_SHARED();
  const auto out = scratch_dir("dress-clo-xvc");
  auto r = run_vgd({"import", shared_dxf("clo-pattern.dxf").string(), "-o", (out / "clo.xvc").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  r = run_vgd({"dress", (out / "clo.xvc").string(), "-o", (out / "joined").string(), "--time-limit", "0.05",
               "--no-previews"});
  EXPECT_NE(r.err.find("blocks 11_M and 37_M are the left and right halves of one piece"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("11 front (the deeper neckline"), std::string::npos) << r.err;
  const auto joined = xvc::load_file(out / "joined" / "garment.xvc");
  EXPECT_EQ(joined.patterns().size(), 5u);
  EXPECT_EQ(xvc::list_seams(joined).size(), 8u);
  r = run_vgd({"edit", (out / "clo.xvc").string(), "--set-parameter", "mesh.spacing=14mm", "-o",
               (out / "clo-own.xvc").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  r = run_vgd({"dress", (out / "clo-own.xvc").string(), "-o", (out / "own").string(), "--time-limit", "0.05",
               "--no-previews"});
  EXPECT_EQ(r.err.find("halves of one piece"), std::string::npos) << r.err;
  EXPECT_EQ(xvc::load_file(out / "own" / "garment.xvc").patterns().size(), 9u);
}

// The project's own skirt as AAMA DXF (what `vgd draft` writes, every size):
// the DXF carries no seams, vgd dress suggests them (the waistband to the
// waist, the side seams) and the skirt drapes on the mannequin of its size.
TEST(CliDress, ADraftedSkirtDxfDrapesInOneCommand) {
  const auto out = scratch_dir("dress-skirt");
  const auto dxf = out / "skirt.dxf";
  const auto drafted = run_vgd({"draft", "skirt", "-o", dxf.string(), "-q"});
  ASSERT_EQ(drafted.code, 0) << drafted.err;
  const auto r = run_vgd({"dress", dxf.string(), "--size", "36", "-o", (out / "d").string(), "--no-previews",
                          "--time-limit", "6"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("suggested at size 38"), std::string::npos) << r.err;
  const json c = read_json(out / "d" / "certificate.json");
  EXPECT_TRUE(c["passed"].get<bool>()) << c["failures"].dump();
  EXPECT_GE(c["seams"].size(), 3u);
  EXPECT_FALSE(std::filesystem::exists(out / "d" / "previews"));

  // Run again into the same folder after correcting its document: the
  // corrected one is kept beside the new one, not lost.
  {
    std::ofstream corrected(out / "d" / "garment.xvc", std::ios::app);
    corrected << "<!-- corrected by hand -->\n";
  }
  const auto again = run_vgd({"dress", dxf.string(), "--size", "36", "-o", (out / "d").string(), "--no-previews",
                              "--time-limit", "0.05"});
  EXPECT_TRUE(again.code == 0 || again.code == 3) << again.err;
  EXPECT_NE(again.err.find("is kept as"), std::string::npos) << again.err;
  EXPECT_NE(vgd::read_file(out / "d" / "garment.previous.xvc").find("corrected by hand"), std::string::npos);
  EXPECT_EQ(vgd::read_file(out / "d" / "garment.xvc").find("corrected by hand"), std::string::npos);

  // A size the file does not grade: the error names the file and lists its sizes.
  const auto wrong =
      run_vgd({"dress", dxf.string(), "--size", "99", "-o", (out / "w").string(), "--no-previews"});
  EXPECT_EQ(wrong.code, 1) << wrong.err;
  EXPECT_NE(wrong.err.find("skirt.dxf: size 99: the document has no pattern of size '99'; its sizes: "),
            std::string::npos)
      << wrong.err;
  EXPECT_NE(wrong.err.find(", 38, "), std::string::npos) << wrong.err;
  EXPECT_NE(wrong.err.find("(sample 38)"), std::string::npos) << wrong.err;
  // A body size its table lacks: the size asked for is named with the table's.
  const auto body = run_vgd({"dress", dxf.string(), "--body-table", "en13402-men", "--body-size", "7", "-o",
                             (out / "b").string(), "--no-previews"});
  EXPECT_EQ(body.code, 1) << body.err;
  EXPECT_NE(body.err.find("size '7': no such size (available: en13402-men: 44 46"), std::string::npos) << body.err;
}

// A T-shirt whose sleeve is cut in two along the arm (a front and a back
// half, each cut twice), with no seam in its document: the halves are sewn to
// each other and to their armholes, each placed on its own side of its arm
// (flipped as the side needs), and the drape passes with every seam closed.
TEST(CliDress, ASleeveCutInTwoDrapesOnBothArms) {
  const auto out = scratch_dir("dress-split-sleeve");
  const auto xvc = out / "split.xvc";
  vgd::xvc::save_file(vgd::xvc::from_style(tee_with_split_sleeves()), xvc);
  const auto r = run_vgd({"dress", xvc.string(), "-o", (out / "d").string(), "--no-previews"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("SLEEVE FRONT sleeve (front half), SLEEVE BACK sleeve (back half)"), std::string::npos) << r.err;
  const json c = read_json(out / "d" / "certificate.json");
  EXPECT_TRUE(c["passed"].get<bool>()) << c["failures"].dump();
  int sleeve_seams = 0;
  for (const auto& s : c["seams"]) {
    EXPECT_EQ(s["closed"], s["pairs"]) << s.dump();
    const std::string name = s["name"];
    sleeve_seams += name.find("armhole") != std::string::npos || name.find("arm seam") != std::string::npos ||
                    name.find("underarm") != std::string::npos;
  }
  EXPECT_EQ(sleeve_seams, 8) << "each arm: front and back armhole, over-arm seam, underarm";
  std::map<std::string, int> on;
  for (const auto& p : c["placement"]) ++on[p["piece"].get<std::string>() + " " + p["segment"].get<std::string>()];
  for (const char* half : {"SLEEVE_FRONT_", "SLEEVE_BACK_"})
    for (const char* arm : {"left-arm", "right-arm"}) {
      int n = 0;
      for (const auto& [k, v] : on) n += k.rfind(half, 0) == 0 && k.find(arm) != std::string::npos ? v : 0;
      EXPECT_EQ(n, 1) << half << " on the " << arm;
    }
}

// Trousers cut as half legs, each cut once and named FRONT and BACK only (as
// Valentina writes them): read as the halves of trouser legs by their length
// and shape, cut as a left and a right copy, their outseams, inseams, rises and
// waist darts sewn, each half on its side of each leg with its crotch to the
// inside, on the body whose hip and crotch height fit; the drape passes with
// every seam closed.
TEST(CliDress, TrousersCutAsHalfLegsDrapeOnBothLegs) {
  const auto out = scratch_dir("dress-trousers");
  const auto xvc = out / "trousers.xvc";
  vgd::xvc::save_file(vgd::xvc::from_style(trousers_in_halves()), xvc);
  const auto r = run_vgd({"dress", xvc.string(), "-o", (out / "d").string(), "--no-previews"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("pieces BACK, FRONT read as the front and back halves of trouser legs"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("piece FRONT is cut as a left and a right half (quantity 2)"), std::string::npos) << r.err;
  const json c = read_json(out / "d" / "certificate.json");
  EXPECT_TRUE(c["passed"].get<bool>()) << c["failures"].dump();
  std::map<std::string, int> seams;
  for (const auto& s : c["seams"]) {
    EXPECT_EQ(s["closed"], s["pairs"]) << s.dump();
    ++seams[s["name"].get<std::string>()];
  }
  EXPECT_EQ(seams, trousers_seams());
  std::map<std::string, int> on;
  for (const auto& p : c["placement"]) ++on[p["piece"].get<std::string>() + " " + p["segment"].get<std::string>()];
  EXPECT_EQ(on, (std::map<std::string, int>{{"FRONT_M left-leg", 1},
                                            {"FRONT_M right-leg", 1},
                                            {"BACK_M left-leg", 1},
                                            {"BACK_M right-leg", 1}}));
}

}  // namespace vgd::test

namespace vgd::test {

// A DXF sewn by the designer's own seam file instead of vgd's suggestions:
// the seams of the shipped skirt written out by `vgd seams list
// --seam-file`, one renamed, applied by `vgd dress --seams` to the skirt's
// DXF; a document that has seams refuses a seam file.
TEST(CliDress, ASeamFileSewsADxfInsteadOfTheSuggestions) {
  const auto out = scratch_dir("dress-seam-file");
  const auto seams = out / "skirt.seams.json";
  const auto listed = run_vgd({"seams", "list", (source_dir() / "data/garments/a-line-skirt.xvc").string(),
                               "--seam-file", seams.string()});
  ASSERT_EQ(listed.code, 0) << listed.err;
  EXPECT_NE(listed.err.find("3 seams of size 38"), std::string::npos) << listed.err;
  auto plan = read_json(seams);
  ASSERT_EQ(plan["seams"].size(), 3u);
  plan["seams"][2]["name"] = "waistband, as the designer says";
  write_file_atomic(seams, plan.dump(2));
  const auto r = run_vgd({"dress", (source_dir() / "data/garments/a-line-skirt.dxf").string(), "--seams",
                          seams.string(), "--no-previews", "--time-limit", "0.05", "--spacing", "0.03", "-o",
                          (out / "d").string()});
  EXPECT_TRUE(r.code == 0 || r.code == 3) << r.err;
  EXPECT_NE(r.err.find("seams from " + seams.string() + ": 3 seams (15 SEAMs over the sizes); none suggested"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("suggested at size"), std::string::npos) << r.err;
  const auto doc = xvc::load_file(out / "d/garment.xvc");
  const auto sewn = xvc::list_seams(doc);
  ASSERT_EQ(sewn.size(), 15u);
  EXPECT_EQ(sewn[2].name, "waistband, as the designer says");
  const json c = read_json(out / "d/certificate.json");
  EXPECT_EQ(c["seams"].size(), 3u);
  const auto refused = run_vgd({"dress", (source_dir() / "data/garments/a-line-skirt.xvc").string(), "--seams",
                                seams.string(), "--no-previews", "-o", (out / "e").string()});
  EXPECT_EQ(refused.code, 1);
  EXPECT_NE(refused.err.find("has seams of its own"), std::string::npos) << refused.err;
}

// Legs smaller round the hip than the body are cut for a stretch fabric: with
// no MATERIAL in the document and none given, the shipped knit is written in
// the document it saves and said with both girths; a fabric given with
// --material is kept, and trousers with ease stay in the woven.
// A piece left out because no suggested seam sews it says which seam vgd
// does not suggest yet, and what the designer can do about it. A shirt's
// collar drawn two ways: the one sewn to the stand is draped, the other is
// left out as its alternative. Trousers' waistband in two halves is sewn, a
// half to each side's waist, and not left out.
TEST(CliDress, APieceNoSeamSewsSaysWhichSeamVgdDoesNotSuggestYet) {
  VGD_REQUIRE_SHARED();
  const auto out = scratch_dir("dress-not-sewn");
  const auto shirt = run_vgd({"dress", shared_dxf("Valentina_MaleShirt_AAMA_R12.dxf").string(), "-o",
                              (out / "s").string(), "--no-previews", "--time-limit", "0.05"});
  for (const char* says :
       {"block COLLARBASE is half a piece (cut once, no side or fold line in the file, a straight 5.3 cm centre edge): "
        "unfolded about that edge into the whole piece",
        "seam 'stand seam' suggested at size base: COLLARBASE to FRONTPANEL + YOKE + FRONTPANEL",
        "seam 'collar seam' suggested at size base: COLLARTOP to COLLARBASE",
        "piece COLLAR (collar) left out: an alternative to the collar COLLARTOP, whose seams fit the garment's other "
        "pieces better"})
    EXPECT_NE(shirt.err.find(says), std::string::npos) << says << "\n" << shirt.err;
  for (const char* sewn : {"piece COLLARBASE (collar stand) left out", "piece COLLARTOP (collar) left out"})
    EXPECT_EQ(shirt.err.find(sewn), std::string::npos) << sewn << "\n" << shirt.err;
  const auto trousers = run_vgd({"dress", shared_dxf("Valentina_Trousers_ASTM_R12.dxf").string(), "-o",
                                 (out / "t").string(), "--no-previews", "--time-limit", "0.05"});
  // Its waistband in two halves, the longer on the wearer's right.
  for (const char* says :
       {"seam 'right waist seam' suggested at size base: WAISTBAND2 to BACK + BACK + BACK + FRONT_NO_POCKET + "
        "FRONT_NO_POCKET, ease 90.5 mm",
        "seam 'left waist seam' suggested at size base: WAISTBAND1 to FRONT_NO_POCKET + FRONT_NO_POCKET + BACK + "
        "BACK + BACK, ease 50.5 mm",
        "seam 'waistband ends' suggested at size base: WAISTBAND2 to WAISTBAND1"})
    EXPECT_NE(trousers.err.find(says), std::string::npos) << says << "\n" << trousers.err;
  for (const char* band : {"piece WAISTBAND1 (waistband) left out", "piece WAISTBAND2 (waistband) left out"})
    EXPECT_EQ(trousers.err.find(band), std::string::npos) << band << "\n" << trousers.err;
}

// A crew neck's rib (GMH1006F18's neck rib, 4 x 42.5 cm, 17 % shorter than
// the neckline) is sewn round the neckline, read as cut double and folded
// (written in the document), cut from the shipped rib, and drapes as the
// 2 cm beside the neckline in two layers. A fabric given for the garment
// (--material) is not replaced by the rib; the fold stays.
TEST(CliDress, ACrewNecksRibIsFoldedAndCutFromRib) {
  VGD_REQUIRE_SHARED();
  const auto out = scratch_dir("dress-rib");
  const auto r = run_vgd({"dress", shared_dxf("GMH1006F18_AAMA.DXF").string(), "-o", (out / "r").string(),
                          "--no-previews", "--time-limit", "0.05"});
  for (const char* says :
       {"seam 'neck seam' suggested at size 50: GMH1006FNR to GMH1006FBK + GMH1006FFR + GMH1006FBK",
        "seam 'neckband ends' suggested at size 50: GMH1006FNR to GMH1006FNR",
        "piece GMH1006FNR (neckband) read as cut double and folded lengthwise (folded=\"true\" written in the "
        "document): it drapes as the half beside the neckline, 2.0 of its 4.0 cm, in two layers",
        "piece GMH1006FNR (neckband) cut from the shipped rib cotton-rib (written in the document): it is 17 % shorter "
        "than the neckline it is sewn to"})
    EXPECT_NE(r.err.find(says), std::string::npos) << says << "\n" << r.err;
  const xvc::Document doc = xvc::load_file(out / "r" / "garment.xvc");
  int ribs = 0;
  for (const auto* p : doc.patterns()) {
    if (p->attribute("piece") != "GMH1006FNR") continue;
    ++ribs;
    EXPECT_EQ(xvc::folded_attribute(*p), std::optional<bool>(true)) << p->id();
    const auto* m = doc.find(xvc::piece_material(doc, *p));
    ASSERT_NE(m, nullptr) << p->id();
    EXPECT_EQ(m->attribute("name"), "cotton 1x1 rib (knit) (estimated values)");
  }
  EXPECT_EQ(ribs, 15);  // every size of the file
  const json c = read_json(out / "r" / "certificate.json");
  bool two_layers = false;
  for (const auto& s : c["strain"])
    if (s["piece"] == "GMH1006FNR_50") two_layers = s["fabric"].get<std::string>().find("(2 layers)") != std::string::npos;
  EXPECT_TRUE(two_layers) << c["strain"].dump();
  // The rib's particles in garment.obj: pattern coordinates (vt) 2 cm across, 42.5 cm along.
  std::ifstream obj(out / "r" / "garment.obj");
  std::string line, group;
  std::vector<std::array<double, 2>> vt;
  std::set<int> mine;
  while (std::getline(obj, line)) {
    if (line.rfind("vt ", 0) == 0) {
      std::istringstream in(line.substr(3));
      std::array<double, 2> t{};
      in >> t[0] >> t[1];
      vt.push_back(t);
    } else if (line.rfind("g ", 0) == 0) {
      group = line.substr(2);
    } else if (line.rfind("f ", 0) == 0 && group == "GMH1006FNR_50") {
      std::istringstream in(line.substr(2));
      std::string corner;
      while (in >> corner) mine.insert(std::stoi(corner.substr(corner.find('/') + 1)) - 1);
    }
  }
  ASSERT_FALSE(mine.empty());
  double lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9};
  for (const int t : mine)
    for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], vt[t][k]), hi[k] = std::max(hi[k], vt[t][k]);
  const double across = std::min(hi[0] - lo[0], hi[1] - lo[1]), along = std::max(hi[0] - lo[0], hi[1] - lo[1]);
  EXPECT_NEAR(across, 0.020, 2e-4);
  EXPECT_NEAR(along, 0.425, 2e-3);

  // Dressed again, the document keeps its fold and fabric and decides neither anew;
  // with its pieces' own fabric taken away, the rib is cut from rib again, as
  // measured on the document's own seams.
  const auto again = run_vgd({"dress", (out / "r" / "garment.xvc").string(), "-o", (out / "a").string(),
                              "--no-previews", "--time-limit", "0.05"});
  EXPECT_EQ(again.code, 3) << again.err;  // stopped at the time limit
  EXPECT_EQ(again.err.find("read as cut double"), std::string::npos) << again.err;
  EXPECT_EQ(again.err.find("cut from the shipped rib"), std::string::npos) << again.err;
  xvc::Document bare = doc;
  for (const auto* p : doc.patterns())
    if (p->attribute("piece") == "GMH1006FNR")
      xvc::execute(bare, *std::make_unique<xvc::SetPieceMaterial>(std::string(p->id()), std::nullopt));
  xvc::save_file(bare, out / "bare.xvc");
  const auto recut = run_vgd({"dress", (out / "bare.xvc").string(), "-o", (out / "b").string(), "--no-previews",
                              "--time-limit", "0.05"});
  EXPECT_NE(recut.err.find("piece GMH1006FNR (neckband) cut from the shipped rib cotton-rib (written in the "
                           "document): it is 17 % shorter than the neckline"),
            std::string::npos)
      << recut.err;

  const auto given = run_vgd({"dress", shared_dxf("GMH1006F18_AAMA.DXF").string(), "-o", (out / "g").string(),
                              "--no-previews", "--time-limit", "0.05", "--material",
                              (source_dir() / "data/materials/cotton-jersey.xvc").string()});
  EXPECT_NE(given.err.find("piece GMH1006FNR (neckband) read as cut double and folded lengthwise"), std::string::npos)
      << given.err;
  EXPECT_EQ(given.err.find("cut from the shipped rib"), std::string::npos) << given.err;
}

// GMG1016S19's rib cuffs (5 x 33 cm, cut twice) go on its short sleeves
// (35 cm hems; not on the long sleeve, its alternative): one on each arm,
// folded, in rib, each closed under the arm; the placement puts two pieces
// more on each arm.
TEST(CliDress, RibCuffsAreSewnToTheShortSleevesHems) {
  VGD_REQUIRE_SHARED();
  const auto out = scratch_dir("dress-cuffs");
  const auto r = run_vgd({"dress", shared_dxf("mirrored.DXF").string(), "-o", (out / "c").string(), "--no-previews",
                          "--time-limit", "0.05"});
  for (const char* says :
       {"seam 'right cuff' suggested at size 50: GMG1016S19-CU to GMG1016S19-SS, ease -20.0 mm",
        "seam 'left cuff' suggested at size 50: GMG1016S19-CU to GMG1016S19-SS, ease -20.0 mm",
        "seam 'right cuff ends' suggested at size 50: GMG1016S19-CU to GMG1016S19-CU",
        "seam 'left cuff ends' suggested at size 50: GMG1016S19-CU to GMG1016S19-CU",
        "piece GMG1016S19-CU (cuff) read as cut double and folded lengthwise (folded=\"true\" written in the "
        "document): it drapes as the half beside the sleeve's hem, 2.5 of its 5.0 cm, in two layers",
        "piece GMG1016S19-CU (cuff) cut from the shipped rib cotton-rib (written in the document): it is 6 % shorter "
        "than the sleeve's hem it is sewn to",
        "piece GMG1016S19-ST left out: an alternative to the sleeve GMG1016S19-SS"})
    EXPECT_NE(r.err.find(says), std::string::npos) << says << "\n" << r.err;
  const json c = read_json(out / "c" / "certificate.json");
  std::map<std::string, int> on;
  for (const auto& p : c["placement"]) ++on[p["segment"].get<std::string>()];
  EXPECT_EQ(on["left-arm"], 2);
  EXPECT_EQ(on["right-arm"], 2);
  int cuff_seams = 0;
  for (const auto& s : c["seams"])
    if (s["name"].get<std::string>().find("cuff") != std::string::npos) ++cuff_seams;
  EXPECT_EQ(cuff_seams, 4);
}

TEST(CliDress, LegsWithNegativeEaseAreDrapedInTheShippedKnit) {
  VGD_REQUIRE_SHARED();
  const auto out = scratch_dir("dress-knit");
  const auto knit = run_vgd({"dress", shared_dxf("GLX4802S19_AAMA.DXF").string(), "-o", (out / "k").string(),
                             "--no-previews", "--time-limit", "0.05"});
  EXPECT_NE(knit.err.find("fabric: the shipped knit cotton-jersey (written in the document): the pattern's hip girth "
                          "is 79 cm, 13 cm less than the body's 92 cm"),
            std::string::npos)
      << knit.err;
  EXPECT_NE(vgd::read_file(out / "k" / "garment.xvc").find("<MATERIAL id=\"cotton-jersey\""), std::string::npos);
  const auto given = run_vgd({"dress", shared_dxf("GLX4802S19_AAMA.DXF").string(), "-o", (out / "g").string(),
                              "--no-previews", "--time-limit", "0.05", "--material",
                              (source_dir() / "data/materials/denim.xvc").string()});
  EXPECT_EQ(given.err.find("fabric:"), std::string::npos) << given.err;
  EXPECT_EQ(vgd::read_file(out / "g" / "garment.xvc").find("<MATERIAL "), std::string::npos);
  const auto trousers = run_vgd({"dress", shared_dxf("Valentina_Trousers_ASTM_R12.dxf").string(), "-o",
                                 (out / "t").string(), "--no-previews", "--time-limit", "0.05"});
  EXPECT_NE(trousers.err.find("6 cm of ease over the body's 108 cm"), std::string::npos) << trousers.err;
  EXPECT_EQ(trousers.err.find("fabric:"), std::string::npos) << trousers.err;
}

}  // namespace vgd::test
