#include <gtest/gtest.h>

#include "fixtures.hpp"

using namespace vgd::xvc;
using namespace vgd::xvc::test;

TEST(Node, SetAttributeReplacesInPlaceAndAppendsNew) {
  Node n{"C2D", {{"x", "1"}, {"y", "2"}}, {}};
  n.set_attribute("x", "3");
  n.set_attribute("kind", "turn");
  ASSERT_EQ(n.attributes.size(), 3u);
  EXPECT_EQ(n.attributes[0].name, "x");
  EXPECT_EQ(n.attributes[0].value, "3");
  EXPECT_EQ(n.attributes[2].name, "kind");
  EXPECT_TRUE(n.remove_attribute("y"));
  EXPECT_FALSE(n.remove_attribute("y"));
  EXPECT_EQ(n.attribute("y"), "");
  EXPECT_EQ(n.find_attribute("y"), nullptr);
}

TEST(Node, EqualityIgnoresLineNumbers) {
  Node a{"SIZE", {{"id", "s"}, {"name", "M"}}, {}};
  Node b = a;
  b.line = 42;
  EXPECT_EQ(a, b);
  b.attributes[1].value = "L";
  EXPECT_NE(a, b);
}

TEST(Document, NewDocumentIsAValidGarmentWithAllContainers) {
  const Document doc;
  EXPECT_EQ(doc.root().tag, "GARMENT");
  EXPECT_EQ(doc.root().attribute("version"), kFormatVersion);
  for (const char* tag : {"PATTERNS", "SEAMS", "GRADATIONS", "MATERIALS", "TEXTURES", "ACCESSORIES"})
    EXPECT_NE(doc.container(tag), nullptr) << tag;
  EXPECT_FALSE(check(doc).has_errors()) << dump(check(doc));
}

TEST(Document, FindsElementsByIdAndPath) {
  const Document doc = from_style(full_style());
  const Node* p = doc.find("pattern3");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->attribute("block"), "FRONT_38");
  const auto path = doc.path_of("pattern3");
  ASSERT_TRUE(path);
  EXPECT_EQ(&doc.at(*path), p);
  EXPECT_EQ(doc.find("nope"), nullptr);
  EXPECT_EQ(doc.patterns().size(), 5u);
}

TEST(Document, FreshIdIsAboveEveryNumberUsedWithThePrefix) {
  const Document doc = load_string(R"(<GARMENT id="g" version="1.0">
  <PARAMETER id="param7" name="a" value="1" unit="1"/>
  <PARAMETER id="param2" name="b" value="1" unit="1"/>
  <PARAMETER id="paramx" name="c" value="1" unit="1"/>
</GARMENT>)", "ids.xvc");
  EXPECT_EQ(doc.fresh_id("param"), "param8");
  EXPECT_EQ(doc.fresh_id("seam"), "seam1");
}

TEST(Document, ConstructorRefusesAnInvalidTree) {
  Node root{"GARMENT", {{"id", "g"}}, {}};  // no version
  try {
    Document doc(root, "mem");
    FAIL() << "expected an error";
  } catch (const vgd::Error& e) {
    EXPECT_EQ(e.diagnostic().file, "mem");
    EXPECT_EQ(e.diagnostic().entity, "g");
    EXPECT_NE(e.diagnostic().message.find("needs attribute version"), std::string::npos) << e.what();
  }
}

TEST(Vocabulary, IdPrefixesAndReferenceAttributes) {
  EXPECT_EQ(id_prefix("PATTERN"), "pattern");
  EXPECT_EQ(id_prefix("C2DSEQ"), "seq");
  EXPECT_EQ(id_prefix("C2D"), "");
  EXPECT_EQ(id_prefix("NOPE"), "");
  EXPECT_TRUE(is_reference_attribute("HEM", "from"));
  EXPECT_TRUE(is_reference_attribute("SIZE", "pattern"));
  EXPECT_FALSE(is_reference_attribute("SIZE", "name"));
  EXPECT_FALSE(is_reference_attribute("PATTERN", "id"));
}
