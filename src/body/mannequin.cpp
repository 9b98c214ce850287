// The parametric mannequin (mannequin.hpp, docs/avatar.md).
//
// Why a signed-distance function and not a template mesh: every measurement
// moves a closed-form shape, the union of parts is smooth and closed by
// construction, and the surface mesher (CGAL Mesh_3, manifold criterion) gives
// a watertight mesh with near-equilateral triangles and resolves the narrow
// gaps (armpits, crotch) adaptively through its facet-distance bound.
#include "vgd/body/mannequin.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/mesh/implicit_surface.hpp"
#include "mannequin_cache.hpp"

namespace vgd::body {

namespace {

constexpr double kPi = std::numbers::pi;

// ---- primitives (Inigo Quilez's distance functions) ------------------------

// Polynomial smooth minimum: C1, equals min(a, b) once |a − b| ≥ k.
double smin(double a, double b, double k) {
  const double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::min(a, b) - h * h * k * 0.25;
}

// Tapered capsule from a (radius ra) to b (radius rb); exact distance.
double round_cone(const Vec3& p, const Vec3& a, const Vec3& b, double ra, double rb) {
  const Vec3 ba = b - a;
  const double l2 = ba.dot(ba), rr = ra - rb, a2 = l2 - rr * rr, il2 = 1.0 / l2;
  const Vec3 pa = p - a;
  const double y = pa.dot(ba), z = y - l2;
  const double x2 = (pa * l2 - ba * y).squaredNorm(), y2 = y * y * l2, z2 = z * z * l2;
  const double k = (rr > 0 ? 1.0 : rr < 0 ? -1.0 : 0.0) * rr * rr * x2;
  if ((z > 0 ? 1.0 : z < 0 ? -1.0 : 0.0) * a2 * z2 > k) return std::sqrt(x2 + z2) * il2 - rb;
  if ((y > 0 ? 1.0 : y < 0 ? -1.0 : 0.0) * a2 * y2 < k) return std::sqrt(x2 + y2) * il2 - ra;
  return (std::sqrt(x2 * a2 * il2) + y * rr) * il2 - ra;
}

// Ellipsoid with semi-axes r in the frame (u, v, w) around c; first-order distance
// (exact zero set, distance-like near it).
double ellipsoid(const Vec3& p, const Vec3& c, const Vec3& r, const Vec3& u, const Vec3& v, const Vec3& w) {
  const Vec3 d = p - c;
  const Vec3 q(d.dot(u), d.dot(v), d.dot(w));
  const double k0 = q.cwiseQuotient(r).norm();
  const double k1 = q.cwiseQuotient(r.cwiseProduct(r)).norm();
  if (k1 < 1e-12) return -r.minCoeff();
  return k0 * (k0 - 1.0) / k1;
}

// 2-D ellipse, same first-order distance.
double ellipse(double x, double z, double a, double b) {
  const double k0 = std::hypot(x / a, z / b);
  const double k1 = std::hypot(x / (a * a), z / (b * b));
  if (k1 < 1e-12) return -std::min(a, b);
  return k0 * (k0 - 1.0) / k1;
}

// Ramanujan's second approximation of an ellipse's perimeter (error < 1e-9 relative here).
double ellipse_perimeter(double a, double b) {
  const double h = std::pow((a - b) / (a + b), 2);
  return kPi * (a + b) * (1.0 + 3.0 * h / (10.0 + std::sqrt(4.0 - 3.0 * h)));
}

// Monotone cubic (Fritsch–Carlson) through (x_i, y_i): no overshoot between
// keyframes, so a girth never bulges past its neighbours.
class MonotoneCubic {
 public:
  MonotoneCubic() = default;
  MonotoneCubic(std::vector<double> x, std::vector<double> y) : x_(std::move(x)), y_(std::move(y)) {
    const std::size_t n = x_.size();
    m_.assign(n, 0.0);
    std::vector<double> d(n - 1);
    for (std::size_t i = 0; i + 1 < n; ++i) d[i] = (y_[i + 1] - y_[i]) / (x_[i + 1] - x_[i]);
    m_[0] = d[0], m_[n - 1] = d[n - 2];
    for (std::size_t i = 1; i + 1 < n; ++i) m_[i] = d[i - 1] * d[i] <= 0 ? 0.0 : 0.5 * (d[i - 1] + d[i]);
    for (std::size_t i = 0; i + 1 < n; ++i) {
      if (d[i] == 0) {
        m_[i] = m_[i + 1] = 0;
        continue;
      }
      const double a = m_[i] / d[i], b = m_[i + 1] / d[i], s = a * a + b * b;
      if (s > 9) m_[i] = 3 * a / std::sqrt(s) * d[i], m_[i + 1] = 3 * b / std::sqrt(s) * d[i];
    }
  }
  double operator()(double x) const {
    if (x <= x_.front()) return y_.front();
    if (x >= x_.back()) return y_.back();
    const std::size_t i = static_cast<std::size_t>(std::upper_bound(x_.begin(), x_.end(), x) - x_.begin()) - 1;
    const double h = x_[i + 1] - x_[i], t = (x - x_[i]) / h, t2 = t * t, t3 = t2 * t;
    return (2 * t3 - 3 * t2 + 1) * y_[i] + (t3 - 2 * t2 + t) * h * m_[i] + (-2 * t3 + 3 * t2) * y_[i + 1] +
           (t3 - t2) * h * m_[i + 1];
  }

 private:
  std::vector<double> x_, y_, m_;
};

bool is_male(const BodyMeasurements& m) { return iequals(m.sex, "male"); }

// Least gap between upper arm and flank below the bust, m: wide enough for the
// surface mesher to keep them apart and for a sleeve to pass.
constexpr double kArmClearance = 0.02;

}  // namespace

// ---- the body ---------------------------------------------------------------

struct MannequinFunction {
  BodyMeasurements m;
  MannequinOptions opt;
  MannequinLandmarks lm;
  // Trunk loft keyframes: height, half-width, half-depth, centre z.
  std::vector<double> ky, ka, kb, kz;
  MonotoneCubic a_of_y, b_of_y, z_of_y;
  double trunk_bottom = 0, trunk_top = 0;
  // Limbs: per side (0 left +X, 1 right −X).
  Vec3 shoulder_joint[2], elbow[2], wrist[2], hip_joint[2], knee[2], ankle[2];
  double r_upper_arm = 0, r_elbow = 0, r_wrist = 0, r_thigh = 0, r_knee = 0, r_calf = 0, r_ankle = 0;
  Vec3 hand_c[2], hand_u[2], hand_v[2], hand_r = Vec3::Zero();
  Vec3 foot_c[2], foot_r = Vec3::Zero();
  Vec3 neck_a = Vec3::Zero(), neck_b = Vec3::Zero();
  double r_neck_base = 0, r_neck_top = 0;
  Vec3 head_c = Vec3::Zero(), head_r = Vec3::Zero();
  // Calibration: girth scale per keyframe, crotch cap and shoulder joint shifts (m).
  std::vector<double> scale;
  double crotch_offset = 0.0, shoulder_offset = 0.0;

  // A lower bound on a limb's value anywhere (its capsules' distance and its
  // ellipsoid's first-order distance, less the blends' dips): a limb whose
  // bound is past the blend with what is already there leaves the body's
  // value unchanged, bit for bit, and is not evaluated.
  struct LimbBound {
    Vec3 c = Vec3::Zero();  // centre of the capsules' enclosing sphere
    double caps = 0.0;      // its radius (capsule radii included)
    Vec3 e = Vec3::Zero();  // the ellipsoid's centre
    double e_max = 0.0, e_min = 0.0;  // its largest and smallest semi-axes
    double dip = 0.0;       // the limb's smooth minima dip at most this far below their parts
    double lower(const Vec3& p) const;
  };
  LimbBound arm_bound[2], leg_bound[2], head_bound;  // the head: the neck's cone and the head's ellipsoid

  void build();
  void bound_limbs();
  double trunk(const Vec3& p) const;
  double arm(const Vec3& p, int side) const;
  double arm_clearance(double th) const;
  double arm_angle = 0.0, shoulder_joint_x = 0.0;  // rad, m
  double leg(const Vec3& p, int side) const;
  Vec3 calf(int s) const { return knee[s] + 0.35 * (ankle[s] - knee[s]); }  // the calf's fullest girth
  double operator()(const Vec3& p) const;
  // every_part: evaluate every part, none skipped by its bound (the
  // definition the skipping must equal bit for bit; tests).
  double body(const Vec3& p, bool with_arms, bool every_part = false) const;
  double girth_at(double y) const;
  double crotch_height() const;
  double half_width_at(double y) const;
  void calibrate();
};

namespace {

// Keyframe indices of the trunk loft (see build()).
enum Key { kCrotch, kHip, kWaist, kUnderBust, kBust, kArmpit, kShoulder, kNeckBase, kKeys };

}  // namespace

MannequinLandmarks mannequin_landmarks(const BodyMeasurements& m) {
  const double H = m.height;
  const bool male = is_male(m);
  MannequinLandmarks l;
  l.height = H;
  l.chin = 0.870 * H;
  l.shoulder = 0.818 * H;
  l.neck_base = l.shoulder + 0.030 * H;
  l.bust = (male ? 0.722 : 0.715) * H;
  l.under_bust = male ? l.bust - 0.03 * H : 0.685 * H;
  l.waist = (male ? 0.605 : 0.625) * H;
  l.crotch = m.inseam;
  // The fullest hip sits about 5 % of the height above the crotch (never above
  // half-way to the waist, for short-waisted inputs).
  l.hip = std::min(std::max((male ? 0.490 : 0.500) * H, l.crotch + 0.035 * H), 0.5 * (l.crotch + l.waist));
  l.knee = 0.285 * H;
  l.ankle = 0.045 * H;
  const double r_upper_arm = (male ? 0.33 : 0.32) * m.bust / (2 * kPi);
  l.shoulder_joint = l.shoulder - r_upper_arm;
  return l;
}

void check_measurements(const BodyMeasurements& m, const std::string& where) {
  const std::string entity = "body '" + m.label + "'";
  auto fail = [&](const std::string& msg) { throw Error(where, entity, msg); };
  const std::pair<const char*, double> fields[] = {
      {"height", m.height},   {"bust", m.bust},       {"under_bust", m.under_bust},
      {"waist", m.waist},     {"hip", m.hip},         {"shoulder_width", m.shoulder_width},
      {"neck", m.neck},       {"arm_length", m.arm_length}, {"inseam", m.inseam}};
  for (const auto& [name, v] : fields)
    if (!std::isfinite(v) || v <= 0) fail(std::string(name) + " must be a positive length in metres (got " + format_double(v) + ")");
  if (m.height < 1.0 || m.height > 2.3)
    fail("height " + format_fixed(m.height, 3) + " m is outside 1.0–2.3 m (give metres: 1.68, not 168)");
  if (!iequals(m.sex, "female") && !iequals(m.sex, "male")) fail("sex must be 'female' or 'male' (got '" + m.sex + "')");
  const double H = m.height;
  auto range = [&](const char* name, double v, double lo, double hi) {
    if (v < lo * H || v > hi * H)
      fail(std::string(name) + " " + format_fixed(v, 3) + " m is implausible for a height of " + format_fixed(H, 2) +
           " m (expected " + format_fixed(lo * H, 2) + "–" + format_fixed(hi * H, 2) + " m)");
  };
  range("bust", m.bust, 0.40, 0.90);
  range("under_bust", m.under_bust, 0.35, 0.90);
  range("waist", m.waist, 0.30, 0.90);
  range("hip", m.hip, 0.40, 0.90);
  range("shoulder_width", m.shoulder_width, 0.17, 0.32);
  range("neck", m.neck, 0.15, 0.30);
  range("arm_length", m.arm_length, 0.28, 0.42);
  range("inseam", m.inseam, 0.40, 0.52);
  if (m.under_bust > m.bust + 1e-9) fail("under_bust (" + format_fixed(m.under_bust, 3) + " m) exceeds bust (" + format_fixed(m.bust, 3) + " m)");
}

// Smallest horizontal gap (m) between the arm and the flank at the bust,
// under-bust and waist heights, for an arm at angle th (rad) from the vertical:
// where the slice of the arm (an ellipse of half-width r / cos th) comes
// closest to the trunk's half-width.
double MannequinFunction::arm_clearance(double th) const {
  double gap = 1e9;
  for (const double y : {lm.bust, lm.under_bust, lm.waist}) {
    const double s = (lm.shoulder_joint - y) / std::cos(th);
    if (s <= 0 || s > m.arm_length) continue;
    const double upper = 0.56 * m.arm_length;
    const double r = s < upper ? r_upper_arm + (r_elbow - r_upper_arm) * s / upper
                               : r_elbow + (r_wrist - r_elbow) * (s - upper) / (m.arm_length - upper);
    gap = std::min(gap, shoulder_joint_x + s * std::sin(th) - r / std::cos(th) - a_of_y(y));
  }
  return gap;
}

void MannequinFunction::build() {
  const double H = m.height;
  const bool male = is_male(m);
  lm = mannequin_landmarks(m);
  if (scale.empty()) scale.assign(kKeys, 1.0);

  // Trunk cross-sections: depth/width ratios of typical adult bodies; the bust
  // keyframe sits forward by half the bust/under-bust depth difference so the
  // back stays flat and the front carries the bust.
  // Larger busts are rounder (deeper for their width), which also keeps the chest
  // inside the shoulders so the arms can hang clear of it.
  const double q_hip = male ? 0.72 : 0.70, q_waist = male ? 0.78 : 0.74, q_ub = male ? 0.72 : 0.72,
               q_bust = male ? 0.75 : std::clamp(0.80 + 0.25 * (m.bust - 0.88) / 0.30, 0.75, 0.95);
  auto half_width = [](double girth, double q) { return girth / ellipse_perimeter(1.0, q); };
  const double a_hip = half_width(m.hip, q_hip) * scale[kHip], a_waist = half_width(m.waist, q_waist) * scale[kWaist];
  const double a_ub = half_width(m.under_bust, q_ub) * scale[kUnderBust], a_bust = half_width(m.bust, q_bust) * scale[kBust];
  r_upper_arm = (male ? 0.33 : 0.32) * m.bust / (2 * kPi);
  r_neck_base = m.neck / (2 * kPi);
  const double shoulder_half = 0.5 * m.shoulder_width;
  const double x_joint = shoulder_half - r_upper_arm + shoulder_offset;
  const double b_bust = q_bust * a_bust, b_ub = q_ub * a_ub;
  r_elbow = (male ? 0.27 : 0.26) * m.bust / (2 * kPi);
  r_wrist = (male ? 0.17 : 0.175) * m.bust / (2 * kPi);
  shoulder_joint_x = x_joint;
  ky = {lm.crotch, lm.hip, lm.waist, lm.under_bust, lm.bust, 0.5 * (lm.bust + lm.shoulder_joint) + 0.01 * H, lm.shoulder,
        lm.neck_base};
  ka = {0.90 * a_hip * scale[kCrotch], a_hip, a_waist, a_ub, a_bust, 0.93 * a_bust,
        std::max(x_joint - 0.2 * r_upper_arm, 1.2 * r_neck_base), 1.25 * r_neck_base};
  kb = {0.86 * q_hip * a_hip * scale[kCrotch], q_hip * a_hip, q_waist * a_waist, b_ub, b_bust, 0.85 * b_bust,
        0.62 * b_bust, 1.15 * r_neck_base};
  const double front = male ? 0.0 : 0.5 * (b_bust - b_ub);
  kz = {-0.01 * H, -0.012 * H, 0.0, 0.0, front, 0.0, -0.01 * H, -0.012 * H};
  if (male) ky[kUnderBust] = 0.5 * (lm.waist + lm.bust);  // no under-bust landmark: an in-between keyframe
  a_of_y = MonotoneCubic(ky, ka);
  b_of_y = MonotoneCubic(ky, kb);
  z_of_y = MonotoneCubic(ky, kz);
  trunk_bottom = lm.crotch + crotch_offset;
  trunk_top = lm.neck_base;

  arm_angle = opt.arm_angle_deg * kPi / 180.0;
  while (arm_angle < 50.0 * kPi / 180.0 && arm_clearance(arm_angle) < kArmClearance) arm_angle += 0.5 * kPi / 180.0;

  // Neck and head.
  r_neck_top = 0.88 * r_neck_base;
  neck_a = Vec3(0, lm.shoulder - 0.01 * H, -0.012 * H);
  neck_b = Vec3(0, lm.chin + 0.01 * H, -0.008 * H);
  head_r = Vec3(0.046 * H, 0.5 * (H - lm.chin) + 0.004 * H, 0.058 * H);
  head_c = Vec3(0, H - head_r.y(), 0.004 * H);

  // Arms in an A-pose, in the frontal plane; forearm 44 % of the arm length.
  // The angle is the option's, opened further (up to 45°) when a broad chest
  // would otherwise touch the upper arm (up to 50°): a tape and a sleeve need the arm clear
  // of the flank below the armpit (arm_clearance()).
  const double th = arm_angle;
  for (int s = 0; s < 2; ++s) {
    const double sx = s == 0 ? 1.0 : -1.0;
    // Raised forward by fw about the shoulder's x axis (0: in the frontal plane).
    const double fw = opt.arm_forward_deg * kPi / 180.0;
    const Vec3 dir(sx * std::sin(th), -std::cos(th) * std::cos(fw), std::cos(th) * std::sin(fw));
    shoulder_joint[s] = Vec3(sx * x_joint, lm.shoulder_joint, 0.0);
    elbow[s] = shoulder_joint[s] + 0.56 * m.arm_length * dir;
    wrist[s] = shoulder_joint[s] + m.arm_length * dir;
    hand_u[s] = dir;
    // Across the hand's width: in the frontal plane when the arm is, turned forward with it.
    hand_v[s] = Vec3(std::cos(th), sx * std::sin(th) * std::cos(fw), -sx * std::sin(th) * std::sin(fw));
    hand_c[s] = wrist[s] + 0.050 * H * dir;
  }
  hand_r = Vec3(0.058 * H, 0.015 * H, 0.026 * H);

  // Legs: thighs ~52 % (women) / 50 % (men) of the hip girth at the crotch,
  // spread so the thighs clear each other by 2.4 cm and the feet stand apart.
  r_thigh = (male ? 0.50 : 0.52) * m.hip / (2 * kPi);
  r_knee = 0.37 * m.hip / (2 * kPi) * (male ? 1.0 : 0.97);
  r_calf = 0.36 * m.hip / (2 * kPi);
  r_ankle = 0.22 * m.hip / (2 * kPi);
  for (int s = 0; s < 2; ++s) {
    const double sx = s == 0 ? 1.0 : -1.0;
    const double x_top = r_thigh + 0.012;
    hip_joint[s] = Vec3(sx * x_top, lm.crotch + 0.6 * r_thigh, -0.004 * H);
    knee[s] = Vec3(sx * (x_top + 0.008 * H), lm.knee, 0.0);
    ankle[s] = Vec3(sx * (x_top + 0.014 * H), lm.ankle, -0.006 * H);
    foot_c[s] = Vec3(sx * (x_top + 0.016 * H), 0.018 * H, 0.032 * H);
  }
  foot_r = Vec3(0.024 * H, 0.032 * H, 0.078 * H);
  bound_limbs();
}

// Capsule (segment ab, radius r): its distance from p is at least |p − c|
// less the farthest point of the capsule from c; a round cone lies inside
// the capsule of its larger radius, so its exact distance is at least that.
// The first-order ellipsoid distance k0 (k0 − 1) / k1 of ellipsoid() is at
// least (k0 − 1) r_min ≥ (|p − e| / r_max − 1) r_min outside (k1 ≤ k0 / r_min,
// k0 ≥ |q| / r_max, the frame orthonormal). smin(a, b, k) ≥ min(a, b) − k/4.
double MannequinFunction::LimbBound::lower(const Vec3& p) const {
  const double dc = (p - c).norm() - caps;
  const double de = (p - e).norm();
  const double ell = de > e_max ? (de / e_max - 1.0) * e_min : -e_max;
  return std::min(dc, ell) - dip;
}

void MannequinFunction::bound_limbs() {
  auto capsules = [](LimbBound& b, std::initializer_list<std::pair<Vec3, double>> balls) {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const auto& [x, r] : balls) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
    b.c = 0.5 * (lo + hi);
    b.caps = 0.0;
    for (const auto& [x, r] : balls) b.caps = std::max(b.caps, (x - b.c).norm() + r);
  };
  capsules(head_bound, {{neck_a, std::max(r_neck_base, r_neck_top)}, {neck_b, std::max(r_neck_base, r_neck_top)}});
  head_bound.e = head_c;
  head_bound.e_max = head_r.maxCoeff();
  head_bound.e_min = head_r.minCoeff();
  head_bound.dip = 0.25 * 0.03;
  for (int s = 0; s < 2; ++s) {
    LimbBound& a = arm_bound[s];
    capsules(a, {{shoulder_joint[s], r_upper_arm}, {elbow[s], std::max(r_upper_arm, r_elbow)},
                 {wrist[s], std::max(r_elbow, r_wrist)}});
    a.e = hand_c[s];
    a.e_max = hand_r.maxCoeff();
    a.e_min = hand_r.minCoeff();
    a.dip = 0.25 * (0.01 + 0.02);
    LimbBound& l = leg_bound[s];
    const double r_shank = std::max({r_knee, r_calf, r_ankle});
    capsules(l, {{hip_joint[s], std::max(r_thigh, r_knee)}, {knee[s], std::max(r_thigh, r_shank)},
                 {calf(s), r_shank}, {ankle[s], r_shank}});
    l.e = foot_c[s];
    l.e_max = foot_r.maxCoeff();
    l.e_min = foot_r.minCoeff();
    l.dip = 0.25 * (0.02 + 0.02 + 0.03);
  }
}

double MannequinFunction::trunk(const Vec3& p) const {
  const double y = std::clamp(p.y(), ky.front(), ky.back());
  const double d2 = ellipse(p.x(), p.z() - z_of_y(y), a_of_y(y), b_of_y(y));
  const double dv = std::max(trunk_bottom - p.y(), p.y() - trunk_top);
  // Extrusion of the 2-D section between the caps (exact for a prism).
  return std::min(std::max(d2, dv), 0.0) + std::hypot(std::max(d2, 0.0), std::max(dv, 0.0));
}

double MannequinFunction::arm(const Vec3& p, int s) const {
  const double upper = round_cone(p, shoulder_joint[s], elbow[s], r_upper_arm, r_elbow);
  const double fore = round_cone(p, elbow[s], wrist[s], r_elbow, r_wrist);
  const double hand = ellipsoid(p, hand_c[s], hand_r, hand_u[s], hand_v[s], hand_u[s].cross(hand_v[s]).normalized());
  return smin(smin(upper, fore, 0.01), hand, 0.02);
}

double MannequinFunction::leg(const Vec3& p, int s) const {
  const Vec3 calf = this->calf(s);
  const double thigh = round_cone(p, hip_joint[s], knee[s], r_thigh, r_knee);
  const double shank = smin(round_cone(p, knee[s], calf, r_knee, r_calf), round_cone(p, calf, ankle[s], r_calf, r_ankle), 0.02);
  const double foot = ellipsoid(p, foot_c[s], foot_r, Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ());
  return smin(smin(thigh, shank, 0.02), foot, 0.03);
}

double MannequinFunction::operator()(const Vec3& p) const { return body(p, true); }

double MannequinFunction::body(const Vec3& p, bool with_arms, bool every_part) const {
  // Each limb is blended into the trunk, never into its twin (the thighs and the
  // arm and the flank stay apart); the floor cuts the soles flat.
  double d = trunk(p);
  // A part (the neck with the head, each limb) whose lower bound is past its
  // blend with d leaves smin(d, ·) equal to d, bit for bit (h = 0): it is not
  // evaluated (1 µm of margin for the rounding of the bound).
  constexpr double kRounding = 1e-6;
  if (every_part || head_bound.lower(p) < d + 0.03 + kRounding) {
    const double neck = round_cone(p, neck_a, neck_b, r_neck_base, r_neck_top);
    const double head = ellipsoid(p, head_c, head_r, Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ());
    d = smin(d, smin(neck, head, 0.03), 0.03);
  }
  // A limb skipped beside the other side's: min(l0, l1) blends to d
  // whenever the skipped one is past it, so the blend is the other's.
  auto limbs = [&](const LimbBound* bound, double k, auto&& limb) {
    double v = std::numeric_limits<double>::infinity();
    for (int s = 0; s < 2; ++s)
      if (every_part || bound[s].lower(p) < d + k + kRounding) v = std::min(v, limb(s));
    return std::isinf(v) ? d : smin(d, v, k);
  };
  d = limbs(leg_bound, 0.03, [&](int s) { return leg(p, s); });
  if (with_arms) d = limbs(arm_bound, 0.015, [&](int s) { return arm(p, s); });
  return std::max(d, -p.y());
}

// First exit from the trunk along a ray in the horizontal plane y from its
// centre line: sphere tracing, then bisection. The arms are left out: a tape
// passes under them.
static double exit_distance(const MannequinFunction& f, double y, double z0, double angle, double r_max) {
  const Vec3 dir(std::cos(angle), 0.0, std::sin(angle));
  const Vec3 o(0.0, y, z0);
  double t = 0.0;
  while (t < r_max) {
    const double v = f.body(o + t * dir, false);
    if (v > 0) break;
    t += std::max(-v * 0.9, 5e-4);
  }
  double lo = std::max(0.0, t - 0.02), hi = t;
  // lo may be outside if the step overshot a thin wall; walk back to an inside point.
  while (lo > 0 && f.body(o + lo * dir, false) > 0) lo = std::max(0.0, lo - 0.01);
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f.body(o + mid * dir, false) > 0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

double MannequinFunction::girth_at(double y) const {
  const double z0 = z_of_y(std::clamp(y, ky.front(), ky.back()));
  std::vector<mesh::Vec2d> pts;
  const int n = 360;
  for (int i = 0; i < n; ++i) {
    const double ang = 2 * kPi * i / n;
    const double r = exit_distance(*this, y, z0, ang, 1.0);
    pts.emplace_back(r * std::cos(ang), z0 + r * std::sin(ang));
  }
  return mesh::convex_hull_perimeter(pts);
}

double MannequinFunction::crotch_height() const {
  // Up from the floor between the legs until the body is met.
  const double z0 = z_of_y(lm.crotch);
  double lo = 0.0, hi = lm.hip;
  // The first inside point along the vertical line x = 0.
  double y = 0.001;
  while (y < hi && (*this)(Vec3(0, y, z0)) > 0) y += std::max((*this)(Vec3(0, y, z0)) * 0.9, 2e-4);
  hi = y, lo = std::max(0.0, y - 0.01);
  while (lo > 0 && (*this)(Vec3(0, lo, z0)) <= 0) lo = std::max(0.0, lo - 0.01);
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo + hi);
    ((*this)(Vec3(0, mid, z0)) > 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double MannequinFunction::half_width_at(double y) const {
  // Largest x of the body at height y (the outside of the left arm at the joint).
  double best = 0.0;
  for (int k = -10; k <= 10; ++k) {
    const double z = 0.004 * k;
    double lo = 0.0, hi = 1.5;
    if ((*this)(Vec3(lo, y, z)) > 0) {
      // Not inside at the centre line: march in from outside instead.
      double x = hi;
      while (x > 0 && (*this)(Vec3(x, y, z)) > 0) x -= std::max((*this)(Vec3(x, y, z)) * 0.9, 2e-4);
      if (x <= 0) continue;
      lo = x;
    } else {
      double x = hi;
      while (x > 0 && (*this)(Vec3(x, y, z)) > 0) x -= std::max((*this)(Vec3(x, y, z)) * 0.9, 2e-4);
      lo = x;
    }
    hi = lo + 0.01;
    for (int i = 0; i < 40; ++i) {
      const double mid = 0.5 * (lo + hi);
      ((*this)(Vec3(mid, y, z)) > 0 ? hi : lo) = mid;
    }
    best = std::max(best, 0.5 * (lo + hi));
  }
  return best;
}

void MannequinFunction::calibrate() {
  // Fixed-point iteration: scale each girth keyframe by wanted / measured, move
  // the crotch cap by the inseam error and the shoulder joints by half the
  // shoulder-width error. The parts barely interact, so a few rounds suffice.
  scale.assign(kKeys, 1.0);
  build();
  const bool male = is_male(m);
  for (int it = 0; it < 6; ++it) {
    double worst = 0.0;
    auto fit = [&](Key k, double y, double wanted) {
      const double got = girth_at(y);
      worst = std::max(worst, std::abs(got / wanted - 1.0));
      scale[k] *= wanted / got;
    };
    fit(kBust, lm.bust, m.bust);
    if (!male) fit(kUnderBust, lm.under_bust, m.under_bust);
    fit(kWaist, lm.waist, m.waist);
    fit(kHip, lm.hip, m.hip);
    const double crotch = crotch_height();
    worst = std::max(worst, std::abs(crotch / m.inseam - 1.0));
    crotch_offset += m.inseam - crotch;
    const double half = half_width_at(lm.shoulder_joint);
    worst = std::max(worst, std::abs(2 * half / m.shoulder_width - 1.0));
    shoulder_offset += 0.5 * m.shoulder_width - half;
    build();
    if (worst < 2e-4) break;
  }
}

MannequinSdf::MannequinSdf(const BodyMeasurements& m, const MannequinOptions& options)
    : f_(std::make_unique<MannequinFunction>()) {
  check_measurements(m);
  f_->m = m;
  f_->opt = options;
  if (options.calibrate && (options.arm_angle_deg > 50.0 || options.arm_forward_deg != 0.0)) {
    // Raised or forward arms (a T-pose) would be measured as the shoulder
    // width: the girths and shoulders are calibrated in the A-pose, then the
    // arms raised.
    f_->opt.arm_angle_deg = 45.0;
    f_->opt.arm_forward_deg = 0.0;
    f_->calibrate();
    f_->opt.arm_angle_deg = options.arm_angle_deg;
    f_->opt.arm_forward_deg = options.arm_forward_deg;
    f_->build();
  } else if (options.calibrate) {
    f_->calibrate();
  } else {
    f_->build();
  }
}
MannequinSdf::~MannequinSdf() = default;
MannequinSdf::MannequinSdf(MannequinSdf&&) noexcept = default;
MannequinSdf& MannequinSdf::operator=(MannequinSdf&&) noexcept = default;
double MannequinSdf::operator()(const Vec3& p) const { return (*f_)(p); }
double MannequinSdf::every_part(const Vec3& p) const { return f_->body(p, true, true); }
const MannequinLandmarks& MannequinSdf::landmarks() const { return f_->lm; }
double MannequinSdf::girth_at(double y) const { return f_->girth_at(y); }

// ---- segments ---------------------------------------------------------------

namespace {

BodySegment trunk_segment(const MannequinFunction& f, const std::string& name, double y0, double y1, int rings) {
  BodySegment s;
  s.name = name;
  s.start = Vec3(0, y0, f.z_of_y(y0));
  s.axis = Vec3::UnitY();
  s.front = Vec3::UnitZ();
  s.length = y1 - y0;
  for (int i = 0; i <= rings; ++i) {
    const double y = y0 + (y1 - y0) * i / rings;
    SegmentRing r;
    r.s = y - y0;
    r.centre = Vec3(0, y, f.z_of_y(y));
    r.half_width = f.a_of_y(y);
    r.half_depth = f.b_of_y(y);
    s.rings.push_back(r);
  }
  return s;
}

// A limb made of tapered capsules: circular rings along the polyline joints.
BodySegment limb_segment(const std::string& name, const std::vector<Vec3>& joints, const std::vector<double>& radii,
                         int rings) {
  BodySegment s;
  s.name = name;
  s.start = joints.front();
  s.axis = (joints.back() - joints.front()).normalized();
  s.front = (Vec3::UnitZ() - Vec3::UnitZ().dot(s.axis) * s.axis).normalized();
  std::vector<double> cum{0.0};
  for (std::size_t i = 1; i < joints.size(); ++i) cum.push_back(cum.back() + (joints[i] - joints[i - 1]).norm());
  s.length = cum.back();
  for (int i = 0; i <= rings; ++i) {
    const double t = s.length * i / rings;
    std::size_t k = 0;
    while (k + 2 < joints.size() && cum[k + 1] < t) ++k;
    const double u = std::clamp((t - cum[k]) / (cum[k + 1] - cum[k]), 0.0, 1.0);
    SegmentRing r;
    r.s = t;
    r.centre = joints[k] + u * (joints[k + 1] - joints[k]);
    r.half_width = r.half_depth = radii[k] + u * (radii[k + 1] - radii[k]);
    s.rings.push_back(r);
  }
  return s;
}

// Distance from p to a segment's surface, approximated by its rings.
double segment_distance(const BodySegment& s, const Vec3& p) {
  const double t = std::clamp((p - s.start).dot(s.axis), 0.0, s.length);
  const SegmentRing r = ring_at(s, t);
  const Vec3 d = p - r.centre;
  const Vec3 side = s.side();
  const double along = (p - s.start).dot(s.axis);
  const double beyond = along < 0 ? -along : along > s.length ? along - s.length : 0.0;
  const double x = d.dot(side), z = d.dot(s.front);
  return std::hypot(std::abs(ellipse(x, z, std::max(r.half_width, 1e-4), std::max(r.half_depth, 1e-4))), beyond);
}

}  // namespace

Avatar make_mannequin(const BodyMeasurements& m, const MannequinOptions& options) {
  const MannequinSdf sdf(m, options);
  const MannequinFunction& f = sdf.function();
  const double H = m.height;

  // Facet size from the triangle target: N ≈ c · area / size², c measured on
  // this mesher with facet distance = size / 8 (docs/avatar.md); a result more
  // than 20 % off the target is meshed once more with the corrected size.
  const int target = std::clamp(options.target_triangles, 5000, 20000);
  const double area_estimate = 1.05 * H * (m.bust + m.waist + m.hip) / 3.0 + 0.2 * H * H * 0.2;
  constexpr double kTrianglesPerArea = 1.5;  // N · size² / area
  double size = options.facet_size > 0 ? options.facet_size : std::sqrt(kTrianglesPerArea * area_estimate / target);
  mesh::Box3 box;
  box.extend(Vec3(-0.8 * H, -0.01, -0.3 * H));
  box.extend(Vec3(0.8 * H, 1.01 * H, 0.3 * H));
  std::vector<Vec3> inside;
  for (int s = 0; s < 2; ++s) {
    inside.push_back(f.wrist[s]);
    inside.push_back(f.hand_c[s]);
    inside.push_back(f.ankle[s]);
    inside.push_back(f.foot_c[s]);
    inside.push_back(f.elbow[s]);
  }
  inside.push_back(f.head_c);
  inside.push_back(Vec3(0, f.lm.waist, 0));
  auto run = [&](double facet_size) {
    mesh::ImplicitSurfaceCriteria c;
    c.facet_size = facet_size;
    c.facet_distance = options.facet_distance > 0 ? options.facet_distance : 0.125 * facet_size;
    c.angle_deg = 25.0;
    return mesh::mesh_implicit_surface([&f](const Vec3& p) { return f(p); }, box, c, inside);
  };
  // Meshing is most of a mannequin's time: a surface meshed before for the
  // same measurements and options comes from the cache (mannequin_cache.hpp).
  const std::string key = options.cache ? detail::mannequin_cache_key(m, options) : std::string();
  std::optional<mesh::SurfaceMesh> cached = detail::read_cached_surface(key);
  mesh::SurfaceMesh surface;
  if (cached) {
    surface = std::move(*cached);
  } else {
    surface = run(size);
    if (options.facet_size <= 0) {
      const double ratio = static_cast<double>(surface.num_triangles()) / target;
      if (ratio < 0.8 || ratio > 1.2) surface = run(size * std::sqrt(ratio));
    }
    detail::count_meshing();
    detail::write_cached_surface(key, surface);
  }
  // Feet on the floor and centred on the Y axis (bounding box centre).
  const mesh::Box3 b = mesh::bounding_box(surface);
  const Vec3 shift(-b.centre().x(), -b.min.y(), -b.centre().z());
  mesh::translate(surface, shift);

  Avatar av;
  av.source = "mannequin " + m.label;
  av.measurements = m;
  av.surface = std::move(surface);
  auto moved = [&](BodySegment s) {
    s.start += shift;
    for (auto& r : s.rings) r.centre += shift;
    return s;
  };
  const auto& lm = f.lm;
  av.segments.push_back(moved(limb_segment("neck", {Vec3(0, lm.neck_base, f.neck_a.z()), f.neck_b},
                                           {f.r_neck_base, f.r_neck_top}, 6)));
  av.segments.push_back(moved(trunk_segment(f, "torso", lm.waist, lm.shoulder, 16)));
  av.segments.push_back(moved(trunk_segment(f, "hips", lm.crotch, lm.waist, 12)));
  av.segments.push_back(moved(limb_segment("left-arm", {f.shoulder_joint[0], f.elbow[0], f.wrist[0]},
                                           {f.r_upper_arm, f.r_elbow, f.r_wrist}, 12)));
  av.segments.push_back(moved(limb_segment("right-arm", {f.shoulder_joint[1], f.elbow[1], f.wrist[1]},
                                           {f.r_upper_arm, f.r_elbow, f.r_wrist}, 12)));
  for (int s = 0; s < 2; ++s)
    av.segments.push_back(moved(limb_segment(s == 0 ? "left-leg" : "right-leg",
                                             {f.hip_joint[s], f.knee[s], f.calf(s), f.ankle[s]},
                                             {f.r_thigh, f.r_knee, f.r_calf, f.r_ankle}, 16)));

  // Nearest segment per triangle; head, hands and feet beyond 6 cm stay −1.
  av.triangle_segment.resize(av.surface.triangles.size(), -1);
  for (std::size_t t = 0; t < av.surface.triangles.size(); ++t) {
    const auto& tri = av.surface.triangles[t];
    const Vec3 c = (av.surface.vertices[tri[0]] + av.surface.vertices[tri[1]] + av.surface.vertices[tri[2]]) / 3.0;
    double best = 0.06;
    for (std::size_t s = 0; s < av.segments.size(); ++s)
      if (const double d = segment_distance(av.segments[s], c); d < best) best = d, av.triangle_segment[t] = static_cast<int>(s);
  }
  return av;
}

}  // namespace vgd::body
