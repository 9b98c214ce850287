// The lab's analytic references (../shared/reference/mechanics.md §1, §2, §6):
// inextensible Euler-Bernoulli cantilevers at large rotation, solved by
// shooting on the clamp curvature θ'(0) with classical RK4 in arc length;
// Cusick's drape-coefficient arithmetic.
#include <array>
#include <cmath>
#include <functional>
#include <numbers>

#include "vgd/lab/lab.hpp"

namespace vgd::lab {

namespace {

// State along s/L: θ (rad, below the horizontal), θ', x/L, w/L (downward).
using Y = std::array<double, 4>;

// θ'' = −load(s) cos θ, θ(0) = 0, θ'(0) = kappa0; integrated to s = 1.
Y shoot(const std::function<double(double)>& load, double kappa0) {
  constexpr int kSteps = 4000;
  const double h = 1.0 / kSteps;
  auto rhs = [&](double s, const Y& y) {
    return Y{y[1], -load(s) * std::cos(y[0]), std::cos(y[0]), std::sin(y[0])};
  };
  Y y{0.0, kappa0, 0.0, 0.0};
  for (int i = 0; i < kSteps; ++i) {
    const double s = i * h;
    auto add = [](const Y& a, const Y& b, double f) { return Y{a[0] + f * b[0], a[1] + f * b[1], a[2] + f * b[2], a[3] + f * b[3]}; };
    const Y k1 = rhs(s, y), k2 = rhs(s + h / 2, add(y, k1, h / 2)), k3 = rhs(s + h / 2, add(y, k2, h / 2)),
            k4 = rhs(s + h, add(y, k3, h));
    for (int c = 0; c < 4; ++c) y[c] += h / 6 * (k1[c] + 2 * k2[c] + 2 * k3[c] + k4[c]);
  }
  return y;
}

// The monotone (physical) equilibrium: the largest clamp curvature in
// (0, kappa_max] with θ'(1) = 0 (mechanics.md §1, note on inflected solutions).
Elastica solve(const std::function<double(double)>& load, double kappa_max) {
  auto tip_moment = [&](double kappa0) { return shoot(load, kappa0)[1]; };
  constexpr int kScan = 400;
  double hi = kappa_max, f_hi = tip_moment(hi), lo = hi;
  for (int i = kScan - 1; i >= 0; --i) {
    lo = kappa_max * i / kScan;
    if (tip_moment(lo) * f_hi <= 0.0) break;
    hi = lo;
  }
  for (int it = 0; it < 80; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (tip_moment(mid) * f_hi <= 0.0) lo = mid;
    else hi = mid;
  }
  const Y y = shoot(load, 0.5 * (lo + hi));
  return {1.0 - y[2], y[3], y[0]};
}

}  // namespace

double Elastica::chord_deg() const { return std::atan2(w_over_L, 1.0 - u_over_L) * 180.0 / std::numbers::pi; }

Elastica tip_load_elastica(double k) {
  return solve([k](double) { return k; }, k);
}

Elastica heavy_elastica(double g) {
  return solve([g](double s) { return g * (1.0 - s); }, 0.5 * g);
}

double peirce_bending_length_over_L(double chord_rad) {
  return std::cbrt(std::cos(0.5 * chord_rad) / (8.0 * std::tan(chord_rad)));
}

double drape_coefficient(double shadow_area, double specimen_diameter, double disk_diameter) {
  const double disk = std::numbers::pi / 4 * disk_diameter * disk_diameter;
  return (shadow_area - disk) / (std::numbers::pi / 4 * specimen_diameter * specimen_diameter - disk);
}

}  // namespace vgd::lab
