#include "vgd/pattern/grading.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <Eigen/Dense>
#include <map>
#include <set>

#include "vgd/pattern/contour.hpp"

namespace vgd::pattern {

namespace {

// m: the smallest distance the alignment treats as a mismatch, so that a
// small piece (a 6 cm collar stand) is not held to a fraction of its size.
constexpr double kMinTolerance = 0.004;

int turns(const Piece& p) {
  return static_cast<int>(
      std::count_if(p.boundary.begin(), p.boundary.end(), [](const ContourPoint& c) { return c.kind == PointKind::turn; }));
}

bool has_marks(const Piece& p) { return !p.notches.empty() || turns(p) > 0; }

// `p` has the marks `source` would give it (a graded block that kept a turn
// point or two of its own has not).
bool marked_as(const Piece& p, const Piece& source) {
  return turns(p) >= turns(source) && p.notches.size() >= source.notches.size();
}

// Arc-length position of each vertex along the closed outline, from vertex 0.
std::vector<double> arc_positions(const std::vector<ContourPoint>& outline) {
  std::vector<double> s(outline.size() + 1, 0.0);
  for (std::size_t i = 0; i < outline.size(); ++i)
    s[i + 1] = s[i] + (outline[(i + 1) % outline.size()].p - outline[i].p).norm();
  return s;
}

// The point at arc length `u` (taken modulo the perimeter) along the outline.
Vec2 point_at(const std::vector<ContourPoint>& outline, const std::vector<double>& s, double u) {
  const double total = s.back();
  u = std::fmod(u, total);
  if (u < 0) u += total;
  const auto it = std::upper_bound(s.begin(), s.end(), u);
  const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(it - s.begin()) - 1, outline.size() - 1);
  const double len = s[i + 1] - s[i];
  const double t = len > 0 ? (u - s[i]) / len : 0.0;
  return (1 - t) * outline[i].p + t * outline[(i + 1) % outline.size()].p;
}

struct Alignment {
  std::vector<int> image;  // per vertex of A: its partner in B, -1 when skipped
  double cost = std::numeric_limits<double>::infinity();
};

// Exterior angle (rad, signed) of the closed polygon at each vertex.
std::vector<double> turning(const std::vector<Vec2>& p) {
  const std::size_t n = p.size();
  std::vector<double> t(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 u = p[i] - p[(i + n - 1) % n], v = p[(i + 1) % n] - p[i];
    if (u.norm() > 0 && v.norm() > 0) t[i] = std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v));
  }
  return t;
}

// Order-keeping alignment of A with B read cyclically from `start`. Pairing
// costs the distance plus `gap` per right angle of difference in how the
// outline turns there; leaving a vertex out costs `gap`, more at a corner, so
// a corner pairs with a corner and an extra point on a straight edge is the
// one left out.
Alignment align(const std::vector<Vec2>& a, const std::vector<Vec2>& b, int start, double gap) {
  const int n = static_cast<int>(a.size()), m = static_cast<int>(b.size());
  const std::vector<double> ta = turning(a), tb = turning(b);
  auto skip = [gap](double t) { return gap * (1 + std::abs(t) / (0.25 * M_PI)); };
  std::vector<double> d((n + 1) * (m + 1), std::numeric_limits<double>::infinity());
  std::vector<unsigned char> from((n + 1) * (m + 1), 0);  // 1 diagonal, 2 skip A, 3 skip B
  auto at = [m](int i, int j) { return i * (m + 1) + j; };
  d[at(0, 0)] = 0;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= m; ++j) {
      if (i == 0 && j == 0) continue;
      double best = std::numeric_limits<double>::infinity();
      unsigned char how = 0;
      if (i > 0 && j > 0) {
        const int jb = (start + j - 1) % m;
        const double c = d[at(i - 1, j - 1)] + (a[i - 1] - b[jb]).norm() +
                         gap * std::abs(ta[i - 1] - tb[jb]) / (0.5 * M_PI);
        if (c < best) best = c, how = 1;
      }
      if (i > 0 && d[at(i - 1, j)] + skip(ta[i - 1]) < best) best = d[at(i - 1, j)] + skip(ta[i - 1]), how = 2;
      if (j > 0) {
        const double c = d[at(i, j - 1)] + skip(tb[(start + j - 1) % m]);
        if (c < best) best = c, how = 3;
      }
      d[at(i, j)] = best;
      from[at(i, j)] = how;
    }
  Alignment out;
  out.cost = d[at(n, m)];
  out.image.assign(n, -1);
  for (int i = n, j = m; i > 0 || j > 0;) {
    const unsigned char how = from[at(i, j)];
    if (how == 1) {
      out.image[i - 1] = (start + j - 1) % m;
      --i, --j;
    } else if (how == 2) {
      --i;
    } else {
      --j;
    }
  }
  return out;
}

}  // namespace

CarriedMarks carry_marks(const Piece& from, Piece& to, double max_rms_fraction) {
  CarriedMarks out;
  if (marked_as(to, from)) {
    out.why = "it has marks of its own";
    return out;
  }
  if (!has_marks(from)) {
    out.why = "the sample size has no marks to carry";
    return out;
  }
  if (from.boundary.size() < 3 || to.boundary.size() < 3) {
    out.why = "an outline has fewer than 3 vertices";
    return out;
  }
  const double area_from = std::abs(signed_area(from.boundary)), area_to = std::abs(signed_area(to.boundary));
  if (!(area_from > 0) || !(area_to > 0)) {
    out.why = "an outline encloses no area";
    return out;
  }
  // First pass: each outline in its own bounding box scaled to the unit square
  // (grade rules grow lengths and widths by different amounts). Second pass:
  // the graded outline mapped onto the sample's by the affine transform that
  // fits the first pass's pairs best, in metres.
  const double size = std::sqrt(area_from);
  auto unit_box = [](const std::vector<ContourPoint>& o) {
    Vec2 lo = o[0].p, hi = o[0].p;
    for (const auto& c : o) lo = lo.cwiseMin(c.p), hi = hi.cwiseMax(c.p);
    const Vec2 ext = (hi - lo).cwiseMax(Vec2::Constant(1e-9));
    std::vector<Vec2> unit;
    for (const auto& c : o) unit.push_back((c.p - 0.5 * (lo + hi)).cwiseQuotient(ext));
    return unit;
  };
  auto best_alignment = [](const std::vector<Vec2>& a, const std::vector<Vec2>& b, double gap) {
    // Start candidates: the three graded vertices nearest the sample's vertex 0.
    std::vector<int> order(b.size());
    for (std::size_t j = 0; j < b.size(); ++j) order[j] = static_cast<int>(j);
    std::sort(order.begin(), order.end(), [&](int x, int y) { return (b[x] - a[0]).norm() < (b[y] - a[0]).norm(); });
    Alignment best;
    for (std::size_t c = 0; c < std::min<std::size_t>(3, order.size()); ++c) {
      Alignment al = align(a, b, order[c], gap);
      if (al.cost < best.cost) best = std::move(al);
    }
    return best;
  };
  std::vector<Vec2> a, b;
  Alignment best = best_alignment(unit_box(from.boundary), unit_box(to.boundary), 0.05);
  for (const auto& p : from.boundary) a.push_back(p.p);
  for (int pass = 0; pass < 2; ++pass) {
    // Least-squares affine map of the paired graded vertices onto the sample's.
    Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
    Eigen::Matrix<double, 3, 2> atb = Eigen::Matrix<double, 3, 2>::Zero();
    int pairs = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (best.image[i] < 0) continue;
      const Vec2& q = to.boundary[best.image[i]].p;
      const Eigen::Vector3d r(q.x(), q.y(), 1.0);
      ata += r * r.transpose();
      atb += r * a[i].transpose();
      ++pairs;
    }
    if (pairs < 3 || std::abs(ata.determinant()) < 1e-30) break;
    const Eigen::Matrix<double, 3, 2> x = ata.ldlt().solve(atb);
    b.clear();
    for (const auto& c : to.boundary) b.push_back(x.transpose() * Eigen::Vector3d(c.p.x(), c.p.y(), 1.0));
    best = best_alignment(a, b, std::max(0.03 * size, kMinTolerance));
  }
  if (b.empty()) {
    out.why = "no alignment of the two outlines was found";
    return out;
  }
  double sum2 = 0;
  int paired = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (best.image[i] < 0) continue;
    sum2 += (a[i] - b[best.image[i]]).squaredNorm();
    ++paired;
  }
  out.unpaired = static_cast<int>(a.size()) - paired;
  out.rms_m = paired > 0 ? std::sqrt(sum2 / paired) : 0.0;
  if (paired == 0 || out.rms_m > std::max(max_rms_fraction * size, kMinTolerance) ||
      out.unpaired * 10 > static_cast<int>(a.size())) {
    out.why = "its outline does not correspond to the sample's point for point (RMS " +
              std::to_string(static_cast<int>(std::lround(out.rms_m * 1000))) + " mm, " + std::to_string(out.unpaired) +
              " of " + std::to_string(a.size()) + " vertices unpaired)";
    return out;
  }

  // Marks on the vertices.
  for (std::size_t i = 0; i < a.size(); ++i) {
    const int j = best.image[i];
    if (j < 0 || from.boundary[i].kind == PointKind::plain || to.boundary[j].kind == PointKind::turn) continue;
    to.boundary[j].kind = from.boundary[i].kind;
    (from.boundary[i].kind == PointKind::turn ? out.turns : out.curves) += 1;
  }
  // Notches: at the same fraction of the arc between the paired vertices
  // before and after them, turned as the outline turned there.
  const std::vector<double> sa = arc_positions(from.boundary), sb = arc_positions(to.boundary);
  const int n = static_cast<int>(a.size()), m = static_cast<int>(b.size());
  const bool own_notches = !to.notches.empty();
  for (const auto& notch : from.notches) {
    if (own_notches) break;
    const NearestEdge ne = nearest_edge(from.boundary, notch.position);
    if (ne.edge < 0) continue;
    int lo = ne.edge, hi = (ne.edge + 1) % n;
    for (int step = 0; step < n && best.image[lo] < 0; ++step) lo = (lo + n - 1) % n;
    for (int step = 0; step < n && best.image[hi] < 0; ++step) hi = (hi + 1) % n;
    const double u = sa[ne.edge] + ne.t * (sa[ne.edge + 1] - sa[ne.edge]);
    auto arc_between = [](const std::vector<double>& s, int x, int y) {
      const double d = s[y] - s[x];
      return d > 0 ? d : d + s.back();
    };
    const double span_a = arc_between(sa, lo, hi);
    double f = 0;
    if (span_a > 0) {
      double du = u - sa[lo];
      if (du < 0) du += sa.back();
      f = std::clamp(du / span_a, 0.0, 1.0);
    }
    const int jl = best.image[lo], jh = best.image[hi];
    const double span_b = (jl == jh) ? 0.0 : arc_between(sb, jl, jh);
    Notch c = notch;
    c.position = point_at(to.boundary, sb, sb[jl] + f * span_b);
    // Turn the cut as the edge under it turned.
    const NearestEdge be = nearest_edge(to.boundary, c.position);
    if (be.edge >= 0) {
      const Vec2 ea = from.boundary[(ne.edge + 1) % n].p - from.boundary[ne.edge].p;
      const Vec2 eb = to.boundary[(be.edge + 1) % m].p - to.boundary[be.edge].p;
      c.angle_deg += (std::atan2(eb.y(), eb.x()) - std::atan2(ea.y(), ea.x())) * 180.0 / M_PI;
      c.angle_deg = std::remainder(c.angle_deg, 360.0);
    }
    c.boundary_index = nearest_vertex(to.boundary, c.position).index;
    to.notches.push_back(c);
    ++out.notches;
  }
  // The graded outline starts where the sample's does, so that boundary
  // stretch k is the same stretch in every size (seam plans name stretches
  // by index).
  if (const int start = best.image[0]; start > 0) {
    std::rotate(to.boundary.begin(), to.boundary.begin() + start, to.boundary.end());
    for (auto& c : to.notches) c.boundary_index = nearest_vertex(to.boundary, c.position).index;
  }
  out.carried = true;
  return out;
}

std::vector<std::pair<std::string, CarriedMarks>> carry_sample_marks(Style& style) {
  std::vector<std::pair<std::string, CarriedMarks>> out;
  std::map<std::string, std::vector<Piece*>> by_name;
  for (auto& p : style.pieces) by_name[p.name].push_back(&p);
  for (auto& [name, blocks] : by_name) {
    if (blocks.size() < 2) continue;
    // Two blocks of one size under one name are two pieces, not two grades.
    std::set<std::string> sizes;
    for (const Piece* p : blocks) sizes.insert(p->size);
    if (sizes.size() != blocks.size()) continue;
    Piece* sample = nullptr;
    for (Piece* p : blocks)
      if (p->size == style.sample_size && has_marks(*p)) sample = p;
    if (!sample) {
      int most = 0;
      for (Piece* p : blocks)
        if (const int marks = turns(*p) + static_cast<int>(p->notches.size()); marks > most) most = marks, sample = p;
    }
    if (!sample) continue;
    // Size by size outwards from the sample, each block taking the marks of
    // its neighbour already marked: neighbouring sizes differ by one grade
    // step, far sizes by non-affine amounts (a 70 against a 50).
    auto rank = [&](const Piece* p) {
      return static_cast<int>(std::find(style.sizes.begin(), style.sizes.end(), p->size) - style.sizes.begin());
    };
    std::stable_sort(blocks.begin(), blocks.end(), [&](const Piece* x, const Piece* y) { return rank(x) < rank(y); });
    const int at = static_cast<int>(std::find(blocks.begin(), blocks.end(), sample) - blocks.begin());
    for (const int dir : {+1, -1}) {
      const Piece* source = sample;
      for (int i = at + dir; i >= 0 && i < static_cast<int>(blocks.size()); i += dir) {
        Piece* p = blocks[i];
        if (marked_as(*p, *source)) {
          source = p;
          continue;
        }
        CarriedMarks c = carry_marks(*source, *p);
        if (c.carried) source = p;
        out.emplace_back(p->block, std::move(c));
      }
    }
  }
  return out;
}

}  // namespace vgd::pattern
