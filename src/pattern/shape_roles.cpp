#include "vgd/pattern/shape_roles.hpp"

#include <algorithm>
#include <cmath>

#include "vgd/core/strings.hpp"
#include "vgd/pattern/contour.hpp"

namespace vgd::pattern {

namespace {

// The outline in the piece's frame: v along the grain (up), u across it.
struct Frame {
  Vec2 up = Vec2::UnitY(), across = Vec2::UnitX();
  double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
  explicit Frame(const Piece& p) {
    if (p.grain_line && (p.grain_line->b - p.grain_line->a).norm() > 0)
      up = (p.grain_line->b - p.grain_line->a).normalized();
    across = Vec2(up.y(), -up.x());
    for (const auto& c : p.boundary) {
      u0 = std::min(u0, c.p.dot(across)), u1 = std::max(u1, c.p.dot(across));
      v0 = std::min(v0, c.p.dot(up)), v1 = std::max(v1, c.p.dot(up));
    }
  }
  double width() const { return u1 - u0; }
  double length() const { return v1 - v0; }
};

// Where the outline crosses its centre line highest (along the grain): how
// far that lies below the piece's top is its neckline's depth.
double middle_depth(const Piece& p, const Frame& f) {
  const double mid = 0.5 * (f.u0 + f.u1);
  double top = -1e300;
  const std::size_t n = p.boundary.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 &a = p.boundary[i].p, &b = p.boundary[(i + 1) % n].p;
    const double ua = a.dot(f.across), ub = b.dot(f.across);
    if ((ua - mid) * (ub - mid) > 0 || ua == ub) continue;
    top = std::max(top, (a + (mid - ua) / (ub - ua) * (b - a)).dot(f.up));
  }
  return top > -1e300 ? f.v1 - top : 0.0;
}

std::string cm(double m) { return format_fixed(100 * m, 1) + " cm"; }

}  // namespace

std::vector<ShapeRole> roles_from_shapes(const std::vector<const Piece*>& pieces) {
  std::vector<ShapeRole> out(pieces.size());
  std::vector<std::size_t> bodies;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const Piece& p = *pieces[i];
    if (p.boundary.size() < 3) continue;
    const Frame f(p);
    const double w = f.width(), l = f.length();
    if (std::min(w, l) < 0.05 && std::max(w, l) >= 4 * std::min(w, l)) {
      out[i] = {Role::binding, "a strip " + cm(std::min(w, l)) + " by " + cm(std::max(w, l))};
      continue;
    }
    // The highest point and how wide the outline is a tenth of its length below it.
    double apex_u = 0, apex_v = -1e300;
    for (const auto& c : p.boundary)
      if (c.p.dot(f.up) > apex_v) apex_v = c.p.dot(f.up), apex_u = c.p.dot(f.across);
    const bool centred = std::abs(apex_u - 0.5 * (f.u0 + f.u1)) <= 0.1 * w;
    const double below = width_at(p.boundary, f.up, f.v1 - 0.1 * l);
    if (centred && below < 0.5 * w) {
      out[i] = {Role::sleeve, "a cap, its top centred, " + cm(below) + " wide a tenth of its length below it (" +
                                  cm(w) + " wide)"};
      continue;
    }
    if (l >= 0.35 && w >= 0.25) bodies.push_back(i);
  }
  if (bodies.size() == 2) {
    const double d0 = middle_depth(*pieces[bodies[0]], Frame(*pieces[bodies[0]]));
    const double d1 = middle_depth(*pieces[bodies[1]], Frame(*pieces[bodies[1]]));
    if (std::abs(d0 - d1) >= 0.01) {
      const std::size_t front = d0 > d1 ? bodies[0] : bodies[1], back = d0 > d1 ? bodies[1] : bodies[0];
      out[front] = {Role::front, "the deeper neckline, " + cm(std::max(d0, d1))};
      out[back] = {Role::back, "the shallower neckline, " + cm(std::min(d0, d1))};
    }
  }
  return out;
}

}  // namespace vgd::pattern
