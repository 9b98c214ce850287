#include <gtest/gtest.h>

#include "fixtures.hpp"

using namespace vgd::xvc;
using namespace vgd::xvc::test;

namespace {
// A small valid document; each test breaks one thing in it. Line numbers matter.
const std::string kBase = R"(<GARMENT id="g" version="1.0">
  <PARAMETER id="par1" name="mesh.spacing" value="0.01" unit="m"/>
  <PATTERNS id="ps">
    <PATTERN id="p1" piece="A" size="M" block="A_M">
      <C2DSEQ id="s1"><C2D x="0" y="0" kind="turn"/><C2D x="1" y="0"/></C2DSEQ>
      <C2DSEQ id="s2"><C2D x="1" y="1" kind="turn"/><C2D x="0" y="1"/></C2DSEQ>
      <C2DSEQ id="g1" role="grain"><C2D x="0.5" y="0.2"/><C2D x="0.5" y="0.8"/></C2DSEQ>
      <POSITION id="n1" type="notch" x="1" y="0.5" angle="180" vertex="1"/>
    </PATTERN>
    <PATTERN id="p2" piece="B" size="M" block="B_M">
      <C2DSEQ id="s3"><C2D x="0" y="0" kind="turn"/><C2D x="1" y="0"/><C2D x="0" y="1"/></C2DSEQ>
    </PATTERN>
  </PATTERNS>
  <SEAMS id="ss">
    <SEAM id="seam1">
      <HEM id="h1" from="s1" to="s1"/>
      <HEM id="h2" from="s3" to="s3" direction="reverse"/>
    </SEAM>
  </SEAMS>
  <GRADATIONS id="gs" sample_size="M">
    <SIZE id="z0" name="M" sample="true"/>
    <GRADATION id="gr1" piece="A">
      <SIZE id="z1" name="M" pattern="p1" sample="true"/>
    </GRADATION>
  </GRADATIONS>
  <MATERIALS id="ms">
    <MATERIAL id="m1" name="cotton"/>
  </MATERIALS>
</GARMENT>
)";

// kBase with `from` (which must occur) replaced by `to`, checked.
vgd::Diagnostics check_with(const std::string& from, const std::string& to) {
  std::string xml = kBase;
  const auto pos = xml.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  if (pos != std::string::npos) xml.replace(pos, from.size(), to);
  return check(parse_tree(xml, "t.xvc"), "t.xvc");
}

// The document has an error at `line` about `entity` whose message holds `fragment`.
::testing::AssertionResult has_error(const vgd::Diagnostics& d, int line, const std::string& entity,
                                     const std::string& fragment) {
  for (const auto& i : d.items())
    if (i.severity == vgd::Severity::error && i.line == line && i.entity == entity &&
        i.message.find(fragment) != std::string::npos && i.file == "t.xvc")
      return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "no error at line " << line << " for " << entity << " with '" << fragment
                                       << "'; got:\n"
                                       << dump(d);
}
}  // namespace

TEST(Check, BaseDocumentIsClean) {
  const auto d = check(parse_tree(kBase, "t.xvc"), "t.xvc");
  EXPECT_TRUE(d.empty()) << dump(d);
}

TEST(Check, WrongRootIsAnError) {
  const auto d = check(parse_tree("<PATTERN id=\"p\"/>", "t.xvc"), "t.xvc");
  EXPECT_TRUE(has_error(d, 1, "PATTERN", "root element is PATTERN"));
}

TEST(Check, DanglingHemReferenceIsAnError) {
  EXPECT_TRUE(has_error(check_with("from=\"s1\"", "from=\"s9\""), 16, "h1", "from names s9, which is not in the document"));
}

TEST(Check, HemMustNameABoundarySequence) {
  EXPECT_TRUE(has_error(check_with("from=\"s1\"", "from=\"p1\""), 16, "h1", "a PATTERN; a hem must name a boundary C2DSEQ"));
  EXPECT_TRUE(has_error(check_with("from=\"s1\"", "from=\"g1\""), 16, "h1", "a grain C2DSEQ"));
}

TEST(Check, HemRunsAlongOnePattern) {
  EXPECT_TRUE(has_error(check_with("to=\"s1\"", "to=\"s3\""), 16, "h1", "different patterns"));
}

TEST(Check, DuplicateIdsAreAnError) {
  EXPECT_TRUE(has_error(check_with("<C2DSEQ id=\"s2\"", "<C2DSEQ id=\"s1\""), 6, "s1", "already used at line 5"));
}

TEST(Check, SizeNamingAMissingPatternIsAnError) {
  EXPECT_TRUE(has_error(check_with("pattern=\"p1\"", "pattern=\"p9\""), 23, "z1", "pattern names p9, which is not"));
}

TEST(Check, GradationSizeMustNameAPatternOfItsPiece) {
  EXPECT_TRUE(has_error(check_with("pattern=\"p1\"", "pattern=\"p2\""), 23, "z1", "in the gradation of piece \"A\""));
  EXPECT_TRUE(has_error(check_with("pattern=\"p1\"", "pattern=\"s1\""), 23, "z1", "a C2DSEQ, not a PATTERN"));
}

TEST(Check, SampleFlagMustMatchTheSampleSize) {
  const auto d = check_with("sample_size=\"M\"", "sample_size=\"L\"");
  EXPECT_TRUE(has_error(d, 21, "z0", "marked sample"));
  EXPECT_TRUE(has_error(d, 23, "z1", "marked sample"));
}

TEST(Check, NegativeNumbersAreRefusedWhereTheyMakeNoSense) {
  EXPECT_TRUE(has_error(check_with("vertex=\"1\"", "vertex=\"1\" length=\"-0.002\""), 8, "n1", "length \"-0.002\" is negative"));
  EXPECT_TRUE(has_error(check_with("vertex=\"1\"", "vertex=\"-1\""), 8, "n1", "is negative"));
  EXPECT_TRUE(has_error(check_with("block=\"A_M\"", "block=\"A_M\" quantity=\"-1\""), 4, "p1", "is negative"));
}

TEST(Check, NonNumericAndNonFiniteNumbersAreErrors) {
  for (const char* bad : {"abc", "1,5", "", "inf", "NaN", "1e999", "0x10"}) {
    SCOPED_TRACE(bad);
    EXPECT_TRUE(has_error(check_with("x=\"1\" y=\"0.5\"", std::string("x=\"") + bad + "\" y=\"0.5\""), 8, "n1",
                          "is not a finite number"));
  }
  EXPECT_TRUE(has_error(check_with("block=\"A_M\"", "block=\"A_M\" quantity=\"2.5\""), 4, "p1", "not a whole number"));
}

TEST(Check, UnknownElementsAndAttributesAreErrors) {
  EXPECT_TRUE(has_error(check_with("<MATERIAL id=\"m1\" name=\"cotton\"/>", "<FABRIC id=\"f\"/>"), 27, "ms",
                        "unknown element FABRIC in MATERIALS"));
  EXPECT_TRUE(has_error(check_with("name=\"cotton\"", "name=\"cotton\" colour=\"red\""), 27, "m1",
                        "unknown attribute colour on MATERIAL"));
  EXPECT_TRUE(has_error(check_with("<MATERIAL id=\"m1\" name=\"cotton\"/>", "<SEAM id=\"x\"/>"), 27, "ms",
                        "a MATERIALS cannot hold a SEAM"));
}

TEST(Check, ChildrenMustComeInSchemaOrder) {
  const auto d = check_with(R"(<POSITION id="n1" type="notch" x="1" y="0.5" angle="180" vertex="1"/>)",
                            R"(<POSITION id="n1" type="notch" x="1" y="0.5" angle="180" vertex="1"/><C2DSEQ id="i1" role="internal"/>)");
  EXPECT_TRUE(has_error(d, 8, "p1", "C2DSEQ must come before POSITION"));
}

TEST(Check, MissingRequiredAttributeIsAnError) {
  EXPECT_TRUE(has_error(check_with("<HEM id=\"h1\" from=\"s1\" to=\"s1\"/>", "<HEM id=\"h1\" from=\"s1\"/>"), 16, "h1",
                        "HEM needs attribute to"));
}

TEST(Check, SeamNeedsTwoHems) {
  EXPECT_TRUE(has_error(check_with(R"(<HEM id="h2" from="s3" to="s3" direction="reverse"/>)", ""), 15, "seam1",
                        "needs at least 2 HEM"));
}

TEST(Check, GrainLineHasExactlyTwoPointsAndAPatternOnlyOne) {
  EXPECT_TRUE(has_error(check_with("<C2D x=\"0.5\" y=\"0.8\"/>", "<C2D x=\"0.5\" y=\"0.8\"/><C2D x=\"0.6\" y=\"0.8\"/>"), 7,
                        "g1", "exactly 2 C2D, this one has 3"));
  EXPECT_TRUE(has_error(
      check_with("<POSITION id=\"n1\"",
                 "<C2DSEQ id=\"g2\" role=\"grain\"><C2D x=\"0\" y=\"0\"/><C2D x=\"0\" y=\"1\"/></C2DSEQ><POSITION id=\"n1\""),
      8, "g2", "at most one grain line"));
}

TEST(Check, NotchVertexMustLieOnTheBoundary) {
  EXPECT_TRUE(has_error(check_with("vertex=\"1\"", "vertex=\"4\""), 8, "n1", "vertex 4 is beyond the boundary of p1, which has 4 points"));
}

TEST(Check, KnownParametersHaveTheirUnitAndRange) {
  EXPECT_TRUE(has_error(check_with("unit=\"m\"", "unit=\"deg\""), 2, "par1", "mesh.spacing is in m, not \"deg\""));
  EXPECT_TRUE(has_error(check_with("unit=\"m\"", "unit=\"mm\""), 2, "par1", "is not a unit vgd knows"));
  EXPECT_TRUE(has_error(check_with("value=\"0.01\"", "value=\"0\""), 2, "par1", "out of range"));
  EXPECT_TRUE(has_error(check_with("value=\"0.01\"", "value=\"-0.01\""), 2, "par1", "out of range"));
}

TEST(Check, AParameterNameIsSetOnlyOnce) {
  const auto d = check_with(R"(<PATTERNS id="ps">)", R"(<PARAMETER id="par2" name="mesh.spacing" value="0.02" unit="m"/>
  <PATTERNS id="ps">)");
  EXPECT_TRUE(has_error(d, 3, "par2", "is set twice"));
}

TEST(Check, AssociationMustNameAnElementOfItsRole) {
  const auto d = check_with(R"(<C2DSEQ id="s3">)", R"(<C2DSEQ id="s3">)");  // unchanged: sanity
  EXPECT_TRUE(d.empty()) << dump(d);
  const auto bad = check_with(R"(</C2DSEQ>
    </PATTERN>
  </PATTERNS>)", R"(</C2DSEQ><ASSOCIATION id="a1" ref="m1" role="texture"/>
    </PATTERN>
  </PATTERNS>)");
  EXPECT_TRUE(has_error(bad, 11, "a1", "ref names m1, a MATERIAL, but role \"texture\" needs a TEXTURE"));
}

TEST(Check, OtherFormatVersionsAreRefused) {
  EXPECT_TRUE(has_error(check_with("version=\"1.0\"", "version=\"2.0\""), 1, "g", "format version 2.0 is not supported"));
  EXPECT_TRUE(has_error(check_with("version=\"1.0\"", "version=\"one\""), 1, "g", "not a version number"));
  EXPECT_FALSE(check_with("version=\"1.0\"", "version=\"1.3\"").has_errors());
}

TEST(Check, ControlCharactersXmlCannotHoldAreErrors) {
  // A parser refuses "&#1;" already; trees built in memory (from_style, AddNode) need the rule.
  Node root = parse_tree(kBase, "t.xvc");
  Node& material = root.children.back().children.at(0);
  ASSERT_EQ(material.id(), "m1");
  material.set_attribute("name", "cot\x01ton");
  EXPECT_TRUE(has_error(check(root, "t.xvc"), 27, "m1", "control character"));
  material.set_attribute("name", "cot\xC3ton");
  EXPECT_TRUE(has_error(check(root, "t.xvc"), 27, "m1", "not valid UTF-8"));
}

TEST(Check, BadIdsAreErrors) {
  EXPECT_TRUE(has_error(check_with("<MATERIAL id=\"m1\"", "<MATERIAL id=\"1m\""), 27, "ms/MATERIAL[1]", "is not an id"));
}

TEST(Check, ElementsWithoutIdAreNamedByTheirOwner) {
  EXPECT_TRUE(has_error(check_with("<C2D x=\"1\" y=\"0\"/>", "<C2D x=\"1\"/>"), 5, "s1/C2D[2]", "C2D needs attribute y"));
}

TEST(Check, DuplicateBlockNamesAreOnlyAWarning) {
  const auto d = check_with("block=\"B_M\"", "block=\"A_M\"");
  EXPECT_FALSE(d.has_errors()) << dump(d);
  ASSERT_EQ(d.count(vgd::Severity::warning), 1u) << dump(d);
  EXPECT_EQ(d.items()[0].entity, "p2");
}

TEST(Check, ReportsEveryProblemInLineOrder) {
  std::string xml = kBase;
  xml.replace(xml.find("x=\"0.5\" y=\"0.2\""), 15, "x=\"?\" y=\"0.2\"");
  xml.replace(xml.find("from=\"s1\""), 9, "from=\"zz\"");
  const auto d = check(parse_tree(xml, "t.xvc"), "t.xvc");
  ASSERT_EQ(d.count(vgd::Severity::error), 2u) << dump(d);
  EXPECT_EQ(d.items()[0].line, 7);
  EXPECT_EQ(d.items()[1].line, 16);
}
