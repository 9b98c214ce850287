#include <gtest/gtest.h>

#include "fixtures.hpp"
#include "vgd/core/file.hpp"

using namespace vgd::xvc;
using namespace vgd::xvc::test;
namespace fs = std::filesystem;

namespace {
// Loads text that must fail and returns the error.
vgd::Error load_error(const std::string& xml, const std::string& name = "bad.xvc") {
  try {
    load_string(xml, name);
  } catch (const vgd::Error& e) {
    return e;
  }
  ADD_FAILURE() << "expected a vgd::Error for:\n" << xml;
  return vgd::Error("", "", "");
}

const char* kSmall = R"(<?xml version="1.0" encoding="UTF-8"?>
<!-- a comment vgd does not keep -->
<GARMENT version="1.0" id="g" name="small">
  <PATTERNS id="ps">
    <PATTERN id="p1" piece="A" size="M" block="A_M">
      <C2DSEQ id="s1"><C2D x="0" y="0" kind="turn"/><C2D x="1.50" y="0"/></C2DSEQ>
      <C2DSEQ id="s2"><C2D x="1" y="1" kind="turn"/></C2DSEQ>
    </PATTERN>
  </PATTERNS>
</GARMENT>
)";
}  // namespace

TEST(Load, KeepsAttributeOrderAndValuesAsWritten) {
  const Document doc = load_string(kSmall, "small.xvc");
  const Node& g = doc.root();
  ASSERT_EQ(g.attributes.size(), 3u);
  EXPECT_EQ(g.attributes[0].name, "version");
  EXPECT_EQ(g.attributes[1].name, "id");
  EXPECT_EQ(doc.find("s1")->children[1].attribute("x"), "1.50");  // not re-formatted
  EXPECT_EQ(doc.find("p1")->line, 5);
}

TEST(Save, LoadSaveLoadSaveIsByteIdentical) {
  const std::string first = save_string(load_string(kSmall, "small.xvc"));
  const std::string second = save_string(load_string(first, "first.xvc"));
  EXPECT_EQ(first, second);
  EXPECT_EQ(first.find("comment"), std::string::npos);
}

TEST(Save, FullDocumentRoundTripsByteIdentical) {
  const std::string first = save_string(full_document());
  const Document again = load_string(first, "full.xvc");
  EXPECT_EQ(save_string(again), first);
  EXPECT_EQ(again, full_document());
}

TEST(Save, EscapesSoTextSurvivesExactly) {
  Document doc;
  SetAttribute set("garment", "name", std::string("a&b <c> \"d\" 'e'\ttab\nline\r\ncr caf\xC3\xA9"));
  execute(doc, set);
  const std::string xml = save_string(doc);
  EXPECT_NE(xml.find("&#9;tab&#10;line&#13;&#10;cr"), std::string::npos) << xml;
  EXPECT_EQ(load_string(xml, "x").root().attribute("name"), doc.root().attribute("name"));
}

TEST(Save, FileIsWrittenAtomicallyAndReadsBack) {
  const auto dir = vgd::test::scratch_dir("xvc_save_file");
  const Document doc = full_document();
  save_file(doc, dir / "g.xvc");
  save_file(doc, dir / "g.xvc");  // over an existing file
  EXPECT_EQ(load_file(dir / "g.xvc"), doc);
  int files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1) << "a temporary file was left behind";
}

TEST(LoadErrors, MalformedXmlNamesFileAndLine) {
  const auto e = load_error("<GARMENT id=\"g\" version=\"1.0\">\n  <PATTERNS id=\"p\">\n  </SEAMS>\n</GARMENT>\n", "broken.xvc");
  EXPECT_EQ(e.diagnostic().file, "broken.xvc");
  EXPECT_EQ(e.diagnostic().line, 3);
  EXPECT_NE(std::string(e.what()).find("malformed XML"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("broken.xvc:3: malformed XML: Opening and ending tag mismatch"), std::string::npos)
      << e.what();
}

TEST(LoadErrors, WhatTinyxml2WouldAcceptIsStillMalformed) {
  const char* cases[] = {
      "<GARMENT id=\"g\" version=\"1.0\"/><GARMENT id=\"h\" version=\"1.0\"/>",  // a second root
      "<GARMENT id=\"g\" version=\"1.0\" name=\"a&nbsp;b\"/>",                    // unknown entity
      "<GARMENT id=\"g\" version=\"1.0\" name=\"a<b\"/>",
      "<GARMENT id=\"g\" version=\"1.0\" name=\"a&b\"/>",
  };
  for (const char* xml : cases) {
    const auto e = load_error(xml);
    EXPECT_NE(std::string(e.what()).find("malformed XML"), std::string::npos) << e.what();
  }
}

TEST(LoadErrors, DoctypeIsRefused) {
  const auto e = load_error("<?xml version=\"1.0\"?>\n<!DOCTYPE GARMENT [<!ENTITY x \"boom\">]>\n"
                            "<GARMENT id=\"g\" version=\"1.0\" name=\"&x;\"/>");
  EXPECT_NE(std::string(e.what()).find("DOCTYPE"), std::string::npos) << e.what();
  EXPECT_TRUE(validate_string("<!DOCTYPE GARMENT><GARMENT id=\"g\" version=\"1.0\"/>", "d.xvc", schema()).has_errors());
}

TEST(LoadErrors, EmptyTextIsMalformed) {
  const auto e = load_error("", "empty.xvc");
  EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos) << e.what();
}

TEST(LoadErrors, WrongRootIsRefused) {
  const auto e = load_error("<?xml version=\"1.0\"?>\n<svg id=\"x\"/>\n");
  EXPECT_EQ(e.diagnostic().line, 2);
  EXPECT_NE(e.diagnostic().message.find("GARMENT"), std::string::npos) << e.what();
}

TEST(LoadErrors, TextContentIsRefusedWithItsLine) {
  const auto e = load_error("<GARMENT id=\"g\" version=\"1.0\">\n\n  hello\n</GARMENT>");
  EXPECT_EQ(e.diagnostic().line, 3);
  EXPECT_NE(e.diagnostic().message.find("unexpected text hello"), std::string::npos) << e.what();
}

TEST(LoadErrors, RepeatedAttributeIsRefused) {
  const auto e = load_error("<GARMENT id=\"g\" version=\"1.0\" id=\"h\"/>");
  EXPECT_NE(std::string(e.what()).find("Attribute id redefined"), std::string::npos) << e.what();
}

TEST(LoadErrors, SemanticErrorNamesLineElementAndCountsTheRest) {
  const auto e = load_error(R"(<GARMENT id="g" version="1.0">
  <PATTERNS id="ps">
    <PATTERN id="p1" quantity="-2">
      <C2DSEQ id="s1"><C2D x="abc" y="0"/></C2DSEQ>
    </PATTERN>
  </PATTERNS>
</GARMENT>)");
  EXPECT_EQ(e.diagnostic().line, 3);
  EXPECT_EQ(e.diagnostic().entity, "p1");
  EXPECT_NE(e.diagnostic().message.find("quantity \"-2\" is negative"), std::string::npos) << e.what();
  EXPECT_NE(e.diagnostic().message.find("and 1 more problem"), std::string::npos) << e.what();
}

TEST(LoadErrors, MissingFileNamesTheFile) {
  try {
    load_file("/nonexistent/garment.xvc");
    FAIL() << "expected an error";
  } catch (const vgd::Error& e) {
    EXPECT_EQ(e.diagnostic().file, "/nonexistent/garment.xvc");
  }
}
