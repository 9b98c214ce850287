// Quantities with units: conversion to SI and the dimension check.
#include <gtest/gtest.h>

#include <cmath>

#include "vgd/scene/units.hpp"

using namespace vgd::scene;

TEST(Units, QuantitiesConvertToSI) {
  auto q = [](const char* s) { return parse_quantity(s); };
  EXPECT_DOUBLE_EQ(q("4 ms")->value, 0.004);
  EXPECT_EQ(q("4ms")->dimension, dim::time);
  EXPECT_DOUBLE_EQ(q("2.5 cm")->value, 0.025);
  EXPECT_DOUBLE_EQ(q("-9.81 m/s2")->value, -9.81);
  EXPECT_EQ(q("-9.81 m/s2")->dimension, dim::acceleration);
  EXPECT_DOUBLE_EQ(q("180 g/m2")->value, 0.18);
  EXPECT_EQ(q("180 g/m2")->dimension, dim::areal_density);
  EXPECT_EQ(q("0.2 N.s/m")->dimension, dim::damping);
  EXPECT_EQ(q("0.2 kg/s")->dimension, dim::damping);
  EXPECT_EQ(q("0.2 N·s/m")->dimension, dim::damping);
  EXPECT_EQ(q("1800 N/m")->dimension, dim::stiffness);
  EXPECT_EQ(q("1e-5 N.m")->dimension, dim::moment);
  EXPECT_DOUBLE_EQ(q("2 MPa")->value, 2e6);
  EXPECT_DOUBLE_EQ(q("1 kg/m^3")->value, 1.0);
  EXPECT_EQ(q("1 kg/m³")->dimension, dim::density);
  EXPECT_DOUBLE_EQ(q("10 %")->value, 0.1);
  EXPECT_DOUBLE_EQ(q("2 Hz")->value, 2.0);
  EXPECT_EQ(q("2 1/s")->dimension, dim::rate);
  EXPECT_NEAR(q("90 deg")->value, M_PI / 2, 1e-15);
  EXPECT_DOUBLE_EQ(q("0.3")->value, 0.3);
  EXPECT_EQ(q("0.3")->dimension, dim::none);
}

TEST(Units, NonsenseIsRefused) {
  EXPECT_FALSE(parse_quantity("fast"));
  EXPECT_FALSE(parse_quantity("4 parsecs"));
  EXPECT_FALSE(parse_quantity("4 m/s/s"));
  EXPECT_FALSE(parse_quantity(""));
  EXPECT_FALSE(parse_quantity("1e999 m"));
}

TEST(Units, DimensionsHaveSINames) {
  EXPECT_EQ(si_name(dim::stiffness), "N/m");
  EXPECT_EQ(si_name(dim::velocity), "m/s");
  EXPECT_EQ(si_name(dim::areal_density), "kg/m2");
  EXPECT_EQ(si_name(dim::time), "s");
  EXPECT_EQ(si_name(dim::rate), "1/s");
  EXPECT_EQ(si_name(dim::none), "1");
}
