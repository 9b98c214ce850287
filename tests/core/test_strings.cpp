#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"

TEST(ParseDouble, AcceptsDxfStyleNumbers) {
  EXPECT_DOUBLE_EQ(*vgd::parse_double(".25"), 0.25);
  EXPECT_DOUBLE_EQ(*vgd::parse_double("-.5"), -0.5);
  EXPECT_DOUBLE_EQ(*vgd::parse_double("  12.5000 "), 12.5);
  EXPECT_DOUBLE_EQ(*vgd::parse_double("1e-3"), 1e-3);
  EXPECT_DOUBLE_EQ(*vgd::parse_double("+3"), 3.0);
}

TEST(ParseDouble, RejectsGarbageAndNonFinite) {
  EXPECT_FALSE(vgd::parse_double(""));
  EXPECT_FALSE(vgd::parse_double("abc"));
  EXPECT_FALSE(vgd::parse_double("1.5x"));
  EXPECT_FALSE(vgd::parse_double("nan"));
  EXPECT_FALSE(vgd::parse_double("inf"));
  EXPECT_FALSE(vgd::parse_double("1e999"));
}

TEST(FormatDouble, RoundTripsExactly) {
  for (double v : {0.1, 1.0 / 3.0, -2.5e-7, 123456.789, 0.0254})
    EXPECT_EQ(*vgd::parse_double(vgd::format_double(v)), v);
}

TEST(FormatSignificant, KeepsTheDigitsAskedFor) {
  EXPECT_EQ(vgd::format_significant(9.002204184187668e-06, 3), "9e-06");
  EXPECT_EQ(vgd::format_significant(2.3358829201807223e-06, 3), "2.34e-06");
  EXPECT_EQ(vgd::format_significant(0.125, 3), "0.125");
  EXPECT_EQ(vgd::format_significant(1234.5, 3), "1.23e+03");
  EXPECT_EQ(*vgd::parse_double(vgd::format_significant(1.2345e-8, 3)), 1.23e-8);
}

TEST(Strings, CaseInsensitiveHelpers) {
  EXPECT_TRUE(vgd::iequals("Piece Name", "PIECE NAME"));
  EXPECT_TRUE(vgd::istarts_with("SIZE: 38", "size"));
  EXPECT_EQ(vgd::trim("  a b \r\n"), "a b");
  EXPECT_EQ(vgd::split("1,2,,3", ',').size(), 4u);
}

TEST(Utf8, DecodesEncodesAndFlagsWhatIsNot) {
  const std::string s = "a\xC3\xA9\xD0\x96\xE2\x82\xAC\xF0\x9F\x91\x95";  // a é Ж € 👕
  std::size_t i = 0;
  std::vector<std::uint32_t> cps;
  while (i < s.size()) cps.push_back(vgd::next_utf8(s, i));
  EXPECT_EQ(cps, (std::vector<std::uint32_t>{0x61, 0xE9, 0x416, 0x20AC, 0x1F455}));
  std::string back;
  for (const auto c : cps) vgd::append_utf8(back, c);
  EXPECT_EQ(back, s);
  EXPECT_TRUE(vgd::is_utf8(s));
  EXPECT_FALSE(vgd::is_utf8("Sp\xE9"));           // ANSI_1252 é
  EXPECT_FALSE(vgd::is_utf8("\xD1\xEF\xE8"));     // ANSI_1251 Спи
  EXPECT_FALSE(vgd::is_utf8("\xE2\x82"));         // cut short
  i = 0;
  EXPECT_EQ(vgd::next_utf8("\xFFx", i), vgd::kInvalidUtf8);
  EXPECT_EQ(i, 1u) << "an invalid byte is stepped over alone";
}

using namespace vgd;

TEST(Printable, KeepsUtf8AndLineBreaksAndEscapesTheRest) {
  EXPECT_EQ(printable("DOS \xd0\x9f\xd0\x95\xd0\xa0\xd0\x95\xd0\x94 line\n\ttab"),
            "DOS \xd0\x9f\xd0\x95\xd0\xa0\xd0\x95\xd0\x94 line\n\ttab");
  EXPECT_EQ(printable("a\x01" "b\xff" "c\x7f"), "a\\x01b\\xFFc\\x7F");
  EXPECT_EQ(printable("cut short \xd0"), "cut short \\xD0");
  EXPECT_EQ(printable("\xc2\x85"), "\\xC2\\x85");  // U+0085, a C1 control
  EXPECT_TRUE(is_utf8(printable(std::string("\x00\xfe\xff\xc0", 4))));
}

TEST(Printable, AnErrorAndACollectedDiagnosticNeverCarryRawBytes) {
  const Error e("f.obj", "", "found '\x02\xfe'");
  EXPECT_EQ(e.diagnostic().message, "found '\\x02\\xFE'");
  EXPECT_STREQ(e.what(), "f.obj: found '\\x02\\xFE'");
  Diagnostics d;
  d.warn("", "BLOCK\xff", "x");
  d.name_file("in.dxf");
  EXPECT_EQ(d.items()[0].format(), "in.dxf: BLOCK\\xFF: x");
}

TEST(JsonErrorMessage, SaysNlohmannsErrorsInWords) {
  EXPECT_EQ(json_error_message("[json.exception.parse_error.101] parse error at line 1, column 19: syntax error while "
                               "parsing object key - invalid string: missing closing quote; last read: '\"di'; "
                               "expected string literal",
                               "not valid JSON"),
            "not valid JSON at line 1, column 19: invalid string: missing closing quote (read up to: \"di); expected "
            "string literal");
  EXPECT_EQ(json_error_message("[json.exception.out_of_range.406] number overflow parsing '1e999'", "not valid JSON"),
            "not valid JSON: a number too large for a double: 1e999");
  EXPECT_EQ(json_error_message("[json.exception.type_error.302] type must be number, but is string", "not a seam file"),
            "not a seam file: type must be number, but is string");
}

TEST(HtmlEscape, TheFiveCharactersHtmlMindsAreReferences) {
  EXPECT_EQ(vgd::html_escape("<a href=\"x\">Tom & Jerry's</a>"),
            "&lt;a href=&quot;x&quot;&gt;Tom &amp; Jerry&#39;s&lt;/a&gt;");
  EXPECT_EQ(vgd::html_escape("skirt 38 — denim"), "skirt 38 — denim");
}
