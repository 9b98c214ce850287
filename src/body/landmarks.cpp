// Landmarks and measurements found on a body's surface (landmarks.hpp).
#include "vgd/body/landmarks.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include <Eigen/Geometry>

#include "vgd/core/strings.hpp"

namespace vgd::body {

namespace {

using mesh::Vec2d;
using Loop = std::vector<Vec2d>;
constexpr double kPi = 3.14159265358979323846;

Vec2d loop_centroid(const Loop& l) {
  Vec2d c = Vec2d::Zero();
  for (const auto& p : l) c += p;
  return c / static_cast<double>(std::max<std::size_t>(l.size(), 1));
}

using mesh::loop_area;

// The loop of the slice at y that encloses the trunk's centre line (x, z) =
// centre, or nullptr. Slices are kept by height (to 1 µm): the chest's
// passes look at the same heights.
struct Slices {
  const mesh::SurfaceMesh& m;
  Vec2d centre;
  std::map<long long, std::vector<Loop>> cache;
  const Loop* central(double y) {
    auto [it, fresh] = cache.try_emplace(std::llround(y * 1e6));
    if (fresh) it->second = mesh::slice_horizontal(m, y);
    // The outermost such loop: a model's inner shells (a mouth, a proxy
    // under the skin) may enclose the centre line too.
    const Loop* best = nullptr;
    double best_area = 0;
    for (const auto& l : it->second)
      if (l.size() > 2 && mesh::point_in_polygon(l, centre))
        if (const double a = loop_area(l); a > best_area) best_area = a, best = &l;
    return best;
  }
};

double half_width(const Loop& l, double cx) {
  double w = 0;
  for (const auto& p : l) w = std::max(w, std::abs(p.x() - cx));
  return w;
}

// The girth of a trunk slice without the arms that touch it: an arm hanging
// against the flank makes a lobe at each side of the loop, joined to the
// trunk by a waist where the loop's depth (its extent in z) has a local
// minimum. The loop is cut there, on each side where a lobe at least 1 cm
// deeper than the cut follows, and the girth is the convex hull of what lies
// between (with the cut's own two points).
// `kept_half`, when given, is the half-width (m) of what is kept.
double trunk_girth(const Loop& l, double cx, double* kept_half = nullptr) {
  if (kept_half) *kept_half = half_width(l, cx);
  if (l.size() < 3) return 0.0;
  double xmin = 1e300, xmax = -1e300;
  for (const auto& p : l) xmin = std::min(xmin, p.x()), xmax = std::max(xmax, p.x());
  const double step = 0.005;
  // Depth of the loop along the vertical line x = c: its crossings' z range.
  auto depth = [&](double c, double& zlo, double& zhi) {
    zlo = 1e300, zhi = -1e300;
    for (std::size_t i = 0; i < l.size(); ++i) {
      const Vec2d& a = l[i];
      const Vec2d& b = l[(i + 1) % l.size()];
      if ((a.x() - c) * (b.x() - c) > 0 || a.x() == b.x()) continue;
      const double z = a.y() + (b.y() - a.y()) * (c - a.x()) / (b.x() - a.x());
      zlo = std::min(zlo, z), zhi = std::max(zhi, z);
    }
    return zhi >= zlo ? zhi - zlo : 0.0;
  };
  auto cut = [&](int side) {  // the x where the loop is cut on this side, or its extreme
    const double end = side > 0 ? xmax : xmin;
    // Lobes are at the sides: the search starts half way out, past the
    // notches at the middle of a slice (the buttocks' cleft, the bust's).
    const double start = cx + 0.5 * (end - cx);
    double lo, hi;
    double min_depth = depth(start, lo, hi), min_c = start;
    for (double c = start; side > 0 ? c < end : c > end; c += side * step) {
      const double d = depth(c, lo, hi);
      if (d < min_depth) min_depth = d, min_c = c;
      else if (d > min_depth + 0.01) return min_c;  // a lobe beyond a waist: an arm
    }
    return end;
  };
  const double left = cut(1), right = cut(-1);
  if (left == xmax && right == xmin) return mesh::convex_hull_perimeter(l);
  if (kept_half) *kept_half = std::max(left - cx, cx - right);
  std::vector<Vec2d> kept;
  for (const auto& p : l)
    if (p.x() >= right && p.x() <= left) kept.push_back(p);
  for (const double c : {left, right}) {
    double lo, hi;
    if (depth(c, lo, hi) > 0) kept.emplace_back(c, lo), kept.emplace_back(c, hi);
  }
  return kept.size() >= 3 ? mesh::convex_hull_perimeter(kept) : mesh::convex_hull_perimeter(l);
}

// The thinnest or fullest central girth over heights [a, b] (m, step dy):
// {height, girth}, or {0, 0} when no slice there encloses the centre line.
std::pair<double, double> girth_extreme(Slices& s, double a, double b, double dy, bool fullest,
                                        double max_half_width = std::numeric_limits<double>::infinity()) {
  double best_y = 0, best = fullest ? 0.0 : std::numeric_limits<double>::infinity();
  for (double y = a; y <= b + 1e-12; y += dy) {
    const Loop* l = s.central(y);
    if (!l) continue;
    double kept = 0;
    const double g = trunk_girth(*l, s.centre.x(), &kept);
    if (kept > max_half_width) continue;
    if (fullest ? g > best : g < best) best = g, best_y = y;
  }
  if (best_y == 0) return {0.0, 0.0};
  return {best_y, best};
}

// A leg's thinnest slice over [a, b]: the largest loop left of the centre line
// (+X, the body's left); {height, girth}.
std::pair<double, double> leg_thinnest(const mesh::SurfaceMesh& m, double cx, double a, double b, double dy) {
  double best_y = 0, best = std::numeric_limits<double>::infinity();
  for (double y = a; y <= b + 1e-12; y += dy) {
    double area = 0, g = 0;
    for (const auto& l : mesh::slice_horizontal(m, y)) {
      if (l.size() < 3 || loop_centroid(l).x() <= cx) continue;
      if (const double ar = loop_area(l); ar > area) area = ar, g = mesh::convex_hull_perimeter(l);
    }
    if (area > 0 && g < best) best = g, best_y = y;
  }
  if (best_y == 0) return {0.0, 0.0};
  return {best_y, best};
}

// The triangles of `m` that reach into the band lo <= y <= hi (all vertices
// kept): slicing it there gives the loops slicing `m` does, at a fraction of
// the cost when the band is a limb's.
mesh::SurfaceMesh band(const mesh::SurfaceMesh& m, double lo, double hi) {
  mesh::SurfaceMesh out;
  out.vertices = m.vertices;
  for (const auto& t : m.triangles) {
    const double a = m.vertices[t[0]].y(), b = m.vertices[t[1]].y(), c = m.vertices[t[2]].y();
    if (std::max({a, b, c}) >= lo && std::min({a, b, c}) <= hi) out.triangles.push_back(t);
  }
  return out;
}

// Where a limb's girth profile bends most: the sample farthest from the
// chord between the profile's two ends (an arm whose forearm tapers to the
// wrist faster than the upper arm does). Samples are (position along the
// limb, girth), m, in order; refined between samples by a parabola through
// the farthest and its two neighbours. Returns the position, or nullopt when
// no sample is more than `least` off the chord (a limb of one taper: the
// surface does not show the joint).
std::optional<double> profile_bend(const std::vector<Vec2d>& s, double least) {
  if (s.size() < 5) return std::nullopt;
  const Vec2d a = s.front(), b = s.back();
  if (!(b.x() > a.x())) return std::nullopt;
  auto off = [&](std::size_t i) {
    return std::abs(a.y() + (b.y() - a.y()) * (s[i].x() - a.x()) / (b.x() - a.x()) - s[i].y());
  };
  std::size_t best = 0;
  double most = least;
  for (std::size_t i = 1; i + 1 < s.size(); ++i)
    if (const double d = off(i); d > most) most = d, best = i;
  if (best == 0) return std::nullopt;
  const double d0 = off(best - 1), d1 = most, d2 = off(best + 1), h0 = s[best].x() - s[best - 1].x(),
               h1 = s[best + 1].x() - s[best].x();
  const double curve = d0 - 2 * d1 + d2;
  if (std::abs(h0 - h1) > 1e-9 * (h0 + h1) || !(curve < 0)) return s[best].x();
  return s[best].x() + std::clamp(0.5 * (d0 - d2) / curve, -0.5, 0.5) * h0;
}

// The knee of each leg, from horizontal slices (the largest loop on the
// leg's side of the centre line) between the calf's fullest girth and 3 % of
// the height below the crotch. Going up from the calf the girth narrows under
// the knee (the profile's first minimum); the knee is the bump above it (the
// joint, a local maximum the girth drops at least 2 mm from before the thigh
// takes over). A leg whose girth rises on into the thigh without one: the
// hollow at the back of the knee, where the back of the leg comes furthest
// forward. Heights, m, of the legs where one was found.
std::vector<double> knees_on_surface(const mesh::SurfaceMesh& m, double cx, double ankle, double crotch, double H) {
  const double top = crotch - 0.03 * H, step = 0.005 * H, span = crotch - ankle;
  const mesh::SurfaceMesh legs = band(m, ankle, top + step);
  std::vector<Vec2d> side[2], back[2];  // (y, girth) and (y, z of the back of the leg)
  for (double y = ankle; y <= top + 1e-12; y += step) {
    double area[2] = {0, 0}, girth[2] = {0, 0}, z[2] = {0, 0};
    for (const auto& l : mesh::slice_horizontal(legs, y)) {
      if (l.size() < 3) continue;
      const int k = loop_centroid(l).x() > cx ? 0 : 1;
      if (const double ar = loop_area(l); ar > area[k]) {
        area[k] = ar, girth[k] = mesh::convex_hull_perimeter(l), z[k] = l.front().y();
        for (const auto& q : l) z[k] = std::min(z[k], q.y());
      }
    }
    for (int k = 0; k < 2; ++k)
      if (area[k] > 0) side[k].push_back({y, girth[k]}), back[k].push_back({y, z[k]});
  }
  std::vector<double> out;
  for (int leg = 0; leg < 2; ++leg) {
    const auto& p = side[leg];
    // The calf: the fullest girth 12–48 % of the way from ankle to crotch.
    std::size_t calf = p.size();
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p[i].x() >= ankle + 0.12 * span && p[i].x() <= ankle + 0.48 * span && (calf == p.size() || p[i].y() > p[calf].y()))
        calf = i;
    if (calf == p.size()) continue;
    const std::size_t n = p.size();
    // Under the knee: the first local minimum above the calf.
    std::size_t under = n;
    for (std::size_t i = calf + 1; i + 1 < n; ++i)
      if (p[i].y() <= p[i - 1].y() && p[i].y() < p[i + 1].y()) {
        under = i;
        break;
      }
    std::optional<double> knee;
    if (under < n) {
      // The bump above it, within 8 % of the height.
      for (std::size_t i = under + 1; i + 1 < n && p[i].x() < p[under].x() + 0.08 * H; ++i) {
        if (!(p[i].y() >= p[i - 1].y() && p[i].y() > p[i + 1].y())) continue;
        double dip = p[i].y();
        for (std::size_t k = i + 1; k < n && p[k].x() < p[i].x() + 0.05 * H; ++k) dip = std::min(dip, p[k].y());
        if (p[i].y() - dip < 0.002) continue;  // a ripple of the plateau under the knee
        const double g0 = p[i - 1].y(), g1 = p[i].y(), g2 = p[i + 1].y(), curve = g0 - 2 * g1 + g2;
        knee = p[i].x() + (curve < 0 ? std::clamp(0.5 * (g0 - g2) / curve, -0.5, 0.5) * step : 0.0);
        break;
      }
    }
    if (!knee && under < n) {
      // No bump: the hollow at the back of the knee, where the back of the
      // leg comes furthest forward (the calf below and the thigh above
      // bulge back at least 3 mm more), from 3 % of the height under the
      // narrowing to 12 % above it. The body faces +Z.
      const auto& b = back[leg];
      std::size_t best = n;
      for (std::size_t i = 1; i + 1 < n; ++i) {
        if (b[i].x() < p[under].x() - 0.03 * H || b[i].x() > p[under].x() + 0.12 * H) continue;
        if (best == n || b[i].y() > b[best].y()) best = i;
      }
      if (best != n) {
        double below = b[best].y(), above = b[best].y();
        for (std::size_t k = 0; k < n; ++k) {
          if (b[k].x() < b[best].x() && b[k].x() > b[best].x() - 0.1 * H) below = std::min(below, b[k].y());
          if (b[k].x() > b[best].x() && b[k].x() < b[best].x() + 0.1 * H) above = std::min(above, b[k].y());
        }
        if (b[best].y() - below >= 0.003 && b[best].y() - above >= 0.003) knee = b[best].x();
      }
    }
    if (knee) out.push_back(*knee);
  }
  return out;
}

// One station of an arm: the slice across it by the plane x = c.
struct ArmStation {
  Vec3 centre;       // m, the loop's centroid
  double perimeter;  // m, convex hull
  double extent_y, extent_z;
};

// The stations of one arm (side +1: the body's left, +X), from beside the
// trunk to the fingertips; empty when no arm is there.
std::vector<ArmStation> arm_stations(const mesh::SurfaceMesh& m, const mesh::SurfaceMesh& across, double cx,
                                     double trunk_half_width, double crotch, double H, int side) {
  const mesh::Box3 b = mesh::bounding_box(m);
  const double reach = side > 0 ? b.max.x() - cx : cx - b.min.x();
  std::vector<ArmStation> out;
  for (double d = trunk_half_width + 0.02; d < reach - 0.005; d += 0.01) {
    const double c = cx + side * d;
    // `across` is the body turned so that x is up: (x, y, z) -> (y, x, -z); a
    // loop point (a, b) is (x = c, y = a, z = -b).
    const ArmStation* pick = nullptr;
    ArmStation best;
    double best_y = crotch - 0.25 * H;  // a hanging hand reaches about the crotch
    for (const auto& l : mesh::slice_horizontal(across, c)) {
      if (l.size() < 3) continue;
      const Vec2d q = loop_centroid(l);
      if (q.x() <= best_y) continue;  // the arm is the highest loop the plane cuts
      // and it goes on from the last station (not a leg of a wide stance).
      if (!out.empty() && (Vec3(c, q.x(), -q.y()) - out.back().centre).norm() > 0.08) continue;
      double ylo = 1e300, yhi = -1e300, zlo = 1e300, zhi = -1e300;
      for (const auto& p : l) ylo = std::min(ylo, p.x()), yhi = std::max(yhi, p.x()), zlo = std::min(zlo, -p.y()), zhi = std::max(zhi, -p.y());
      best = {Vec3(c, q.x(), -q.y()), mesh::convex_hull_perimeter(l), yhi - ylo, zhi - zlo};
      best_y = q.x();
      pick = &best;
    }
    if (!pick) {
      if (out.empty()) continue;  // not out of the trunk's shadow yet
      break;                      // past the fingertips
    }
    out.push_back(best);
  }
  return out;
}

// Rotation taking unit `a` to +Y (a proper rotation).
Eigen::Matrix3d to_up(const Vec3& a) {
  return Eigen::Quaterniond::FromTwoVectors(a, Vec3::UnitY()).toRotationMatrix();
}

std::optional<ArmLandmarks> arm_landmarks(const mesh::SurfaceMesh& m, const std::vector<ArmStation>& st, double cx,
                                          double trunk_half_width) {
  if (st.size() < 8) return std::nullopt;
  ArmLandmarks a;
  const Vec3 tip = st.back().centre;
  Vec3 axis = (tip - st.front().centre).normalized();
  // The shoulder joint (the centre of the arm's ball, as vgd's mannequin is
  // built): on the arm's axis, 3 cm inside the chest's half-width.
  const double inside = std::abs(st.front().centre.x() - cx) - (trunk_half_width - 0.03);
  a.shoulder = st.front().centre - std::max(inside, 0.0) / std::max(std::abs(axis.x()), 0.2) * axis;
  const double L = (tip - a.shoulder).norm();
  // The wrist: the thinnest true cross-section (planes normal to the arm, not
  // the oblique planes x = const, which take in the hand's thickness early)
  // between 45 % and 92 % of the way to the fingertips.
  const Eigen::Matrix3d r = to_up(axis);
  mesh::SurfaceMesh along = m;
  mesh::transform(along, r);
  double thinnest = std::numeric_limits<double>::infinity(), at = 0;
  for (double t = 0.45 * L; t <= 0.92 * L; t += 0.005) {
    const Vec3 c = r * (a.shoulder + t * axis);
    const Vec2d cxz(c.x(), c.z());
    double best_d = 0.06, perimeter = 0;
    for (const auto& l : mesh::slice_horizontal(along, c.y())) {
      if (l.size() < 3) continue;
      const double d = (loop_centroid(l) - cxz).norm();
      if (d < best_d) best_d = d, perimeter = mesh::convex_hull_perimeter(l);
    }
    if (perimeter > 0 && perimeter < thinnest) thinnest = perimeter, at = t;
  }
  if (!std::isfinite(thinnest)) return std::nullopt;
  a.wrist = a.shoulder + at * axis;
  a.wrist_girth = thinnest;
  // The girth profile from 15 % of the way down (below the armpit) to the
  // wrist, for the elbow: at each station the loop nearest the last
  // station's (an arm bent at the elbow leaves the straight shoulder–fingertip
  // line by several cm), the first within 6 cm of that line.
  std::vector<Vec2d> profile;
  std::optional<Vec2d> last;
  const double y_from = (r * (a.shoulder + 0.15 * L * axis)).y(), y_to = (r * (a.shoulder + at * axis)).y();
  const mesh::SurfaceMesh arm = band(along, std::min(y_from, y_to) - 0.01, std::max(y_from, y_to) + 0.01);
  for (double t = 0.15 * L; t <= at + 1e-9; t += 0.005) {
    const Vec3 c = r * (a.shoulder + t * axis);
    const Vec2d from = last ? *last : Vec2d(c.x(), c.z());
    double best_d = 0.06, perimeter = 0;
    Vec2d centre;
    for (const auto& l : mesh::slice_horizontal(arm, c.y())) {
      if (l.size() < 3) continue;
      const Vec2d q = loop_centroid(l);
      if (const double d = (q - from).norm(); d < best_d) best_d = d, perimeter = mesh::convex_hull_perimeter(l), centre = q;
    }
    if (perimeter > 0) profile.push_back({t, perimeter}), last = centre;
  }
  // The elbow. Going up from the wrist the girth grows to the forearm's
  // fullest (a local maximum) and narrows above it where the upper arm's
  // muscles end (at least 2 mm less within 8 cm); the joint lies between the
  // two, and the elbow is put half-way. An arm without that narrowing: where
  // its profile bends over the lower 70 % (profile_bend, at least 5 mm of
  // girth off the chord; the armpit's flare above is left out).
  std::optional<double> bend;
  for (std::size_t i = profile.size() < 2 ? 0 : profile.size() - 2; i >= 1 && !bend; --i) {
    const double t = profile[i].x();
    if (t > 0.8 * at) continue;
    if (t < 0.3 * at) break;
    if (!(profile[i].y() >= profile[i + 1].y() && profile[i].y() > profile[i - 1].y())) continue;
    std::size_t narrow = i;
    for (std::size_t k = i; k-- > 0 && profile[k].x() > t - 0.08;)
      if (profile[k].y() < profile[narrow].y()) narrow = k;
    if (profile[i].y() - profile[narrow].y() >= 0.002) bend = 0.5 * (t + profile[narrow].x());
  }
  if (!bend) {
    std::vector<Vec2d> lower;
    for (const auto& p : profile)
      if (p.x() >= 0.3 * at - 1e-9 && p.x() <= at + 1e-9) lower.push_back(p);
    bend = profile_bend(lower, 0.005);
  }
  a.elbow_on_surface = bend && *bend > 0.25 * at && *bend < 0.8 * at;
  a.elbow = a.shoulder + (a.elbow_on_surface ? *bend / at : 0.56) * (a.wrist - a.shoulder);
  return a;
}

// An arm as a tube round its axis, to cut it out of trunk slices.
struct ArmTube {
  Vec3 a, b;       // m, shoulder joint and wrist
  double r = 0.0;  // m, the largest radius of its rings, and 5 mm
};

// The girth of a trunk loop at height y without the points inside an arm's
// tube: what a tape passing under the arms reads where they press against the
// flanks. `kept_half`: the half-width (m) of what is kept.
double girth_without_arms(const Loop& l, double y, double cx, const std::vector<ArmTube>& arms, double* kept_half) {
  std::vector<Vec2d> kept;
  kept.reserve(l.size());
  for (const auto& p : l) {
    const Vec3 q(p.x(), y, p.y());
    bool in_arm = false;
    for (const auto& t : arms) {
      const Vec3 ab = t.b - t.a;
      const double u = std::clamp((q - t.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      in_arm = in_arm || (q - (t.a + u * ab)).norm() < t.r;
    }
    if (!in_arm) kept.push_back(p);
  }
  if (kept_half) *kept_half = kept.empty() ? 0.0 : half_width(kept, cx);
  return kept.size() >= 3 ? mesh::convex_hull_perimeter(kept) : 0.0;
}

}  // namespace

Vec2d trunk_centre(const mesh::SurfaceMesh& m) {
  const mesh::Box3 box = mesh::bounding_box(m);
  Vec2d centre(box.centre().x(), box.centre().z());
  double largest = 0;
  for (const auto& l : mesh::slice_horizontal(m, box.min.y() + 0.62 * box.size().y()))
    if (const double a = loop_area(l); a > largest) largest = a, centre.y() = loop_centroid(l).y();
  return centre;
}

BodyMeasuring measure_body(const mesh::SurfaceMesh& m) {
  BodyMeasuring out;
  BodyLandmarks& lm = out.landmarks;
  BodyMeasurements& bm = out.measurements;
  bm = BodyMeasurements{};
  bm.label = "measured";
  bm.bust = bm.under_bust = bm.waist = bm.hip = bm.shoulder_width = bm.neck = bm.arm_length = bm.inseam = 0.0;
  const mesh::Box3 box = mesh::bounding_box(m);
  const double H = box.size().y(), y0 = box.min.y();
  lm.height = bm.height = H;
  if (!(H > 0)) return out;
  const double dy = 0.0025 * H;
  auto at = [&](double f) { return y0 + f * H; };
  Slices s{m, trunk_centre(m), {}};

  // Crotch: the lowest slice from 30 % up whose loop encloses the centre line.
  for (double y = at(0.30); y < at(0.60); y += dy)
    if (s.central(y)) {
      lm.crotch = y - y0;
      break;
    }
  if (lm.crotch == 0) out.notes.push_back("no crotch found: no slice at 30–60 % of the height encloses the centre line");
  bm.inseam = lm.crotch;

  const auto [waist_y, waist_g] = girth_extreme(s, at(0.55), at(0.68), dy, false);
  lm.waist = waist_y > 0 ? waist_y - y0 : 0.0, bm.waist = waist_g;
  double waist_half = 0.0;
  if (waist_y > 0) trunk_girth(*s.central(waist_y), s.centre.x(), &waist_half);
  if (lm.crotch > 0 && waist_y > 0) {
    const auto [hy, hg] = girth_extreme(s, y0 + lm.crotch + 0.01 * H, std::min(waist_y, at(0.58)), dy, true);
    lm.hip = hy > 0 ? hy - y0 : 0.0, bm.hip = hg;
  }
  if (waist_y > 0) {
    // The chest: a slice that takes in an arm (a hanging arm touching the
    // flank, the shoulders) is wider than the trunk; such slices are skipped.
    // Going up from the waist, the first slice whose loop, arm lobes cut
    // off, is over 1 cm wider than the one below (the trunk's sides are never
    // that steep) is where an arm joins it without a notch to cut at; the
    // chest is looked for below.
    double top = at(0.76);
    double prev_half = waist_half;
    for (double y = waist_y + dy; y <= top; y += dy) {
      const Loop* l = s.central(y);
      if (!l) break;
      double h = 0;
      trunk_girth(*l, s.centre.x(), &h);
      if (h > prev_half + 0.01 && y > waist_y + 0.04 * H) {
        top = y - dy;
        break;
      }
      prev_half = h;
    }
    const auto [by, bg] = girth_extreme(s, waist_y + 0.04 * H, top, dy, true, 1.45 * waist_half + 0.03);
    lm.bust = by > 0 ? by - y0 : 0.0, bm.bust = bg;
    // Under the bust: the girth 3 % of the height below it (the trunk narrows
    // on down to the waist, so it has no minimum of its own to find).
    if (by > 0)
      if (const Loop* l = s.central(by - 0.03 * H)) lm.under_bust = by - 0.03 * H - y0, bm.under_bust = trunk_girth(*l, s.centre.x());
  }
  const auto [ny, ng] = girth_extreme(s, at(0.80), at(0.92), dy, false);
  lm.neck = ny > 0 ? ny - y0 : 0.0, bm.neck = ng;
  if (ny > 0) {
    // Shoulders: going down from the neck, the first slice whose trunk loop is
    // more than twice as wide as the neck's.
    const double neck_half = half_width(*s.central(ny), s.centre.x());
    for (double y = ny; y > at(0.70); y -= dy)
      if (const Loop* l = s.central(y); l && half_width(*l, s.centre.x()) > 2.0 * neck_half) {
        lm.shoulder = y - y0;
        break;
      }
  }
  lm.ankle = leg_thinnest(m, s.centre.x(), at(0.03), at(0.10), dy).first;
  if (lm.ankle > 0) lm.ankle -= y0;
  if (lm.ankle > 0 && lm.crotch > 0) {
    const auto knees = knees_on_surface(m, s.centre.x(), y0 + lm.ankle, y0 + lm.crotch, H);
    double sum = 0;
    for (const double k : knees) sum += k;
    if (!knees.empty()) lm.knee = sum / static_cast<double>(knees.size()) - y0;
    if (knees.size() < 2)
      out.notes.push_back(knees.empty() ? "no knee found on the surface: neither leg shows one between calf and thigh "
                                          "(no bump over the narrowing under it, no hollow behind it)"
                                        : "knee found on the surface of one leg only");
  }

  // Arms: slices across x beside the trunk (its width at the chest).
  const Loop* chest = s.central(lm.bust > 0 ? y0 + lm.bust : at(0.70));
  if (!chest || lm.crotch == 0) {
    out.notes.push_back("no arms looked for: the trunk or the crotch was not found");
  } else {
    double trunk_half = 0;  // without the arms' lobes
    trunk_girth(*chest, s.centre.x(), &trunk_half);
    mesh::SurfaceMesh across = m;
    Eigen::Matrix3d q;
    q << 0, 1, 0, 1, 0, 0, 0, 0, -1;  // (x, y, z) -> (y, x, -z), a proper rotation
    mesh::transform(across, q);
    for (int side : {1, -1}) {
      auto arm = arm_landmarks(m, arm_stations(m, across, s.centre.x(), trunk_half, y0 + lm.crotch, H, side),
                               s.centre.x(), trunk_half);
      if (!arm) out.notes.push_back(std::string("no ") + (side > 0 ? "left" : "right") +
                                    " arm found beside the trunk (arms held in front of the body are not found)");
      (side > 0 ? lm.left_arm : lm.right_arm) = arm;
    }
    // The chest again, the arms cut out by their tubes: where an arm rests
    // against the flank without a notch between them, the loop's lobes are
    // not cut at the bust and the slices there were skipped (above).
    out.arms = arm_segments(m, lm);
    std::vector<ArmTube> tubes;
    for (const auto& seg : out.arms) {
      double r = 0;
      for (const auto& ring : seg.rings) r = std::max(r, ring.half_width);
      tubes.push_back({seg.start, seg.start + seg.length * seg.axis, r + 0.005});
    }
    if (!tubes.empty() && waist_y > 0) {
      double best = 0, best_y = 0;
      for (double y = waist_y + 0.04 * H; y <= at(0.76) + 1e-12; y += dy) {
        const Loop* l = s.central(y);
        if (!l) continue;
        double kept = 0;
        const double g = girth_without_arms(*l, y, s.centre.x(), tubes, &kept);
        if (kept <= 1.45 * waist_half + 0.03 && g > best) best = g, best_y = y;
      }
      if (best_y > 0) {
        lm.bust = best_y - y0, bm.bust = best;
        if (const Loop* l = s.central(best_y - 0.03 * H))
          lm.under_bust = best_y - 0.03 * H - y0, bm.under_bust = girth_without_arms(*l, best_y - 0.03 * H, s.centre.x(), tubes, nullptr);
      }
    }
    double arms = 0;
    int n = 0;
    for (const auto* a : {&lm.left_arm, &lm.right_arm})
      if (*a) arms += ((*a)->wrist - (*a)->shoulder).norm(), ++n;
    bm.arm_length = n ? arms / n : 0.0;
    // The shoulder width, outside of one upper arm to the other at the
    // joints' height (as vgd's mannequin is made), for arms that hang (A-pose).
    if (lm.left_arm && lm.right_arm) {
      const Vec3 la = (lm.left_arm->wrist - lm.left_arm->shoulder).normalized();
      if (std::abs(la.y()) > 0.5) {
        const double yj = 0.5 * (lm.left_arm->shoulder.y() + lm.right_arm->shoulder.y());
        double lo = 1e300, hi = -1e300;
        if (const Loop* l = s.central(yj))
          for (const auto& p : *l) lo = std::min(lo, p.x()), hi = std::max(hi, p.x());
        if (hi > lo) bm.shoulder_width = hi - lo;
      } else {
        out.notes.push_back("shoulder width not measured: the arms are raised (T-pose)");
      }
    }
  }
  // A girth longer than the body is tall is no human girth (a slice of a
  // mesh whose loops do not close, a prop round the body): not reported.
  for (auto [name, v] : {std::pair{"bust", &bm.bust}, {"under-bust", &bm.under_bust}, {"waist", &bm.waist},
                         {"hip", &bm.hip}, {"neck", &bm.neck}})
    if (*v > 1.2 * H) {
      out.notes.push_back(std::string(name) + " girth " + format_fixed(100 * *v, 1) + " cm left out: longer than 1.2 × the height");
      *v = 0.0;
    }
  for (auto [name, v] : {std::pair{"waist", bm.waist}, {"hip", bm.hip}, {"bust", bm.bust}, {"neck", bm.neck}})
    if (v == 0) out.notes.push_back(std::string("no ") + name + " found");
  return out;
}

std::string skeleton_joint_kind(std::string_view bone_name) {
  std::string n;
  for (const char c : bone_name.substr(bone_name.find_last_of(':') == std::string_view::npos ? 0 : bone_name.find_last_of(':') + 1))
    n += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  auto has = [&](const char* w) { return n.find(w) != std::string::npos; };
  for (const char* finger : {"index", "middle", "ring", "pinky", "thumb", "finger", "toe", "twist", "roll", "end"})
    if (has(finger)) return "";
  if (has("forearm") || has("lowerarm") || has("elbow")) return "elbow";
  if (has("wrist") || has("hand")) return "wrist";
  // The upper arm's bone starts at the shoulder joint (Mixamo LeftArm, SMPL
  // L_Shoulder, MakeHuman upperarm01, Rigify upper_arm, 3ds Max UpperArm);
  // Mixamo's LeftShoulder and Rigify's shoulder are the collarbone.
  if (has("upperarm") || has("upper_arm") || has("_shoulder")) return "shoulder";
  if (has("arm") && !has("armature")) return "shoulder";
  if (has("knee") || has("lowerleg") || has("shin") || has("calf")) return "knee";
  if (has("leg") && !has("up") && !has("thigh")) return "knee";  // Mixamo's LeftLeg starts at the knee
  if (has("ankle") || has("foot")) return "ankle";
  return "";
}

int landmarks_from_skeleton(BodyLandmarks& lm, const std::vector<ModelJoint>& joints, std::vector<std::string>& notes) {
  int taken = 0;
  std::map<std::string, int> kinds;  // joints taken, by kind
  // Where a joint lies against the arm on its side (the body's left is +X)
  // found on the surface: how far along from shoulder to wrist (0 to 1) and
  // how far off that line, m.
  const auto along = [](const ArmLandmarks& arm, const Vec3& p) {
    const Vec3 a = arm.shoulder, b = arm.wrist;
    const double u = (p - a).dot(b - a) / std::max((b - a).squaredNorm(), 1e-12);
    return std::pair{u, (p - (a + u * (b - a))).norm()};
  };
  // The arm's ends first (the shoulder and wrist joints): an elbow is then
  // judged against the skeleton's own arm. Each end within 8 cm of the line
  // the surface found and no more than a quarter of the arm beyond where the
  // surface put it (the collarbone's start, at the neck, is not a shoulder).
  for (const auto& j : joints) {
    const std::string kind = skeleton_joint_kind(j.name);
    if (kind != "shoulder" && kind != "wrist") continue;
    auto& arm = j.position.x() >= 0 ? lm.left_arm : lm.right_arm;
    if (!arm) continue;
    const auto [u, off] = along(*arm, j.position);
    const double end = kind == "shoulder" ? 0.0 : 1.0;
    if (off > 0.08 || std::abs(u - end) > 0.25) {
      notes.push_back("skeleton joint " + j.name + " left out: " + format_fixed(100 * off, 1) + " cm from the arm's axis, " +
                      format_fixed(100 * u, 0) + " % of the way from the shoulder to the wrist found on the surface");
      continue;
    }
    (kind == "shoulder" ? arm->shoulder : arm->wrist) = j.position;
    (kind == "shoulder" ? arm->shoulder_from_skeleton : arm->wrist_from_skeleton) = true;
    ++kinds[kind], ++taken;
  }
  std::vector<double> knees;
  for (const auto& j : joints) {
    const std::string kind = skeleton_joint_kind(j.name);
    if (kind == "elbow") {
      // The arm on the joint's side (the body's left is +X).
      auto& arm = j.position.x() >= 0 ? lm.left_arm : lm.right_arm;
      if (!arm) continue;
      const auto [u, off] = along(*arm, j.position);
      if (off > 0.08 || u < 0.2 || u > 0.9) {
        notes.push_back("skeleton joint " + j.name + " left out: " + format_fixed(100 * off, 1) +
                        " cm from the arm's axis, " + format_fixed(100 * u, 0) + " % of the way to the wrist");
        continue;
      }
      arm->elbow = j.position;
      arm->elbow_from_skeleton = true;
      arm->elbow_on_surface = false;
      ++kinds[kind], ++taken;
    } else if (kind == "knee") {
      const double y = j.position.y();
      if (lm.crotch > 0 && (y <= lm.ankle || y >= lm.crotch)) {
        notes.push_back("skeleton joint " + j.name + " left out: at " + format_fixed(100 * y, 1) +
                        " cm, not between the ankle and the crotch");
        continue;
      }
      knees.push_back(y);
      ++kinds[kind], ++taken;
    }
  }
  if (!knees.empty()) {
    double sum = 0;
    for (const double y : knees) sum += y;
    lm.knee = sum / static_cast<double>(knees.size());
  }
  if (taken > 0) {
    std::string what;
    for (const char* k : {"shoulder", "elbow", "wrist", "knee"})
      if (const auto it = kinds.find(k); it != kinds.end())
        what += (what.empty() ? "" : ", ") + std::to_string(it->second) + " " + k + (it->second > 1 ? "s" : "");
    notes.push_back("joints from the file's skeleton: " + what);
  }
  return taken;
}

std::vector<BodySegment> arm_segments(const mesh::SurfaceMesh& m, const BodyLandmarks& lm) {
  std::vector<BodySegment> out;
  for (int side : {1, -1}) {
    const auto& arm = side > 0 ? lm.left_arm : lm.right_arm;
    if (!arm) continue;
    BodySegment s;
    s.name = side > 0 ? "left-arm" : "right-arm";
    s.start = arm->shoulder;
    s.axis = (arm->wrist - arm->shoulder).normalized();
    s.front = (Vec3::UnitZ() - Vec3::UnitZ().dot(s.axis) * s.axis).normalized();
    s.length = (arm->wrist - arm->shoulder).norm();
    // Rings from true cross-sections (planes normal to the axis): the loop
    // nearest the axis, as a circle of its perimeter. Near the shoulder the
    // plane also cuts the trunk; the radius is capped at the first clean
    // section's.
    const Eigen::Matrix3d r = to_up(s.axis);
    mesh::SurfaceMesh along = m;
    mesh::transform(along, r);
    const int n = 12;
    std::vector<double> radius(n + 1, 0.0);
    for (int i = 0; i <= n; ++i) {
      const double t = s.length * i / n;
      const Vec3 c = r * (s.start + t * s.axis);
      const Vec2d cxz(c.x(), c.z());
      double best_d = 0.05;
      for (const auto& l : mesh::slice_horizontal(along, c.y())) {
        if (l.size() < 3) continue;
        if (const double d = (loop_centroid(l) - cxz).norm(); d < best_d)
          best_d = d, radius[i] = mesh::convex_hull_perimeter(l) / (2 * kPi);
      }
    }
    // The largest plausible radius: the section a third of the way down.
    const double cap = std::max(radius[n / 3], 0.02) * 1.25;
    for (int i = 0; i <= n; ++i) {
      SegmentRing ring;
      ring.s = s.length * i / n;
      ring.centre = s.start + ring.s * s.axis;
      const double rr = radius[i] > 0 ? std::min(radius[i], cap) : cap / 1.25;
      ring.half_width = ring.half_depth = rr;
      s.rings.push_back(ring);
    }
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace vgd::body
