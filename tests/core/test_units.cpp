#include <gtest/gtest.h>

#include "vgd/core/units.hpp"

TEST(Units, AamaWordsMapToLengths) {
  EXPECT_EQ(vgd::parse_length_unit("METRIC"), vgd::LengthUnit::millimetre);
  EXPECT_EQ(vgd::parse_length_unit("English"), vgd::LengthUnit::inch);
  EXPECT_EQ(vgd::parse_length_unit(" cm "), vgd::LengthUnit::centimetre);
  EXPECT_FALSE(vgd::parse_length_unit("furlongs"));
}

TEST(Units, InchIsExactly25_4mm) {
  EXPECT_DOUBLE_EQ(vgd::metres_per(vgd::LengthUnit::inch), 0.0254);
  EXPECT_DOUBLE_EQ(vgd::metres_per(vgd::LengthUnit::millimetre) * 1000.0, 1.0);
}
