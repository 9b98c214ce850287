#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

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
