#include <gtest/gtest.h>

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
