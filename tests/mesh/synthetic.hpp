#pragma once
// Synthetic pieces shared by the mesh tests: shapes chosen for what they stress.
#include <cmath>
#include <vector>

#include "vgd/pattern/piece.hpp"

namespace vgd::test {

using pattern::ContourPoint;
using pattern::Piece;
using pattern::Vec2;

inline constexpr double kPi = 3.14159265358979323846;

inline std::vector<ContourPoint> contour(const std::vector<Vec2>& pts) {
  std::vector<ContourPoint> c;
  for (const Vec2& p : pts) c.push_back({p, pattern::PointKind::plain});
  return c;
}

inline Piece piece(const std::string& name, const std::vector<Vec2>& outline) {
  Piece p;
  p.block = p.name = name;
  p.size = "M";
  p.boundary = contour(outline);
  return p;
}

// 0.5 m square.
inline std::vector<Vec2> square(double s = 0.5) { return {{0, 0}, {s, 0}, {s, s}, {0, s}}; }

// L-shape, 0.4 x 0.6 m with a 0.25 m notch: one reflex corner.
inline std::vector<Vec2> l_shape() { return {{0, 0}, {0.4, 0}, {0.4, 0.2}, {0.15, 0.2}, {0.15, 0.6}, {0, 0.6}}; }

// Concave outline with a 10° spike sticking out of its top edge, and a notch.
inline std::vector<Vec2> spiked() {
  const double half = 0.2 * std::tan(5.0 * kPi / 180.0);  // spike 0.2 m tall, 10° at its tip
  return {{0, 0}, {0.5, 0}, {0.5, 0.3}, {0.3 + half, 0.3}, {0.3, 0.5}, {0.3 - half, 0.3},
          {0.2, 0.3}, {0.15, 0.2}, {0.1, 0.3}, {0, 0.3}};
}

// Circle (polygon) centred at c.
inline std::vector<Vec2> circle(Vec2 c, double r, int n, bool ccw = true) {
  std::vector<Vec2> out;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * kPi * i / n * (ccw ? 1 : -1);
    out.push_back(c + r * Vec2(std::cos(a), std::sin(a)));
  }
  return out;
}

// A sleeve-like pattern piece: straight hem and underarm seams and a sleeve-cap
// curve, 500 vertices in all, the way ASTM exports draw curves densely.
inline std::vector<Vec2> sleeve(int n = 500) {
  std::vector<Vec2> out;
  const int cap = n - 4;  // the cap curve: every vertex but the hem corners and underarm points
  out.push_back({0.05, 0.0});
  out.push_back({0.40, 0.0});
  out.push_back({0.45, 0.35});
  // Cap from (0.45, 0.35) over the top back to (0, 0.35): a skewed bell curve.
  for (int i = 1; i <= cap; ++i) {
    const double t = static_cast<double>(i) / (cap + 1);
    const double x = 0.45 * (1 - t);
    const double bump = std::exp(-std::pow((t - 0.45) / 0.22, 2));
    out.push_back({x, 0.35 + 0.16 * bump + 0.01 * std::sin(6 * kPi * t) * t * (1 - t)});
  }
  out.push_back({0.0, 0.35});
  return out;
}

}  // namespace vgd::test
