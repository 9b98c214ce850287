// Cloth against a static body: detection on a signed distance grid, responses
// after each step (positions and velocities) and, for seed 002's slide, on the
// total force (include/vgd/sim/effects/body_collision.hpp).
//
// Why a grid and not the BVH (docs/collisions.md has the figures): a query on
// the grid costs a few tens of ns whatever the body's triangle count, the BVH's
// several hundred; the grid's error near a body-like surface (≈ 0.02 mm at 5 mm
// spacing on a 0.3 m sphere) is two orders below the 3 mm clearance. The BVH is
// kept as the fallback where the grid knows no direction (deeper inside than
// its band) and as the exact option for bodies with features finer than the
// spacing.
#include "vgd/sim/effects/body_collision.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>

#include <omp.h>

#include "vgd/core/diagnostics.hpp"

namespace vgd::sim {
namespace {

// Below this many particles the threads cost more than the queries they share.
constexpr int kParallelMinParticles = 2000;
// m: cell of the body-vertex grid (a few vertices of a scanned body per cell).
constexpr double kVertexCell = 0.02;
constexpr long kMaxVertexCells = 4'000'000;
// m: body triangles with an edge longer than this get points between their
// corners, this far apart at most (at most kMaxLattice per edge).
constexpr double kBodySample = 0.006;
constexpr int kMaxLattice = 32;
// m: body parts of a radius of curvature below this push cloth triangles with
// their points (see build_vertex_grid).
constexpr double kSharpRadius = 0.03;
// m: a cloth sample is tested only when one of its particles is this near the
// body (a triangle wholly further has no part of the body between its corners
// unless the body is thinner than it: a particle within a triangle's edge).
constexpr double kSampleNear = 0.02;

// Runs visit(i, mine) for i in [0, n), on OpenMP threads when `parallel`,
// each thread appending to its own list, and joins the lists in thread
// order: with the static schedule that is the order of i, as on one thread,
// so what is found does not depend on the threads.
template <class T, class Visit>
std::vector<T> gather_in_order(int n, bool parallel, Visit&& visit) {
  std::vector<std::vector<T>> by_thread;
#pragma omp parallel if (parallel)
  {
#pragma omp single
    by_thread.resize(omp_get_num_threads());
    std::vector<T> mine;
#pragma omp for schedule(static) nowait
    for (int i = 0; i < n; ++i) visit(i, mine);
    by_thread[omp_get_thread_num()] = std::move(mine);
  }
  std::vector<T> out;
  for (auto& list : by_thread) out.insert(out.end(), list.begin(), list.end());
  return out;
}


class BodyCollision final : public Effect {
 public:
  BodyCollision(const Model& m, const BodyCollisionDef& d)
      : def_(d), bvh_(d.body), n_(m.num_particles()), tris_(m.triangles) {
    if (d.body.triangles.empty()) throw SimulationError("body collision: the body mesh has no triangles");
    if (!(d.clearance >= 0.0)) throw SimulationError("body collision: clearance must be >= 0");
    if (d.query == BodyQuery::grid) {
      if (d.grid.band <= d.clearance)
        throw SimulationError("body collision: the distance grid's band (" + std::to_string(d.grid.band) +
                              " m) must exceed the clearance (" + std::to_string(d.clearance) + " m)");
      grid_.emplace(d.body, d.grid);
    }
    role_.assign(n_, 0);
    auto mark = [&](const std::vector<int>& list, unsigned char bit, const char* what) {
      for (int p : list) {
        if (p < 0 || p >= n_)
          throw SimulationError(std::string("body collision: ") + what + " particle " + std::to_string(p) +
                                " does not exist (the model has " + std::to_string(n_) + ")");
        role_[p] |= bit;
      }
    };
    mark(d.seam_particles, kSeam, "seam");
    mark(d.sticky_particles, kSticky, "sticky");
    mark(d.fixed, kFixed, "fixed");
    contact_.assign(n_, 0);
    normal_.assign(n_, Vec3::Zero());
    solve_dvn_.assign(n_, 0.0);
    static_.assign(n_, 0);
    contacts_.body_velocity = d.velocity;
    contacts_.friction = d.response == ContactResponse::provot ? d.friction : 0.0;
    anchor_.assign(n_, Vec3::Zero());
    if (!(d.vertex_clearance >= 0.0) || !(d.vertex_reach > 0.0))
      throw SimulationError("body collision: vertex_clearance must be >= 0 and vertex_reach > 0");
    if (d.vertex_clearance > 0.0 && !tris_.empty()) {
      build_vertex_grid();
      build_cloth_samples();
    }
    rep_.resize(n_);
    std::iota(rep_.begin(), rep_.end(), 0);
    dist_.assign(n_, 0.0);
    constrains_ = d.response == ContactResponse::slide || !d.sticky_particles.empty() ||
                  (!d.seam_particles.empty() && d.seam_contact != SeamContact::glide);
  }

  const char* name() const override { return "body-collision"; }
  bool needs_every_step() const override { return true; }
  void add_forces(const Eval&, VecX&) override {}  // acts on the total force and after steps
  bool add_jacobian(const Eval&, Triplets&, Triplets&) override { return true; }

  bool constrains_forces() const override { return constrains_; }

  // The contacts found after the last step stand for the whole next step (the
  // seed cancels the force of a particle that has struck the body).
  void constrain_forces(const Eval&, VecX& f) override {
    for (int i = 0; i < n_; ++i) {
      if (!contact_[i]) continue;
      auto fi = at(f, i);
      if (contact_[i] == kStuckContact) {
        fi.setZero();
        continue;
      }
      const Vec3& nrm = normal_[i];
      const double fn = fi.dot(nrm);
      if (fn >= 0.0) continue;  // pulling away from the body: free to leave
      if ((role_[i] & kSeam) && def_.seam_contact != SeamContact::glide) {
        fi = def_.seam_contact == SeamContact::seed ? keep_magnitude_tangential(fi, nrm, fn) : Vec3(fi - fn * nrm);
      } else if (def_.response == ContactResponse::slide) {
        fi -= fn * nrm;
      }
    }
  }

  void after_step(const Model&, State& s) override {
    int in_contact = 0;
    long contacts = 0;
    double max_pen = stats_.max_penetration, max_viol = stats_.max_clearance_violation;
    int stuck = 0;
    const double c = def_.clearance;
    // The step just taken (s), for the friction's position correction; unknown
    // (0: no correction) at the first call.
    const double h = std::isfinite(last_t_) && s.t > last_t_ ? s.t - last_t_ : 0.0;
    last_t_ = s.t;
    h_ = h;
    const double near = 1.5 * c;  // within this, a particle counts as touching for the force constraint
    double* x = s.x.data();
    double* v = s.v.data();
    // A moving body: positions in its frame, velocities relative to it.
    const Vec3 offset = def_.velocity * s.t, vb = def_.velocity;
#pragma omp parallel for schedule(static) if (n_ >= kParallelMinParticles) \
    reduction(+ : in_contact, contacts, stuck) reduction(max : max_pen, max_viol)
    for (int i = 0; i < n_; ++i) {
      dist_[i] = 0.0;  // unknown: not pruned by the body points' test
      if (role_[i] & kFixed) continue;
      Eigen::Map<Vec3> xi(x + 3 * i), vi(v + 3 * i);
      if (contact_[i] == kStuckContact) {
        xi = anchor_[i] + offset;  // anchors are kept in the body's frame
        vi = vb;
        ++in_contact;
        ++stuck;
        continue;
      }
      Vec3 nrm;
      const double d = query(xi - offset, nrm);
      dist_[i] = std::max(0.0, d);
      // Normal velocity change the step's contact constraint took (implicit
      // Euler; 0 for the other methods): friction counts it below.
      const double held = solve_dvn_[i];
      solve_dvn_[i] = 0.0;
      static_[i] = 0;
      contact_[i] = 0;
      if (d >= near) continue;
      contact_[i] = 1;
      normal_[i] = nrm;
      ++in_contact;
      if (d >= c && held <= 0.0) continue;
      if (d < c) {
        ++contacts;
        max_pen = std::max(max_pen, -d);
        max_viol = std::max(max_viol, c - d);
        xi += (c - d) * nrm;  // out to the clearance along the normal
        if (role_[i] & kSticky) {
          anchor_[i] = xi - offset;
          vi = vb;
          contact_[i] = kStuckContact;
          ++stuck;
          continue;
        }
      }
      const Vec3 vr = vi - vb;  // relative to the body
      const double vn = vr.dot(nrm);
      if (vn >= 0.0 && (held <= 0.0 || def_.response == ContactResponse::slide || (role_[i] & kSeam)))
        continue;  // already leaving (friction only where the step held the particle)
      if (role_[i] & kSeam) {
        vi = vb + (def_.seam_contact == SeamContact::seed ? keep_magnitude_tangential(vr, nrm, vn) : Vec3(vr - vn * nrm));
        continue;
      }
      const Vec3 vt = vr - vn * nrm;
      if (def_.response == ContactResponse::slide) {
        vi = vb + vt;
        continue;
      }
      // Provot: bounce fast impacts, stop slow ones; Coulomb friction takes at
      // most μ times the normal velocity change off the tangential velocity:
      // the one made here and the one the step's contact constraint made.
      const double vin = std::min(vn, 0.0);
      const double e = -vin > def_.min_bounce_speed ? def_.restitution : 0.0;
      const double dvn = -(1.0 + e) * vin + held;
      const double vt_len = vt.norm();
      const double keep = vt_len > 0.0 ? std::max(0.0, 1.0 - def_.friction * dvn / vt_len) : 0.0;
      vi = vb + keep * vt - e * vin * nrm;
      static_[i] = keep == 0.0;
      if (vn > 0.0) vi += vn * nrm;  // held by the step and leaving: the normal velocity stays
      // The step moved the particle with its velocity before friction: take
      // back the tangential part friction removed (x = x0 + h v_after), or a
      // particle held by static friction would creep h² g sin θ per step.
      if (held <= 0.0) xi -= h * (1.0 - keep) * vt;
    }
    stats_.in_contact = in_contact;
    stats_.stuck = stuck;
    stats_.contacts += contacts;
    stats_.max_penetration = max_pen;
    stats_.max_clearance_violation = max_viol;
    stats_.queries += n_;
    if (!samples_.empty()) push_cloth_samples_out(s, offset, vb);
    if (!cells_.empty()) push_triangles_off_body_vertices(s, offset, vb);
  }

  // A merged seam particle has no partner left to slide towards: it takes the
  // ordinary response from now on.
  void particles_merged(const Model&, const std::vector<int>& representative) override {
    const int n = std::min<int>(n_, static_cast<int>(representative.size()));
    std::vector<int> copies(n, 0);  // original particles per reduced particle
    for (int i = 0; i < n; ++i) ++copies[representative[i]];
    for (int i = 0; i < n; ++i)
      if (copies[representative[i]] > 1) role_[i] &= static_cast<unsigned char>(~kSeam);
    // The first original particle of each reduced one stands for its copies.
    std::vector<int> first(n_, -1);
    for (int i = 0; i < n; ++i) {
      int& f = first[representative[i]];
      if (f < 0) f = i;
      rep_[i] = f;
    }
  }

  const BodyCollisionStats& stats() const { return stats_; }
  // The particles touching after the last after-step, for an implicit step
  // that holds them (IntegratorSettings::hold_contacts). Gathered when asked,
  // so that scenes that do not hold contacts pay nothing for it.
  const BodyContacts& contacts() const {
    contacts_.particle.clear();
    contacts_.normal.clear();
    contacts_.stuck.clear();
    for (int i = 0; i < n_; ++i)
      if (contact_[i] == 1 && !(role_[i] & kFixed)) {
        contacts_.particle.push_back(i);
        contacts_.normal.push_back(normal_[i]);
        contacts_.stuck.push_back(static_[i]);
      }
    return contacts_;
  }
  void add_normal_impulse(int i, double dv) {
    if (i >= 0 && i < n_ && dv > 0.0) solve_dvn_[i] += dv;
  }
  const SignedDistanceGrid* grid() const { return grid_ ? &*grid_ : nullptr; }

 private:
  static constexpr unsigned char kSeam = 1, kSticky = 2, kFixed = 4;
  static constexpr unsigned char kStuckContact = 2;  // contact_ value of a stuck particle

  // Seed 002 §3.2.2: the tangential direction of w, with w's magnitude. A w
  // purely along the normal has no tangential direction: it is stopped.
  static Vec3 keep_magnitude_tangential(const Vec3& w, const Vec3& nrm, double wn) {
    const Vec3 t = w - wn * nrm;
    const double len = t.norm();
    if (len <= 1e-12 * w.norm()) return Vec3::Zero();
    return (w.norm() / len) * t;
  }

  // Signed distance (m) and outward unit normal at p.
  double query(const Vec3& p, Vec3& nrm) const {
    if (grid_) {
      Vec3 g;
      const double d = grid_->sample(p, g);
      const double len = g.norm();
      // Inside the band the gradient of a distance is unit; beyond it (deep
      // inside, where the grid holds −band) it vanishes, and on the medial axis
      // of thin parts it is unreliable: there ask the BVH.
      if (d > -grid_->band() + grid_->spacing() && len > 0.5) {
        nrm = g / len;
        return d;
      }
      if (d >= 1.5 * def_.clearance) {  // outside and not touching: no direction needed
        nrm.setZero();
        return d;
      }
    }
    const auto cl = bvh_.closest(p);
    nrm = cl.normal;
    return cl.distance;
  }

  // ---- body vertices against cloth triangles ----
  // A uniform grid of the body's points (static, in the body's frame), in
  // compressed rows.
  void build_vertex_grid() {
    const auto& bv0 = def_.body.vertices;
    const auto& tris = def_.body.triangles;
    const int nv = static_cast<int>(bv0.size());
    const MeshNormals& normals = bvh_.normals();
    // The points: the sharp vertices, and over the triangles that have one,
    // points on a lattice kBodySample apart (inside each triangle, and on
    // each of its edges once), their normals interpolated, so that a coarse
    // body's faces and ridges between vertices push as well as its corners.
    // Sharp: a convex part of radius R lies under a chord of length L
    // between particles kept `clearance` out by the sag L²/8R, which reaches
    // the vertex clearance only where R < L²/8(c − cv) (2.5 cm for a 2 cm
    // edge; kSharpRadius = 3 cm); flatter and concave parts stay under the
    // cloth by themselves. A vertex's sharpness is its largest normal
    // curvature towards a neighbour, 2 n·(p − q)/|p − q|².
    std::vector<double> sharp(nv, 0.0);
    for (const auto& t : tris)
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          const Vec3 e = bv0[t[a]] - bv0[t[b]];
          const double l2 = e.squaredNorm();
          if (a != b && l2 > 0.0)
            sharp[t[a]] = std::max(sharp[t[a]], 2.0 * normals.vertex_normal(t[a]).dot(e) / l2);
        }
    std::vector<char> keep(nv, 0);
    for (int k = 0; k < nv; ++k)
      if (normals.vertex_normal(k).allFinite() && normals.vertex_normal(k).squaredNorm() > 0.0 &&
          sharp[k] * kSharpRadius > 1.0) {
        keep[k] = 1;
        bpoint_.push_back(bv0[k]);
        vnormal_.push_back(normals.vertex_normal(k));
      }
    // Lattice point i, j of m over corners A, B, C (weights 1 − (i + j)/m, i/m, j/m).
    auto add = [&](const std::array<int, 3>& t, int i, int j, int m) {
      const double wb = static_cast<double>(i) / m, wc = static_cast<double>(j) / m, wa = 1.0 - wb - wc;
      const Vec3 n = wa * normals.vertex_normal(t[0]) + wb * normals.vertex_normal(t[1]) +
                     wc * normals.vertex_normal(t[2]);
      if (!(n.squaredNorm() > 0.0) || !n.allFinite()) return;
      bpoint_.push_back(wa * bv0[t[0]] + wb * bv0[t[1]] + wc * bv0[t[2]]);
      vnormal_.push_back(n.normalized());
    };
    auto divisions = [&](int u, int v) {
      return std::clamp(static_cast<int>(std::ceil((bv0[u] - bv0[v]).norm() / kBodySample)), 1, kMaxLattice);
    };
    std::vector<std::array<int, 2>> edges;
    for (const auto& t : tris) {
      if (!(keep[t[0]] || keep[t[1]] || keep[t[2]])) continue;
      const int m = std::max({divisions(t[0], t[1]), divisions(t[1], t[2]), divisions(t[2], t[0])});
      for (int i = 1; i < m; ++i)
        for (int j = 1; i + j < m; ++j) add(t, i, j, m);
      for (int k = 0; k < 3; ++k) edges.push_back({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (const auto& e : edges) {
      const int m = divisions(e[0], e[1]);
      for (int i = 1; i < m; ++i) add({e[0], e[1], e[1]}, i, 0, m);
    }
    const auto& bv = bpoint_;
    if (bv.empty()) return;
    lo_ = bv[0];
    Vec3 hi = bv[0];
    for (const Vec3& p : bv) {
      lo_ = lo_.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    cell_ = kVertexCell;
    for (int a = 0; a < 3; ++a) dim_[a] = std::max(1, static_cast<int>(std::floor((hi[a] - lo_[a]) / cell_)) + 1);
    const long cells = static_cast<long>(dim_[0]) * dim_[1] * dim_[2];
    if (cells > kMaxVertexCells) {  // a body hundreds of metres wide: coarser cells
      cell_ *= std::cbrt(static_cast<double>(cells) / kMaxVertexCells) * 1.01;
      for (int a = 0; a < 3; ++a) dim_[a] = std::max(1, static_cast<int>(std::floor((hi[a] - lo_[a]) / cell_)) + 1);
    }
    cells_.assign(static_cast<size_t>(dim_[0]) * dim_[1] * dim_[2] + 1, 0);
    std::vector<int> cell_of(bv.size(), -1);
    for (size_t k = 0; k < bv.size(); ++k) {
      cell_of[k] = cell_index(cell_coord(bv[k]));
      ++cells_[cell_of[k] + 1];
    }
    for (size_t c = 1; c < cells_.size(); ++c) cells_[c] += cells_[c - 1];
    // The points sorted by cell: a cell's points lie next to each other.
    std::vector<Vec3> point(bv.size()), normal(bv.size());
    std::vector<int> fill(cells_.begin(), cells_.end() - 1);
    for (size_t k = 0; k < bv.size(); ++k) {
      const int at = fill[cell_of[k]]++;
      point[at] = bv[k];
      normal[at] = vnormal_[k];
    }
    bpoint_ = std::move(point);
    vnormal_ = std::move(normal);
    if (cells_.back() == 0) cells_.clear();
  }
  std::array<int, 3> cell_coord(const Vec3& p) const {
    std::array<int, 3> c;
    for (int a = 0; a < 3; ++a)
      c[a] = std::clamp(static_cast<int>(std::floor((p[a] - lo_[a]) / cell_)), 0, dim_[a] - 1);
    return c;
  }
  int cell_index(const std::array<int, 3>& c) const { return (c[2] * dim_[1] + c[1]) * dim_[0] + c[0]; }

  // ---- the cloth between its particles against the body ----
  // Points of the cloth between particles: each edge's midpoint and each
  // triangle's centre, as barycentric weights of two or three particles.
  struct Sample {
    std::array<int, 3> p;  // particles (p[2] < 0: an edge's midpoint)
  };
  void build_cloth_samples() {
    std::vector<std::array<int, 2>> edges;
    edges.reserve(3 * tris_.size());
    for (const auto& t : tris_)
      for (int k = 0; k < 3; ++k) edges.push_back({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    samples_.reserve(edges.size() + tris_.size());
    for (const auto& e : edges) samples_.push_back({{e[0], e[1], -1}});
    for (const auto& t : tris_) samples_.push_back({{t[0], t[1], t[2]}});
  }
  Vec3 sample_at(const Sample& sm, const double* x) const {
    Vec3 p = Vec3::Zero();
    const int k = sm.p[2] < 0 ? 2 : 3;
    for (int i = 0; i < k; ++i) p += Eigen::Map<const Vec3>(x + 3 * rep_[sm.p[i]]);
    return p / k;
  }
  // Each sample inside the body is moved out to its surface along the body's
  // normal, its particles shared by weight (Gauss-Seidel, in sample order),
  // its approach stopped and its slip limited by friction: the body does not
  // show between particles that are all outside it (a heel slicing through a
  // hem's triangle, a ridge under an edge). To the surface, not to a
  // clearance: pushed to 1 mm, samples on the tights' rise fought the seam's
  // pull at every step and the leggings did not come to rest in 8 s.
  void push_cloth_samples_out(State& s, const Vec3& offset, const Vec3& vb) {
    const int ns = static_cast<int>(samples_.size());
    const double cv = 0.0;  // m: the surface itself (see above)
    const double* x = s.x.data();
    inside_ = gather_in_order<int>(ns, ns >= 2 * kParallelMinParticles, [&](int i, std::vector<int>& mine) {
      const Sample& sm = samples_[i];
      // Only where a particle is near the body: the others cannot have it between them.
      bool near = false;
      for (int k = 0; k < 3 && !near; ++k) near = sm.p[k] >= 0 && dist_[rep_[sm.p[k]]] < kSampleNear;
      if (!near) return;
      Vec3 nrm;
      if (query(sample_at(sm, x) - offset, nrm) < cv) mine.push_back(i);
    });
    long pushed = 0;
    double deepest = stats_.max_sample_depth;
    for (int i : inside_) {
      const Sample& sm = samples_[i];
      Vec3 nrm;
      const double d = query(sample_at(sm, x) - offset, nrm);
      if (d >= cv || nrm.squaredNorm() == 0.0) continue;
      deepest = std::max(deepest, -d);
      const int k = sm.p[2] < 0 ? 2 : 3;
      const int p[3] = {rep_[sm.p[0]], rep_[sm.p[1]], k == 3 ? rep_[sm.p[2]] : rep_[sm.p[0]]};
      const Vec3 w = k == 3 ? Vec3::Constant(1.0 / 3.0) : Vec3(0.5, 0.5, 0.0);
      pushed += push_out(s, p, w, nrm, cv - d, vb);
    }
    if (pushed > 0) follow_representatives(s);
    stats_.sample_contacts += pushed;
    stats_.max_sample_depth = deepest;
  }
  // Moves the point of the cloth with barycentric weights w on particles p
  // out by `gap` (m) along the body's normal `nrm`, shared by weight and
  // inverse mass (pinned and stuck particles do not move; a zero weight
  // takes nothing), stops its approach, takes slip off it by friction, and
  // marks its particles as touching. False when none of them can move.
  bool push_out(State& s, const int p[3], const Vec3& w, const Vec3& nrm, double gap, const Vec3& vb) {
    double* x = s.x.data();
    double* v = s.v.data();
    double im[3], sum = 0.0;
    Vec3 vel = Vec3::Zero();
    for (int k = 0; k < 3; ++k) {
      im[k] = (role_[p[k]] & kFixed) || contact_[p[k]] == kStuckContact ? 0.0 : 1.0;
      sum += w[k] * w[k] * im[k];
      vel += w[k] * (Eigen::Map<const Vec3>(v + 3 * p[k]) - vb);
    }
    if (sum <= 0.0) return false;
    const double vn = vel.dot(nrm);
    const double lift = gap / sum, stop = vn < 0.0 ? -vn / sum : 0.0;
    const Vec3 slip = friction_change(vel, nrm, vn, gap);
    for (int k = 0; k < 3; ++k) {
      const double share = w[k] * im[k];
      if (share == 0.0) continue;
      Eigen::Map<Vec3>(x + 3 * p[k]) += (share * lift) * nrm - (h_ * share / sum) * slip;
      Eigen::Map<Vec3>(v + 3 * p[k]) += (share * stop) * nrm - (share / sum) * slip;
      touch(p[k], nrm);
    }
    return true;
  }
  // Coulomb friction at a point of the cloth between particles that the body
  // pushed out by `gap` (m) and whose approach `vn` (m/s, < 0 approaching)
  // it stopped: the tangential velocity change of the point (m/s) that takes
  // at most μ times the normal change (the approach stopped and the push
  // over the step, gap/h) off its tangential velocity, as the particles'
  // Provot response does. The slide response has no friction.
  Vec3 friction_change(const Vec3& vel, const Vec3& nrm, double vn, double gap) const {
    if (def_.response != ContactResponse::provot || def_.friction <= 0.0 || !(h_ > 0.0)) return Vec3::Zero();
    const Vec3 vt = vel - vel.dot(nrm) * nrm;
    const double len = vt.norm();
    if (len == 0.0) return Vec3::Zero();
    const double dvn = std::max(0.0, -vn) + std::max(0.0, gap) / h_;
    return std::min(1.0, def_.friction * dvn / len) * vt;
  }
  // A particle of cloth the body pushed from between particles counts as
  // touching the body along that push (unless it touches it itself): an
  // implicit step holds it there as it holds a particle on the body
  // (body_collision_contacts), so the cloth's tension is met by the body in
  // the solve instead of pulling the cloth back in at every step.
  void touch(int p, const Vec3& nrm) {
    if (contact_[p] != 0) return;
    contact_[p] = 1;
    normal_[p] = nrm;
    static_[p] = 0;
  }
  // Copies of merged particles take their representative's position and velocity.
  void follow_representatives(State& s) const {
    double* x = s.x.data();
    double* v = s.v.data();
    for (int i = 0; i < n_; ++i)
      if (rep_[i] != i) {
        Eigen::Map<Vec3>(x + 3 * i) = Eigen::Map<const Vec3>(x + 3 * rep_[i]);
        Eigen::Map<Vec3>(v + 3 * i) = Eigen::Map<const Vec3>(v + 3 * rep_[i]);
      }
  }

  // One body vertex under one cloth triangle.
  struct VertexContact {
    int triangle, vertex;  // cloth triangle, body point
  };

  // Finds the body vertices under the cloth's triangles (in parallel, joined
  // in triangle order, so the result does not depend on the threads), then
  // pushes each triangle out in that order (Gauss-Seidel, from the positions
  // as the earlier contacts left them).
  void push_triangles_off_body_vertices(State& s, const Vec3& offset, const Vec3& vb) {
    const int nt = static_cast<int>(tris_.size());
    const double cv = def_.vertex_clearance, reach = def_.vertex_reach;
    const auto& bv = bpoint_;
    const double* x = s.x.data();
    auto pos = [&](int p) { return Vec3(Eigen::Map<const Vec3>(x + 3 * rep_[p]) - offset); };
    found_ = gather_in_order<VertexContact>(nt, nt >= kParallelMinParticles, [&](int t, std::vector<VertexContact>& mine) {
      const auto& tri = tris_[t];
      // A triangle whose corners are all further from the body than its
      // longest edge and the reach has no body point under it.
      const double near = std::min({dist_[rep_[tri[0]]], dist_[rep_[tri[1]]], dist_[rep_[tri[2]]]});
      const Vec3 a = pos(tri[0]), b = pos(tri[1]), c = pos(tri[2]);
      const double longest = std::sqrt(std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()}));
      if (near > longest + reach) return;
      const Frame f(a, b, c);
      if (!f.valid) return;
      Vec3 nrm;
      double height;
      const Vec3 lo = a.cwiseMin(b).cwiseMin(c).array() - reach, hi = a.cwiseMax(b).cwiseMax(c).array() + reach;
      const auto c0 = cell_coord(lo), c1 = cell_coord(hi);
      for (int k = c0[2]; k <= c1[2]; ++k)
        for (int j = c0[1]; j <= c1[1]; ++j) {
          const int row = cell_index({c0[0], j, k});
          for (int q = cells_[row]; q < cells_[row + c1[0] - c0[0] + 1]; ++q)
            if (f.under(bv[q], vnormal_[q], cv, reach, &nrm, nullptr, &height) && through(bv[q], nrm, height))
              mine.push_back({t, q});
        }
    });
    if (found_.empty()) return;
    long pushed = 0;
    double deepest = stats_.max_vertex_depth;
    const double* xs = s.x.data();
    for (const VertexContact& vc : found_) {
      const auto& tri = tris_[vc.triangle];
      int p[3];
      Vec3 corner[3];
      for (int k = 0; k < 3; ++k) {
        p[k] = rep_[tri[k]];
        corner[k] = Eigen::Map<const Vec3>(xs + 3 * p[k]) - offset;
      }
      Vec3 nrm, w;
      double height;
      if (!Frame(corner[0], corner[1], corner[2]).under(bv[vc.vertex], vnormal_[vc.vertex], cv, reach, &nrm, &w, &height) ||
          !through(bv[vc.vertex], nrm, height))
        continue;  // an earlier push lifted it
      deepest = std::max(deepest, -height);
      pushed += push_out(s, p, w, nrm, cv - height, vb);
    }
    if (pushed > 0) follow_representatives(s);
    stats_.vertex_contacts += pushed;
    stats_.max_vertex_depth = deepest;
  }

  // A body point `pb` found `height` (m) under a cloth triangle's plane
  // (outward normal `nrm`) has come through the triangle when its foot on
  // the plane is inside the body: the body reaches from the point back
  // through the plane. Where the foot is outside, the point is on the far
  // side of a part thinner than the reach (the underside of a rail the
  // cloth lies on), and the triangle is left alone.
  bool through(const Vec3& pb, const Vec3& nrm, double height) const {
    if (height >= 0.0) return true;  // not through yet: within the vertex clearance over it
    Vec3 g;
    return query(pb + height * nrm, g) < 0.0;
  }

  // A cloth triangle abc, for asking whether a body point lies under it.
  struct Frame {
    Vec3 a, e1, e2, n;  // corner, edges, unit normal (m)
    double d00, d01, d11, inv;
    bool valid = false;
    Frame(const Vec3& a_, const Vec3& b, const Vec3& c) : a(a_), e1(b - a_), e2(c - a_) {
      n = e1.cross(e2);
      const double len = n.norm();
      d00 = e1.dot(e1), d01 = e1.dot(e2), d11 = e2.dot(e2);
      const double den = d00 * d11 - d01 * d01;
      valid = len > 0.0 && den > 0.0;
      if (valid) n /= len, inv = 1.0 / den;
    }
    // Whether the body point pb (outward normal nb) lies under the triangle:
    // the triangle facing along the body's normal (|cos| >= 0.5; `out` the
    // triangle's normal turned outward), its plane less than `cv` out from
    // the point (`height`, m, negative when the point is through) and not
    // more than `reach` in, and the point's projection inside it (barycentric
    // weights `w`, all >= 0).
    bool under(const Vec3& pb, const Vec3& nb, double cv, double reach, Vec3* out = nullptr, Vec3* w = nullptr,
               double* height = nullptr) const {
      const double cosang = n.dot(nb);
      if (std::abs(cosang) < 0.5) return false;
      const Vec3 r = pb - a;
      const double h = cosang > 0.0 ? -r.dot(n) : r.dot(n);  // the plane's height over the point, outward
      if (h >= cv || h < -reach) return false;
      const double d20 = r.dot(e1), d21 = r.dot(e2);
      const double wb = (d11 * d20 - d01 * d21) * inv, wc = (d00 * d21 - d01 * d20) * inv, wa = 1.0 - wb - wc;
      if (wa < 0.0 || wb < 0.0 || wc < 0.0) return false;
      if (out) *out = cosang > 0.0 ? n : Vec3(-n);
      if (w) *w = Vec3(wa, wb, wc);
      if (height) *height = h;
      return true;
    }
  };

  BodyCollisionDef def_;
  std::optional<SignedDistanceGrid> grid_;
  TriangleBvh bvh_;
  int n_;
  std::vector<std::array<int, 3>> tris_;  // the cloth's triangles (Model indexing)
  std::vector<int> rep_;                  // per particle: the particle it is merged into (itself if none)
  std::vector<Vec3> bpoint_;              // m: the body's points that push (its vertices, and lattices over large triangles)
  std::vector<Vec3> vnormal_;             // per point: the body's outward unit normal there
  Vec3 lo_ = Vec3::Zero();                // m: the vertex grid's corner
  double cell_ = 0.0;                     // m: its cell
  int dim_[3] = {0, 0, 0};
  std::vector<int> cells_;                // the points' grid: cell c holds points cells_[c] .. cells_[c + 1] (empty: the rule is off)
  std::vector<double> dist_;              // per particle: its distance from the body at the last after-step (m, 0 if unknown)
  std::vector<VertexContact> found_;      // the last detection's contacts
  std::vector<Sample> samples_;           // the cloth's points between particles (empty: the rule is off)
  std::vector<int> inside_;               // the last detection's samples near or in the body
  bool constrains_ = false;
  std::vector<unsigned char> role_;     // per particle: kSeam | kSticky | kFixed
  std::vector<unsigned char> contact_;  // per particle: 0 free, 1 touching, kStuckContact stuck
  std::vector<Vec3> normal_;            // per particle: the body normal at the last contact
  std::vector<Vec3> anchor_;            // per stuck particle: where it stays (m)
  std::vector<double> solve_dvn_;       // per particle: normal velocity change the step's constraint took (m/s)
  std::vector<unsigned char> static_;   // per particle: friction stopped it at the last after-step
  mutable BodyContacts contacts_;       // contacts()'s answer (its storage reused)
  BodyCollisionStats stats_;
  double last_t_ = -std::numeric_limits<double>::infinity();  // s: time of the last after_step
  double h_ = 0.0;  // s: the step the last after_step followed (0: unknown)
};

}  // namespace

std::unique_ptr<Effect> make_body_collision(const Model& model, const BodyCollisionDef& def) {
  return std::make_unique<BodyCollision>(model, def);
}

const BodyCollisionStats& body_collision_stats(const Effect& effect) {
  const auto* b = dynamic_cast<const BodyCollision*>(&effect);
  VGD_ASSERT(b != nullptr, "body_collision_stats: the effect is not a body collision");
  return b->stats();
}

const SignedDistanceGrid* body_collision_grid(const Effect& effect) {
  const auto* b = dynamic_cast<const BodyCollision*>(&effect);
  return b ? b->grid() : nullptr;
}

const BodyContacts* body_collision_contacts(const Effect& effect) {
  const auto* b = dynamic_cast<const BodyCollision*>(&effect);
  return b ? &b->contacts() : nullptr;
}

void body_collision_add_normal_impulse(Effect& effect, int particle, double dv) {
  auto* b = dynamic_cast<BodyCollision*>(&effect);
  VGD_ASSERT(b != nullptr, "body_collision_add_normal_impulse: the effect is not a body collision");
  b->add_normal_impulse(particle, dv);
}

}  // namespace vgd::sim
