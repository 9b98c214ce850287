// Contact with a guarantee: distance bounds on each particle's move
// (include/vgd/sim/effects/contact.hpp, docs/collisions.md "Offset contact").
//
// Everything works on the merged mesh (sim/topology.hpp): copies of one
// particle are one vertex, read from their first copy and written to all.
// Detection finds the pairs within the reach, from which each particle's
// half-spaces (the bound) and the next step's forces come. Each thread
// collects its own pairs and the pairs are sorted, so the result does not
// depend on the threads.
#include "vgd/sim/effects/contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>

#include <omp.h>

#include "spatial_hash.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/sim/topology.hpp"

namespace vgd::sim {

double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& w) {
  // Ericson, Real-Time Collision Detection §5.1.5, by Voronoi regions.
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) {
    w = {1, 0, 0};
    return ap.norm();
  }
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) {
    w = {0, 1, 0};
    return bp.norm();
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    w = {1 - v, v, 0};
    return (p - (a + v * ab)).norm();
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) {
    w = {0, 0, 1};
    return cp.norm();
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double t = d2 / (d2 - d6);
    w = {1 - t, 0, t};
    return (p - (a + t * ac)).norm();
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    w = {0, 1 - t, t};
    return (p - (b + t * (c - b))).norm();
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) {  // degenerate triangle: the nearest of its edges
    double best = std::numeric_limits<double>::infinity();
    const Vec3* q[3] = {&a, &b, &c};
    for (int i = 0; i < 3; ++i) {
      double s, t;
      const Vec3& u = *q[i];
      const Vec3& v = *q[(i + 1) % 3];
      const double d = segment_distance(p, p, u, v, s, t);
      if (d < best) {
        best = d;
        w = Vec3::Zero();
        w[i] = 1 - t;
        w[(i + 1) % 3] = t;
      }
    }
    return best;
  }
  const double v = vb / sum, t = vc / sum;
  w = {1 - v - t, v, t};
  return (p - (a + v * ab + t * ac)).norm();
}

double segment_distance(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1, double& s, double& t) {
  // Ericson §5.1.9, with the degenerate and parallel cases.
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  constexpr double eps = 1e-30;
  if (a <= eps && e <= eps) {
    s = t = 0.0;
    return r.norm();
  }
  if (a <= eps) {
    s = 0.0;
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= eps) {
      t = 0.0;
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > 1e-14 * a * e ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return (p0 + s * d1 - (q0 + t * d2)).norm();
}

namespace {

using detail::SpatialHash;

// Below this many cloth vertices the threads cost more than they share.
constexpr int kParallelMin = 2000;

enum class Kind : unsigned char {
  vertex_triangle,  // a: cloth vertex, b: cloth triangle
  edge_edge,        // a < b: cloth edges
  vertex_body,      // a: cloth vertex, b: body triangle
  body_triangle,    // a: cloth triangle, b: body vertex
  edge_body,        // a: cloth edge, b: body edge
};

struct Pair {
  Kind kind;
  int a, b;
  bool operator<(const Pair& o) const {
    return std::tie(kind, a, b) < std::tie(o.kind, o.a, o.b);
  }
  bool operator==(const Pair& o) const { return kind == o.kind && a == o.a && b == o.b; }
};

// One pair's geometry at given positions: up to four cloth particles with
// their weights (positive on the side the normal points to), the normal from
// the other primitive to this one, the distance.
struct Contact4 {
  int n = 0;
  std::array<int, 4> v{};
  std::array<double, 4> w{};
  std::array<int, 4> side{1, 1, 1, 1};  // +1: on the primitive the normal points to; −1: the other
  Vec3 normal = Vec3::Zero();
  double d = 0.0;
  bool body = false;
  Vec3 base = Vec3::Zero();  // the body's point of a body pair: d = n · (Σ w x − base)
  // The distance along the normal frozen at the detection (m): linear in x.
  template <class X>
  double along(const X& x) const {
    Vec3 p = Vec3::Zero();
    for (int k = 0; k < n; ++k) p += w[k] * at(x, v[k]);
    return normal.dot(p - base);
  }
};

// The squared distance between two axis-aligned boxes (0 when they overlap), m²: no
// two points of them are nearer, so a pair whose boxes are a reach apart is
// no pair.
inline double box_gap2(const Vec3& alo, const Vec3& ahi, const Vec3& blo, const Vec3& bhi) {
  return (blo - ahi).cwiseMax(alo - bhi).cwiseMax(0.0).squaredNorm();
}

class ContactEffect final : public Effect {
 public:
  ContactEffect(const Model& m, const ContactDef& d) : def_(d), mass_(m.mass) {
    if (!(d.radius > 0.0)) throw SimulationError("contact: radius must be > 0");
    if (!(d.reach >= d.radius)) throw SimulationError("contact: reach must be >= radius");
    if (!(d.gamma > 0.0 && d.gamma < 0.5)) throw SimulationError("contact: gamma must be in (0, 0.5)");
    if (!(d.stiffness >= 0.0)) throw SimulationError("contact: stiffness must be >= 0");
    if (!(d.friction >= 0.0) || !(d.slip_speed > 0.0))
      throw SimulationError("contact: friction must be >= 0 and slip_speed > 0");
    if (d.rounds < 1) throw SimulationError("contact: rounds must be >= 1");
    if (!(d.floor >= 0.0 && d.floor < d.radius)) throw SimulationError("contact: floor must be in [0, radius)");
    model_tris_ = m.triangles;
    nfull_ = m.num_particles();
    // Mean rest edge: the cloth hashes' cell.
    double sum = 0.0;
    int count = 0;
    for (const auto& t : m.triangles)
      for (int k = 0; k < 3; ++k) {
        sum += (m.uv[t[k]] - m.uv[t[(k + 1) % 3]]).norm();
        ++count;
      }
    cloth_cell_ = std::max(count ? sum / count : d.reach, 2.0 * d.reach);
    set_topology(identity_representative(nfull_));
    // The body: its edges once, three static hashes.
    const auto& bv = d.body.vertices;
    for (const auto& t : d.body.triangles)
      for (int k : t)
        if (k < 0 || k >= static_cast<int>(bv.size())) throw SimulationError("contact: a body triangle names a missing vertex");
    std::vector<std::array<int, 2>> be;
    double bsum = 0.0;
    for (const auto& t : d.body.triangles)
      for (int k = 0; k < 3; ++k) {
        const int a = t[k], b = t[(k + 1) % 3];
        be.push_back({std::min(a, b), std::max(a, b)});
        bsum += (bv[a] - bv[b]).norm();
      }
    std::sort(be.begin(), be.end());
    be.erase(std::unique(be.begin(), be.end()), be.end());
    body_edges_ = std::move(be);
    if (!d.body.triangles.empty()) {
      const double cell = std::max(bsum / (3.0 * d.body.triangles.size()), 2.0 * d.reach);
      const auto& bt = d.body.triangles;
      body_tri_box_.resize(bt.size());
      body_tri_hash_.build_items(static_cast<int>(bt.size()), cell, [&](int k, Vec3& lo, Vec3& hi) {
        lo = bv[bt[k][0]].cwiseMin(bv[bt[k][1]]).cwiseMin(bv[bt[k][2]]);
        hi = bv[bt[k][0]].cwiseMax(bv[bt[k][1]]).cwiseMax(bv[bt[k][2]]);
        body_tri_box_[k] = {lo, hi};
        return k;
      });
      body_vertex_hash_.build_items(static_cast<int>(bv.size()), cell, [&](int k, Vec3& lo, Vec3& hi) {
        lo = hi = bv[k];
        return k;
      });
      body_edge_box_.resize(body_edges_.size());
      body_edge_hash_.build_items(static_cast<int>(body_edges_.size()), cell, [&](int k, Vec3& lo, Vec3& hi) {
        lo = bv[body_edges_[k][0]].cwiseMin(bv[body_edges_[k][1]]);
        hi = bv[body_edges_[k][0]].cwiseMax(bv[body_edges_[k][1]]);
        body_edge_box_[k] = {lo, hi};
        return k;
      });
    }
  }

  const char* name() const override { return "contact"; }
  bool needs_every_step() const override { return true; }
  const ContactStats& stats() const { return stats_; }

  void add_forces(const Eval& e, VecX& f) override {
    start_if_needed(e);
    for_each_touching(e.x, e.v, [&](const Contact4& c, double fn, const Vec3& friction) {
      for (int k = 0; k < c.n; ++k) at(f, c.v[k]) += c.w[k] * (fn * c.normal + friction);
    });
  }

  bool add_jacobian(const Eval& e, Triplets& dfdx, Triplets& dfdv) override {
    start_if_needed(e);
    for_each_touching(e.x, e.v, [&](const Contact4& c, double fn, const Vec3&) {
      const Mat3 nn = c.normal * c.normal.transpose();
      const double drag = c.body ? def_.friction * fn / def_.slip_speed : 0.0;
      const double k2 = def_.stiffness;
      for (int k = 0; k < c.n; ++k) {
        for (int j = 0; j < c.n; ++j) add_block(dfdx, c.v[k], c.v[j], -k2 * c.w[k] * c.w[j] * nn);
        if (drag > 0.0) add_block(dfdv, c.v[k], c.v[k], -drag * c.w[k] * c.w[k] * (Mat3::Identity() - nn));
      }
    });
    return true;
  }

  double energy(const Eval& e) const override {
    double sum = 0.0;
    for (const Contact4& c : linear_) {
      const double d = c.along(e.x);
      if (d < def_.radius) sum += 0.5 * def_.stiffness * (def_.radius - d) * (def_.radius - d);
    }
    return sum;
  }

  void add_stiffness_bound(const Model& m, VecX& k_rows, VecX& c_rows) const override {
    // A particle rarely presses on more than a few primitives at once.
    k_rows.array() += 4.0 * def_.stiffness;
    c_rows.array() += def_.friction * def_.stiffness * def_.radius / def_.slip_speed;
  }

  void after_step(const Model& m, State& s) override {
    if (!started_) {  // no force was asked for (an integrator without forces): start here
      xs_ = s.x;
      ts_ = s.t;
      started_ = true;
      detect(reduced(xs_));
      return;
    }
    ++stats_.steps;
    const int n = vertices_;
    std::vector<Vec3> target = reduced(s.x), start = reduced(xs_), cur = start;
    if (!detected_) detect(start);
    std::vector<char> moving(n, 0);
    for (int round = 0; round < def_.rounds; ++round) {
      bool left = false;
      std::fill(moving.begin(), moving.end(), 0);
      for (int r = 0; r < n; ++r) {
        if (fixed_[r]) {
          cur[r] = target[r];
          continue;
        }
        const Vec3 delta = target[r] - cur[r];
        const double a = allowed(r, delta);
        if (a >= 1.0) {
          cur[r] = target[r];
        } else {
          cur[r] += a * delta;
          ++stats_.cut;
          left = true;
          moving[r] = 1;
        }
      }
      if (!left || round + 1 == def_.rounds) {
        detect(cur);
        break;
      }
      detect_moving(cur, moving);
    }
    const double h = s.t - ts_;
    std::vector<Vec3> vel(n);
    for (int r = 0; r < n; ++r) {
      const int i = first_[r];
      vel[r] = cur[r] != target[r] && h > 0.0 ? Vec3((cur[r] - start[r]) / h) : Vec3(at(s.v, i));
    }
    stop_approach(cur, vel);
    for (int i = 0; i < nfull_; ++i) {
      const int r = rep_[i];
      at(s.x, i) = cur[r];
      at(s.v, i) = vel[r];
    }
    for (int r = 0; r < n; ++r)
      if (cur[r] != target[r]) ++stats_.unfinished;
    xs_ = s.x;
    ts_ = s.t;
  }

  // A frame's merges join particles into groups (a seam's corner joins four),
  // each moved to its mass-weighted mean. A group is allowed when each of its
  // particles moves at most γ times its distance to everything that will not
  // be its neighbour after the merge (primitives holding none of the group),
  // so the merges of one frame together keep the bound's promise; the others
  // wait (the seam keeps pulling and asks again).
  void review_merges(const Model& m, const State& full, std::vector<std::array<int, 2>>& requests) override {
    if (requests.empty()) return;
    const std::vector<Vec3> P = reduced(full.x);
    detect(P);  // the hashes at the frame's positions
    // Groups of merged vertices (union–find over the requests).
    std::vector<int> parent(vertices_);
    for (int r = 0; r < vertices_; ++r) parent[r] = r;
    const auto find = [&](int r) {
      while (parent[r] != r) r = parent[r] = parent[parent[r]];
      return r;
    };
    for (const auto& rq : requests) {
      const int a = find(rep_[rq[0]]), b = find(rep_[rq[1]]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
    const std::vector<double>& mass = vertex_mass_;
    std::vector<std::vector<int>> members(vertices_);
    for (const auto& rq : requests)
      for (int k : rq) {
        const int r = rep_[k];
        auto& g = members[find(r)];
        if (std::find(g.begin(), g.end(), r) == g.end()) g.push_back(r);
      }
    std::vector<char> allowed(vertices_, 1);
    for (int root = 0; root < vertices_; ++root) {
      const auto& g = members[root];
      if (g.size() < 2) continue;
      Vec3 mid = Vec3::Zero();
      double total = 0.0;
      bool pinned = false;
      for (int r : g) {
        mid += mass[r] * P[r];
        total += mass[r];
        pinned = pinned || fixed_[r];
      }
      mid /= total;
      if (pinned) continue;  // a pinned particle's group goes where the pin is: not bounded
      for (int r : g)
        if ((mid - P[r]).norm() > def_.gamma * (clearance(r, g, P) - def_.floor)) allowed[root] = 0;
      if (!allowed[root]) ++stats_.merges_held;
    }
    std::vector<std::array<int, 2>> kept;
    for (const auto& rq : requests)
      if (allowed[find(rep_[rq[0]])]) kept.push_back(rq);
    requests = std::move(kept);
  }

  void particles_merged(const Model& m, const std::vector<int>& representative) override {
    set_topology(representative);
    started_ = false;  // the next force call starts from the merged state
    detected_ = false;
  }

 private:
  // Pairs within the contact radius at the step's end stop approaching: an
  // inelastic impulse along their normal, shared by inverse mass and weight
  // (one Gauss–Seidel pass in pair order). It only takes kinetic energy out.
  void stop_approach(const std::vector<Vec3>& P, std::vector<Vec3>& vel) const {
    VecX x(3 * nfull_);
    for (int i = 0; i < nfull_; ++i) at(x, i) = P[rep_[i]];
    for (const Pair& p : pairs_) {
      Contact4 c;
      if (!geometry(p, x, c) || c.d >= def_.radius || sewn(c)) continue;
      double vn = 0.0, wm = 0.0;
      for (int k = 0; k < c.n; ++k) {
        const int r = rep_[c.v[k]];
        vn += c.w[k] * vel[r].dot(c.normal);
        wm += c.w[k] * c.w[k] * inv_mass_[r];
      }
      if (vn >= 0.0 || !(wm > 0.0)) continue;
      const double j = -vn / wm;
      for (int k = 0; k < c.n; ++k) {
        const int r = rep_[c.v[k]];
        vel[r] += (j * c.w[k] * inv_mass_[r]) * c.normal;
      }
    }
  }

  // The largest fraction a ≤ 1 of the move delta vertex r may make: at most
  // γ R in all (pairs beyond the reach), and for each pair no nearer the other
  // primitive than its slack. Two convex primitives d apart stay apart while
  // every point of one moves at most δ₁ towards the other along the normal of
  // their closest points and every point of the other at most δ₂, with
  // δ₁ + δ₂ < d: the plane between them keeps separating them. Sideways and
  // away a vertex moves freely, so cloth pressed onto cloth or the body still
  // slides and lifts off.
  double allowed(int r, const Vec3& delta) const {
    const double len = delta.norm();
    if (len == 0.0) return 1.0;
    double a = std::min(1.0, def_.gamma * def_.reach / len);
    for (int q = limit_start_[r]; q < limit_start_[r + 1]; ++q) {
      const double toward = -limits_[q].u.dot(delta);
      if (limits_[q].u == Vec3::Zero()) a = 0.0;  // touching: no move
      else if (toward > 0.0) a = std::min(a, limits_[q].slack / toward);
    }
    return std::max(0.0, a);
  }

  // ---- topology ------------------------------------------------------------------

  void set_topology(const std::vector<int>& rep) {
    rep_ = rep;
    Model tmp;
    tmp.triangles = model_tris_;
    tmp.mass = VecX::Ones(nfull_);
    const MergedMesh mm = merged_topology(tmp, rep_);
    vertices_ = mm.particles;
    tris_ = mm.triangles;
    edges_ = mm.edges;
    first_.assign(vertices_, -1);
    for (int i = 0; i < nfull_; ++i)
      if (first_[rep_[i]] < 0) first_[rep_[i]] = i;
    vertex_tris_.assign(vertices_, {});
    vertex_edges_.assign(vertices_, {});
    for (int t = 0; t < static_cast<int>(tris_.size()); ++t)
      for (int k : tris_[t]) vertex_tris_[k].push_back(t);
    for (int e = 0; e < static_cast<int>(edges_.size()); ++e)
      for (int k : edges_[e]) vertex_edges_[k].push_back(e);
    fixed_.assign(vertices_, 0);
    for (int p : def_.fixed)
      if (p >= 0 && p < nfull_) fixed_[rep_[p]] = 1;
    vertex_mass_.assign(vertices_, 0.0);
    for (int i = 0; i < nfull_; ++i) vertex_mass_[rep_[i]] += mass_[i];
    partners_.assign(vertices_, {});
    for (const auto& pr : def_.sewn) {
      if (pr[0] < 0 || pr[0] >= nfull_ || pr[1] < 0 || pr[1] >= nfull_) continue;
      const int a = rep_[pr[0]], b = rep_[pr[1]];
      if (a == b) continue;  // merged already
      partners_[a].push_back(b);
      partners_[b].push_back(a);
    }
    inv_mass_.resize(vertices_);
    for (int r = 0; r < vertices_; ++r)
      inv_mass_[r] = fixed_[r] || !(vertex_mass_[r] > 0.0) ? 0.0 : 1.0 / vertex_mass_[r];
  }

  // Vertex v may touch triangle t: not one of its corners.
  bool may_touch_triangle(int v, int t) const {
    const auto& tr = tris_[t];
    return tr[0] != v && tr[1] != v && tr[2] != v;
  }
  // Edges e and g may touch: they share no particle.
  bool may_touch_edge(int e, int g) const {
    const auto& a = edges_[e];
    const auto& b = edges_[g];
    return a[0] != b[0] && a[0] != b[1] && a[1] != b[0] && a[1] != b[1];
  }

  std::vector<Vec3> reduced(const VecX& x) const {
    std::vector<Vec3> p(vertices_);
    for (int r = 0; r < vertices_; ++r) p[r] = at(x, first_[r]);
    return p;
  }

  void start_if_needed(const Eval& e) {
    if (started_) return;
    xs_ = e.x;
    ts_ = e.t;
    started_ = true;
    detect(reduced(xs_));
  }

  // ---- detection -----------------------------------------------------------------

  void detect(const std::vector<Vec3>& P) {
    ++stats_.detections;
    detected_ = true;
    const double R = def_.reach;
    const int nv = vertices_, ne = static_cast<int>(edges_.size()), nt = static_cast<int>(tris_.size());
    const auto& bv = def_.body.vertices;
    const auto& bt = def_.body.triangles;
    const bool body = !bt.empty();
    build_cloth_hashes(P);
    const int threads = nv >= kParallelMin ? omp_get_max_threads() : 1;
    std::vector<std::vector<Pair>> found(threads);
    std::vector<double> min_cloth(threads, 1e300), min_body(threads, 1e300);
    const Vec3 pad = Vec3::Constant(R);
    const double R2 = R * R;
    // A candidate met in several cells is tested once (the last query that
    // met it is remembered per thread), and only when the boxes come within
    // the reach: the exact distances were most of the detection's time.
    if (static_cast<int>(seen_.size()) < threads) seen_.resize(threads);
    for (auto& sn : seen_) {
      sn.tri.assign(nt, -1);
      sn.edge.assign(ne, -1);
      sn.body_tri.assign(def_.body.triangles.size(), -1);
      sn.body_edge.assign(body_edges_.size(), -1);
    }
#pragma omp parallel num_threads(threads)
    {
      const int id = omp_get_thread_num();
      auto& out = found[id];
      double& mc = min_cloth[id];
      double& mb = min_body[id];
      Seen& sn = seen_[id];
      Vec3 w;
#pragma omp for schedule(static)
      for (int v = 0; v < nv; ++v) {
        const Vec3& p = P[v];
        cloth_tri_hash_.for_each_in_box(p - pad, p + pad, [&](int t) {
          if (sn.tri[t] == v) return;
          sn.tri[t] = v;
          if (box_gap2(p, p, tri_box_[t].lo, tri_box_[t].hi) >= R2 || !may_touch_triangle(v, t)) return;
          const auto& tr = tris_[t];
          const double d = point_triangle_distance(p, P[tr[0]], P[tr[1]], P[tr[2]], w);
          if (d < R) out.push_back({Kind::vertex_triangle, v, t});
          mc = std::min(mc, d);
        });
        if (body)
          body_tri_hash_.for_each_in_box(p - pad, p + pad, [&](int t) {
            if (sn.body_tri[t] == v) return;
            sn.body_tri[t] = v;
            if (box_gap2(p, p, body_tri_box_[t].lo, body_tri_box_[t].hi) >= R2) return;
            const double d = point_triangle_distance(p, bv[bt[t][0]], bv[bt[t][1]], bv[bt[t][2]], w);
            if (d < R) out.push_back({Kind::vertex_body, v, t});
            mb = std::min(mb, d);
          });
      }
#pragma omp for schedule(static)
      for (int t = 0; t < (body ? nt : 0); ++t) {
        const auto& tr = tris_[t];
        const Vec3 lo = P[tr[0]].cwiseMin(P[tr[1]]).cwiseMin(P[tr[2]]) - pad;
        const Vec3 hi = P[tr[0]].cwiseMax(P[tr[1]]).cwiseMax(P[tr[2]]) + pad;
        body_vertex_hash_.for_each_in_box(lo, hi, [&](int q) {
          const double d = point_triangle_distance(bv[q], P[tr[0]], P[tr[1]], P[tr[2]], w);
          if (d < R) out.push_back({Kind::body_triangle, t, q});
          mb = std::min(mb, d);
        });
      }
#pragma omp for schedule(static)
      for (int e = 0; e < ne; ++e) {
        const Vec3& a = P[edges_[e][0]];
        const Vec3& b = P[edges_[e][1]];
        const Vec3 lo = a.cwiseMin(b) - pad, hi = a.cwiseMax(b) + pad;
        double s, u;
        const Box& be = edge_box_[e];
        cloth_edge_hash_.for_each_in_box(lo, hi, [&](int g) {
          if (g <= e || sn.edge[g] == e) return;
          sn.edge[g] = e;
          if (box_gap2(be.lo, be.hi, edge_box_[g].lo, edge_box_[g].hi) >= R2 || !may_touch_edge(e, g)) return;
          const double d = segment_distance(a, b, P[edges_[g][0]], P[edges_[g][1]], s, u);
          if (d < R) out.push_back({Kind::edge_edge, e, g});
          mc = std::min(mc, d);
        });
        if (body)
          body_edge_hash_.for_each_in_box(lo, hi, [&](int g) {
            if (sn.body_edge[g] == e) return;
            sn.body_edge[g] = e;
            if (box_gap2(be.lo, be.hi, body_edge_box_[g].lo, body_edge_box_[g].hi) >= R2) return;
            const double d = segment_distance(a, b, bv[body_edges_[g][0]], bv[body_edges_[g][1]], s, u);
            if (d < R) out.push_back({Kind::edge_body, e, g});
            mb = std::min(mb, d);
          });
      }
    }
    pairs_.clear();
    for (auto& f : found) pairs_.insert(pairs_.end(), f.begin(), f.end());
    std::sort(pairs_.begin(), pairs_.end());
    pairs_.erase(std::unique(pairs_.begin(), pairs_.end()), pairs_.end());
    for (int k = 0; k < threads; ++k) {
      stats_.min_cloth = std::min(stats_.min_cloth, min_cloth[k]);
      stats_.min_body = std::min(stats_.min_body, min_body[k]);
    }
    stats_.pairs = static_cast<int>(pairs_.size());
    // Each pair's normal, weights and the body's point, frozen here: the
    // forces until the next detection are linear in the positions, so an
    // implicit step's linearisation of them is exact (a normal recomputed
    // at the step's unbounded end would flip where that end has passed
    // through, and the step be refused).
    VecX x(3 * nfull_);
    for (int i = 0; i < nfull_; ++i) at(x, i) = P[rep_[i]];
    // Against the body one pair per cloth vertex, its nearest body triangle:
    // every triangle, edge and vertex of a finely meshed body near it would
    // each push, and stiffen the contact by their number. The body's
    // vertices and edges against the cloth's triangles and edges stay in the
    // bound (a sharp part never passes between particles) but push nothing.
    linear_.clear();
    int nearest_body = -1;  // index in linear_ of the current vertex's body pair
    for (const Pair& p : pairs_) {
      if (p.kind == Kind::body_triangle || p.kind == Kind::edge_body) continue;
      Contact4 c;
      if (!geometry(p, x, c) || sewn(c)) continue;
      if (p.kind == Kind::vertex_body) {
        // Pairs are sorted by vertex: keep the nearest of this vertex's.
        if (nearest_body >= 0 && linear_[nearest_body].v[0] == c.v[0]) {
          if (c.d < linear_[nearest_body].d) linear_[nearest_body] = c;
          continue;
        }
        nearest_body = static_cast<int>(linear_.size());
      }
      linear_.push_back(c);
    }
    set_limits(pairs_, x, nullptr);
  }

  // The bound (header): per vertex, the half-spaces of every pair it is in
  // (of those vertices flagged in `only`, when given; the others get none).
  void set_limits(const std::vector<Pair>& pairs, const VecX& x, const std::vector<char>* only) {
    const int nv = vertices_;
    limit_start_.assign(nv + 1, 0);
    std::vector<Contact4> all;
    all.reserve(pairs.size());
    for (const Pair& p : pairs) {
      Contact4 c;
      if (geometry(p, x, c)) all.push_back(c);
      else {  // touching (d ≤ 1e-12): nothing of it may move nearer, in any direction
        c.normal = Vec3::Zero();
        c.d = 0.0;
        all.push_back(c);
      }
    }
    const auto wanted = [&](int r) { return !only || (*only)[r]; };
    for (const Contact4& c : all)
      for (int k = 0; k < c.n; ++k)
        if (wanted(rep_[c.v[k]])) ++limit_start_[rep_[c.v[k]] + 1];
    for (int r = 0; r < nv; ++r) limit_start_[r + 1] += limit_start_[r];
    limits_.resize(limit_start_[nv]);
    std::vector<int> fill(limit_start_.begin(), limit_start_.end() - 1);
    for (const Contact4& c : all)
      for (int k = 0; k < c.n; ++k)
        if (wanted(rep_[c.v[k]]))
          limits_[fill[rep_[c.v[k]]]++] = {c.side[k] * c.normal, def_.gamma * std::max(0.0, c.d - def_.floor)};
  }

  void build_cloth_hashes(const std::vector<Vec3>& P) {
    const int nt = static_cast<int>(tris_.size()), ne = static_cast<int>(edges_.size()), nv = vertices_;
    tri_box_.resize(nt);
    edge_box_.resize(ne);
    cloth_tri_hash_.build_items(nt, cloth_cell_, [&](int k, Vec3& lo, Vec3& hi) {
      lo = P[tris_[k][0]].cwiseMin(P[tris_[k][1]]).cwiseMin(P[tris_[k][2]]);
      hi = P[tris_[k][0]].cwiseMax(P[tris_[k][1]]).cwiseMax(P[tris_[k][2]]);
      tri_box_[k] = {lo, hi};
      return k;
    });
    cloth_edge_hash_.build_items(ne, cloth_cell_, [&](int k, Vec3& lo, Vec3& hi) {
      lo = P[edges_[k][0]].cwiseMin(P[edges_[k][1]]);
      hi = P[edges_[k][0]].cwiseMax(P[edges_[k][1]]);
      edge_box_[k] = {lo, hi};
      return k;
    });
    cloth_vertex_hash_.build_items(nv, cloth_cell_, [&](int k, Vec3& lo, Vec3& hi) {
      lo = hi = P[k];
      return k;
    });
  }

  // Between a step's rounds only the particles still short of their end move:
  // their half-spaces come from the pairs that hold one of them (found from
  // their vertices, edges and triangles; the same pairs a whole detection
  // finds for them), and nothing else is detected. The step's last detection
  // is whole: the next step's forces and first round need every pair.
  void detect_moving(const std::vector<Vec3>& P, const std::vector<char>& moving) {
    ++stats_.local_detections;
    build_cloth_hashes(P);
    const double R = def_.reach, R2 = R * R;
    const Vec3 pad = Vec3::Constant(R);
    const int nt = static_cast<int>(tris_.size()), ne = static_cast<int>(edges_.size());
    const auto& bv = def_.body.vertices;
    const auto& bt = def_.body.triangles;
    const bool body = !bt.empty();
    std::vector<char> tri_in(nt, 0), edge_in(ne, 0);
    for (int v = 0; v < vertices_; ++v)
      if (moving[v]) {
        for (int t : vertex_tris_[v]) tri_in[t] = 1;
        for (int e : vertex_edges_[v]) edge_in[e] = 1;
      }
    if (seen_.empty()) seen_.resize(1);
    Seen& sn = seen_[0];
    sn.tri.assign(nt, -1);
    sn.edge.assign(ne, -1);
    sn.body_tri.assign(bt.size(), -1);
    sn.body_edge.assign(body_edges_.size(), -1);
    std::vector<Pair> found;
    Vec3 w;
    double s, u;
    for (int v = 0; v < vertices_; ++v) {
      if (!moving[v]) continue;
      const Vec3& p = P[v];
      cloth_tri_hash_.for_each_in_box(p - pad, p + pad, [&](int t) {
        if (sn.tri[t] == v) return;
        sn.tri[t] = v;
        if (box_gap2(p, p, tri_box_[t].lo, tri_box_[t].hi) >= R2 || !may_touch_triangle(v, t)) return;
        if (point_triangle_distance(p, P[tris_[t][0]], P[tris_[t][1]], P[tris_[t][2]], w) < R)
          found.push_back({Kind::vertex_triangle, v, t});
      });
      if (body)
        body_tri_hash_.for_each_in_box(p - pad, p + pad, [&](int t) {
          if (sn.body_tri[t] == v) return;
          sn.body_tri[t] = v;
          if (box_gap2(p, p, body_tri_box_[t].lo, body_tri_box_[t].hi) >= R2) return;
          if (point_triangle_distance(p, bv[bt[t][0]], bv[bt[t][1]], bv[bt[t][2]], w) < R)
            found.push_back({Kind::vertex_body, v, t});
        });
    }
    for (int t = 0; t < nt; ++t) {
      if (!tri_in[t]) continue;
      const auto& tr = tris_[t];
      const Vec3 lo = tri_box_[t].lo - pad, hi = tri_box_[t].hi + pad;
      cloth_vertex_hash_.for_each_in_box(lo, hi, [&](int q) {
        if (!may_touch_triangle(q, t)) return;
        if (point_triangle_distance(P[q], P[tr[0]], P[tr[1]], P[tr[2]], w) < R)
          found.push_back({Kind::vertex_triangle, q, t});
      });
      if (body)
        body_vertex_hash_.for_each_in_box(lo, hi, [&](int q) {
          if (point_triangle_distance(bv[q], P[tr[0]], P[tr[1]], P[tr[2]], w) < R)
            found.push_back({Kind::body_triangle, t, q});
        });
    }
    for (int e = 0; e < ne; ++e) {
      if (!edge_in[e]) continue;
      const Vec3& a = P[edges_[e][0]];
      const Vec3& b = P[edges_[e][1]];
      const Box& be = edge_box_[e];
      cloth_edge_hash_.for_each_in_box(be.lo - pad, be.hi + pad, [&](int g) {
        if (g == e || sn.edge[g] == e) return;
        sn.edge[g] = e;
        if (box_gap2(be.lo, be.hi, edge_box_[g].lo, edge_box_[g].hi) >= R2 || !may_touch_edge(e, g)) return;
        // In the whole detection's order (smaller edge first): the same arithmetic.
        const int e0 = std::min(e, g), e1 = std::max(e, g);
        if (segment_distance(P[edges_[e0][0]], P[edges_[e0][1]], P[edges_[e1][0]], P[edges_[e1][1]], s, u) < R)
          found.push_back({Kind::edge_edge, e0, e1});
      });
      if (body)
        body_edge_hash_.for_each_in_box(be.lo - pad, be.hi + pad, [&](int g) {
          if (sn.body_edge[g] == e) return;
          sn.body_edge[g] = e;
          if (box_gap2(be.lo, be.hi, body_edge_box_[g].lo, body_edge_box_[g].hi) >= R2) return;
          if (segment_distance(a, b, bv[body_edges_[g][0]], bv[body_edges_[g][1]], s, u) < R)
            found.push_back({Kind::edge_body, e, g});
        });
    }
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    VecX x(3 * nfull_);
    for (int i = 0; i < nfull_; ++i) at(x, i) = P[rep_[i]];
    set_limits(found, x, &moving);
    detected_ = false;  // pairs_ and the forces' pairs are not those of P
  }

  // The distance (capped at the reach) from vertex v and the edges and
  // triangles holding it to every primitive holding none of `group`.
  double clearance(int v, const std::vector<int>& group, const std::vector<Vec3>& P) const {
    const double R = def_.reach;
    const Vec3 pad = Vec3::Constant(R);
    const auto& bv = def_.body.vertices;
    const auto& bt = def_.body.triangles;
    const bool body = !bt.empty();
    const auto in_group = [&](int k) { return std::find(group.begin(), group.end(), k) != group.end(); };
    const auto holds = [&](const auto& prim) {
      for (int k : prim)
        if (in_group(k)) return true;
      return false;
    };
    double best = R, s, u;
    Vec3 w;
    const Vec3& p = P[v];
    cloth_tri_hash_.for_each_in_box(p - pad, p + pad, [&](int t) {
      if (holds(tris_[t])) return;
      best = std::min(best, point_triangle_distance(p, P[tris_[t][0]], P[tris_[t][1]], P[tris_[t][2]], w));
    });
    if (body)
      body_tri_hash_.for_each_in_box(p - pad, p + pad, [&](int t) {
        best = std::min(best, point_triangle_distance(p, bv[bt[t][0]], bv[bt[t][1]], bv[bt[t][2]], w));
      });
    for (int e : vertex_edges_[v]) {
      const auto& ev = edges_[e];
      const Vec3& e0 = P[ev[0]];
      const Vec3& e1 = P[ev[1]];
      const Vec3 lo = e0.cwiseMin(e1) - pad, hi = e0.cwiseMax(e1) + pad;
      cloth_edge_hash_.for_each_in_box(lo, hi, [&](int g) {
        const auto& eg = edges_[g];
        if (holds(eg) || eg[0] == ev[0] || eg[0] == ev[1] || eg[1] == ev[0] || eg[1] == ev[1]) return;
        best = std::min(best, segment_distance(e0, e1, P[eg[0]], P[eg[1]], s, u));
      });
      if (body)
        body_edge_hash_.for_each_in_box(lo, hi, [&](int g) {
          best = std::min(best, segment_distance(e0, e1, bv[body_edges_[g][0]], bv[body_edges_[g][1]], s, u));
        });
    }
    for (int t : vertex_tris_[v]) {
      const auto& tr = tris_[t];
      const Vec3 lo = P[tr[0]].cwiseMin(P[tr[1]]).cwiseMin(P[tr[2]]) - pad;
      const Vec3 hi = P[tr[0]].cwiseMax(P[tr[1]]).cwiseMax(P[tr[2]]) + pad;
      cloth_vertex_hash_.for_each_in_box(lo, hi, [&](int q) {
        if (in_group(q) || q == tr[0] || q == tr[1] || q == tr[2]) return;
        best = std::min(best, point_triangle_distance(P[q], P[tr[0]], P[tr[1]], P[tr[2]], w));
      });
      if (body)
        body_vertex_hash_.for_each_in_box(lo, hi, [&](int q) {
          best = std::min(best, point_triangle_distance(bv[q], P[tr[0]], P[tr[1]], P[tr[2]], w));
        });
    }
    return best;
  }

  // ---- forces --------------------------------------------------------------------

  // A cloth pair whose two primitives hold a particle and its seam partner.
  bool sewn(const Contact4& c) const {
    if (c.body) return false;
    const int n = std::min(c.n, 4);  // c.v holds at most four
    for (int k = 0; k < n; ++k) {
      if (c.side[k] < 0) continue;
      for (int partner : partners_[rep_[c.v[k]]])
        for (int j = 0; j < n; ++j)
          if (c.side[j] < 0 && rep_[c.v[j]] == partner) return true;
    }
    return false;
  }

  // The pair's geometry at positions x (full vector; a vertex is read from
  // its first copy and its force goes there). False when degenerate.
  bool geometry(const Pair& p, const VecX& x, Contact4& c) const {
    const auto& bv = def_.body.vertices;
    const auto X = [&](int r) -> Vec3 { return at(x, first_[r]); };
    Vec3 w;
    double s, u;
    Vec3 from, to;  // closest points: `to` on the primitive the normal points to
    switch (p.kind) {
      case Kind::vertex_triangle: {
        const auto& t = tris_[p.b];
        const Vec3 q = X(p.a);
        c.d = point_triangle_distance(q, X(t[0]), X(t[1]), X(t[2]), w);
        from = w[0] * X(t[0]) + w[1] * X(t[1]) + w[2] * X(t[2]);
        to = q;
        c.n = 4;
        c.v = {first_[p.a], first_[t[0]], first_[t[1]], first_[t[2]]};
        c.w = {1.0, -w[0], -w[1], -w[2]};
        c.side = {1, -1, -1, -1};
        break;
      }
      case Kind::edge_edge: {
        const auto& e = edges_[p.a];
        const auto& g = edges_[p.b];
        c.d = segment_distance(X(e[0]), X(e[1]), X(g[0]), X(g[1]), s, u);
        to = (1 - s) * X(e[0]) + s * X(e[1]);
        from = (1 - u) * X(g[0]) + u * X(g[1]);
        c.n = 4;
        c.v = {first_[e[0]], first_[e[1]], first_[g[0]], first_[g[1]]};
        c.w = {1 - s, s, -(1 - u), -u};
        c.side = {1, 1, -1, -1};
        break;
      }
      case Kind::vertex_body: {
        const auto& t = def_.body.triangles[p.b];
        to = X(p.a);
        c.d = point_triangle_distance(to, bv[t[0]], bv[t[1]], bv[t[2]], w);
        from = w[0] * bv[t[0]] + w[1] * bv[t[1]] + w[2] * bv[t[2]];
        c.base = from;
        c.n = 1;
        c.v[0] = first_[p.a];
        c.w[0] = 1.0;
        c.body = true;
        break;
      }
      case Kind::body_triangle: {
        const auto& t = tris_[p.a];
        from = bv[p.b];
        c.base = from;
        c.d = point_triangle_distance(from, X(t[0]), X(t[1]), X(t[2]), w);
        to = w[0] * X(t[0]) + w[1] * X(t[1]) + w[2] * X(t[2]);
        c.n = 3;
        c.v = {first_[t[0]], first_[t[1]], first_[t[2]], 0};
        c.w = {w[0], w[1], w[2], 0.0};
        c.body = true;
        break;
      }
      case Kind::edge_body: {
        const auto& e = edges_[p.a];
        const auto& g = body_edges_[p.b];
        c.d = segment_distance(X(e[0]), X(e[1]), bv[g[0]], bv[g[1]], s, u);
        to = (1 - s) * X(e[0]) + s * X(e[1]);
        from = (1 - u) * bv[g[0]] + u * bv[g[1]];
        c.base = from;
        c.n = 2;
        c.v = {first_[e[0]], first_[e[1]], 0, 0};
        c.w = {1 - s, s, 0.0, 0.0};
        c.body = true;
        break;
      }
    }
    if (!(c.d > 1e-12)) return false;
    c.normal = (to - from) / c.d;
    return true;
  }

  // Calls f(contact, normal force magnitude, friction force on the cloth
  // point) for every pair within the contact radius at x.
  template <class F>
  void for_each_touching(const VecX& x, const VecX& v, F&& f) {
    int touching = 0;
    for (const Contact4& c : linear_) {
      const double d = c.along(x);
      if (d >= def_.radius) continue;
      ++touching;
      const double fn = def_.stiffness * (def_.radius - d);
      Vec3 friction = Vec3::Zero();
      if (c.body && def_.friction > 0.0) {
        Vec3 u = Vec3::Zero();
        for (int k = 0; k < c.n; ++k) u += c.w[k] * at(v, c.v[k]);
        const Vec3 slip = u - u.dot(c.normal) * c.normal;
        friction = -def_.friction * fn * slip / std::max(slip.norm(), def_.slip_speed);
      }
      f(c, fn, friction);
    }
    stats_.touching = touching;
  }

  ContactDef def_;
  VecX mass_;                // kg, per model particle
  std::vector<double> vertex_mass_;  // kg per merged vertex
  std::vector<double> inv_mass_;     // 1/kg per merged vertex (0: fixed)
  std::vector<std::array<int, 3>> model_tris_;
  int nfull_ = 0;
  // The merged mesh.
  std::vector<int> rep_, first_;
  int vertices_ = 0;
  std::vector<std::array<int, 3>> tris_;
  std::vector<std::array<int, 2>> edges_;
  std::vector<std::vector<int>> vertex_tris_, vertex_edges_;
  std::vector<char> fixed_;
  std::vector<std::vector<int>> partners_;  // per merged vertex: its seam partners
  // The body.
  std::vector<std::array<int, 2>> body_edges_;
  SpatialHash body_tri_hash_, body_vertex_hash_, body_edge_hash_;
  // Detection.
  double cloth_cell_ = 0.0;
  SpatialHash cloth_tri_hash_, cloth_edge_hash_, cloth_vertex_hash_;
  struct Box {
    Vec3 lo, hi;
  };
  std::vector<Box> tri_box_, edge_box_, body_tri_box_, body_edge_box_;
  struct Seen {  // per thread: the last query item that met each candidate
    std::vector<int> tri, edge, body_tri, body_edge;
  };
  std::vector<Seen> seen_;
  std::vector<Pair> pairs_;
  std::vector<Contact4> linear_;  // pairs_ frozen at the detection
  // Per vertex (CSR): each pair it is in allows it to move at most `slack`
  // towards the other primitive: u · Δ ≥ −slack, u its unit normal away from it.
  struct Limit {
    Vec3 u;
    double slack;
  };
  std::vector<int> limit_start_;
  std::vector<Limit> limits_;
  bool detected_ = false;
  // The step's start.
  VecX xs_;
  double ts_ = 0.0;
  bool started_ = false;
  ContactStats stats_;
};

}  // namespace

std::unique_ptr<Effect> make_contact(const Model& model, const ContactDef& def) {
  return std::make_unique<ContactEffect>(model, def);
}

const ContactStats& contact_stats(const Effect& effect) {
  const auto* c = dynamic_cast<const ContactEffect*>(&effect);
  VGD_ASSERT(c, "contact_stats: not a contact effect");
  return c->stats();
}

}  // namespace vgd::sim
