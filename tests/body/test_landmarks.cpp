// Landmarks and measurements found on a body's surface, checked on vgd's
// mannequin, whose measurements are known: in the A-pose, the T-pose and with
// the arms swung forward, women's and men's sizes. Girths and heights within 1 cm; the
// arms found on both sides, along the mannequin's own arm axes, their elbows
// within 2.5 cm of its elbow joints and the knee within 1 cm; and MakeHuman's
// body, whose knees and elbows have no skeleton to come from.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "vgd/body/avatar_io.hpp"
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
    // The elbow where the girth profile bends: the mannequin's elbow joint is
    // 56 % of the way from the shoulder joint to the wrist.
    const Vec3 elbow = s->start + 0.56 * s->length * s->axis;
    std::printf("[ figures  ] %s elbow %.2f cm off\n", name, 100 * ((*arm)->elbow - elbow).norm());
    EXPECT_TRUE((*arm)->elbow_on_surface) << name;
    EXPECT_LT(((*arm)->elbow - elbow).norm(), 0.025) << name;
  }
  // The knee: the bump above the narrowing under it, at the mannequin's knee
  // joints' height.
  std::printf("[ figures  ] knee %+.2f cm\n", 100 * (l.knee - known.knee));
  EXPECT_NEAR(l.knee, known.knee, 0.01);
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

// MakeHuman's body in Debian's assimp-testmodels (a Collada export without a
// skeleton, arms in a T-pose bent at the elbows): knees and elbows from its
// surface alone. Its leg has no bump at the knee; the hollow behind it
// gives the knee. Bounds: knee heights of adults stand at 27–31 % of their
// height (mid-patella), elbows 50–65 % of the way from the shoulder joint to
// the wrist.
TEST(MeasuredImport, MakeHumansKneesAndElbowsAreFoundWithoutASkeleton) {
  const std::filesystem::path file = "/usr/share/assimp/models/Collada/human.zae";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " not installed (Debian package assimp-testmodels)";
  AvatarReport r;
  import_avatar(file, {}, &r);
  ASSERT_TRUE(r.measuring.has_value());
  const BodyLandmarks& l = r.measuring->landmarks;
  std::printf("[ figures  ] human.zae: knee %.1f cm of %.1f cm (%.1f %%)\n", 100 * l.knee, 100 * l.height,
              100 * l.knee / l.height);
  EXPECT_GT(l.knee, 0.27 * l.height);
  EXPECT_LT(l.knee, 0.31 * l.height);
  for (const auto* arm : {&l.left_arm, &l.right_arm}) {
    ASSERT_TRUE(arm->has_value());
    const auto& a = **arm;
    const double u = (a.elbow - a.shoulder).norm() / (a.wrist - a.shoulder).norm();
    std::printf("[ figures  ] human.zae: elbow %.0f %% of the way to the wrist\n", 100 * u);
    EXPECT_TRUE(a.elbow_on_surface);
    EXPECT_GT(u, 0.50);
    EXPECT_LT(u, 0.65);
  }
}

}  // namespace
}  // namespace vgd::body
