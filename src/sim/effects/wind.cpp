// Wind on faces (seed 000: proportional to the wind's component along the face
// normal). f_face = c·A·((w - v_face)·n) n, split equally over the corners.
// Turbulence: a deterministic sum of three sines per axis with seeded phases,
// travelling with the wind so that gusts sweep across the cloth. Cost per call:
// 9 sin/cos for the instant plus a few multiply-adds per face.
#include <cmath>
#include <random>
#include <vector>

#include "vgd/sim/effects/basic.hpp"

namespace vgd::sim {

namespace {

struct Gusts {
  double freq[3][3];
  double phase[3][3];
};

Gusts gusts(const WindDef& d) {
  std::mt19937 rng(d.seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  Gusts g{};
  for (int axis = 0; axis < 3; ++axis)
    for (int k = 0; k < 3; ++k) {
      g.freq[axis][k] = d.gust_frequency * (0.5 + 1.5 * u01(rng));  // 0.5x .. 2x the gust rate
      g.phase[axis][k] = 2.0 * M_PI * u01(rng);
    }
  return g;
}

Vec3 wind(const WindDef& d, const Gusts& g, double t, const Vec3& p) {
  if (d.turbulence == 0.0) return d.velocity;
  const double speed = d.velocity.norm();
  // Gusts travel with the mean wind: what hits p at t left the origin at t - (p·ŵ)/|w|.
  const double tau = speed > 0 ? t - p.dot(d.velocity) / (speed * speed) : t;
  Vec3 n;
  for (int axis = 0; axis < 3; ++axis) {
    double s = 0.0;
    for (int k = 0; k < 3; ++k) s += std::sin(2.0 * M_PI * g.freq[axis][k] * tau + g.phase[axis][k]);
    n[axis] = s / 3.0;  // in [-1, 1]
  }
  // Along-wind gusts scale the speed; cross-wind ones turn it.
  const double scale = std::max(speed, 1e-9);
  return d.velocity + d.turbulence * scale * n;
}

class Wind final : public Effect {
 public:
  explicit Wind(const WindDef& d) : def_(d), gusts_(gusts(d)) {}
  const char* name() const override { return "wind"; }
  void add_forces(const Eval& e, VecX& f) override {
    const auto& tris = e.model.triangles;
    if (def_.turbulence != 0.0 && delay_.empty()) prepare_gusts(e.model);
    // The gust phases of this instant, shared by every face (9 sin/cos per call).
    double sw[3][3], cw[3][3];
    if (def_.turbulence != 0.0)
      for (int axis = 0; axis < 3; ++axis)
        for (int k = 0; k < 3; ++k) {
          const double a = 2.0 * M_PI * gusts_.freq[axis][k] * e.t + gusts_.phase[axis][k];
          sw[axis][k] = std::sin(a);
          cw[axis][k] = std::cos(a);
        }
    const double scale = def_.turbulence * std::max(def_.velocity.norm(), 1e-9);
    for (std::size_t ti = 0; ti < tris.size(); ++ti) {
      const auto& t = tris[ti];
      const Vec3 a = at(e.x, t[0]), b = at(e.x, t[1]), c = at(e.x, t[2]);
      const Vec3 cross = (b - a).cross(c - a);  // |cross| = 2A, direction n
      const double len = cross.norm();
      if (len == 0.0) continue;
      Vec3 w = def_.velocity;
      if (def_.turbulence != 0.0) {
        // sin(ωt + φ - ωs) = sin(ωt + φ) cos(ωs) - cos(ωt + φ) sin(ωs), with the
        // delay s of this face precomputed: gusts sweep across the cloth.
        const double* d = &delay_[ti * 18];
        for (int axis = 0; axis < 3; ++axis) {
          double sum = 0.0;
          for (int k = 0; k < 3; ++k) sum += sw[axis][k] * d[2 * (3 * axis + k)] - cw[axis][k] * d[2 * (3 * axis + k) + 1];
          w[axis] += scale * sum / 3.0;
        }
      }
      const Vec3 vface = (at(e.v, t[0]) + at(e.v, t[1]) + at(e.v, t[2])) / 3.0;
      // c A (rel·n) n = c (rel·cross) cross / (2 |cross|)
      const Vec3 ff = def_.coefficient * (w - vface).dot(cross) / (2.0 * len) * cross;
      for (int k = 0; k < 3; ++k) at(f, t[k]) += ff / 3.0;
    }
  }
  // The velocity part only (relative wind): an approximation, hence false.
  bool add_jacobian(const Eval& e, Triplets&, Triplets& dfdv) override {
    for (const auto& t : e.model.triangles) {
      const Vec3 a = at(e.x, t[0]), b = at(e.x, t[1]), c = at(e.x, t[2]);
      const Vec3 cross = (b - a).cross(c - a);
      const double len = cross.norm();
      if (len == 0.0) continue;
      const Mat3 blk = -def_.coefficient / (2.0 * len) * cross * cross.transpose() / 9.0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) add_block(dfdv, t[i], t[j], blk);
    }
    return false;
  }
  void add_stiffness_bound(const Model& m, VecX&, VecX& c) const override {
    // |df_i/dv_j| summed over a face's corners: c A / 3 per face at each corner.
    for (const auto& t : m.triangles) {
      const Vec2 a = m.uv[t[1]] - m.uv[t[0]], b = m.uv[t[2]] - m.uv[t[0]];
      const double area = 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
      for (int k : t) c[k] += def_.coefficient * area / 3.0;
    }
  }

 private:
  // Each face's gust delay is taken at its rest centroid (x0): the gust field
  // travels with the mean wind over where the cloth started. Exact for
  // wind_at() at those points; the cloth's own motion shifts it by a fraction
  // of a gust wavelength, which turbulence does not resolve anyway.
  void prepare_gusts(const Model& m) {
    const double speed = def_.velocity.norm();
    delay_.resize(m.triangles.size() * 18);
    for (std::size_t ti = 0; ti < m.triangles.size(); ++ti) {
      const auto& t = m.triangles[ti];
      const Vec3 centre = (at(m.x0, t[0]) + at(m.x0, t[1]) + at(m.x0, t[2])) / 3.0;
      const double s = speed > 0 ? centre.dot(def_.velocity) / (speed * speed) : 0.0;
      for (int axis = 0; axis < 3; ++axis)
        for (int k = 0; k < 3; ++k) {
          const double ws = 2.0 * M_PI * gusts_.freq[axis][k] * s;
          delay_[ti * 18 + 2 * (3 * axis + k)] = std::cos(ws);
          delay_[ti * 18 + 2 * (3 * axis + k) + 1] = std::sin(ws);
        }
    }
  }

  WindDef def_;
  Gusts gusts_;
  std::vector<double> delay_;  // per face: cos and sin of ω·delay for 3 axes x 3 sines
};

}  // namespace

Vec3 wind_at(const WindDef& def, double t, const Vec3& p) { return wind(def, gusts(def), t, p); }

std::unique_ptr<Effect> make_wind(const WindDef& def) { return std::make_unique<Wind>(def); }

}  // namespace vgd::sim
