// Landmarks and measurements found on a body's surface, checked on vgd's
// mannequin, whose measurements are known: in the A-pose, the T-pose and with
// the arms swung forward, women's and men's sizes. Girths and heights within 1 cm; the
// arms found on both sides, along the mannequin's own arm axes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "vgd/body/landmarks.hpp"
#include "vgd/body/mannequin.hpp"
#include "vgd/body/sizes.hpp"

namespace vgd::body {
namespace {

struct Case {
  std::string table, size;
  double arm_angle;
  double arm_forward = 0.0;  // deg, arms swung forward from the frontal plane
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.table << ' ' << c.size << ", arms at " << c.arm_angle << " deg, " << c.arm_forward << " deg forward";
}

class Measured : public ::testing::TestWithParam<Case> {};

TEST_P(Measured, TheMannequinsMeasurementsAreFoundOnItsSurface) {
  const Case& c = GetParam();
  const BodyMeasurements want = find_size(c.size, c.table);
  MannequinOptions o;
  o.arm_angle_deg = c.arm_angle;
  o.arm_forward_deg = c.arm_forward;
  const Avatar body = make_mannequin(want, o);
  const MannequinLandmarks known = mannequin_landmarks(want);
  const BodyMeasuring got = measure_body(body.surface);
  const auto& m = got.measurements;
  const auto& l = got.landmarks;
  std::printf("[ figures  ] %s %s, arms at %.0f deg, %.0f forward: height %+.2f, bust %+.2f, under-bust %+.2f, waist %+.2f, "
              "hip %+.2f, inseam %+.2f, neck %+.2f, arm %+.2f cm off\n",
              c.table.c_str(), c.size.c_str(), c.arm_angle, c.arm_forward, 100 * (m.height - want.height), 100 * (m.bust - want.bust),
              100 * (m.under_bust - want.under_bust), 100 * (m.waist - want.waist), 100 * (m.hip - want.hip),
              100 * (m.inseam - want.inseam), 100 * (m.neck - want.neck), 100 * (m.arm_length - want.arm_length));
  EXPECT_NEAR(m.height, want.height, 0.01);
  EXPECT_NEAR(m.bust, want.bust, 0.01);
  EXPECT_NEAR(m.waist, want.waist, 0.01);
  EXPECT_NEAR(m.hip, want.hip, 0.01);
  EXPECT_NEAR(m.inseam, want.inseam, 0.01);
  // Heights of the landmarks the girths are taken at.
  // A man's chest girth changes by under 1 % over 5 cm of height: its fullest
  // slice is found that far from the mannequin's chest line (the girth itself
  // within 1 cm, above).
  EXPECT_NEAR(l.bust, known.bust, want.sex == "male" ? 0.05 : 0.02);
  EXPECT_NEAR(l.waist, known.waist, 0.03);
  EXPECT_NEAR(l.hip, known.hip, 0.03);
  EXPECT_NEAR(l.crotch, known.crotch, 0.01);
  EXPECT_NEAR(l.shoulder, known.shoulder, 0.03);
  // Both arms, along the mannequin's arm axes, their wrists within 4 cm.
  for (const auto& [arm, name] : {std::pair{&l.left_arm, "left-arm"}, {&l.right_arm, "right-arm"}}) {
    ASSERT_TRUE(arm->has_value()) << name;
    const BodySegment* s = body.segment(name);
    ASSERT_NE(s, nullptr);
    const Vec3 wrist = s->start + s->length * s->axis;
    EXPECT_LT(((*arm)->wrist - wrist).norm(), 0.04) << name;
    const Vec3 axis = ((*arm)->wrist - (*arm)->shoulder).normalized();
    EXPECT_GT(axis.dot(s->axis), std::cos(5.0 * 3.14159265358979 / 180)) << name << ": the arm's direction";
  }
  // The segments placement wraps sleeves round.
  const auto arms = arm_segments(body.surface, l);
  ASSERT_EQ(arms.size(), 2u);
  EXPECT_EQ(arms[0].name, "left-arm");
  EXPECT_GT(arms[0].axis.x(), 0.5);
  EXPECT_LT(arms[1].axis.x(), -0.5);
  // The nearest size of the tables is the one the body was made from.
  const NearestSize n = nearest_size(m);
  EXPECT_EQ(n.table, c.table);
  EXPECT_EQ(n.size.label, c.size);
}

INSTANTIATE_TEST_SUITE_P(Bodies, Measured,
                         ::testing::Values(Case{"en13402-women", "38", 45.0}, Case{"en13402-women", "38", 90.0},
                                           Case{"en13402-men", "50", 45.0}, Case{"en13402-women", "44", 60.0},
                                           Case{"en13402-women", "40", 45.0, 30.0}, Case{"en13402-men", "54", 40.0, 20.0},
                                           // arms pressed against a full bust and flanks (no gap under the arm)
                                           Case{"en13402-women", "50", 45.0}),
                         [](const auto& p) {
                           const Case& c = p.param;
                           return (c.table == "en13402-men" ? "men_" : "women_") + c.size + "_arms_" +
                                  std::to_string(static_cast<int>(c.arm_angle)) +
                                  (c.arm_forward > 0 ? "_forward_" + std::to_string(static_cast<int>(c.arm_forward)) : "");
                         });

}  // namespace
}  // namespace vgd::body
