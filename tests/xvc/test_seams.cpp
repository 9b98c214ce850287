// Seam suggestions reproduce the drafter's own seams; ease figures; planned seams;
// a real Gerber T-shirt (MEN_CLASSIC_TEE) from ../shared.
#include <gtest/gtest.h>

#include <fstream>
#include <algorithm>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "fixtures.hpp"
#include "support/split_sleeve.hpp"
#include "support/trousers.hpp"
#include "shared_style.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/io/dxf/import.hpp"
#include "vgd/pattern/draft.hpp"
#include "vgd/pattern/halves.hpp"
#include "vgd/xvc/commands.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/seams.hpp"
#include "vgd/xvc/style.hpp"
#include "vgd/xvc/validate.hpp"

using namespace vgd;
using namespace vgd::xvc;

namespace {

using HemKey = std::tuple<std::string, int, int, bool>;  // piece, from, to, reverse
using SeamKey = std::vector<HemKey>;

int stretch_of(const Document& doc, const std::string& pattern, const std::string& seq) {
  const auto st = boundary_stretches(*doc.find(pattern));
  for (std::size_t k = 0; k < st.size(); ++k)
    if (st[k].id == seq) return static_cast<int>(k);
  return -1;
}

// The first suggestion of that name, or found.end().
std::vector<SeamSuggestion>::const_iterator named(const std::vector<SeamSuggestion>& found, const std::string& name) {
  return std::find_if(found.begin(), found.end(), [&](const SeamSuggestion& s) { return s.name == name; });
}

SeamKey key(const Document& doc, const std::vector<HemRef>& hems) {
  SeamKey k;
  for (const auto& h : hems)
    k.emplace_back(std::string(doc.find(h.pattern)->attribute("piece")), stretch_of(doc, h.pattern, h.from),
                   stretch_of(doc, h.pattern, h.to), h.reverse);
  return k;
}

std::multiset<SeamKey> plan_keys(const std::vector<pattern::SeamPlan>& plans) {
  std::multiset<SeamKey> out;
  for (const auto& p : plans) {
    SeamKey k;
    for (const auto& h : p.hems) k.emplace_back(h.piece, h.from, h.to, h.reverse);
    out.insert(k);
  }
  return out;
}

std::string describe(const SeamKey& k) {
  std::ostringstream o;
  for (const auto& [piece, a, b, rev] : k) o << piece << ":" << a << ".." << b << (rev ? " rev" : " fwd") << "  ";
  return o.str();
}

void expect_suggestions_reproduce(const pattern::Style& style, const std::vector<pattern::SeamPlan>& plans) {
  const Document doc = from_style(style);
  const auto suggestions = suggest_seams(doc);
  for (const auto& size : style.sizes) {
    SCOPED_TRACE("size " + size);
    std::multiset<SeamKey> got;
    for (const auto& s : suggestions)
      if (s.size == size) {
        got.insert(key(doc, s.hems));
        EXPECT_GE(s.score, 0.5);
      }
    const auto want = plan_keys(plans);
    for (const auto& k : want) EXPECT_EQ(got.count(k), 1u) << "missing: " << describe(k);
    for (const auto& k : got) EXPECT_EQ(want.count(k), 1u) << "extra: " << describe(k);
  }
}

}  // namespace

TEST(SeamSuggestions, ReproduceTheDraftedTShirtSeams) {
  expect_suggestions_reproduce(pattern::draft_tshirt_style(), pattern::tshirt_seams());
}

TEST(SeamSuggestions, ReproduceTheDraftedSkirtSeams) {
  expect_suggestions_reproduce(pattern::draft_skirt_style(), pattern::skirt_seams());
}

TEST(SeamSuggestions, EaseIsTheLengthDifference) {
  const pattern::TShirtMeasurements m;
  const Document doc = from_style(pattern::draft_tshirt_style({m}));
  int caps = 0, sides = 0;
  for (const auto& s : suggest_seams(doc)) {
    EXPECT_NEAR(s.ease, s.length_a - s.length_b, 1e-15);
    double sum = 0;
    for (std::size_t i = 1; i < s.hems.size(); ++i) sum += s.hems[i].length;
    EXPECT_NEAR(s.length_b, sum, 1e-12);
    if (s.name.find("armhole") != std::string::npos) {
      ++caps;
      EXPECT_NEAR(s.ease, m.cap_ease, 1e-9) << s.name;
      EXPECT_EQ(s.hems.size(), 3u);
      EXPECT_EQ(s.notches_matched, 3) << s.reason;  // back pair, front, shoulder (at the junction)
    } else {
      ++sides;
      EXPECT_NEAR(s.ease, 0.0, 1e-9) << s.name;
    }
  }
  EXPECT_EQ(caps, 2);
  EXPECT_EQ(sides, 6);
}

TEST(SeamSuggestions, AppliedSeamsValidateAndUndoOneByOne) {
  Document doc = from_style(pattern::draft_skirt_style({pattern::skirt_size_table()[2]}));
  const Document before = doc;
  std::vector<Node> nodes;
  for (const auto& s : suggest_seams(doc)) nodes.push_back(seam_node(s));
  ASSERT_EQ(nodes.size(), 3u);
  UndoStack stack(doc);
  stack.execute(std::make_unique<AddSeams>(nodes));
  EXPECT_EQ(list_seams(doc).size(), 3u);
  EXPECT_FALSE(check(doc).has_errors());
  // Each seam is its own element: delete one, the others stay.
  const std::string first = list_seams(doc).front().id;
  stack.execute(std::make_unique<DeleteNode>(first));
  EXPECT_EQ(list_seams(doc).size(), 2u);
  stack.undo();
  stack.undo();
  EXPECT_EQ(doc, before);
}

TEST(SeamPlans, JsonRoundTripAndErrorsNameTheProblem) {
  const auto plans = pattern::tshirt_seams();
  const auto back = parse_seam_plans(seam_plans_to_json(plans), "t.json");
  EXPECT_EQ(plan_keys(back), plan_keys(plans));
  EXPECT_THROW(parse_seam_plans("{\"seams\": [{\"hems\": [{\"piece\": \"A\", \"from\": 0}]}]}", "x.json"), Error);
  EXPECT_THROW(parse_seam_plans("[]", "x.json"), Error);
  const Document doc = from_style(pattern::draft_tshirt_style({pattern::TShirtMeasurements{}}));
  try {
    plan_seam_nodes(doc, {{"bad", {{"FRONT", 0, 0, false}, {"BACK", 42, 42, true}}}});
    FAIL() << "no error for a missing stretch";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no stretch 42"), std::string::npos) << e.what();
  }
}

// The project's own garments in data/garments are what the drafter makes today.
TEST(GarmentData, CommittedXvcFilesMatchTheDraft) {
  struct Case {
    const char* file;
    pattern::Style style;
    std::vector<pattern::SeamPlan> seams;
  };
  for (auto& c : {Case{"t-shirt.xvc", pattern::draft_tshirt_style(), pattern::tshirt_seams()},
                  Case{"a-line-skirt.xvc", pattern::draft_skirt_style(), pattern::skirt_seams()}}) {
    SCOPED_TRACE(c.file);
    const auto path = vgd::test::source_dir() / "data" / "garments" / c.file;
    ASSERT_TRUE(std::filesystem::exists(path)) << "regenerate with: vgd draft ... -o data/garments/" << c.file;
    const Document committed = load_file(path);
    EXPECT_EQ(to_style(committed).pieces.size(), c.style.pieces.size());
    // Same patterns, bit for bit, and the drafter's seams in every size.
    const auto fresh = to_style(from_style(c.style));
    const auto got = to_style(committed);
    for (std::size_t i = 0; i < fresh.pieces.size() && i < got.pieces.size(); ++i) {
      ASSERT_EQ(fresh.pieces[i].boundary.size(), got.pieces[i].boundary.size());
      for (std::size_t j = 0; j < fresh.pieces[i].boundary.size(); ++j)
        EXPECT_EQ(fresh.pieces[i].boundary[j].p, got.pieces[i].boundary[j].p);
    }
    std::multiset<SeamKey> want, have;
    for (const auto& k : plan_keys(c.seams))
      for (std::size_t s = 0; s < c.style.sizes.size(); ++s) want.insert(k);
    for (const auto& s : list_seams(committed)) have.insert(key(committed, s.hems));
    EXPECT_EQ(have, want);
    // Every pattern has its arrangement(s).
    for (const Node* p : committed.patterns()) {
      int n = 0;
      for (const auto& ch : p->children) n += ch.tag == "POSITION" && ch.attribute("type") == "arrangement";
      EXPECT_GE(n, 1) << p->id();
    }
    const auto diags = validate_file(path, default_schema_path());
    EXPECT_EQ(diags.count(Severity::error), 0u);
  }
}

TEST(SeamSuggestions, MenClassicTeeFindsSideSeamsAndShoulders) {
  VGD_REQUIRE_SHARED();
  const auto imported = dxf::import_file(vgd::test::shared_dxf("MEN_CLASSIC_TEE.DXF"));
  const Document doc = from_style(imported.style);
  SeamOptions opts;
  opts.size = imported.style.sample_size;
  const auto s = suggest_seams(doc, opts);
  int side = 0, shoulder = 0;
  std::cout << "MEN_CLASSIC_TEE, size " << opts.size << ": " << s.size() << " suggestions\n";
  for (const auto& x : s) {
    std::cout << "  " << x.name << " (score " << format_fixed(x.score, 3) << ", ease " << format_fixed(x.ease * 1000, 1)
              << " mm): " << describe(key(doc, x.hems)) << "\n    " << x.reason << "\n";
    const bool fb = x.hems.size() == 2 && std::get<0>(key(doc, x.hems)[0]) == "REGULAR TEEFR" &&
                    std::get<0>(key(doc, x.hems)[1]) == "REGULAR TEEBK";
    if (fb && x.name.find("side seam") != std::string::npos) ++side;
    if (fb && x.name.find("shoulder") != std::string::npos) ++shoulder;
  }
  EXPECT_GE(side, 1);
  EXPECT_GE(shoulder, 1);
  // The seam file for the later drape test applies cleanly to this garment.
  const auto file = vgd::test::source_dir() / "tests" / "data" / "men-classic-tee.seams.json";
  std::ifstream in(file);
  ASSERT_TRUE(in) << file;
  std::stringstream text;
  text << in.rdbuf();
  const auto plans = parse_seam_plans(text.str(), file.string());
  Document applied = doc;
  execute(applied, *std::make_unique<AddSeams>(plan_seam_nodes(applied, plans, opts.size)));
  EXPECT_EQ(list_seams(applied).size(), plans.size());
}

// Graded sizes of a real file carry no turn points or notches; the importer
// gives them the sample size's, so every size has the sample's stretches and
// the suggester finds the same seams, at each size's own lengths, in every size.
TEST(SeamSuggestions, EverySizeOfAGradedFileSewsAsTheSampleSize) {
  VGD_REQUIRE_SHARED();
  for (const std::string file : {"MEN_CLASSIC_TEE.DXF", "WM_SLIM_TANK.DXF", "GMH1006F18_AAMA.DXF", "drill-holes.DXF"}) {
    SCOPED_TRACE(file);
    dxf::ImportOptions unfold;
    unfold.unfold_mirrored = true;
    const auto imported = dxf::import_file(vgd::test::shared_dxf(file), unfold);
    // Every block of a piece has as many turn points and notches as its sample block.
    for (const auto& p : imported.style.pieces) {
      const pattern::Piece* sample = nullptr;
      for (const auto& q : imported.style.pieces)
        if (q.name == p.name && q.size == imported.style.sample_size) sample = &q;
      ASSERT_NE(sample, nullptr) << p.block;
      auto turns = [](const pattern::Piece& x) {
        return std::count_if(x.boundary.begin(), x.boundary.end(),
                             [](const pattern::ContourPoint& c) { return c.kind == pattern::PointKind::turn; });
      };
      EXPECT_EQ(turns(p), turns(*sample)) << p.block;
      EXPECT_EQ(p.notches.size(), sample->notches.size()) << p.block;
    }
    const Document doc = from_style(imported.style);
    // MEN_CLASSIC_TEE's back sleeve half is not graded (one outline in all its
    // sizes) while its front half is: the halves sew each other at the sample
    // size only, and are left out of the comparison.
    std::set<std::string> ungraded;
    if (file == "MEN_CLASSIC_TEE.DXF") {
      std::set<double> bk_perimeter;
      for (const auto& p : imported.style.pieces)
        if (p.name == "REGULAR TEESL BK") bk_perimeter.insert(std::round(pattern::perimeter(p.boundary) * 1e6));
      EXPECT_EQ(bk_perimeter.size(), 1u) << "the back half is graded now: compare it";
      ungraded = {"REGULAR TEESL BK", "REGULAR TEESL FR"};
    }
    const auto compared = [&](const SeamKey& k) {
      return std::none_of(k.begin(), k.end(), [&](const HemKey& h) { return ungraded.count(std::get<0>(h)) > 0; });
    };
    SeamOptions at_sample;
    at_sample.size = imported.style.sample_size;
    std::multiset<SeamKey> want;
    std::map<std::string, double> sample_length;
    for (const auto& x : suggest_seams(doc, at_sample)) {
      if (!compared(key(doc, x.hems))) continue;
      want.insert(key(doc, x.hems));
      sample_length[x.name] = x.length_a;
    }
    ASSERT_GE(want.size(), 4u);
    for (const std::string& size : {imported.style.sizes.front(), imported.style.sizes.back()}) {
      SeamOptions o;
      o.size = size;
      std::multiset<SeamKey> got;
      for (const auto& x : suggest_seams(doc, o)) {
        if (!compared(key(doc, x.hems))) continue;
        got.insert(key(doc, x.hems));
        // Graded lengths differ from the sample's: the seam is measured on this size
        // (not the shoulders' and a band's ends: a rib is as wide in every size).
        if (sample_length.count(x.name) && x.name.find("shoulder") == std::string::npos &&
            x.name.find("ends") == std::string::npos) {
          EXPECT_NE(x.length_a, sample_length[x.name]) << size << " " << x.name;
        }
      }
      EXPECT_EQ(got, want) << "size " << size;
    }
  }
}

// A crew neck's rib (cut double, 4 cm wide) is sewn by its long edge round
// the neckline: from centre back along the back's half, the front's neckline,
// the back's other half back to centre back, each the run of outline between
// the piece's two shoulder seams; its two ends meet at centre back. Lengths
// of the files' own outlines at the sample size.
TEST(SeamSuggestions, ACrewNecksRibIsSewnRoundTheNecklineBetweenTheShoulders) {
  VGD_REQUIRE_SHARED();
  struct Case {
    const char* file;
    const char* rib;
    double rib_length, neckline;  // m
  };
  for (const Case& c : {Case{"GMH1006F18_AAMA.DXF", "GMH1006FNR", 0.425, 0.5133},
                        Case{"MEN_CLASSIC_TEE.DXF", "REGULAR TEECO", 0.390, 0.5193}}) {
    SCOPED_TRACE(c.file);
    const auto [doc, sample] = vgd::test::shared_style(c.file);
    const auto found = suggest_seams(doc, sample);
    const auto neck = named(found, "neck seam");
    ASSERT_NE(neck, found.end());
    const SeamKey k = key(doc, neck->hems);
    ASSERT_EQ(k.size(), 4u);
    EXPECT_EQ(std::get<0>(k[0]), c.rib);
    EXPECT_EQ(std::get<0>(k[1]), std::get<0>(k[3]));  // the back, split at centre back
    EXPECT_NE(std::get<0>(k[1]).find("BK"), std::string::npos);
    EXPECT_NE(std::get<0>(k[2]).find("FR"), std::string::npos);
    EXPECT_NEAR(neck->length_a, c.rib_length, 0.0005);
    EXPECT_NEAR(neck->length_b, c.neckline, 0.0005);
    // Each neckline run ends where a shoulder seam begins on that piece.
    for (const int part : {1, 2, 3}) {
      const auto& [piece, from, to, reverse] = k[part];
      bool before = false, after = false;
      for (const auto& s : found) {
        if (s.name.find("shoulder") == std::string::npos) continue;
        for (const auto& h : key(doc, s.hems)) {
          if (std::get<0>(h) != piece) continue;
          const int n = static_cast<int>(boundary_stretches(*doc.find(neck->hems[part].pattern)).size());
          before = before || (std::get<2>(h) + 1) % n == from;
          after = after || (to + 1) % n == std::get<1>(h);
        }
      }
      EXPECT_TRUE(part == 1 ? before : part == 3 ? after : before && after) << "part " << part;
    }
    const auto ends = named(found, "neckband ends");
    ASSERT_NE(ends, found.end());
    EXPECT_EQ(std::get<0>(key(doc, ends->hems)[0]), c.rib);
    EXPECT_NEAR(ends->length_a, 0.040, 0.001);
  }
}

// A polo's one-piece collar (no collar stand in the garment) is sewn round
// the neckline from centre front, where its ends meet open: the front's
// neckline split at its centre, the back's whole between them. Its sewn edge
// is the one with the shoulder notches (the curved one, not the straight
// finished edge), whichever way the collar is drawn.
TEST(SeamSuggestions, APolosCollarIsSewnRoundTheNecklineFromCentreFront) {
  VGD_REQUIRE_SHARED();
  const auto [doc, sample] = vgd::test::shared_style("drill-holes.DXF");
  const auto found = suggest_seams(doc, sample);
  const auto collar = named(found, "collar seam");
  ASSERT_NE(collar, found.end());
  const SeamKey k = key(doc, collar->hems);
  ASSERT_EQ(k.size(), 4u);
  EXPECT_EQ(std::get<0>(k[0]), "SS17_M POLO REG CO");
  EXPECT_EQ(std::get<0>(k[1]), "SS17_M POLO REG FR");
  EXPECT_EQ(std::get<0>(k[2]), "SS17_M POLO REG BK");
  EXPECT_EQ(std::get<0>(k[3]), "SS17_M POLO REG FR");
  // The front's two halves meet at centre front: one ends where the other begins.
  const int nf = static_cast<int>(boundary_stretches(*doc.find(collar->hems[1].pattern)).size());
  EXPECT_EQ((std::get<2>(k[1]) + 1) % nf, std::get<1>(k[3]));
  // Its curved edge, 136.9 + 4.3 + 79.3 + 79.3 + 4.5 + 136.7 mm in the file
  // (the straight one is 439.8 mm), on a neckline 20.6 mm longer.
  EXPECT_NEAR(collar->length_a, 0.4410, 0.0005);
  EXPECT_NEAR(collar->length_b, 0.4615, 0.0005);
  EXPECT_EQ(collar->notches_a, 2);
  EXPECT_EQ(collar->notches_matched, 2);
  // Its ends are not sewn to each other (the placket's opening is between them).
  for (const auto& s : found) EXPECT_EQ(s.name.find("collar ends"), std::string::npos);
  // A garment with a collar stand sews no collar to its neckline.
  for (const char* file : {"mirrored.DXF", "Valentina_MaleShirt_AAMA_R12.dxf"}) {
    const auto other = vgd::test::shared_style(file);
    for (const auto& s : suggest_seams(other.doc, other.sample)) {
      if (s.name != "collar seam") continue;
      for (const auto& h : s.hems) {
        EXPECT_NE(vgd::xvc::piece_role(other.doc, *other.doc.find(h.pattern)).role, vgd::pattern::Role::front) << file;
      }
    }
  }
}

// data/garments/t-shirt.dxf is what `vgd draft tshirt -o data/garments/t-shirt.dxf` writes
// today (as DraftedSkirtData does for the skirt in tests/io/dxf/test_roundtrip.cpp).
TEST(GarmentData, CommittedTShirtDxfMatchesTheDraft) {
  const auto committed = dxf::import_file(vgd::test::source_dir() / "data/garments/t-shirt.dxf");
  const auto fresh = pattern::draft_tshirt_style();
  ASSERT_EQ(committed.style.pieces.size(), fresh.pieces.size());
  EXPECT_EQ(committed.style.sample_size, "38");
  for (std::size_t i = 0; i < fresh.pieces.size(); ++i) {
    const auto &a = fresh.pieces[i], &b = committed.style.pieces[i];
    SCOPED_TRACE(a.block);
    EXPECT_EQ(a.name, b.name);
    ASSERT_EQ(a.boundary.size(), b.boundary.size());
    for (std::size_t j = 0; j < a.boundary.size(); ++j) {
      EXPECT_LT((a.boundary[j].p - b.boundary[j].p).norm(), 1e-6);  // the DXF holds mm with 4 decimals or more
      EXPECT_EQ(a.boundary[j].kind, b.boundary[j].kind);
    }
    EXPECT_EQ(a.notches.size(), b.notches.size());
  }
  EXPECT_EQ(committed.diagnostics.count(Severity::warning), 0u);
}

namespace {

// The shared file imported (mirrored halves unfolded) as a document. A file
// whose every piece says "Quantity: 0" (mirrored.DXF) reads as each cut once,
// as vgd dress reads it.
vgd::xvc::Document shared_document(const std::string& file) {
  vgd::dxf::ImportOptions unfold;
  unfold.unfold_mirrored = true;
  auto style = vgd::dxf::import_file(vgd::test::shared_dxf(file), unfold).style;
  if (std::all_of(style.pieces.begin(), style.pieces.end(), [](const auto& p) { return p.quantity == 0; }))
    for (auto& p : style.pieces) p.quantity = 1;
  return vgd::xvc::from_style(style);
}

std::vector<vgd::xvc::SeamSuggestion> at_size(const vgd::xvc::Document& doc, const std::string& size) {
  vgd::xvc::SeamOptions o;
  o.size = size;
  return vgd::xvc::suggest_seams(doc, o);
}

}  // namespace

// Tights cut as one piece per leg, twice (Gerber GLX4802S19, AAMA and ASTM):
// each copy's inseam is sewn to itself, and the two copies' front rises to
// each other, and their back rises; the front rise is the shorter. In the
// sample size and the largest graded one.
TEST(SeamSuggestions, OnePieceLegsCutTwiceSewTheirInseamsAndRises) {
  VGD_REQUIRE_SHARED();
  for (const std::string file : {"GLX4802S19_AAMA.DXF", "GLX4802S19_ASTM.DXF"}) {
    vgd::dxf::ImportOptions unfold;
    unfold.unfold_mirrored = true;
    const auto style = vgd::dxf::import_file(vgd::test::shared_dxf(file), unfold).style;
    const Document doc = from_style(style);
    for (const std::string& size : {style.sample_size, style.sizes.back()}) {
      SCOPED_TRACE(file + " size " + size);
      std::map<std::string, int> count;
      std::map<std::string, double> length;
      for (const auto& s : at_size(doc, size)) {
        if (doc.find(s.hems[0].pattern)->attribute("piece") != "GLX4802S19SLL") continue;  // the long leg
        ++count[s.name];
        length[s.name] = s.length_a;
        ASSERT_EQ(s.hems.size(), 2u);
        EXPECT_EQ(s.hems[0].pattern, s.hems[1].pattern) << s.name;
        EXPECT_NEAR(s.length_a, s.length_b, 0.002) << s.name << " (the suggester eases in 2 mm without a mark)";
        if (s.name.find("rise") != std::string::npos) {
          EXPECT_EQ(s.hems[0].from, s.hems[1].from) << "the same stretches of the two copies";
          EXPECT_NE(s.hems[0].reverse, s.hems[1].reverse) << "the flipped copy's rise read the other way";
        }
      }
      EXPECT_EQ(count, (std::map<std::string, int>{{"back rise", 1}, {"front rise", 1}, {"left inseam", 1}, {"right inseam", 1}}));
      EXPECT_LT(length["front rise"], length["back rise"]);
      EXPECT_GT(length["left inseam"], 0.6) << "a long leg's inseam, crotch to ankle";
    }
  }
}

// Side seams whose front is one edge and whose back is two (a waist shaped
// on one piece only), and a back cut 12 mm longer than its front (eased in):
// both sides are found (Gerber tank C-S1615 in size 36; GMG1016S19 in 50).
TEST(SeamSuggestions, SideSeamsAcrossAGentleTurnAndWithADroppedBackHem) {
  VGD_REQUIRE_SHARED();
  for (const auto& [file, size, min_length, ease] :
       {std::tuple{"simple.DXF", "36", 0.40, 0.0}, std::tuple{"mirrored.DXF", "50", 0.46, -0.012}}) {
    SCOPED_TRACE(file);
    const Document doc = shared_document(file);
    int sides = 0;
    for (const auto& s : at_size(doc, size)) {
      if (s.name.find("side seam") == std::string::npos) continue;
      ++sides;
      EXPECT_GT(s.length_a, min_length) << s.name;
      EXPECT_NEAR(s.ease, ease, 0.001) << s.name;
    }
    EXPECT_EQ(sides, 2);
  }
}

// Every piece of the shared files gets the role its name says; what no
// dictionary word names is said to be unknown, not guessed.
TEST(PieceRoles, EveryPieceOfTheSharedFiles) {
  VGD_REQUIRE_SHARED();
  const std::map<std::string, std::string> want = {
      {"drill-holes.DXF", "back 1, collar 1, front 1, interfacing 2, placket 2, sleeve 1"},
      {"MEN_CLASSIC_TEE.DXF", "back 1, collar 1, front 1, neckband 1, sleeve 3"},
      {"mirrored.DXF", "back 1, collar 7, collar stand 2, cuff 1, front 1, neckband 1, placket 2, sleeve 2"},
      {"GMH1006F18_AAMA.DXF", "back 1, front 1, neckband 2, sleeve 2"},
      {"simple.DXF", "back 1, binding 2, front 1"},
      {"WM_SLIM_TANK.DXF", "back 1, front 1"},
      {"GLX4802S19_AAMA.DXF", "leg 2, unknown 1"},
      {"ORILEGWB_AAMA.DXF", "unknown 1, waistband 1"},
      {"Valentina_MaleShirt_AAMA_R12.dxf",
       "back 1, collar 2, collar stand 1, front 1, interfacing 3, placket 2, pocket 2, pocket flap 2, sleeve 2, yoke 1"},
      {"Valentina_Trousers_ASTM_R12.dxf", "back 1, front 3, pocket 4, unknown 1, waistband 2"},
      {"clo-pattern.dxf", "unknown 9"},
  };
  for (const auto& [file, roles] : want) {
    const Document doc = shared_document(file);
    std::map<std::string, int> count;
    std::set<std::string> seen;
    for (const auto* p : doc.patterns())
      if (seen.insert(std::string(p->attribute("piece"))).second) ++count[std::string(pattern::role_name(piece_role(doc, *p).role))];
    std::string got;
    for (const auto& [r, n] : count) got += (got.empty() ? "" : ", ") + r + " " + std::to_string(n);
    EXPECT_EQ(got, roles) << file;
  }
}

// A sleeve cut in two along the arm, each half cut twice: each half's cap is
// sewn to the armhole on its side of the arm (the front half's to the front),
// the halves to each other along the centre line (over the arm) and along the
// underarm, once per copy; their hems stay open.
TEST(SeamSuggestions, ASleeveCutInTwoSewsItsHalvesToEachOtherAndToTheirArmholes) {
  const pattern::Style style = vgd::test::tee_with_split_sleeves();
  const Document doc = from_style(style);
  std::map<std::string, int> count;
  for (const auto& s : at_size(doc, style.sample_size)) {
    std::set<std::string> pieces;
    for (const auto& h : s.hems) pieces.insert(std::string(doc.find(h.pattern)->attribute("piece")));
    if (!pieces.count("SLEEVE FRONT") && !pieces.count("SLEEVE BACK")) continue;
    SCOPED_TRACE(s.name + ": " + s.reason);
    ++count[s.name];
    ASSERT_EQ(s.hems.size(), 2u);
    EXPECT_GE(s.score, 0.5);
    if (s.name.find("over-arm") != std::string::npos || s.name.find("underarm") != std::string::npos) {
      EXPECT_EQ(pieces, (std::set<std::string>{"SLEEVE FRONT", "SLEEVE BACK"}));
      EXPECT_NEAR(s.length_a, s.length_b, 1e-9) << "the two sides of one cut";
    } else {
      const bool front = s.name.find("front") != std::string::npos;
      EXPECT_EQ(pieces, (std::set<std::string>{front ? "SLEEVE FRONT" : "SLEEVE BACK", front ? "FRONT" : "BACK"}));
      EXPECT_GE(s.ease, -0.005);
    }
  }
  EXPECT_EQ(count, (std::map<std::string, int>{{"left back armhole", 1},
                                                {"left front armhole", 1},
                                                {"left over-arm seam", 1},
                                                {"left underarm", 1},
                                                {"right back armhole", 1},
                                                {"right front armhole", 1},
                                                {"right over-arm seam", 1},
                                                {"right underarm", 1}}));
}

// Trousers cut as a front and a back half of each leg (named with the trouser
// word, cut twice): the outseams and inseams of the halves sewn to each other
// per leg, the front rises of the two front copies to each other and the back
// rises likewise, each half's waist dart closed per copy. The inseam runs from
// the hem to the crotch point, the rise from there to the centre line.
TEST(SeamSuggestions, TrouserLegsCutInHalvesSewTheirOutseamsInseamsRisesAndDarts) {
  const pattern::Style style = vgd::test::trousers_in_halves("TROUSER FRONT", "TROUSER BACK", 2);
  const Document doc = from_style(style);
  std::map<std::string, int> count;
  const auto length = [](double x0, double y0, double x1, double y1) { return std::hypot(x1 - x0, y1 - y0); };
  for (const auto& s : at_size(doc, "M")) {
    SCOPED_TRACE(s.name + ": " + s.reason);
    ++count[s.name];
    ASSERT_EQ(s.hems.size(), 2u);
    EXPECT_NEAR(s.length_a, s.length_b, 1e-9) << "drafted to sew without ease";
    std::set<std::string> pieces;
    for (const auto& h : s.hems) pieces.insert(std::string(doc.find(h.pattern)->attribute("piece")));
    if (s.name.find("outseam") != std::string::npos || s.name.find("inseam") != std::string::npos) {
      EXPECT_EQ(pieces, (std::set<std::string>{"TROUSER FRONT", "TROUSER BACK"}));
      EXPECT_EQ(doc.find(s.hems[0].pattern)->attribute("piece"), "TROUSER FRONT");
      EXPECT_FALSE(s.hems[0].reverse);
      EXPECT_TRUE(s.hems[1].reverse);
    }
    if (s.name.find("inseam") != std::string::npos) {
      EXPECT_NEAR(s.length_a, length(0.19, 0, 0.25, 0.62), 1e-9);
    }
    if (s.name.find("outseam") != std::string::npos) {
      EXPECT_NEAR(s.length_a, length(-0.04, 0.89, -0.05, 0.70) + length(-0.05, 0.70, 0.02, 0), 1e-9);
    }
    if (s.name.find("rise") != std::string::npos || s.name.find("dart") != std::string::npos) {
      EXPECT_EQ(pieces.size(), 1u);
      EXPECT_EQ(s.hems[0].pattern, s.hems[1].pattern);
      EXPECT_NE(s.hems[0].reverse, s.hems[1].reverse);
      EXPECT_EQ(*pieces.begin(), s.name == "front rise" ? "TROUSER FRONT" : s.name == "back rise" ? "TROUSER BACK"
                                                                                                : *pieces.begin());
    }
    if (s.name.find("dart") != std::string::npos) {
      EXPECT_NE(s.hems[0].from, s.hems[1].from) << "one leg to the other";
    }
  }
  EXPECT_EQ(count, vgd::test::trousers_seams());
}


// Leggings (Gerber ORILEGWB): a leg cut twice and a rectangular waistband cut
// once. The band is sewn to both legs' waists and closed into a loop, its two
// ends (the short edges) to each other, bottom corner to bottom corner; a
// skirt's waistband, with its opening, keeps its ends apart
// (ReproduceTheDraftedSkirtSeams lists the skirt's seams exactly).
TEST(SeamSuggestions, ALeggingsWaistbandIsClosedIntoALoop) {
  VGD_REQUIRE_SHARED();
  Document doc = shared_document("ORILEGWB_AAMA.DXF");
  // The leg is read as a leg by elimination (vgd dress writes it in the
  // document); its name says nothing.
  Journal journal;
  Editor ed(doc, journal);
  for (const auto* p : std::vector<const Node*>(doc.patterns()))
    if (p->attribute("piece") == "ORILEG WB LL") ed.set_attribute(*doc.path_of(p->id()), "role", "leg");
  std::map<std::string, int> count;
  for (const auto& s : at_size(doc, "36")) {
    ++count[s.name];
    if (s.name != "waistband ends") continue;
    ASSERT_EQ(s.hems.size(), 2u);
    EXPECT_EQ(s.hems[0].pattern, s.hems[1].pattern);
    EXPECT_EQ(doc.find(s.hems[0].pattern)->attribute("piece"), "ORILEG WB WB");
    EXPECT_NE(s.hems[0].from, s.hems[1].from) << "the two ends, not one edge twice";
    EXPECT_NE(s.hems[0].reverse, s.hems[1].reverse) << "one end read up, the other down";
    EXPECT_NEAR(s.length_a, s.length_b, 1e-4);
    EXPECT_GT(s.score, 0.9);
  }
  EXPECT_EQ(count, (std::map<std::string, int>{{"back rise", 1},
                                               {"front rise", 1},
                                               {"left inseam", 1},
                                               {"right inseam", 1},
                                               {"waist seam", 1},
                                               {"waistband ends", 1}}));
}

// Valentina's shirt draws its front and its back as halves with no fold line:
// the straight centre front (70 cm, the button stand's edge) and centre back
// are not side seams. Only the real side seam pairs the front with the back
// (45 cm); before, the centre front was sewn to the centre back as the
// "right side seam" (70 cm).
TEST(SeamSuggestions, TheCentreEdgesOfHalvesWithNoFoldLineAreNotSideSeams) {
  VGD_REQUIRE_SHARED();
  const Document doc = shared_document("Valentina_MaleShirt_AAMA_R12.dxf");
  int sides = 0;
  for (const auto& s : at_size(doc, "base")) {
    if (s.name.find("side seam") == std::string::npos) continue;
    ++sides;
    EXPECT_NEAR(s.length_a, 0.454, 0.005) << s.name;
  }
  EXPECT_EQ(sides, 1);
}

// Valentina's shirt with its halves unfolded (pattern::unfold_top_halves):
// the yoke's lowest edge takes the back's top (the back 63.5 mm longer, the
// box pleat at its centre), the yoke's shoulders the front's, and each short
// sleeve's cap (629.7 mm) the armhole of the back, the yoke and the front
// (628.1 mm), in that order round the left arm and the reverse round the
// right; the side seams stay the front's and the back's (45 cm).
TEST(SeamSuggestions, AShirtsYokeTakesTheBackTheShouldersAndTheArmholesTop) {
  VGD_REQUIRE_SHARED();
  vgd::dxf::ImportOptions unfold;
  unfold.unfold_mirrored = true;
  auto style = vgd::dxf::import_file(vgd::test::shared_dxf("Valentina_MaleShirt_AAMA_R12.dxf"), unfold).style;
  ASSERT_EQ(vgd::pattern::unfold_top_halves(style).unfolded.size(), 5u);  // with the collar and its stand
  const Document doc = vgd::xvc::from_style(style);
  const auto piece = [&](const vgd::xvc::HemRef& h) { return std::string(doc.find(h.pattern)->attribute("piece")); };
  std::map<std::string, std::vector<std::string>> pieces;  // seam name -> its hems' pieces (the first sleeve's)
  std::map<std::string, double> ease;
  for (const auto& s : at_size(doc, "base")) {
    if (pieces.count(s.name)) continue;
    for (const auto& h : s.hems) pieces[s.name].push_back(piece(h));
    ease[s.name] = s.ease;
    if (s.name.find("side seam") != std::string::npos) {
      EXPECT_NEAR(s.length_a, 0.454, 0.005) << s.name;
    }
  }
  using V = std::vector<std::string>;
  EXPECT_EQ(pieces["yoke seam"], (V{"YOKE", "BACKPANEL"}));
  EXPECT_NEAR(ease["yoke seam"], -0.0635, 0.001);
  for (const char* side : {"left shoulder", "right shoulder"}) {
    EXPECT_EQ(pieces[side], (V{"FRONTPANEL", "YOKE"})) << side;
    EXPECT_NEAR(ease[side], 0.0, 0.001) << side;
  }
  EXPECT_EQ(pieces["left armhole"], (V{"SHORTSLEEVE", "BACKPANEL", "YOKE", "FRONTPANEL"}));
  EXPECT_EQ(pieces["right armhole"], (V{"SHORTSLEEVE", "FRONTPANEL", "YOKE", "BACKPANEL"}));
  EXPECT_NEAR(ease["left armhole"], 0.0015, 0.001);
  EXPECT_EQ(pieces["left side seam"], (V{"FRONTPANEL", "BACKPANEL"}));
  EXPECT_EQ(pieces["right side seam"], (V{"FRONTPANEL", "BACKPANEL"}));
}

// Valentina's shirt, its halves unfolded (the collar COLLARTOP and the stand
// COLLARBASE too, about their centre backs): the stand's lower edge (500 mm)
// is sewn round the neckline from centre front, the front's half, the yoke's
// (which carries the back neckline), the front's other half (558 mm: the
// front is drawn with its button extension, in its neckline on both sides
// once unfolded); its ends are not sewn (they overlap at centre front). The
// collar's neck edge (444 mm) is sewn to the stand's top (488 mm, the stand's
// ends reaching past the collar's), both hems forward: the collar turns down
// over the stand. The other collar (COLLAR, a 31 cm rectangle) is sewn nowhere.
TEST(SeamSuggestions, AShirtsStandIsSewnRoundTheNecklineAndItsCollarToTheStandsTop) {
  VGD_REQUIRE_SHARED();
  const Document doc = vgd::test::shared_style_halves_unfolded("Valentina_MaleShirt_AAMA_R12.dxf").doc;
  const auto found = at_size(doc, "base");
  const auto stand = named(found, "stand seam");
  ASSERT_NE(stand, found.end());
  const SeamKey k = key(doc, stand->hems);
  ASSERT_EQ(k.size(), 4u);
  EXPECT_EQ(std::get<0>(k[0]), "COLLARBASE");
  EXPECT_EQ(std::get<0>(k[1]), "FRONTPANEL");
  EXPECT_EQ(std::get<0>(k[2]), "YOKE");
  EXPECT_EQ(std::get<0>(k[3]), "FRONTPANEL");
  const int nf = static_cast<int>(boundary_stretches(*doc.find(stand->hems[1].pattern)).size());
  EXPECT_EQ((std::get<2>(k[1]) + 1) % nf, std::get<1>(k[3])) << "the front's halves meet at centre front";
  EXPECT_NEAR(stand->length_a, 0.5001, 0.001);
  EXPECT_NEAR(stand->length_b, 0.5585, 0.001);
  EXPECT_FALSE(stand->hems[0].reverse);
  for (std::size_t i = 1; i < stand->hems.size(); ++i) EXPECT_TRUE(stand->hems[i].reverse);
  const auto collar = named(found, "collar seam");
  ASSERT_NE(collar, found.end());
  ASSERT_EQ(collar->hems.size(), 2u);
  EXPECT_EQ(std::string(doc.find(collar->hems[0].pattern)->attribute("piece")), "COLLARTOP");
  EXPECT_EQ(std::string(doc.find(collar->hems[1].pattern)->attribute("piece")), "COLLARBASE");
  EXPECT_NEAR(collar->length_a, 0.4440, 0.001);
  EXPECT_NEAR(collar->length_b, 0.4883, 0.001);
  EXPECT_FALSE(collar->hems[0].reverse);
  EXPECT_FALSE(collar->hems[1].reverse) << "turned down over the stand: not opened flat beside it";
  // The stand's top is the edge the neckline seam leaves: they share no stretch.
  EXPECT_NE(collar->hems[1].from, stand->hems[0].from);
  EXPECT_NE(collar->hems[1].to, stand->hems[0].to);
  for (const auto& s : found) {
    EXPECT_EQ(s.name.find("ends"), std::string::npos) << s.name;
    for (const auto& h : s.hems) EXPECT_NE(std::string(doc.find(h.pattern)->attribute("piece")), "COLLAR") << s.name;
  }
}

// A seam flipped: hem B's HEMs in reverse order, each direction flipped; hem
// A as it was; flipped twice, the document as before; not a SEAM: refused.
TEST(FlipSeam, ReversesTheSecondSideAndTwiceIsNoChange) {
  Document doc = vgd::xvc::test::full_document();
  const Document before = doc;
  const Node* seam = nullptr;
  for (const auto& s : doc.container("SEAMS")->children) seam = &s;
  ASSERT_NE(seam, nullptr);
  const std::string id(seam->id());
  std::vector<Node> hems;
  for (const auto& h : seam->children)
    if (h.tag == "HEM") hems.push_back(h);
  ASSERT_GE(hems.size(), 2u);
  FlipSeam flip(id);
  EXPECT_EQ(execute(doc, flip), id);
  std::vector<Node> after;
  for (const auto& h : doc.find(id)->children)
    if (h.tag == "HEM") after.push_back(h);
  ASSERT_EQ(after.size(), hems.size());
  EXPECT_EQ(after[0], hems[0]) << "hem A stays";
  for (std::size_t k = 1; k < hems.size(); ++k) {
    const Node& was = hems[hems.size() - k];
    EXPECT_EQ(after[k].attribute("from"), was.attribute("from"));
    EXPECT_NE(after[k].attribute("direction") == "reverse", was.attribute("direction") == "reverse");
  }
  EXPECT_FALSE(check(doc).has_errors()) << vgd::xvc::test::dump(check(doc));
  FlipSeam again(id);
  execute(doc, again);
  EXPECT_EQ(doc.root(), before.root());
  FlipSeam wrong("pattern1");
  EXPECT_THROW(execute(doc, wrong), vgd::Error);
}

namespace {

// Gerber's tank with bindings: the neck binding (a 3.8 cm strip cut long,
// 67 cm along the edge sewn for a 58.5 cm neckline in size 36) is sewn round
// the back's and the front's necklines between the shoulder seams, from
// centre back, and its ends to each other there (one drawn square, one
// slanted: trimmed, both are square); the armhole binding (81 cm), further
// from the neckline's length, is not sewn there, nor anywhere yet. Graded:
// the same in size 50.
TEST(SeamSuggestions, ATanksNeckBindingIsSewnRoundItsNeckline) {
  VGD_REQUIRE_SHARED();
  const Document doc = shared_document("simple.DXF");
  for (const auto& [size, neckline] : {std::pair{"36", 0.585}, std::pair{"50", 0.631}}) {
    SCOPED_TRACE(size);
    std::map<std::string, int> count;
    for (const auto& s : at_size(doc, size)) {
      ++count[s.name];
      std::set<std::string> pieces;
      for (const auto& h : s.hems) pieces.insert(std::string(doc.find(h.pattern)->attribute("piece")));
      EXPECT_FALSE(pieces.count("C-S1615WWO206-AB")) << s.name;
      if (s.name == "binding ends") {
        EXPECT_EQ(pieces, (std::set<std::string>{"C-S1615WWO206-NB"}));
        EXPECT_NE(s.reason.find("cut square when trimmed"), std::string::npos) << s.reason;
      }
      if (s.name != "neck seam") continue;
      SCOPED_TRACE(s.reason);
      EXPECT_EQ(doc.find(s.hems[0].pattern)->attribute("piece"), "C-S1615WWO206-NB");
      EXPECT_EQ(pieces, (std::set<std::string>{"C-S1615WWO206-NB", "C-S1615WWO206-F", "C-S1615WWO206-B"}));
      EXPECT_EQ(s.hems.size(), 4u) << "the binding; the back from centre back, the front, the back to centre back";
      EXPECT_NEAR(s.length_b, neckline, 0.001);
      EXPECT_GT(s.ease, 0.08) << "cut long";
      EXPECT_NE(s.reason.find("cut long: trimmed to the neckline"), std::string::npos);
    }
    EXPECT_EQ(count, (std::map<std::string, int>{{"binding ends", 1},
                                                  {"left shoulder", 1},
                                                  {"left side seam", 1},
                                                  {"neck seam", 1},
                                                  {"right shoulder", 1},
                                                  {"right side seam", 1}}));
  }
}

}  // namespace
