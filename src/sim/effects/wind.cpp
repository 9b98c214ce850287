// Wind on faces (seed 000: proportional to the wind's component along the face
// normal). f_face = c·A·((w - v_face)·n) n, split equally over the corners.
// Turbulence: a deterministic sum of three sines per axis with seeded phases,
// travelling with the wind so that gusts sweep across the cloth (sampled once
// per call along the wind, interpolated per face).
#include <algorithm>
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
    const bool gusty = def_.turbulence != 0.0;
    if (gusty) sample_gusts(e.model, e.t);
    // Raw loops: this kernel runs once per face per force evaluation.
    const double* x = e.x.data();
    const double* v = e.v.data();
    double* out = f.data();
    const double k = def_.coefficient / 6.0;  // c/(2|cross|) · (1/3 per corner) · |cross| folded below
    for (std::size_t ti = 0; ti < tris.size(); ++ti) {
      const int i0 = 3 * tris[ti][0], i1 = 3 * tris[ti][1], i2 = 3 * tris[ti][2];
      const double e1x = x[i1] - x[i0], e1y = x[i1 + 1] - x[i0 + 1], e1z = x[i1 + 2] - x[i0 + 2];
      const double e2x = x[i2] - x[i0], e2y = x[i2 + 1] - x[i0 + 1], e2z = x[i2 + 2] - x[i0 + 2];
      const double cx = e1y * e2z - e1z * e2y, cy = e1z * e2x - e1x * e2z, cz = e1x * e2y - e1y * e2x;
      const double len2 = cx * cx + cy * cy + cz * cz;  // |cross|² = 4A²
      if (len2 == 0.0) continue;
      const Vec3 w = gusty ? (1.0 - weight_[ti]) * table_[slot_[ti]] + weight_[ti] * table_[slot_[ti] + 1]
                           : def_.velocity;
      constexpr double third = 1.0 / 3.0;  // a multiply, not three divisions, per face
      const double rx = w.x() - (v[i0] + v[i1] + v[i2]) * third;
      const double ry = w.y() - (v[i0 + 1] + v[i1 + 1] + v[i2 + 1]) * third;
      const double rz = w.z() - (v[i0 + 2] + v[i1 + 2] + v[i2 + 2]) * third;
      // Per corner: c A (rel·n) n / 3 = c (rel·cross) cross / (6 |cross|).
      const double s = k * (rx * cx + ry * cy + rz * cz) / std::sqrt(len2);
      const double fx = s * cx, fy = s * cy, fz = s * cz;
      for (const int i : {i0, i1, i2}) {
        out[i] += fx;
        out[i + 1] += fy;
        out[i + 2] += fz;
      }
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
  // Gusts travel with the mean wind, so a face feels the gust field delayed by
  // its distance along the wind over the wind speed. The delay is taken at the
  // face's rest centroid (x0), and the field is sampled once per call at delays
  // spaced so that the fastest sine advances at most kPhaseStep rad between
  // samples; faces interpolate linearly. Error ≤ kPhaseStep²/8 of the gust
  // amplitude (0.125 %); cost: 9 sines per sample instead of 9 per face.
  static constexpr double kPhaseStep = 0.1;  // rad

  void sample_gusts(const Model& m, double t) {
    if (delay_.empty() && !m.triangles.empty()) {
      const double speed = def_.velocity.norm();
      delay_.resize(m.triangles.size());
      for (std::size_t ti = 0; ti < m.triangles.size(); ++ti) {
        const auto& tr = m.triangles[ti];
        const Vec3 centre = (at(m.x0, tr[0]) + at(m.x0, tr[1]) + at(m.x0, tr[2])) / 3.0;
        delay_[ti] = speed > 0 ? centre.dot(def_.velocity) / (speed * speed) : 0.0;
      }
      s_min_ = *std::min_element(delay_.begin(), delay_.end());
      const double span = *std::max_element(delay_.begin(), delay_.end()) - s_min_;
      double omega_max = 0.0;
      for (const auto& row : gusts_.freq)
        for (double fq : row) omega_max = std::max(omega_max, 2.0 * M_PI * fq);
      const int samples = std::clamp(static_cast<int>(std::ceil(span * omega_max / kPhaseStep)) + 1, 2, 1 << 16);
      ds_ = span > 0 ? span / (samples - 1) : 1.0;
      table_.resize(samples);
      // Each face's place in the table is fixed: precompute it.
      slot_.resize(delay_.size());
      weight_.resize(delay_.size());
      for (std::size_t ti = 0; ti < delay_.size(); ++ti) {
        const double u = (delay_[ti] - s_min_) / ds_;
        slot_[ti] = std::min(static_cast<std::size_t>(u), table_.size() - 2);
        weight_[ti] = u - static_cast<double>(slot_[ti]);
      }
    }
    for (std::size_t k = 0; k < table_.size(); ++k) table_[k] = wind(def_, gusts_, t - (s_min_ + k * ds_), Vec3::Zero());
  }

  WindDef def_;
  Gusts gusts_;
  std::vector<double> delay_;  // per face, s: its rest centroid's distance along the wind / speed
  double s_min_ = 0.0, ds_ = 1.0;
  std::vector<Vec3> table_;  // the wind at delays s_min_ + k ds_, this call
  std::vector<std::size_t> slot_;  // per face: table entry below its delay
  std::vector<double> weight_;     // per face: interpolation weight towards slot_ + 1
};

}  // namespace

Vec3 wind_at(const WindDef& def, double t, const Vec3& p) { return wind(def, gusts(def), t, p); }

std::unique_ptr<Effect> make_wind(const WindDef& def) { return std::make_unique<Wind>(def); }

}  // namespace vgd::sim
