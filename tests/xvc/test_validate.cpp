#include <gtest/gtest.h>

#include <cstdlib>

#include "fixtures.hpp"
#include "vgd/core/file.hpp"

using namespace vgd::xvc;
using namespace vgd::xvc::test;
namespace fs = std::filesystem;

namespace {
// xmllint, independent of vgd's code, on a saved document: true when the XSD accepts it.
bool xmllint_accepts(const std::string& xml, const std::string& name) {
  const auto dir = vgd::test::scratch_dir("xvc_xmllint_" + name);
  vgd::write_file_atomic(dir / "doc.xvc", xml);
  return run("xmllint --noout --nonet --schema '" + schema().string() + "' '" + (dir / "doc.xvc").string() + "' > '" +
             (dir / "out.txt").string() + "' 2>&1") == 0;
}

// Sets an env variable for one scope.
struct ScopedEnv {
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (old_) ::setenv(name_, old_->c_str(), 1);
    else ::unsetenv(name_);
  }
  const char* name_;
  std::optional<std::string> old_;
};
}  // namespace

TEST(Validate, EveryDocumentVgdWritesIsValid) {
  for (const Document& doc : {from_style(full_style()), full_document(), Document{}, from_style({})}) {
    const std::string xml = save_string(doc);
    const auto d = validate_string(xml, "written.xvc", schema());
    EXPECT_TRUE(d.empty()) << dump(d) << xml.substr(0, 2000);
    EXPECT_TRUE(xmllint_accepts(xml, "written"));
  }
}

TEST(Validate, MalformedXmlIsADiagnosticWithItsLine) {
  const auto d = validate_string("<GARMENT id=\"g\" version=\"1.0\">\n<PATTERNS id=\"p\">\n</GARMENT>\n", "m.xvc", schema());
  ASSERT_TRUE(d.has_errors());
  EXPECT_EQ(d.items()[0].file, "m.xvc");
  EXPECT_GT(d.items()[0].line, 0);
  EXPECT_NE(d.items()[0].message.find("malformed XML"), std::string::npos) << dump(d);
}

TEST(Validate, SchemaAndRulesAgreeOnBrokenDocuments) {
  // Each breaks one rule both the XSD and check() can see.
  const std::string good = save_string(full_document());
  const std::pair<std::string, std::string> breaks[] = {
      {"quantity=\"2\"", "quantity=\"-2\""},
      {"x=\"0.3\"", "x=\"abc\""},
      {"x=\"0.3\"", "x=\"INF\""},
      {"kind=\"turn\"", "kind=\"corner\""},
      {"<GARMENT id=\"garment\"", "<GARMENT id=\"9garment\""},
      {"id=\"seq2\"", "id=\"seq1\""},
      {"unit=\"m\"", "unit=\"furlong\""},
      {"role=\"grain\"", "role=\"weft\""},
      {"<SEAMS id=\"seams\">", "<SEAMS id=\"seams\" colour=\"red\">"},
      {"<GARMENT id=\"garment\" version=\"1.0\"", "<GARMENT id=\"garment\" version=\"x\""},
      {"from=\"seq2\"", "from=\"seq999\""},
      {"r=\"0.1\"", "r=\"1.5\""},
      {"type=\"notch\"", "type=\"nick\""},
  };
  for (const auto& [from, to] : breaks) {
    SCOPED_TRACE(to);
    std::string xml = good;
    const auto pos = xml.find(from);
    ASSERT_NE(pos, std::string::npos) << from;
    xml.replace(pos, from.size(), to);
    EXPECT_TRUE(check(parse_tree(xml, "b.xvc"), "b.xvc").has_errors());
    EXPECT_FALSE(xmllint_accepts(xml, "broken"));
    EXPECT_TRUE(validate_string(xml, "b.xvc", schema()).has_errors());
  }
}

TEST(Validate, ProblemsCarryFileLineAndEntity) {
  std::string xml = save_string(full_document());
  xml.replace(xml.find("from=\"seq2\""), 11, "from=\"seq999\"");
  const auto d = validate_string(xml, "shirt.xvc", schema());
  ASSERT_TRUE(d.has_errors());
  bool found = false;
  for (const auto& i : d.items())
    if (i.entity == "hem1" && i.message.find("seq999") != std::string::npos) {
      found = true;
      EXPECT_EQ(i.file, "shirt.xvc");
      EXPECT_GT(i.line, 0);
      EXPECT_NE(i.format().find("shirt.xvc:" + std::to_string(i.line) + ": hem1: "), std::string::npos);
    }
  EXPECT_TRUE(found) << dump(d);
}

TEST(Validate, OneMessagePerProblemLine) {
  std::string xml = save_string(full_document());
  xml.replace(xml.find("quantity=\"2\""), 12, "quantity=\"-2\"");
  const auto d = validate_string(xml, "q.xvc", schema());
  ASSERT_EQ(d.count(vgd::Severity::error), 1u) << dump(d);
  EXPECT_NE(d.items()[0].message.find("negative"), std::string::npos) << dump(d);
}

TEST(Validate, ValidateFileReadsTheFile) {
  const auto dir = vgd::test::scratch_dir("xvc_validate_file");
  save_file(full_document(), dir / "g.xvc");
  EXPECT_TRUE(validate_file(dir / "g.xvc", schema()).empty());
  EXPECT_THROW(validate_file(dir / "missing.xvc", schema()), vgd::Error);
}

TEST(Validate, MissingOrBrokenSchemaIsAnError) {
  const auto dir = vgd::test::scratch_dir("xvc_bad_schema");
  EXPECT_THROW(validate_string("<GARMENT/>", "x", dir / "none.xsd"), vgd::Error);
  vgd::write_file_atomic(dir / "broken.xsd", "<xs:schema xmlns:xs=\"http://www.w3.org/2001/XMLSchema\"><xs:bogus/></xs:schema>");
  try {
    validate_string("<GARMENT/>", "x", dir / "broken.xsd");
    FAIL() << "expected an error";
  } catch (const vgd::Error& e) {
    EXPECT_NE(std::string(e.what()).find("broken.xsd"), std::string::npos) << e.what();
  }
}

TEST(SchemaPath, DefaultFindsTheSourceTreeSchema) {
  ScopedEnv env("VGD_SCHEMA_DIR", "");
  EXPECT_TRUE(fs::equivalent(default_schema_path(), schema()));
  EXPECT_TRUE(fs::equivalent(find_schema_file("xvc-to-svg.xsl"), stylesheet()));
}

TEST(SchemaPath, EnvironmentVariableComesFirst) {
  const auto dir = vgd::test::scratch_dir("xvc_schema_env");
  fs::copy_file(schema(), dir / "xvc.xsd");
  ScopedEnv env("VGD_SCHEMA_DIR", dir.string());
  EXPECT_EQ(default_schema_path(), dir / "xvc.xsd");
}

TEST(SchemaPath, UnknownFileNamesThePlacesTried) {
  try {
    find_schema_file("no-such.xsd");
    FAIL() << "expected an error";
  } catch (const vgd::Error& e) {
    EXPECT_NE(std::string(e.what()).find("VGD_SCHEMA_DIR"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("schemas/no-such.xsd"), std::string::npos) << e.what();
  }
}

TEST(Docs, ExampleIsValid) {
  // The complete example in docs/xvc.md: valid, and already in vgd's own layout.
  const std::string md = vgd::read_file(vgd::test::source_dir() / "docs" / "xvc.md");
  const auto start = md.find("```xml\n");
  ASSERT_NE(start, std::string::npos);
  const auto end = md.find("```", start + 7);
  const std::string xml = md.substr(start + 7, end - start - 7);
  const auto d = validate_string(xml, "docs/xvc.md", schema());
  EXPECT_TRUE(d.empty()) << dump(d);
  EXPECT_EQ(save_string(load_string(xml, "docs/xvc.md")), xml);
}
