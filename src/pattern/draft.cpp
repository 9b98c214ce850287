#include "vgd/pattern/draft.hpp"

#include <algorithm>
#include <cmath>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/pattern/contour.hpp"

namespace vgd::pattern {

std::vector<SkirtMeasurements> skirt_size_table() {
  // size, waist, hip (m). Hip depth and length grow slightly with size.
  const struct { const char* size; double waist, hip; } rows[] = {
      {"34", 0.64, 0.90}, {"36", 0.68, 0.94}, {"38", 0.72, 0.97}, {"40", 0.76, 1.00}, {"42", 0.80, 1.03}};
  std::vector<SkirtMeasurements> out;
  int step = -2;
  for (const auto& r : rows) {
    SkirtMeasurements m;
    m.size = r.size;
    m.waist = r.waist;
    m.hip = r.hip;
    m.hip_depth = 0.20 + 0.0025 * step;
    m.length = 0.60 + 0.005 * step;
    out.push_back(m);
    ++step;
  }
  return out;
}

namespace {

// Quadratic Bézier from a to b with control c, n segments (excluding a).
void bezier(std::vector<ContourPoint>& out, const Vec2& a, const Vec2& c, const Vec2& b, int n) {
  for (int i = 1; i <= n; ++i) {
    const double t = static_cast<double>(i) / n;
    const Vec2 p = (1 - t) * (1 - t) * a + 2 * (1 - t) * t * c + t * t * b;
    out.push_back({p, i == n ? PointKind::turn : PointKind::curve});
  }
}

// A skirt panel, hem on y = 0, centred on x = 0, waist at y = length.
Piece panel(const SkirtMeasurements& m, bool back) {
  const double hip_half = (m.hip + m.hip_ease) / 4.0;      // half of one panel at the hip
  const double waist_half = (m.waist + m.waist_ease) / 4.0;
  const double hem_half = hip_half + m.flare;
  const double hip_y = m.length - m.hip_depth;
  const double rise = 0.012;                  // side seams rise at the waist so the waist curve meets them square
  const double centre_dip = back ? 0.01 : 0.0;  // the back waist sits a little lower at centre back

  Piece p;
  p.name = back ? "BACK" : "FRONT";
  p.size = m.size;
  p.block = p.name + "_" + m.size;
  p.quantity = 1;
  p.category = "SELF";
  p.annotation = back ? "CUT 1 BACK" : "CUT 1 FRONT";

  auto& o = p.boundary;
  // Hem, left to right (straight: an A-line hem is nearly straight at this flare).
  o.push_back({Vec2(-hem_half, 0.0), PointKind::turn});
  o.push_back({Vec2(hem_half, 0.0), PointKind::turn});
  // Right side seam: straight from hem to hip, then a curve to the waist.
  const Vec2 hip_r(hip_half, hip_y), waist_r(waist_half, m.length + rise);
  const int n_side = 6;
  for (int i = 1; i <= n_side; ++i) {
    const double t = static_cast<double>(i) / n_side;
    o.push_back({Vec2(hem_half, 0.0) + t * (hip_r - Vec2(hem_half, 0.0)), i == n_side ? PointKind::curve : PointKind::plain});
  }
  bezier(o, hip_r, Vec2(hip_half, hip_y + 0.6 * m.hip_depth), waist_r, 8);
  // Waist: a shallow curve through the centre.
  bezier(o, waist_r, Vec2(0.0, m.length - centre_dip), Vec2(-waist_half, m.length + rise), 12);
  // Left side seam, mirrored.
  const Vec2 hip_l(-hip_half, hip_y);
  std::vector<ContourPoint> left;
  bezier(left, Vec2(-waist_half, m.length + rise), Vec2(-hip_half, hip_y + 0.6 * m.hip_depth), hip_l, 8);
  left.back().kind = PointKind::curve;  // the hip point is on a smooth seam, like hip_r
  for (auto& c : left) o.push_back(c);
  for (int i = 1; i < n_side; ++i) {
    const double t = static_cast<double>(i) / n_side;
    o.push_back({hip_l + t * (Vec2(-hem_half, 0.0) - hip_l), PointKind::plain});
  }
  remove_duplicate_vertices(o);
  make_counter_clockwise(o);
  // The back opens at centre back: a turn point there splits the waist into two
  // stretches, so the waistband seam can start and end at the opening (skirt_seams).
  // The waist curve's middle vertex lies exactly on x = 0 (a symmetric Bézier at t = 1/2).
  if (back)
    for (auto& c : o)
      if (c.p.x() == 0.0 && c.p.y() > hip_y) c.kind = PointKind::turn;

  // Side-seam notches just below the hip line, on the straight part of the seam:
  // one at the front, a pair 12 mm apart at the back (the pattern maker's code).
  auto notch = [&](const Vec2& at, double angle) {
    Notch n;
    n.position = at;
    n.angle_deg = angle;
    n.length_m = 0.004;
    n.boundary_index = nearest_vertex(o, at).index;
    p.notches.push_back(n);
  };
  const double notch_y = hip_y - 0.02;
  const std::vector<double> heights = back ? std::vector<double>{notch_y - 0.006, notch_y + 0.006}
                                           : std::vector<double>{notch_y};
  for (const double side : {1.0, -1.0})
    for (const double y : heights) {
      const double x = side * (hem_half + (y / hip_y) * (hip_half - hem_half));
      notch(Vec2(x, y), side > 0 ? 180.0 : 0.0);
    }
  // Centre front/back notch at the waist.
  notch(Vec2(0.0, m.length + 0.5 * (rise - centre_dip)), -90.0);  // the waist curve's midpoint

  p.grain_line = Segment{Vec2(0.0, 0.1), Vec2(0.0, m.length - 0.1)};
  return p;
}

Piece waistband(const SkirtMeasurements& m) {
  const double len = m.waist + m.waist_ease + m.waistband_overlap;
  const double h = 2.0 * m.waistband_width;  // folded in half lengthwise
  Piece p;
  p.name = "WAISTBAND";
  p.size = m.size;
  p.block = p.name + "_" + m.size;
  p.category = "SELF";
  p.annotation = "CUT 1, FOLD LENGTHWISE";
  // The lower edge has a turn point where the centre-back overlap (button stand)
  // ends, so the waist seam can leave the overlap open.
  p.boundary = {{Vec2(0, 0), PointKind::turn}, {Vec2(m.waistband_overlap, 0), PointKind::turn},
                {Vec2(len, 0), PointKind::turn},
                {Vec2(len, h), PointKind::turn}, {Vec2(0, h), PointKind::turn}};
  // Side seams and centre front along the waistband (from the back opening).
  const double quarter = (m.waist + m.waist_ease) / 4.0;
  for (const double x : {m.waistband_overlap + quarter, m.waistband_overlap + 2 * quarter,
                         m.waistband_overlap + 3 * quarter}) {
    Notch n;
    n.position = Vec2(x, 0.0);
    n.angle_deg = 90.0;
    n.length_m = 0.004;
    p.notches.push_back(n);
  }
  // Fold line along the middle, grain along the length.
  p.internal_lines.push_back({{Vec2(0, m.waistband_width), Vec2(len, m.waistband_width)}, false});
  p.grain_line = Segment{Vec2(0.05, h / 2 + 0.01), Vec2(len - 0.05, h / 2 + 0.01)};
  return p;
}

}  // namespace

std::vector<Piece> draft_skirt(const SkirtMeasurements& m) {
  const std::string entity = "skirt size " + m.size;
  for (const auto& [v, what] : {std::pair{m.waist, "waist"}, {m.hip, "hip"}, {m.hip_depth, "hip depth"},
                                {m.length, "length"}, {m.waistband_width, "waistband width"}})
    if (!(v > 0) || !std::isfinite(v)) throw Error("", entity, std::string(what) + " must be positive (m)");
  if (m.waist + m.waist_ease > m.hip + m.hip_ease)
    throw Error("", entity, "waist (" + format_fixed(m.waist, 3) + " m) is larger than hip (" +
                                format_fixed(m.hip, 3) + " m): this draft needs a waist smaller than the hip");
  if (m.hip_depth >= m.length)
    throw Error("", entity, "hip depth must be shorter than the skirt length");
  return {panel(m, false), panel(m, true), waistband(m)};
}

Style draft_skirt_style(const std::vector<SkirtMeasurements>& sizes) {
  return graded_style("VGD A-LINE SKIRT", sizes, draft_skirt);
}

std::vector<SeamPlan> skirt_seams() {
  // FRONT stretches: 0 hem, 1 right side, 2 waist, 3 left side. BACK: 0 hem,
  // 1 right side, 2 waist right half (to centre back), 3 waist left half, 4 left
  // side. WAISTBAND: 0 overlap, 1 lower edge, 2 right end, 3 top, 4 left end.
  // FRONT's right side (+x) is the wearer's left, like BACK's left side (-x).
  return {
      {"left side seam", {{"FRONT", 1, 1, false}, {"BACK", 4, 4, true}}},
      {"right side seam", {{"FRONT", 3, 3, false}, {"BACK", 1, 1, true}}},
      {"waist seam", {{"WAISTBAND", 1, 1, false}, {"BACK", 2, 2, true}, {"FRONT", 2, 2, true}, {"BACK", 3, 3, true}}},
  };
}

}  // namespace vgd::pattern
