// The drafted T-shirt (draft.hpp): FRONT, BACK, LEFT SLEEVE, RIGHT SLEEVE.
//
// Construction (after Aldrich's T-shirt block, simplified; metres, y up, hem on y = 0):
//   W  = (bust + bust_ease) / 4       half-width of a body piece at the chest
//   NP = (nw, L)                      neck point, nw = neck / 6 + 5 mm
//   SP = (nw + √(shoulder² − drop²), L − drop)   shoulder point
//   UA = (W, L − armhole_depth)       underarm point
//   HM = (max(W, (hip + hip_ease) / 4), 0)   hem corner; the side seam UA–HM is
//                                     straight (it flares when the hips are wider
//                                     than the chest with its ease)
// The right half of each body piece is built, the left half is its exact mirror
// (x → −x), so the two side seams and the two shoulders are equal bit for bit,
// and FRONT and BACK share NP, SP, UA and the hem, so their side seams and
// shoulders are equal too. Front and back differ in the neckline depth and the
// armhole curve (the front armhole is scooped deeper). The sleeve cap is two
// S-shaped cubic halves whose height is found by bisection so that the cap is
// exactly front armhole + back armhole + cap_ease (polyline lengths).
#include <algorithm>
#include <cmath>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/pattern/contour.hpp"
#include "vgd/pattern/draft.hpp"

namespace vgd::pattern {

std::vector<TShirtMeasurements> tshirt_size_table() {
  // size, bust, hip, neck, upper arm (m): bust and hip of EN 13402-3 (data/bodies),
  // neck and upper arm from the skirt's chart (German DOB), one row per size.
  const struct { const char* size; double bust, hip, neck, arm; } rows[] = {
      {"34", 0.80, 0.88, 0.34, 0.26}, {"36", 0.84, 0.92, 0.35, 0.27}, {"38", 0.88, 0.97, 0.36, 0.28},
      {"40", 0.92, 1.00, 0.37, 0.29}, {"42", 0.96, 1.04, 0.38, 0.30}};
  std::vector<TShirtMeasurements> out;
  int step = -2;
  for (const auto& r : rows) {
    TShirtMeasurements m;
    m.size = r.size;
    m.bust = r.bust;
    m.hip = r.hip;
    m.neck = r.neck;
    m.upper_arm = r.arm;
    m.shoulder = 0.135 + 0.0025 * step;
    m.length = 0.62 + 0.01 * step;
    m.armhole_depth = 0.20 + 0.005 * step;
    out.push_back(m);
    ++step;
  }
  return out;
}

namespace {

// Cubic Bézier a, b, c, d sampled with n segments, excluding a.
std::vector<Vec2> cubic(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, int n) {
  std::vector<Vec2> out;
  for (int i = 1; i <= n; ++i) {
    const double t = static_cast<double>(i) / n, u = 1 - t;
    out.push_back(u * u * u * a + 3 * u * u * t * b + 3 * u * t * t * c + t * t * t * d);
  }
  return out;
}

double polyline_length(const Vec2& start, const std::vector<Vec2>& pts) {
  double len = 0;
  Vec2 prev = start;
  for (const auto& p : pts) {
    len += (p - prev).norm();
    prev = p;
  }
  return len;
}

// The point at arc length s along start, pts...; and the direction of the edge there.
std::pair<Vec2, Vec2> point_at(const Vec2& start, const std::vector<Vec2>& pts, double s) {
  Vec2 prev = start;
  for (const auto& p : pts) {
    const double l = (p - prev).norm();
    if (s <= l && l > 0) return {prev + (s / l) * (p - prev), (p - prev) / l};
    s -= l;
    prev = p;
  }
  return {prev, Vec2(1, 0)};
}

void add_notch(Piece& piece, const Vec2& at, const Vec2& edge_dir) {
  // The cut points into the piece: the edge direction turned +90° (the piece lies on
  // the left of a counter-clockwise contour).
  const Vec2 in(-edge_dir.y(), edge_dir.x());
  Notch n;
  n.position = at;
  n.angle_deg = std::atan2(in.y(), in.x()) * 180.0 / M_PI;
  n.length_m = 0.004;
  n.boundary_index = nearest_vertex(piece.boundary, at).index;
  piece.notches.push_back(n);
}

struct BodyFrame {
  double W, L, yu, nw;
  double Wh;  // half-width at the hem
  Vec2 NP, SP, UA;
};

BodyFrame body_frame(const TShirtMeasurements& m) {
  BodyFrame f;
  f.W = (m.bust + m.bust_ease) / 4.0;
  f.Wh = std::max(f.W, (m.hip + m.hip_ease) / 4.0);
  f.L = m.length;
  f.yu = m.length - m.armhole_depth;
  f.nw = m.neck / 6.0 + 0.005;
  f.NP = Vec2(f.nw, f.L);
  f.SP = Vec2(f.nw + std::sqrt(m.shoulder * m.shoulder - m.shoulder_drop * m.shoulder_drop), f.L - m.shoulder_drop);
  f.UA = Vec2(f.W, f.yu);
  return f;
}

// Right armhole from UA to SP (excluding UA): the front is scooped deeper.
std::vector<Vec2> armhole(const BodyFrame& f, bool back) {
  const double dx = f.W - f.SP.x(), dy = f.SP.y() - f.yu;
  const Vec2 c1(f.SP.x() + (back ? 0.45 : 0.15) * dx, f.yu);
  const Vec2 c2(f.SP.x() + (back ? 0.01 : -0.01), f.yu + (back ? 0.60 : 0.50) * dy);
  return cubic(f.UA, c1, c2, f.SP, 16);
}

constexpr double kArmNotch = 0.09;     // armhole notch: arc length from the underarm, m
constexpr double kDoubleGap = 0.006;   // half the spacing of a double notch, m

Piece body(const TShirtMeasurements& m, bool back) {
  const BodyFrame f = body_frame(m);
  const double depth = back ? m.back_neck_depth : m.front_neck_depth;
  Piece p;
  p.name = back ? "BACK" : "FRONT";
  p.size = m.size;
  p.block = p.name + "_" + m.size;
  p.category = "SELF";
  p.annotation = back ? "CUT 1 BACK" : "CUT 1 FRONT";

  // Right half from the hem's centre up to the neck's centre, then mirrored.
  const auto arm = armhole(f, back);
  const auto neck = cubic(f.NP, Vec2(f.nw, f.L - 0.55 * depth), Vec2(0.55 * f.nw, f.L - depth), Vec2(0.0, f.L - depth), 10);
  auto& o = p.boundary;
  o.push_back({Vec2(-f.Wh, 0.0), PointKind::turn});                // 0 hem
  o.push_back({Vec2(f.Wh, 0.0), PointKind::turn});                 // 1 right side seam
  o.push_back({f.UA, PointKind::turn});                            // 2 right armhole
  for (std::size_t i = 0; i + 1 < arm.size(); ++i) o.push_back({arm[i], PointKind::curve});
  o.push_back({f.SP, PointKind::turn});                            // 3 right shoulder
  o.push_back({f.NP, PointKind::turn});                            // 4 neckline
  for (std::size_t i = 0; i + 1 < neck.size(); ++i) o.push_back({neck[i], PointKind::curve});
  o.push_back({neck.back(), PointKind::curve});                    // centre neck
  for (int i = static_cast<int>(neck.size()) - 2; i >= 0; --i) o.push_back({Vec2(-neck[i].x(), neck[i].y()), PointKind::curve});
  o.push_back({Vec2(-f.NP.x(), f.NP.y()), PointKind::turn});       // 5 left shoulder
  o.push_back({Vec2(-f.SP.x(), f.SP.y()), PointKind::turn});       // 6 left armhole
  for (int i = static_cast<int>(arm.size()) - 2; i >= 0; --i) o.push_back({Vec2(-arm[i].x(), arm[i].y()), PointKind::curve});
  o.push_back({Vec2(-f.W, f.yu), PointKind::turn});                // 7 left side seam

  // Armhole notches, measured from the underarm along each armhole.
  const std::vector<double> at = back ? std::vector<double>{kArmNotch - kDoubleGap, kArmNotch + kDoubleGap}
                                      : std::vector<double>{kArmNotch};
  for (const double s : at) {
    const auto [q, d] = point_at(f.UA, arm, s);
    add_notch(p, q, d);                                   // right armhole runs UA -> SP
    add_notch(p, Vec2(-q.x(), q.y()), Vec2(d.x(), -d.y()));  // left armhole runs SP -> UA: mirrored, reversed
  }
  p.grain_line = Segment{Vec2(0.0, 0.1), Vec2(0.0, f.L - depth - 0.05)};
  return p;
}

struct Cap {
  double height = 0;
  std::vector<Vec2> half;  // right half from (s, 0) to the top (0, height), excluding (s, 0)
};

Cap make_cap(double s, double h) {
  Cap c;
  c.height = h;
  c.half = cubic(Vec2(s, 0), Vec2(0.65 * s, 0), Vec2(0.45 * s, h), Vec2(0, h), 16);
  return c;
}

Piece left_sleeve(const TShirtMeasurements& m, double arm_front, double arm_back) {
  const double s = (m.upper_arm + m.arm_ease) / 2.0;
  const double target = arm_front + arm_back + m.cap_ease;
  // Cap length grows with its height: bisection to well below 1e-9 m.
  double lo = 0.005, hi = 0.5;
  if (2 * polyline_length(Vec2(s, 0), make_cap(s, hi).half) < target)
    throw Error("", "t-shirt size " + m.size, "the armhole (" + format_fixed(arm_front + arm_back, 3) +
                                                  " m) is too long for a sleeve of this width");
  if (2 * polyline_length(Vec2(s, 0), make_cap(s, lo).half) > target)
    throw Error("", "t-shirt size " + m.size, "the sleeve (upper arm " + format_fixed(m.upper_arm, 3) +
                                                  " m + ease) is wider than its armhole allows");
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (2 * polyline_length(Vec2(s, 0), make_cap(s, mid).half) < target ? lo : hi) = mid;
  }
  const Cap cap = make_cap(s, 0.5 * (lo + hi));
  const double yu = m.sleeve_length - cap.height;  // underarm seam height
  if (yu < 0.02)
    throw Error("", "t-shirt size " + m.size, "the sleeve cap (" + format_fixed(cap.height, 3) +
                                                  " m) is taller than the sleeve length allows");
  const double hw = s - m.sleeve_hem_taper;

  Piece p;
  p.name = "LEFT SLEEVE";
  p.size = m.size;
  p.block = "LEFT_SLEEVE_" + m.size;
  p.category = "SELF";
  p.annotation = "CUT 1 LEFT SLEEVE";
  // Right half of the cap in CCW order runs from (s, yu) to the top; the left half
  // mirrors it. Seen from outside, the left sleeve has its back half on +x.
  std::vector<Vec2> cap_pts;  // CCW, excluding the start (s, yu)
  for (const auto& q : cap.half) cap_pts.push_back(q + Vec2(0, yu));
  for (int i = static_cast<int>(cap.half.size()) - 2; i >= 0; --i) cap_pts.push_back(Vec2(-cap.half[i].x(), cap.half[i].y() + yu));
  cap_pts.push_back(Vec2(-s, yu));
  auto& o = p.boundary;
  o.push_back({Vec2(-hw, 0), PointKind::turn});  // 0 sleeve hem
  o.push_back({Vec2(hw, 0), PointKind::turn});   // 1 right underarm seam (back)
  o.push_back({Vec2(s, yu), PointKind::turn});   // 2 cap
  for (std::size_t i = 0; i + 1 < cap_pts.size(); ++i) o.push_back({cap_pts[i], PointKind::curve});
  o.push_back({cap_pts.back(), PointKind::turn});  // 3 left underarm seam (front)

  // Notches: the armhole's marks at the same distance from the underarm, scaled by
  // cap / armhole so the ease is spread evenly; the shoulder notch where front
  // armhole ends. The cap runs back underarm -> top -> front underarm.
  const double r = target / (arm_front + arm_back);
  const double cap_len = polyline_length(Vec2(s, yu), cap_pts);
  for (const double a : {kArmNotch - kDoubleGap, kArmNotch + kDoubleGap}) {
    const auto [q, d] = point_at(Vec2(s, yu), cap_pts, a * r);
    add_notch(p, q, d);
  }
  for (const double a : {kArmNotch, arm_front}) {
    const auto [q, d] = point_at(Vec2(s, yu), cap_pts, cap_len - a * r);
    add_notch(p, q, d);
  }
  p.grain_line = Segment{Vec2(0.0, 0.03), Vec2(0.0, m.sleeve_length - 0.04)};
  return p;
}

// The right sleeve: the left one mirrored about x = 0, kept counter-clockwise and
// starting at its hem's left corner, so its stretches are numbered as the left's.
Piece right_sleeve(const Piece& left) {
  Piece p = left;
  p.name = "RIGHT SLEEVE";
  p.block = "RIGHT_SLEEVE_" + left.size;
  p.annotation = "CUT 1 RIGHT SLEEVE";
  p.boundary.clear();
  const auto& lb = left.boundary;
  const std::size_t n = lb.size();
  // Reversed mirror: vertex i of the new outline is the mirror of vertex (k - i) mod n;
  // the left's vertex 1 (its hem's right corner) becomes the new hem's left corner.
  for (std::size_t i = 0; i < n; ++i) {
    const auto& c = lb[(1 + n - i) % n];
    p.boundary.push_back({Vec2(-c.p.x(), c.p.y()), c.kind});
  }
  for (auto& nt : p.notches) {
    nt.position.x() = -nt.position.x();
    nt.angle_deg = 180.0 - nt.angle_deg;
    if (nt.angle_deg > 180.0) nt.angle_deg -= 360.0;
    nt.boundary_index = nearest_vertex(p.boundary, nt.position).index;
  }
  p.grain_line = Segment{Vec2(-left.grain_line->a.x(), left.grain_line->a.y()), Vec2(-left.grain_line->b.x(), left.grain_line->b.y())};
  return p;
}

}  // namespace

std::vector<Piece> draft_tshirt(const TShirtMeasurements& m) {
  const std::string entity = "t-shirt size " + m.size;
  for (const auto& [v, what] : {std::pair{m.bust, "bust"}, {m.neck, "neck"}, {m.shoulder, "shoulder length"},
                                {m.length, "length"}, {m.armhole_depth, "armhole depth"},
                                {m.upper_arm, "upper arm"}, {m.sleeve_length, "sleeve length"}})
    if (!(v > 0) || !std::isfinite(v)) throw Error("", entity, std::string(what) + " must be positive (m)");
  if (!(m.shoulder_drop >= 0 && m.shoulder_drop < m.shoulder))
    throw Error("", entity, "the shoulder drop must be at least 0 and less than the shoulder length");
  const BodyFrame f = body_frame(m);
  if (f.SP.x() >= f.W - 0.02)
    throw Error("", entity, "neck plus shoulder (" + format_fixed(f.SP.x(), 3) + " m) reach past the chest half-width (" +
                                format_fixed(f.W, 3) + " m)");
  if (m.armhole_depth <= m.shoulder_drop + 0.05 || m.armhole_depth >= m.length - 0.05)
    throw Error("", entity, "the armhole depth must lie between the shoulder and the hem");
  if (m.front_neck_depth <= 0 || m.back_neck_depth <= 0 || m.front_neck_depth >= m.armhole_depth)
    throw Error("", entity, "neck depths must be positive and above the underarm line");
  Piece front = body(m, false), back = body(m, true);
  const double arm_front = polyline_length(f.UA, armhole(f, false));
  const double arm_back = polyline_length(f.UA, armhole(f, true));
  Piece left = left_sleeve(m, arm_front, arm_back);
  Piece right = right_sleeve(left);
  return {std::move(front), std::move(back), std::move(left), std::move(right)};
}

Style draft_tshirt_style(const std::vector<TShirtMeasurements>& sizes) {
  return graded_style("VGD T-SHIRT", sizes, draft_tshirt);
}

std::vector<SeamPlan> tshirt_seams() {
  // FRONT's +x side and BACK's -x side are the wearer's left (both laid face up).
  // The left sleeve's cap runs (forward) from its back underarm over the top to its
  // front underarm; the armholes, reversed, run the same way: BACK's left armhole
  // (stretch 6 reversed: underarm -> shoulder), then FRONT's right armhole (stretch 2
  // reversed: shoulder -> underarm). The right sleeve mirrors this.
  return {
      {"left side seam", {{"FRONT", 1, 1, false}, {"BACK", 7, 7, true}}},
      {"right side seam", {{"FRONT", 7, 7, false}, {"BACK", 1, 1, true}}},
      {"left shoulder", {{"FRONT", 3, 3, false}, {"BACK", 5, 5, true}}},
      {"right shoulder", {{"FRONT", 5, 5, false}, {"BACK", 3, 3, true}}},
      {"left armhole", {{"LEFT SLEEVE", 2, 2, false}, {"BACK", 6, 6, true}, {"FRONT", 2, 2, true}}},
      {"right armhole", {{"RIGHT SLEEVE", 2, 2, false}, {"FRONT", 6, 6, true}, {"BACK", 2, 2, true}}},
      {"left underarm", {{"LEFT SLEEVE", 3, 3, false}, {"LEFT SLEEVE", 1, 1, true}}},
      {"right underarm", {{"RIGHT SLEEVE", 3, 3, false}, {"RIGHT SLEEVE", 1, 1, true}}},
  };
}

}  // namespace vgd::pattern
