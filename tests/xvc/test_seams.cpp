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

#include "support/test_paths.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/io/dxf/import.hpp"
#include "vgd/pattern/draft.hpp"
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
    SeamOptions at_sample;
    at_sample.size = imported.style.sample_size;
    std::multiset<SeamKey> want;
    std::map<std::string, double> sample_length;
    for (const auto& x : suggest_seams(doc, at_sample)) {
      want.insert(key(doc, x.hems));
      sample_length[x.name] = x.length_a;
    }
    ASSERT_GE(want.size(), 4u);
    for (const std::string& size : {imported.style.sizes.front(), imported.style.sizes.back()}) {
      SeamOptions o;
      o.size = size;
      std::multiset<SeamKey> got;
      for (const auto& x : suggest_seams(doc, o)) {
        got.insert(key(doc, x.hems));
        // Graded lengths differ from the sample's: the seam is measured on this size.
        if (sample_length.count(x.name) && x.name.find("shoulder") == std::string::npos) {
          EXPECT_NE(x.length_a, sample_length[x.name]) << size << " " << x.name;
        }
      }
      EXPECT_EQ(got, want) << "size " << size;
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
