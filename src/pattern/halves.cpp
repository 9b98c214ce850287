#include "vgd/pattern/halves.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "vgd/core/strings.hpp"
#include "vgd/pattern/contour.hpp"
#include "vgd/pattern/roles.hpp"

namespace vgd::pattern {

namespace {

// The piece's "up": along its grain line, else +y.
Vec2 up_of(const Piece& p) {
  if (p.grain_line && (p.grain_line->b - p.grain_line->a).norm() > 0) return (p.grain_line->b - p.grain_line->a).normalized();
  return Vec2::UnitY();
}

Vec2 centroid(const std::vector<ContourPoint>& o) {
  Vec2 c = Vec2::Zero();
  double a2 = 0;
  const std::size_t n = o.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 &p = o[i].p, &q = o[(i + 1) % n].p;
    const double w = p.x() * q.y() - q.x() * p.y();
    a2 += w;
    c += w * (p + q);
  }
  return std::abs(a2) > 0 ? Vec2(c / (3.0 * a2)) : o.front().p;
}

// Whether every vertex of each outline lies within tol of the other outline
// (stops at the first that does not: most pairs differ at once).
bool within(const std::vector<ContourPoint>& a, const std::vector<ContourPoint>& b, double tol) {
  for (const auto& c : a)
    if (nearest_edge(b, c.p).distance > tol) return false;
  for (const auto& c : b)
    if (nearest_edge(a, c.p).distance > tol) return false;
  return true;
}

// The outline's extents along `up` and across it (m).
Vec2 extents(const std::vector<ContourPoint>& o, const Vec2& up) {
  const Vec2 across(up.y(), -up.x());
  double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
  for (const auto& c : o) {
    u0 = std::min(u0, c.p.dot(across)), u1 = std::max(u1, c.p.dot(across));
    v0 = std::min(v0, c.p.dot(up)), v1 = std::max(v1, c.p.dot(up));
  }
  return Vec2(u1 - u0, v1 - v0);
}

// b moved onto a's centroid, reflected across the line along `up` first when asked.
std::vector<ContourPoint> laid_on(const std::vector<ContourPoint>& b, const Vec2& onto, const Vec2& up, bool reflect) {
  const Vec2 cb = centroid(b);
  std::vector<ContourPoint> out = b;
  for (auto& c : out) {
    Vec2 d = c.p - cb;
    if (reflect) d = 2.0 * d.dot(up) * up - d;
    c.p = onto + d;
  }
  return out;
}

// The longest straight run of the outline along `up` with the whole piece on
// one side of its line: its two end vertices. Runs of consecutive edges
// within `tol` of the line through their ends. With `square`, only a run
// the outline leaves at right angles at both ends (its chord over the next
// 2 cm within 10 degrees of square: the outline goes on smoothly across the
// fold once unfolded; a collar's centre back, not its pointed front end).
std::optional<Segment> centre_edge(const std::vector<ContourPoint>& o, const Vec2& up, double tol, bool square = false) {
  const int n = static_cast<int>(o.size());
  const Vec2 across(-up.y(), up.x());
  auto along = [&](int i) {  // edge i runs along up (within 0.5 degree)
    const Vec2 e = o[(i + 1) % n].p - o[i].p;
    const double len = e.norm();
    return len > 0 && std::abs(e.dot(across)) <= std::max(tol, len * std::sin(0.5 * M_PI / 180));
  };
  std::optional<Segment> best;
  double best_len = 0;
  for (int i = 0; i < n; ++i) {
    if (!along(i) || along((i - 1 + n) % n)) continue;  // start of a run
    int j = i;
    while (along(j % n) && j - i < n) {
      const Vec2 a = o[i].p, b = o[(j + 1) % n].p;
      // the run's vertices stay on the line from its start
      if (std::abs((b - a).dot(across)) > tol) break;
      ++j;
    }
    if (j == i) continue;
    const Vec2 a = o[i].p, b = o[j % n].p;
    const double len = (b - a).norm();
    if (len <= best_len) continue;
    if (square) {
      // The chord from the run's end to the first vertex 2 cm away (or the
      // farthest within n vertices), stepping `step` along the outline.
      const auto leaves_square = [&](int from, int step) {
        const Vec2 p0 = o[((from % n) + n) % n].p;
        Vec2 e = Vec2::Zero();
        for (int k = 1; k < n && e.norm() < 0.02; ++k) e = o[(((from + step * k) % n) + n) % n].p - p0;
        return e.norm() > 0 && std::abs(e.normalized().dot(up)) <= std::sin(10 * M_PI / 180);
      };
      if (!leaves_square(i, -1) || !leaves_square(j, +1)) continue;
    }
    double lo = 0, hi = 0;
    for (const auto& c : o) {
      const double s = (c.p - a).dot(across);
      lo = std::min(lo, s), hi = std::max(hi, s);
    }
    if (lo < -tol && hi > tol) continue;  // cloth on both sides: not an edge the piece folds about
    best = Segment{a, b};
    best_len = len;
  }
  return best;
}

double extent_along(const std::vector<ContourPoint>& o, const Vec2& up) {
  double lo = 1e300, hi = -1e300;
  for (const auto& c : o) lo = std::min(lo, c.p.dot(up)), hi = std::max(hi, c.p.dot(up));
  return hi - lo;
}

}  // namespace

std::vector<JoinedPieces> join_pieces_written_per_side(Style& style, double tol) {
  std::vector<JoinedPieces> out;
  std::vector<char> drop(style.pieces.size(), 0);
  auto eligible = [&](const Piece& p) {
    return p.closed && !p.mirror_line && p.quantity <= 1 && p.boundary.size() >= 3 &&
           piece_role(p.name, p.category, p.annotation).role == Role::unknown;
  };
  for (std::size_t i = 0; i < style.pieces.size(); ++i) {
    if (drop[i] || !eligible(style.pieces[i])) continue;
    Piece& a = style.pieces[i];
    const Vec2 up = up_of(a);
    const double area = std::abs(signed_area(a.boundary)), per = perimeter(a.boundary);
    const Vec2 size = extents(a.boundary, up);
    for (std::size_t j = i + 1; j < style.pieces.size(); ++j) {
      const Piece& b = style.pieces[j];
      if (drop[j] || !eligible(b) || b.size != a.size || b.category != a.category || b.fabric != a.fabric) continue;
      if ((up_of(b) - up).norm() > 0.01 && (up_of(b) + up).norm() > 0.01) continue;
      if (std::abs(std::abs(signed_area(b.boundary)) - area) > 0.01 * area ||
          std::abs(perimeter(b.boundary) - per) > 0.01 * per || (extents(b.boundary, up) - size).cwiseAbs().maxCoeff() > 2 * tol)
        continue;
      const Vec2 ca = centroid(a.boundary);
      const bool same = within(a.boundary, laid_on(b.boundary, ca, up, false), tol);
      const bool mirrored = !same && within(a.boundary, laid_on(b.boundary, ca, up, true), tol);
      if (!same && !mirrored) continue;
      JoinedPieces jp;
      jp.size = a.size;
      jp.kept = a.block;
      jp.dropped = b.block;
      if (mirrored) {
        if (const auto c = centre_edge(a.boundary, up, tol);
            c && (c->b - c->a).norm() >= 0.4 * extent_along(a.boundary, up)) {
          Piece whole = a;
          whole.mirror_line = *c;
          if (unfold_about_mirror_line(whole, tol)) {
            for (auto& nt : whole.notches) nt.boundary_index = nearest_vertex(whole.boundary, nt.position).index;
            a = std::move(whole);
            jp.halves = true;
            jp.centre_length = (c->b - c->a).norm();
          }
        }
      }
      if (!jp.halves) a.quantity = 2;
      drop[j] = 1;
      out.push_back(jp);
      break;
    }
  }
  std::vector<Piece> kept;
  for (std::size_t i = 0; i < style.pieces.size(); ++i)
    if (!drop[i]) kept.push_back(std::move(style.pieces[i]));
  style.pieces = std::move(kept);
  return out;
}

std::string describe(const JoinedPieces& j) {
  if (j.halves)
    return "blocks " + j.kept + " and " + j.dropped + " are the left and right halves of one piece (mirror images, " +
           "cut once each): joined along their " + format_fixed(100 * j.centre_length, 1) + " cm centre edge into " +
           j.kept;
  return "blocks " + j.kept + " and " + j.dropped + " have the same outline" + " (or its mirror image), cut once each: " +
         j.kept + " is cut twice instead";
}

TopHalves unfold_top_halves(Style& style, double tol) {
  TopHalves out;
  // Every piece cut 0 times: the field left at its default by a file that
  // says its cutting in the annotations (mirrored.DXF's "2XFABRIC"), not one
  // that states nothing.
  if (!style.pieces.empty() &&
      std::all_of(style.pieces.begin(), style.pieces.end(), [](const Piece& p) { return p.quantity == 0; }))
    return out;
  bool sleeve = false;
  for (const auto& p : style.pieces) {
    if (p.quantity > 1 || p.mirror_line) return out;  // the file states quantities or folds
    const Role r = piece_role(p.name, p.category, p.annotation, style.name).role;
    if (r == Role::leg) return out;
    sleeve = sleeve || r == Role::sleeve;
  }
  if (!sleeve) return out;
  bool bodice = false;  // a front, back or yoke unfolded
  for (auto& p : style.pieces) {
    const RoleGuess g = piece_role(p.name, p.category, p.annotation, style.name);
    const bool band = g.role == Role::collar || g.role == Role::collar_stand;
    if ((g.role != Role::front && g.role != Role::back && g.role != Role::yoke && !band) || g.side != Side::none ||
        !p.closed || p.boundary.size() < 3)
      continue;
    // A collar's or a stand's centre back runs across its length, whatever
    // its grain: along the shorter of its two extents.
    Vec2 up = up_of(p);
    if (band) {
      const Vec2 e = extents(p.boundary, up);
      if (e.x() < e.y()) up = Vec2(up.y(), -up.x());
    }
    const auto c = centre_edge(p.boundary, up, tol, band);
    if (!c || (c->b - c->a).norm() < 0.4 * extent_along(p.boundary, up)) continue;
    if (mirror_symmetric(p.boundary, up, tol)) continue;  // a whole piece with straight sides
    Piece whole = p;
    whole.mirror_line = *c;
    if (!unfold_about_mirror_line(whole, tol)) continue;
    for (auto& nt : whole.notches) nt.boundary_index = nearest_vertex(whole.boundary, nt.position).index;
    whole.quantity = 1;
    p = std::move(whole);
    out.unfolded.push_back({p.size, p.block, (c->b - c->a).norm()});
    bodice = bodice || !band;
  }
  if (!bodice) return out;
  for (auto& p : style.pieces) {
    const RoleGuess g = piece_role(p.name, p.category, p.annotation, style.name);
    if (g.role != Role::sleeve || g.side != Side::none || g.half != Half::none) continue;
    p.quantity = 2;
    out.sleeves_cut_twice.push_back(p.block);
  }
  return out;
}

std::vector<std::string> describe(const TopHalves& h) {
  std::vector<std::string> out;
  for (const auto& u : h.unfolded)
    out.push_back("block " + u.block + " is half a piece (cut once, no side or fold line in the file, a straight " +
                  format_fixed(100 * u.centre_length, 1) + " cm centre edge): unfolded about that edge into the whole piece");
  if (!h.sleeves_cut_twice.empty()) {
    std::string list;
    for (const auto& b : h.sleeves_cut_twice) list += (list.empty() ? "" : ", ") + b;
    out.push_back(h.sleeves_cut_twice.size() == 1
                      ? "sleeve " + list + " is cut twice, left and right: the file cuts it once and names no side"
                      : "sleeves " + list + " are cut twice, left and right: the file cuts them once and names no side");
  }
  return out;
}

void fold_lengthwise(Piece& piece, const Vec2& point, const Vec2& direction) {
  const double len = direction.norm();
  if (!(len > 0) || !std::isfinite(len)) throw std::invalid_argument("fold_lengthwise: the edge's direction is zero");
  const Vec2 across(-direction.y() / len, direction.x() / len);
  const auto fold = [&](Vec2& p) { p -= 0.5 * (p - point).dot(across) * across; };
  // A direction is halved across too (the map is linear about `point`).
  const auto fold_dir = [&](const Vec2& d) { return Vec2(d - 0.5 * d.dot(across) * across); };
  for (auto& c : piece.boundary) fold(c.p);
  for (auto& n : piece.notches) {
    fold(n.position);
    const double a = n.angle_deg * M_PI / 180.0;
    const Vec2 d = fold_dir(Vec2(std::cos(a), std::sin(a)));
    n.angle_deg = std::atan2(d.y(), d.x()) * 180.0 / M_PI;
  }
  for (auto* s : {&piece.grain_line, &piece.mirror_line, &piece.grade_reference})
    if (*s) fold((*s)->a), fold((*s)->b);
  for (auto* lines : {&piece.internal_lines, &piece.cutouts, &piece.sew_lines})
    for (auto& l : *lines)
      for (auto& p : l.points) fold(p);
  for (auto& p : piece.drill_holes) fold(p);
}

}  // namespace vgd::pattern
