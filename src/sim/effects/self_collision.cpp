// Cloth self-collision: spatial hash, point–triangle repulsion and after-step
// impulses and corrections (include/vgd/sim/effects/self_collision.hpp).
//
// The hash holds particles, not triangles: one entry per particle (N inserts,
// a counting sort into a table of ≥ 2N buckets), and each triangle visits the
// cells its box (grown by the thickness) covers. Cells are as wide as the mean
// rest edge (at least two thicknesses), so a triangle visits about 8–27 cells.
#include "vgd/sim/effects/self_collision.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <tuple>

#include <omp.h>

#include "vgd/core/diagnostics.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/topology.hpp"
#include "spatial_hash.hpp"

namespace vgd::sim {
namespace {

// Barycentric tolerance of "the projection is inside the triangle": a point
// over a shared edge belongs to both triangles rather than to neither.
constexpr double kInsideTolerance = 0.02;

// Below this many triangles the threads cost more than the detection they share.
constexpr int kParallelMinTriangles = 2000;

using sim::detail::SpatialHash;

struct Pair {
  int p, t;
  double side;           // +1 / −1: the side of the triangle the particle must stay on
  bool layered = false;  // between two layers: the side is the body's order
};

// The particle's height over the triangle's plane and the barycentric
// coordinates of its projection; false for a degenerate triangle.
inline bool project(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& nrm, double& dn,
                    Vec3& w) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 cr = e1.cross(e2);
  const double len2 = cr.squaredNorm();
  if (len2 <= 0.0) return false;
  nrm = cr / std::sqrt(len2);
  const Vec3 r = p - a;
  dn = r.dot(nrm);
  // Barycentric coordinates of the projection (r − dn n) in (e1, e2).
  const double w1 = r.cross(e2).dot(cr) / len2, w2 = e1.cross(r).dot(cr) / len2;
  w = {1.0 - w1 - w2, w1, w2};
  return true;
}

inline bool inside(const Vec3& w) { return w.minCoeff() >= -kInsideTolerance; }

// Closest points of segments p0p1 and q0q1 (Ericson §5.1.9): parameters s, t
// in [0, 1]; false when both are degenerate or parallel.
inline bool closest_segments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1, double& s,
                             double& t) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  const double c = d1.dot(r), b = d1.dot(d2);
  const double denom = a * e - b * b;
  if (a <= 0.0 || e <= 0.0 || denom <= 1e-12 * a * e) return false;  // parallel: the point tests cover it
  s = std::clamp((b * f - c * e) / denom, 0.0, 1.0);
  t = (b * s + f) / e;
  if (t < 0.0) {
    t = 0.0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1.0) {
    t = 1.0;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return true;
}

// Per particle, its mesh neighbours (in the order the edges list them), all
// in one array (no allocation per particle): the detection's edge tests and
// the one-ring exemption both walk them.
struct Adjacency {
  std::vector<int> start, item;
  void build(int n, const std::vector<std::array<int, 2>>& edges) {
    start.assign(n + 1, 0);
    for (const auto& e : edges) ++start[e[0] + 1], ++start[e[1] + 1];
    for (int i = 0; i < n; ++i) start[i + 1] += start[i];
    item.resize(start[n]);
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (const auto& e : edges) item[fill[e[0]]++] = e[1], item[fill[e[1]]++] = e[0];
  }
  std::span<const int> operator[](int i) const { return {item.data() + start[i], item.data() + start[i + 1]}; }
};

// Two edges (a0, a1) and (b0, b1) to be kept `thickness` apart along dir
// (from b towards a, as before the step).
struct EdgePair {
  int a0, a1, b0, b1;
  Vec3 dir;
};

class SelfCollision final : public Effect {
 public:
  SelfCollision(const Model& m, const SelfCollisionDef& d)
      : def_(d), tris_(m.triangles), n_(m.num_particles()) {
    if (!(d.thickness > 0.0)) throw SimulationError("self collision: thickness must be > 0");
    inv_mass_.resize(n_);
    mass_ = m.mass;
    for (int i = 0; i < n_; ++i) inv_mass_[i] = 1.0 / m.mass[i];
    for (int p : d.fixed) {
      if (p < 0 || p >= n_)
        throw SimulationError("self collision: fixed particle " + std::to_string(p) + " does not exist");
      inv_mass_[p] = 0.0;
    }
    double sum = 0.0;
    const auto edges = mesh_edges(tris_);
    for (const auto& e : edges) sum += (at(m.x0, e[0]) - at(m.x0, e[1])).norm();
    const double mean_edge = edges.empty() ? d.thickness : sum / edges.size();
    cell_ = std::max(mean_edge, 2.0 * d.thickness);
    adj_.build(n_, edges);
    stats_.min_distance = d.thickness;
    group_.resize(n_);
    for (int i = 0; i < n_; ++i) group_[i] = i;
    for (const auto& [a, b] : d.joined) {
      if (a < 0 || a >= n_ || b < 0 || b >= n_)
        throw SimulationError("self collision: joined pair (" + std::to_string(a) + ", " + std::to_string(b) +
                              ") names a particle that does not exist");
      join(a, b);
    }
    flatten();
    // Hem particles by garment (the cloth connected through edges and seams):
    // a T-shirt's side seam over a skirt's still collides with it (with one
    // label for every hem, the two garments crossed at their side seams).
    std::vector<int> cloth(n_);
    for (int i = 0; i < n_; ++i) cloth[i] = i;
    auto top = [&](int i) {
      while (cloth[i] != i) i = cloth[i] = cloth[cloth[i]];
      return i;
    };
    for (const auto& e : edges) cloth[top(e[0])] = top(e[1]);
    for (const auto& [a, b] : d.joined) cloth[top(a)] = top(b);
    hem_.assign(n_, 0);
    for (const auto& [a, b] : d.joined) hem_[a] = hem_[b] = top(a) + 1, joined_.push_back({a, b});
    strip_.assign(n_, 0);
    for (const auto& t : tris_)
      if (hem_[t[0]] || hem_[t[1]] || hem_[t[2]]) strip_[t[0]] = strip_[t[1]] = strip_[t[2]] = 1;
    if (!d.layer.empty()) {
      if (static_cast<int>(d.layer.size()) != n_)
        throw SimulationError("self collision: " + std::to_string(d.layer.size()) + " layers for " +
                              std::to_string(n_) + " particles");
      if (d.body == nullptr) throw SimulationError("self collision: layers need the body's distance grid");
      if (!(d.layer_depth >= 0.0) || !(d.held_distance >= 0.0))
        throw SimulationError("self collision: layer depth and held distance must be >= 0");
      // One layer everywhere is no layering: skip the body queries.
      if (std::any_of(d.layer.begin(), d.layer.end(), [&](int l) { return l != d.layer.front(); })) {
        layered_ = true;
        const int layers = *std::max_element(d.layer.begin(), d.layer.end()) + 1;
        if (*std::min_element(d.layer.begin(), d.layer.end()) < 0)
          throw SimulationError("self collision: layers must be >= 0 (0 next to the body)");
        layer_particles_.assign(layers, {});
        for (int i = 0; i < n_; ++i) layer_particles_[d.layer[i]].push_back(i);
        layer_hash_.resize(layers);
      }
    }
  }

  // Merged copies are one particle: never a collision between them.
  void particles_merged(const Model&, const std::vector<int>& representative) override {
    // Merged copies jumped to their common position (the mass-weighted mean
    // of the positions the last after-step left): the next step starts there.
    // Every other particle keeps its start, so the next step's motion is
    // still checked.
    merged_once_ = true;
    std::vector<int> first(n_, -1);
    for (int i = 0; i < n_; ++i) {
      int& f = first[representative[i]];
      if (f < 0)
        f = i;
      else
        join(f, i);
    }
    flatten();
    // Once every seam is sewn, hems are ordinary cloth again: nothing needs
    // the strips along a seam to pass each other any more, and left exempt
    // they folded through each other while the garment settled (T-shirt: 5
    // crossing pairs when the last seam closed, 48 at rest). Lifted seam by
    // seam instead, a sleeve's half-sewn underarm folded through itself.
    if (std::all_of(joined_.begin(), joined_.end(),
                    [&](const std::array<int, 2>& j) { return representative[j[0]] == representative[j[1]]; }))
      std::fill(hem_.begin(), hem_.end(), 0), std::fill(strip_.begin(), strip_.end(), 0);
    rep_ = representative;
    if (!rep_.empty()) average_merged_copies(rep_, mass_, x_prev_);
  }

  const char* name() const override { return "self-collision"; }
  bool needs_every_step() const override { return true; }

  // The repulsion acts on the pairs the last after-step found near (within
  // the thickness plus their motion over that step): the positions a step
  // tries stay within about that motion of them. A full search at every force
  // evaluation cost more than the rest of the step.
  void add_forces(const Eval& e, VecX& f) override {
    if (def_.stiffness <= 0.0) return;
    if (!searched_) find_near(e.x);  // before the first after-step
    const double th = def_.thickness, k = def_.stiffness;
    for (const Pair& pr : near_) {
      const auto& tr = tris_[pr.t];
      Vec3 nrm, w;
      double dn;
      if (!pressed(e.x, pr, nrm, dn, w)) continue;
      const double sgn = pr.side != 0.0 ? pr.side : (dn >= 0.0 ? 1.0 : -1.0);
      Vec3 fp = (k * (th - sgn * dn) * sgn) * nrm;
      if (def_.damping > 0.0) {
        Vec3 vr = at(e.v, pr.p);
        for (int q = 0; q < 3; ++q) vr -= w[q] * at(e.v, tr[q]);
        fp -= damping(pr.p) * vr.dot(nrm) * nrm;
      }
      at(f, pr.p) += fp;
      for (int q = 0; q < 3; ++q) at(f, tr[q]) -= w[q] * fp;
    }
  }
  // N·s/m: the repulsion's damping on particle p (SelfCollisionDef::damping).
  double damping(int p) const { return def_.damping * 2.0 * std::sqrt(def_.stiffness * mass_[p]); }
  // f = k (th − |dn|) sgn(dn) n on the particle and −w_q f on the triangle's
  // corners; with n held fixed, ∂f_i/∂x_j = −k c_i c_j n nᵀ, c = (1, −w₀, −w₁,
  // −w₂): negative semi-definite. Explicitly, a 1 N/m spring on a 40 mg
  // particle is unstable above a 13 ms step (k h²/m > 4 for two springs) —
  // pressed layers (a sleeve cap under a bodice) blew up at 10 ms.
  bool add_jacobian(const Eval& e, Triplets& dfdx, Triplets& dfdv) override {
    if (def_.stiffness <= 0.0) return true;
    if (!searched_) find_near(e.x);
    const double k = def_.stiffness;
    for (const Pair& pr : near_) {
      const auto& tr = tris_[pr.t];
      Vec3 nrm, w;
      double dn;
      if (!pressed(e.x, pr, nrm, dn, w)) continue;
      const Mat3 nn = -k * nrm * nrm.transpose();
      const int idx[4] = {pr.p, tr[0], tr[1], tr[2]};
      const double c[4] = {1.0, -w[0], -w[1], -w[2]};
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) add_block(dfdx, idx[i], idx[j], (c[i] * c[j]) * nn);
      if (def_.damping > 0.0) {
        const Mat3 dd = -damping(pr.p) * nrm * nrm.transpose();
        for (int i = 0; i < 4; ++i)
          for (int j = 0; j < 4; ++j) add_block(dfdv, idx[i], idx[j], (c[i] * c[j]) * dd);
      }
    }
    return true;
  }
  void add_stiffness_bound(const Model&, VecX& k, VecX&) const override { k.array() += 2.0 * def_.stiffness; }

  void after_step(const Model& m, State& s) override {
    searched_ = true;
    if (tris_.empty()) return;
    if (x_prev_.size() != s.x.size()) x_prev_ = m.x0.size() == s.x.size() && !merged_once_ ? m.x0 : s.x;
    const double th = def_.thickness;
    if (layered_) {
      held_.resize(n_);
      for (int i = 0; i < n_; ++i) held_[i] = def_.body->distance(at(s.x, i)) < def_.held_distance;
    }
    // Corrections move particles too, and a push can carry a neighbour
    // through other cloth: the detection is repeated on the whole step's
    // motion (start to corrected end) until it finds no crossing. A crossing
    // left undetected becomes the "side" the next step defends.
    bool clean = false;
    for (int round = 0; round < std::max(1, def_.rounds); ++round) {
      const int crossings = detect(s, round > 0);
      if (round == 0) {
        stats_.crossings = crossings;
        stats_.pairs_total += static_cast<long>(pairs_.size() + edge_pairs_.size());
      } else if (crossings == 0) {
        clean = true;
        break;
      }
      x_round_ = s.x;
      correct(s);
      rejoin(s);
      for (int i = 0; i < n_; ++i) moved_[i] = moved_[i] || at(s.x, i) != at(x_round_, i);
    }
    if (!clean) revert_crossed(s);
    untangle(s);
    double dmin = th;
    for (const Pair& pr : pairs_) {
      const auto& tr = tris_[pr.t];
      Vec3 nrm, w;
      double dn;
      if (project(at(s.x, pr.p), at(s.x, tr[0]), at(s.x, tr[1]), at(s.x, tr[2]), nrm, dn, w) && inside(w))
        dmin = std::min(dmin, pr.side * dn);
    }
    stats_.min_distance = dmin;
    x_prev_ = s.x;
    // The system moves a merged particle by the mass-weighted mean of its
    // copies' corrections: where it will be.
    if (!rep_.empty()) average_merged_copies(rep_, mass_, x_prev_);
  }

  const SelfCollisionStats& stats() const { return stats_; }

 private:
  // Pairs within the thickness, or crossed, over the step from x_prev_ to
  // s.x: pairs_, edge_pairs_ and the repulsion's near_. Returns the number of
  // point–triangle crossings. Incremental (a round after a correction): a
  // pair none of whose particles the correction moved (moved_) is what the
  // last detection found, and is kept; only pairs with a moved particle are
  // looked for again (a triangle that did not move meets only the moved
  // particles, from their own hash). Most of a correction's particles are
  // few: the later rounds cost a fraction of the first.
  int detect(const State& s, bool incremental = false) {
    ++stats_.detections;
    const double th = def_.thickness;
    std::vector<Pair> kept_pairs, kept_near;
    std::vector<EdgePair> kept_edges;
    int kept_crossings = 0;
    if (static_cast<int>(moved_.size()) != n_) moved_.assign(n_, 0), incremental = false;
    auto still = [&](int i) { return !incremental || !moved_[i]; };
    auto tri_still = [&](int t) { return still(tris_[t][0]) && still(tris_[t][1]) && still(tris_[t][2]); };
    if (incremental) {
      // The moved particles and their neighbours: an edge with one moved end
      // is tested from its other end too (the moved end's own box may miss
      // the triangle's).
      moved_list_.clear();
      for (int i = 0; i < n_; ++i) {
        bool touched = moved_[i];
        for (int q : adj_[i]) touched = touched || moved_[q];
        if (touched) moved_list_.push_back(i);
      }
      for (const Pair& pr : pairs_) {
        if (!still(pr.p) || !tri_still(pr.t)) continue;
        kept_pairs.push_back(pr);
        const auto& tr = tris_[pr.t];
        Vec3 nrm, w;
        double dn;
        if (project(at(s.x, pr.p), at(s.x, tr[0]), at(s.x, tr[1]), at(s.x, tr[2]), nrm, dn, w) && pr.side * dn < 0.0)
          ++kept_crossings;
      }
      for (const Pair& pr : near_)
        if (still(pr.p) && tri_still(pr.t)) kept_near.push_back(pr);
      for (const EdgePair& ep : edge_pairs_)
        if (still(ep.a0) && still(ep.a1) && still(ep.b0) && still(ep.b1)) kept_edges.push_back(ep);
    }
    // How far each particle moved this step. A pair can only have crossed, or
    // come within th, if it is within th plus their two motions now: the
    // particles are hashed by their swept boxes grown by th, each triangle
    // looks in its own swept box, and every bound below is per pair. (One
    // global motion grew every query by the fastest particle's: a cloth
    // falling at 2.4 m/s made each triangle meet dozens of particles.)
    disp_.resize(n_);
    for (int i = 0; i < n_; ++i) disp_[i] = (at(s.x, i) - at(x_prev_, i)).norm();
    hash_.build_boxes(x_prev_, s.x, n_, cell_, th);
    if (incremental) moved_hash_.build_boxes(x_prev_, s.x, moved_list_, cell_, th);
    if (layered_)
      for (std::size_t l = 0; l < layer_hash_.size(); ++l)
        if (!layer_particles_[l].empty()) layer_hash_[l].build_boxes(x_prev_, s.x, layer_particles_[l], cell_, th);
    // Between layers a particle is looked for deeper on the wrong side: the
    // triangle's query box grows by the depth, the particle's test by its
    // pair's reach.
    const double depth = layered_ ? def_.layer_depth : 0.0;
    pairs_.clear();
    edge_pairs_.clear();
    std::vector<Pair> near;
    int crossings = 0;
    const int nt = static_cast<int>(tris_.size());
    // Edge pairs per thread, joined in thread order after the loop: with the
    // static schedule that is triangle order, as with one thread, so the
    // sort below leaves the same one of two equal pairs (met from both ends,
    // computed with rounding of their own) whatever the thread count.
    std::vector<std::vector<EdgePair>> edges_by_thread;
#pragma omp parallel if (nt >= kParallelMinTriangles) reduction(+ : crossings)
    {
#pragma omp single
      edges_by_thread.resize(omp_get_num_threads());
      std::vector<Pair> my_pairs, my_near;
      std::vector<EdgePair> my_edges;
      std::vector<int> stamp(n_, -1);  // the triangle that last met each particle (dedupe)
      // The triangle whose edges were last tested from each particle. (Marked
      // when the edges are tested, not when the particle is met: a particle
      // met but outside the box tests none, and its neighbour must still test
      // their shared edge. Marked on meeting, the edges tested depended on the
      // order the hash gave the particles in.)
      std::vector<int> edges_from(n_, -1);
#pragma omp for schedule(static) nowait
      for (int t = 0; t < nt; ++t) {
        const auto& tr = tris_[t];
        const Vec3 a = at(s.x, tr[0]), b = at(s.x, tr[1]), c = at(s.x, tr[2]);
        Vec3 lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
        for (int q : tr) {
          lo = lo.cwiseMin(at(x_prev_, q));
          hi = hi.cwiseMax(at(x_prev_, q));
        }
        // Same-layer candidates come from the particles' hash with the
        // triangle's own box; other layers' (looked for `depth` deeper) from
        // their layer's hash with the grown box, so the depth costs nothing
        // where the garments do not overlap.
        const Vec3 lo0 = lo, hi0 = hi;
        lo.array() -= depth;
        hi.array() += depth;
        const double tri_motion = std::max({disp_[tr[0]], disp_[tr[1]], disp_[tr[2]]});
        // The triangle's edges' boxes, once per triangle rather than per candidate edge.
        Vec3 edge_lo[3], edge_hi[3];
        for (int k = 0; k < 3; ++k) {
          edge_lo[k] = at(s.x, tr[k]).cwiseMin(at(s.x, tr[(k + 1) % 3]));
          edge_hi[k] = at(s.x, tr[k]).cwiseMax(at(s.x, tr[(k + 1) % 3]));
        }
        const Vec3 tn = (b - a).cross(c - a);
        const double tn_len = tn.norm();
        const Vec3 unit = tn_len > 0.0 ? Vec3(tn / tn_len) : Vec3::Zero();
        // The body's outward normal against the triangle's (+1: the normal
        // points away from the body), when the triangle faces the body.
        double facing = 0.0;
        if (layered_) {
          Vec3 g;
          def_.body->sample((a + b + c) / 3.0, g);
          const double cosine = unit.dot(g) / std::max(g.norm(), 1e-12);
          if (std::abs(cosine) >= 0.5) facing = cosine > 0.0 ? 1.0 : -1.0;
        }
        bool only_moved = false;  // an unmoved triangle in an incremental detection
        auto visit = [&](int p) {
          if (stamp[p] == t) return;
          stamp[p] = t;
          // The particle's swept box, grown by th, must meet the triangle's.
          const int lp = layered_ ? def_.layer[p] : 0, lt = layered_ ? def_.layer[tr[0]] : 0;
          const bool between = facing != 0.0 && lp != lt;
          const double reach = th + (between ? 0.0 : -depth);  // against the grown box
          const Vec3 plo = at(s.x, p).cwiseMin(at(x_prev_, p)) - Vec3::Constant(reach);
          const Vec3 phi = at(s.x, p).cwiseMax(at(x_prev_, p)) + Vec3::Constant(reach);
          if ((plo.array() > hi.array()).any() || (phi.array() < lo.array()).any()) return;
          const double lim = th + disp_[p] + tri_motion;
          // Point–triangle (not for an unmoved particle against an unmoved
          // triangle: the last detection's pair is kept).
          const bool known = only_moved && !moved_[p];
          if (!known && !skip(p, tr)) {
            Vec3 nrm, w;
            double dn;
            if (between) {
              // Between layers: the outer one on the triangle's side away
              // from the body, wherever it came from.
              const double side = lp > lt ? facing : -facing;
              if (project(at(s.x, p), a, b, c, nrm, dn, w) && inside(w) && side * dn < th &&
                  side * dn > -(lim + def_.layer_depth)) {
                if (std::abs(dn) < lim) my_near.push_back({p, t, side, true});
                if (side * dn < 0.0) ++crossings;
                my_pairs.push_back({p, t, side, true});
              }
            } else if (project(at(s.x, p), a, b, c, nrm, dn, w) && inside(w) && std::abs(dn) < lim) {
              my_near.push_back({p, t, 0.0});
              // The side before the step.
              Vec3 nrm0, w0;
              double dn0;
              double side = dn >= 0.0 ? 1.0 : -1.0;
              if (project(at(x_prev_, p), at(x_prev_, tr[0]), at(x_prev_, tr[1]), at(x_prev_, tr[2]), nrm0,
                          dn0, w0) &&
                  std::abs(dn0) > 1e-12)
                side = dn0 > 0.0 ? 1.0 : -1.0;
              if (side * dn < th) {
                if (side * dn < 0.0) ++crossings;
                my_pairs.push_back({p, t, side});
              }
            }
          }
          // Edge–edge: the edges at p against the triangle's edges. An edge
          // with both ends on one side of the triangle's plane, farther than
          // the pair's bound, cannot come that close to the triangle's edges
          // (they lie in the plane), nor can one whose box, grown by the
          // bound, misses the other edge's: both cheap tests go first.
          if (tn_len <= 0.0) return;
          edges_from[p] = t;
          const double hp = (at(s.x, p) - a).dot(unit);
          for (int q : adj_[p]) {
            if (edges_from[q] == t) continue;  // tested from q already
            if (known && !moved_[q]) continue;  // neither end moved: kept
            const double elim = th + std::max(disp_[p], disp_[q]) + tri_motion;
            const double hq = (at(s.x, q) - a).dot(unit);
            if ((hp > elim && hq > elim) || (hp < -elim && hq < -elim)) continue;
            const Vec3 elo = at(s.x, p).cwiseMin(at(s.x, q)) - Vec3::Constant(elim);
            const Vec3 ehi = at(s.x, p).cwiseMax(at(s.x, q)) + Vec3::Constant(elim);
            for (int k = 0; k < 3; ++k) {
              const int b0 = tr[k], b1 = tr[(k + 1) % 3];
              // Edges sharing a particle first (cheap, and common: the triangle's neighbours).
              if (same(p, b0) || same(p, b1) || same(q, b0) || same(q, b1)) continue;
              if ((edge_lo[k].array() > ehi.array()).any() || (edge_hi[k].array() < elo.array()).any()) continue;
              if (on_one_hem(hem_[p] | hem_[q], hem_[b0] | hem_[b1])) continue;
              edge_pair(s, p, q, b0, b1, th, elim - th, my_edges);
            }
          }
        };
        only_moved = incremental && tri_still(t);
        if (only_moved) {
          // Only the moved particles, any layer: the grown box, the visit's
          // own test takes each layer's reach.
          moved_hash_.for_each_in_box(lo, hi, visit);
          continue;
        }
        hash_.for_each_in_box(lo0, hi0, visit);
        if (layered_)
          for (std::size_t l = 0; l < layer_hash_.size(); ++l)
            if (static_cast<int>(l) != def_.layer[tr[0]] && !layer_particles_[l].empty())
              layer_hash_[l].for_each_in_box(lo, hi, visit);
      }
      edges_by_thread[omp_get_thread_num()] = std::move(my_edges);
#pragma omp critical(vgd_self_collision_merge)
      {
        pairs_.insert(pairs_.end(), my_pairs.begin(), my_pairs.end());
        near.insert(near.end(), my_near.begin(), my_near.end());
      }
    }
    pairs_.insert(pairs_.end(), kept_pairs.begin(), kept_pairs.end());
    near.insert(near.end(), kept_near.begin(), kept_near.end());
    edge_pairs_.insert(edge_pairs_.end(), kept_edges.begin(), kept_edges.end());
    crossings += kept_crossings;
    for (const auto& e : edges_by_thread) edge_pairs_.insert(edge_pairs_.end(), e.begin(), e.end());
    // Threads finish in any order: sort, so the Gauss–Seidel passes below see
    // the pairs in one order whatever the thread count.
    auto by_triangle = [](const Pair& x, const Pair& y) { return std::tie(x.t, x.p) < std::tie(y.t, y.p); };
    std::sort(pairs_.begin(), pairs_.end(), by_triangle);
    std::sort(near.begin(), near.end(), by_triangle);
    near_ = std::move(near);
    std::sort(edge_pairs_.begin(), edge_pairs_.end(), [](const EdgePair& x, const EdgePair& y) {
      return std::tie(x.a0, x.a1, x.b0, x.b1) < std::tie(y.a0, y.a1, y.b0, y.b1);
    });
    edge_pairs_.erase(std::unique(edge_pairs_.begin(), edge_pairs_.end(),
                                  [](const EdgePair& x, const EdgePair& y) {
                                    return x.a0 == y.a0 && x.a1 == y.a1 && x.b0 == y.b0 && x.b1 == y.b1;
                                  }),
                      edge_pairs_.end());
    stats_.pairs = static_cast<int>(pairs_.size() + edge_pairs_.size());
    std::fill(moved_.begin(), moved_.end(), 0);  // moves from here on are the next detection's
    return crossings;
  }

  // The fail-safe after the rounds: a pair still crossed (on the wrong side
  // of the side it came from) has its particles put back where the step
  // started them, at rest, until no such pair is left. The start had no
  // crossing, so with every particle back it has none again: the loop ends.
  // Without it a crossing the rounds left became the side the next step
  // defended, and crossings piled up (the skirt in size 40: contact pairs
  // past 1 GB after 11 minutes). Pairs between layers are left to their own
  // rule (their side is the body's order, which a start may not meet yet).
  void revert_crossed(State& s) {
    std::vector<char> back(n_, 0);
    for (int k = 0; k < kMaxReverts; ++k) {
      if (k > 0) detect(s, true);  // only around what was put back (and the last round moved)
      bool any = false;
      auto mark = [&](int i) {
        if (inv_mass_[i] == 0.0) return;
        back[rep_.empty() ? i : rep_[i]] = 1;
        any = true;
      };
      for (const Pair& pr : pairs_) {
        if (pr.layered) continue;
        const auto& tr = tris_[pr.t];
        Vec3 nrm, w;
        double dn;
        if (project(at(s.x, pr.p), at(s.x, tr[0]), at(s.x, tr[1]), at(s.x, tr[2]), nrm, dn, w) && inside(w) &&
            pr.side * dn < 0.0) {
          mark(pr.p);
          for (int q : tr) mark(q);
        }
      }
      for (const EdgePair& ep : edge_pairs_) {
        double u, w;
        if (!closest_segments(at(s.x, ep.a0), at(s.x, ep.a1), at(s.x, ep.b0), at(s.x, ep.b1), u, w)) continue;
        const Vec3 r = (1 - u) * at(s.x, ep.a0) + u * at(s.x, ep.a1) - (1 - w) * at(s.x, ep.b0) - w * at(s.x, ep.b1);
        if (r.dot(ep.dir) < 0.0) {
          for (int q : {ep.a0, ep.a1, ep.b0, ep.b1}) mark(q);
        }
      }
      if (!any) return;
      long moved = 0;
      for (int i = 0; i < n_; ++i) {
        if (!back[rep_.empty() ? i : rep_[i]] || inv_mass_[i] == 0.0) continue;
        if (at(s.x, i) != at(x_prev_, i)) ++moved, moved_[i] = 1;
        at(s.x, i) = at(x_prev_, i);
        at(s.v, i).setZero();
      }
      stats_.reverted += moved;
      if (moved == 0) return;  // all already back: what is left came in with the start
    }
  }

  // History-free untangling: cloth that is through other cloth at the end of
  // the step, whatever the step started with. The rounds and the fail-safe
  // keep the side each pair had at the step's start, so a crossing that came
  // in with the start (an exempt seam strip folded through its neighbour
  // while the seam closed, a merge's jump) was defended for ever. Here every
  // edge through a triangle, not exempt and within one layer, has its end
  // nearer the plane (the smaller region is the one that went through) put
  // back to the thickness on its other end's side; the triangle takes the
  // opposite share by barycentric weight and inverse mass, and the normal
  // approach is stopped. A few Gauss–Seidel passes; what is left waits for
  // the next step. Measured (docs/collisions.md): T-shirts in sizes 34–42
  // and skirts in 36–40 went from 8–207 and 0–19 crossing pairs at rest to
  // none; run every 4th step instead, the skirt in size 38 kept 8–15.
  void untangle(State& s) {
    if (def_.untangle_passes <= 0 || ++untangle_clock_ % std::max(1, def_.untangle_every) != 0) return;
    // Triangles hashed by their boxes; every edge looks in its own box (an
    // edge through a triangle meets its box). About as many tests as edges.
    const int nt = static_cast<int>(tris_.size());
    tri_lo_.resize(3 * nt);
    tri_hi_.resize(3 * nt);
    for (int t = 0; t < nt; ++t) {
      const auto& tr = tris_[t];
      at(tri_lo_, t) = at(s.x, tr[0]).cwiseMin(at(s.x, tr[1])).cwiseMin(at(s.x, tr[2]));
      at(tri_hi_, t) = at(s.x, tr[0]).cwiseMax(at(s.x, tr[1])).cwiseMax(at(s.x, tr[2]));
    }
    tri_hash_.build_boxes(tri_lo_, tri_hi_, nt, cell_, 0.0);
    struct Hit {
      int p, q, t;
    };
    // Edges by particle in parallel; each thread's hits joined in thread
    // order (static schedule: particle order, as with one thread).
    std::vector<std::vector<Hit>> hits_by_thread;
#pragma omp parallel if (nt >= kParallelMinTriangles)
    {
#pragma omp single
      hits_by_thread.resize(omp_get_num_threads());
      std::vector<Hit> my_hits;
      std::vector<int> seen(nt, -1);  // per triangle, the last edge that met it
      int edge = 0;
#pragma omp for schedule(static) nowait
      for (int p = 0; p < n_; ++p)
        for (int q : adj_[p]) {
          if (q < p) continue;
          ++edge;
          const Vec3 lo = at(s.x, p).cwiseMin(at(s.x, q)), hi = at(s.x, p).cwiseMax(at(s.x, q));
          tri_hash_.for_each_in_box(lo, hi, [&](int t) {
            if (seen[t] == edge) return;  // met in another cell
            seen[t] = edge;
            const auto& tr = tris_[t];
            if ((at(tri_lo_, t).array() > hi.array()).any() || (at(tri_hi_, t).array() < lo.array()).any()) return;
            for (int k : tr)
              if (same(p, k) || same(q, k)) return;
            if (layered_ && (def_.layer[p] != def_.layer[tr[0]] || def_.layer[q] != def_.layer[tr[0]])) return;
            if (on_one_hem(hem_[p] | hem_[q], hem_[tr[0]] | hem_[tr[1]] | hem_[tr[2]])) return;
            if (through(s.x, p, q, tr)) my_hits.push_back({p, q, t});
          });
        }
      hits_by_thread[omp_get_thread_num()] = std::move(my_hits);
    }
    std::vector<Hit> hits;
    for (const auto& h : hits_by_thread) hits.insert(hits.end(), h.begin(), h.end());
    stats_.tangled = static_cast<int>(hits.size());
    for (int pass = 0; pass < def_.untangle_passes && !hits.empty(); ++pass) {
      bool moved = false;
      if (def_.body) pass_start_ = s.x;
      for (const Hit& h : hits) moved = pull_back(s, h.p, h.q, tris_[h.t]) || moved;
      if (def_.body) out_of_body(s);
      rejoin(s);
      if (!moved) break;
    }
  }

  // Edge pq passes through the inside of triangle tr at x.
  static bool through(const VecX& x, int p, int q, const std::array<int, 3>& tr) {
    const Vec3 a = at(x, tr[0]), n = (at(x, tr[1]) - a).cross(at(x, tr[2]) - a);
    const double dp = (at(x, p) - a).dot(n), dq = (at(x, q) - a).dot(n);
    if (!(dp * dq < 0.0)) return false;
    const Vec3 hit = at(x, p) + dp / (dp - dq) * (at(x, q) - at(x, p));
    Vec3 nrm, w;
    double dn;
    return project(hit, a, at(x, tr[1]), at(x, tr[2]), nrm, dn, w) && w.minCoeff() > 0.0;
  }

  // One untangling move for edge pq through triangle tr (see untangle).
  bool pull_back(State& s, int p, int q, const std::array<int, 3>& tr) {
    if (!through(s.x, p, q, tr)) return false;
    Vec3 nrm, w;
    double dp, dq;
    const Vec3 a = at(s.x, tr[0]), b = at(s.x, tr[1]), c = at(s.x, tr[2]);
    if (!project(at(s.x, p), a, b, c, nrm, dp, w) || !project(at(s.x, q), a, b, c, nrm, dq, w)) return false;
    const bool p_went = std::abs(dp) < std::abs(dq);
    const int i = p_went ? p : q;
    const double di = p_went ? dp : dq, side = (p_went ? dq : dp) > 0.0 ? 1.0 : -1.0;
    // Where the intruder meets the plane: the triangle's share goes there.
    Vec3 wi;
    double dn;
    project(at(s.x, i), a, b, c, nrm, dn, wi);
    wi = wi.cwiseMax(0.0);
    wi /= wi.sum();
    const double gap = def_.thickness - side * di;  // m along side·n to close
    const double wp = inv_mass_[i];
    double wt = 0.0;
    for (int k = 0; k < 3; ++k) wt += wi[k] * wi[k] * inv_mass_[tr[k]];
    if (wp + wt <= 0.0) return false;
    const double lambda = gap / (wp + wt);
    const Vec3 dir = side * nrm;
    at(s.x, i) += wp * lambda * dir;
    for (int k = 0; k < 3; ++k) at(s.x, tr[k]) -= inv_mass_[tr[k]] * wi[k] * lambda * dir;
    // Stop the relative approach along dir (inelastic), shared the same way.
    Vec3 vt = Vec3::Zero();
    for (int k = 0; k < 3; ++k) vt += wi[k] * at(s.v, tr[k]);
    const double approach = (at(s.v, i) - vt).dot(dir);
    if (approach < 0.0) {
      const double mu = -approach / (wp + wt);
      at(s.v, i) += wp * mu * dir;
      for (int k = 0; k < 3; ++k) at(s.v, tr[k]) -= inv_mass_[tr[k]] * wi[k] * mu * dir;
    }
    ++stats_.untangled;
    return true;
  }

  // A merged particle's copies, moved apart by corrections, back to their
  // mass-weighted mean (what the system does after the step): the next
  // detection must see where the particle will be. Left to the system, a
  // seam junction (an armpit: four copies) ended up through cloth no round
  // had seen.
  void rejoin(State& s) const {
    if (rep_.empty()) return;
    average_merged_copies(rep_, mass_, s.x);
    average_merged_copies(rep_, mass_, s.v);
  }

  // Gauss–Seidel: each pair in turn moves its four particles.
  void correct(State& s) {
    for (int pass = 0; pass < def_.passes && !(pairs_.empty() && edge_pairs_.empty()); ++pass) {
      if (def_.body) pass_start_ = s.x;
      bool moved = false;
      for (const Pair& pr : pairs_) moved = resolve(s, pr) || moved;
      for (const EdgePair& ep : edge_pairs_) moved = resolve(s, ep) || moved;
      if (def_.body) out_of_body(s);
      if (!moved) break;
    }
  }
  // The body is one more constraint of the Gauss–Seidel passes (corrections
  // and untangling): a particle the pass pushed inside it goes back to its
  // surface, its approach stopped. Without it the body's push (before this
  // effect) and the corrections took turns in the armpit crease: cloth under
  // other cloth, pushed out through it by the body, was put back on its side,
  // inside the body, up to 2 cm deep at the end of each step; a step put back
  // by the fail-safe started there again. The strips along the seams (the
  // particles of triangles touching a hem) are left alone while seams sew, as
  // their collisions are: with the hem particles alone left, an armpit corner
  // held out of the crease stayed 3–5 cm from its partner in some runs, and
  // the panels sewn round a cylinder (bench sew-cylinder --self-collision)
  // kept 4 of 60 pairs open with 14 crossing pairs.
  void out_of_body(State& s) {
    for (int i = 0; i < n_; ++i) {
      if (inv_mass_[i] == 0.0 || strip_[i] || at(s.x, i) == at(pass_start_, i)) continue;
      Vec3 g;
      const double d = def_.body->sample(at(s.x, i), g);
      if (d >= 0.0) continue;
      const double len = g.norm();
      if (len <= 0.0) continue;
      const Vec3 nrm = g / len;
      at(s.x, i) -= d * nrm;
      const double vn = at(s.v, i).dot(nrm);
      if (vn < 0.0) at(s.v, i) -= vn * nrm;
    }
  }

  // Particle and triangle of a near pair within the thickness at x, the
  // projection inside the triangle: the repulsion acts (normal, height, weights).
  bool pressed(const VecX& x, const Pair& pr, Vec3& nrm, double& dn, Vec3& w) const {
    const auto& tr = tris_[pr.t];
    return project(at(x, pr.p), at(x, tr[0]), at(x, tr[1]), at(x, tr[2]), nrm, dn, w) &&
           std::abs(dn) < def_.thickness && inside(w);
  }

  // The point–triangle pairs within the thickness at x (no motion known yet).
  void find_near(const VecX& x) {
    searched_ = true;
    near_.clear();
    const double th = def_.thickness;
    hash_.build(x, n_, cell_);
    for (int t = 0; t < static_cast<int>(tris_.size()); ++t) {
      const auto& tr = tris_[t];
      const Vec3 a = at(x, tr[0]), b = at(x, tr[1]), c = at(x, tr[2]);
      const Vec3 lo = a.cwiseMin(b).cwiseMin(c) - Vec3::Constant(th),
                 hi = a.cwiseMax(b).cwiseMax(c) + Vec3::Constant(th);
      hash_.for_each_in_box(lo, hi, [&](int p) {
        Vec3 nrm, w;
        double dn;
        if (!skip(p, tr) && project(at(x, p), a, b, c, nrm, dn, w) && inside(w) && std::abs(dn) < th)
          near_.push_back({p, t, 0.0});
      });
    }
  }

  // Union–find over particles that are one (or will be): seam pairs, merges.
  int root(int i) {
    while (group_[i] != i) i = group_[i] = group_[group_[i]];
    return i;
  }
  void join(int a, int b) {
    a = root(a), b = root(b);
    if (a != b) group_[std::max(a, b)] = std::min(a, b);
  }
  void flatten() {
    for (int i = 0; i < n_; ++i) group_[i] = root(i);
  }
  bool same(int a, int b) const { return group_[a] == group_[b]; }
  // The hem labels of two edges (an edge's: either end's, both ends being of
  // one garment): both on a hem of the same garment.
  static bool on_one_hem(int a, int b) { return a != 0 && a == b; }

  bool skip(int p, const std::array<int, 3>& tr) const {
    if (same(p, tr[0]) || same(p, tr[1]) || same(p, tr[2])) return true;
    if (hem_[p] && (hem_[tr[0]] == hem_[p] || hem_[tr[1]] == hem_[p] || hem_[tr[2]] == hem_[p])) return true;
    if (def_.skip_one_ring)
      for (int q : tr)
        for (int r : adj_[q])
          if (r == p) return true;
    return false;
  }

  // Records edges (a0, a1) and (b0, b1) if closer than the thickness now, or
  // crossed during the step (their closest-point direction reversed).
  void edge_pair(const State& s, int a0, int a1, int b0, int b1, double th, double motion,
                 std::vector<EdgePair>& out) const {
    double u, w;
    if (!closest_segments(at(s.x, a0), at(s.x, a1), at(s.x, b0), at(s.x, b1), u, w)) return;
    if (u <= 0.0 || u >= 1.0 || w <= 0.0 || w >= 1.0) return;  // an end point: the point tests see it
    const Vec3 r = (1 - u) * at(s.x, a0) + u * at(s.x, a1) - (1 - w) * at(s.x, b0) - w * at(s.x, b1);
    const double dist = r.norm();
    if (dist >= th + motion) return;
    // Direction before the step, at the same parameters.
    const Vec3 r0 =
        (1 - u) * at(x_prev_, a0) + u * at(x_prev_, a1) - (1 - w) * at(x_prev_, b0) - w * at(x_prev_, b1);
    Vec3 dir;
    if (r0.norm() > 1e-12)
      dir = r0.normalized();
    else if (dist > 1e-12)
      dir = r / dist;
    else
      return;
    if (r.dot(dir) >= th) return;
    out.push_back({std::min(a0, a1), std::max(a0, a1), std::min(b0, b1), std::max(b0, b1), dir});
  }

  bool resolve(State& s, const EdgePair& ep) {
    double u, w;
    if (!closest_segments(at(s.x, ep.a0), at(s.x, ep.a1), at(s.x, ep.b0), at(s.x, ep.b1), u, w)) return false;
    const int idx[4] = {ep.a0, ep.a1, ep.b0, ep.b1};
    const double c[4] = {1 - u, u, -(1 - w), -w};
    double wsum = 0.0, dist = 0.0, vn = 0.0;
    for (int k = 0; k < 4; ++k) {
      wsum += c[k] * c[k] * inv_mass_[idx[k]];
      dist += c[k] * at(s.x, idx[k]).dot(ep.dir);
      vn += c[k] * at(s.v, idx[k]).dot(ep.dir);
    }
    if (wsum <= 0.0) return false;
    bool moved = false;
    const double gap = def_.thickness - dist;
    if (gap > 1e-9 * def_.thickness) {
      for (int k = 0; k < 4; ++k) at(s.x, idx[k]) += (gap / wsum) * c[k] * inv_mass_[idx[k]] * ep.dir;
      moved = true;
    }
    if (vn < 0.0) {
      for (int k = 0; k < 4; ++k) at(s.v, idx[k]) += (-vn / wsum) * c[k] * inv_mass_[idx[k]] * ep.dir;
      moved = true;
    }
    return moved;
  }

  // One pair: position back to the thickness on its side, then no approach.
  bool resolve(State& s, const Pair& pr) {
    const auto& tr = tris_[pr.t];
    Vec3 nrm, w;
    double dn;
    if (!project(at(s.x, pr.p), at(s.x, tr[0]), at(s.x, tr[1]), at(s.x, tr[2]), nrm, dn, w)) return false;
    // A particle that went through the triangle may have ended beside it:
    // the push acts at the nearest point of the triangle, never with weights
    // outside [0, 1] (they would fling the far corners).
    w = w.cwiseMax(0.0);
    w /= w.sum();
    const Vec3 dir = pr.side * nrm;  // from the triangle towards where the particle belongs
    // Between layers the inner one does not move where the body holds it.
    auto im = [&](int i) {
      if (pr.layered && held_[i] && def_.layer[i] == std::min(def_.layer[pr.p], def_.layer[tr[0]])) return 0.0;
      return inv_mass_[i];
    };
    const double ip = im(pr.p), i0 = im(tr[0]), i1 = im(tr[1]), i2 = im(tr[2]);
    const double wsum = ip + w[0] * w[0] * i0 + w[1] * w[1] * i1 + w[2] * w[2] * i2;
    if (wsum <= 0.0) return false;
    bool moved = false;
    const double gap = def_.thickness - pr.side * dn;
    if (gap > 1e-9 * def_.thickness) {
      const double lambda = gap / wsum;
      at(s.x, pr.p) += lambda * ip * dir;
      at(s.x, tr[0]) -= lambda * w[0] * i0 * dir;
      at(s.x, tr[1]) -= lambda * w[1] * i1 * dir;
      at(s.x, tr[2]) -= lambda * w[2] * i2 * dir;
      moved = true;
    }
    const Vec3 vr = at(s.v, pr.p) - w[0] * at(s.v, tr[0]) - w[1] * at(s.v, tr[1]) - w[2] * at(s.v, tr[2]);
    const double vn = vr.dot(dir);
    if (vn < 0.0) {  // approaching: an inelastic impulse stops it
      // Between layers, Coulomb friction too (Bridson et al. 2002 §7.2): the
      // relative tangential velocity loses at most μ times the normal change.
      const Vec3 vt = vr - vn * dir;
      const double vt_len = vt.norm();
      const double mu = pr.layered ? def_.layer_friction : 0.0;
      const double cut = mu > 0.0 && vt_len > 0.0 ? std::min(1.0, mu * -vn / vt_len) : 0.0;
      // Without friction the scalar form, as before layers: single garments
      // keep their trajectories bit for bit (their crossing counts are chaotic
      // in the last bit, docs/performance.md).
      if (cut > 0.0) {
        const Vec3 j = (-vn * dir - cut * vt) / wsum;
        at(s.v, pr.p) += ip * j;
        at(s.v, tr[0]) -= w[0] * i0 * j;
        at(s.v, tr[1]) -= w[1] * i1 * j;
        at(s.v, tr[2]) -= w[2] * i2 * j;
      } else {
        const double j = -vn / wsum;
        at(s.v, pr.p) += j * ip * dir;
        at(s.v, tr[0]) -= j * w[0] * i0 * dir;
        at(s.v, tr[1]) -= j * w[1] * i1 * dir;
        at(s.v, tr[2]) -= j * w[2] * i2 * dir;
      }
      moved = true;
    }
    return moved;
  }

  SelfCollisionDef def_;
  std::vector<std::array<int, 3>> tris_;
  int n_;
  double cell_;
  std::vector<double> inv_mass_;
  VecX mass_;             // kg
  std::vector<int> rep_;  // per particle: its merged particle (empty before the first merge)
  static constexpr int kMaxReverts = 16;  // detections of the fail-safe per step
  SpatialHash hash_;
  std::vector<SpatialHash> layer_hash_;           // per layer, its particles only (layered_)
  std::vector<std::vector<int>> layer_particles_;  // per layer
  std::vector<Pair> pairs_;
  std::vector<Pair> near_;  // point–triangle pairs near at the last after-step (the repulsion's candidates)
  bool searched_ = false;   // near_ has been filled once
  bool merged_once_ = false;
  long untangle_clock_ = 0;
  VecX x_round_;                 // positions before a round's correction
  VecX pass_start_;               // positions before a Gauss–Seidel pass (out_of_body)
  std::vector<char> moved_;      // per particle: moved since the last detection (corrections, the fail-safe)
  std::vector<int> moved_list_;  // the same, listed
  SpatialHash moved_hash_;       // the moved particles, by their swept boxes
  SpatialHash tri_hash_;     // untangling: triangles by their boxes
  VecX tri_lo_, tri_hi_;     // m: the triangles' boxes
  std::vector<EdgePair> edge_pairs_;
  Adjacency adj_;  // per particle: its mesh neighbours
  VecX x_prev_;
  std::vector<double> disp_;  // m: per particle, how far it moved in the last step
  std::vector<int> group_;
  // Per particle: on a seam's hem. Hems approach each other edge on while a
  // seam closes: a hem particle never collides with a triangle or edge
  // touching a hem, or the strips along the seam would block it.
  std::vector<std::array<int, 2>> joined_;  // the seam pairs
  std::vector<int> hem_;  // per particle: 0, or 1 + its garment's label when it is on a seam's hem
  std::vector<char> strip_;  // per particle: on a triangle touching a hem, while hems are exempt
  bool layered_ = false;     // more than one layer (def_.layer, def_.body set)
  std::vector<char> held_;   // per particle, layered: within held_distance of the body at the after-step's start
  SelfCollisionStats stats_;
};

}  // namespace

std::unique_ptr<Effect> make_self_collision(const Model& model, const SelfCollisionDef& def) {
  return std::make_unique<SelfCollision>(model, def);
}

const SelfCollisionStats& self_collision_stats(const Effect& effect) {
  const auto* c = dynamic_cast<const SelfCollision*>(&effect);
  VGD_ASSERT(c != nullptr, "self_collision_stats: the effect is not a self collision");
  return c->stats();
}

}  // namespace vgd::sim
