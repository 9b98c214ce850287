#include "vgd/sim/system.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <omp.h>

#include "vgd/core/diagnostics.hpp"
#include "vgd/sim/topology.hpp"

namespace vgd::sim {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Union–find over original particles (path halving; the root is the smallest index).
struct Sets {
  std::vector<int> parent;
  int find(int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void unite(int a, int b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};
}  // namespace

System::System(Model model, std::vector<std::unique_ptr<Effect>> effects)
    : model_(std::move(model)), effects_(std::move(effects)) {
  validate(model_);
  const int n = model_.num_particles();
  profile_.resize(effects_.size());
  active_.assign(effects_.size(), true);
  for (std::size_t i = 0; i < effects_.size(); ++i) profile_[i].name = effects_[i]->name();
  for (const auto& e : effects_) block_effects_.push_back(dynamic_cast<BlockJacobianEffect*>(e.get()));
  rep_ = identity_representative(n);
  first_ = rep_;
  mass_ = model_.mass;

  // Prescribed particles (pins) and the per-dof inverse mass.
  for (const auto& e : effects_) e->prescribed_particles(prescribed_full_);
  std::sort(prescribed_full_.begin(), prescribed_full_.end());
  prescribed_full_.erase(std::unique(prescribed_full_.begin(), prescribed_full_.end()), prescribed_full_.end());
  prescribed_ = prescribed_full_;
  free_ = VecX::Ones(3 * n);
  for (int p : prescribed_) at(free_, p).setZero();
  inv_mass_dof_.resize(3 * n);
  for (int i = 0; i < n; ++i) at(inv_mass_dof_, i).setConstant(1.0 / mass_[i]);
  inv_mass_dof_ = inv_mass_dof_.cwiseProduct(free_);
  compute_stiffness();
}

// Stiffness bounds: which particle and effect limit explicit steps. Effects
// bound the rows of the full Jacobian; a reduced row is the sum of its copies'
// rows with their columns summed, so the sum of the copies' bounds bounds it.
void System::compute_stiffness() {
  const int nf = num_particles_full(), n = num_particles();
  stiffness_ = {};
  VecX k = VecX::Zero(n), c = VecX::Zero(n);
  std::vector<VecX> k_by_effect;
  for (const auto& e : effects_) {
    VecX ke = VecX::Zero(nf), ce = VecX::Zero(nf);
    e->add_stiffness_bound(model_, ke, ce);
    if (merged_) {
      VecX kr = VecX::Zero(n), cr = VecX::Zero(n);
      for (int i = 0; i < nf; ++i) kr[rep_[i]] += ke[i], cr[rep_[i]] += ce[i];
      ke = std::move(kr), ce = std::move(cr);
    }
    k += ke;
    c += ce;
    k_by_effect.push_back(std::move(ke));
  }
  for (int i = 0; i < n; ++i) {
    if (free_[3 * i] == 0.0) continue;  // a pinned particle does not oscillate
    const double w2 = k[i] / mass_[i], rate = c[i] / mass_[i];
    if (w2 > stiffness_.omega2) {
      stiffness_.omega2 = w2;
      stiffness_.particle = first_[i];
    }
    stiffness_.damping_rate = std::max(stiffness_.damping_rate, rate);
  }
  if (stiffness_.particle >= 0) {
    const int r = rep_[stiffness_.particle];
    double best = -1.0;
    for (std::size_t e = 0; e < effects_.size(); ++e)
      if (k_by_effect[e][r] > best) {
        best = k_by_effect[e][r];
        stiffness_.effect = effects_[e]->name();
      }
  }
}

// ---- expanding and reducing ---------------------------------------------------

void System::expand_into(const VecX& reduced, VecX& full) const {
  const int nf = num_particles_full();
  full.resize(3 * nf);
  for (int i = 0; i < nf; ++i) at(full, i) = at(reduced, rep_[i]);
}

VecX System::expand(const VecX& reduced) const {
  VGD_ASSERT(reduced.size() == num_dofs(), "System::expand takes a vector of the reduced particle set");
  if (!merged_) return reduced;
  VecX full;
  expand_into(reduced, full);
  return full;
}

void System::reduce_sum(const VecX& full, VecX& reduced) const {
  reduced.setZero(num_dofs());
  for (int i = 0; i < num_particles_full(); ++i) at(reduced, rep_[i]) += at(full, i);
}

State System::reduce(const State& full) const {
  VGD_ASSERT(full.x.size() == model_.num_dofs() && full.v.size() == model_.num_dofs(),
             "System::reduce takes a state of the model's full particle set");
  if (!merged_) return full;
  State r{full.t, VecX::Zero(num_dofs()), VecX::Zero(num_dofs())};
  for (int i = 0; i < num_particles_full(); ++i) {
    const double w = model_.mass[i] / mass_[rep_[i]];
    at(r.x, rep_[i]) += w * at(full.x, i);
    at(r.v, rep_[i]) += w * at(full.v, i);
  }
  return r;
}

// ---- forces and Jacobians -------------------------------------------------------

void System::force(double t, const VecX& x, const VecX& v, VecX& f) {
  sum_forces(t, x, v, f);
  if (!prescribed_.empty()) f = f.cwiseProduct(free_);
}

void System::acceleration(double t, const VecX& x, const VecX& v, VecX& a) {
  // inv_mass_dof_ is zero on prescribed dofs: one pass scales and masks.
  sum_forces(t, x, v, a);
  a = a.cwiseProduct(inv_mass_dof_);
}

void System::sum_forces(double t, const VecX& x, const VecX& v, VecX& f) {
  // Before any merge the effects write straight into f (no copies).
  const bool full = !merged_;
  if (!full) {
    expand_into(x, xf_);
    expand_into(v, vf_);
  }
  VecX& out = full ? f : ff_;
  out.setZero(model_.num_dofs());
  const Eval e{model_, t, full ? x : xf_, full ? v : vf_};
  for (std::size_t i = 0; i < effects_.size(); ++i) {
    if (!active_[i]) continue;
    const auto t0 = Clock::now();
    effects_[i]->add_forces(e, out);
    profile_[i].seconds += seconds_since(t0);
    ++profile_[i].force_calls;
  }
  for (std::size_t i = 0; i < effects_.size(); ++i) {
    if (!active_[i] || !effects_[i]->constrains_forces()) continue;
    const auto t0 = Clock::now();
    effects_[i]->constrain_forces(e, out);
    profile_[i].seconds += seconds_since(t0);
  }
  if (!full) reduce_sum(ff_, f);
  ++force_evals_;
}

bool System::jacobian(double t, const VecX& x, const VecX& v, SparseMatrix& dfdx, SparseMatrix& dfdv) {
  dfdx_t_.clear();
  dfdv_t_.clear();
  if (merged_) {
    expand_into(x, xf_);
    expand_into(v, vf_);
  }
  const Eval e{model_, t, merged_ ? xf_ : x, merged_ ? vf_ : v};
  bool complete = true;
  for (std::size_t i = 0; i < effects_.size(); ++i) {
    if (!active_[i]) continue;
    const auto t0 = Clock::now();
    complete = effects_[i]->add_jacobian(e, dfdx_t_, dfdv_t_) && complete;
    profile_[i].seconds += seconds_since(t0);
    ++profile_[i].jacobian_calls;
  }
  // Merged particles: rows and columns of copies land on their reduced
  // particle (duplicates are summed by setFromTriplets): J_r = Rᵀ J R.
  if (merged_) {
    auto remap = [&](Triplets& ts) {
      for (Triplet& tr : ts)
        tr = Triplet(3 * rep_[tr.row() / 3] + tr.row() % 3, 3 * rep_[tr.col() / 3] + tr.col() % 3, tr.value());
    };
    remap(dfdx_t_);
    remap(dfdv_t_);
  }
  // Prescribed dofs neither move nor feel forces: drop their rows and columns.
  if (!prescribed_.empty()) {
    auto drop = [&](Triplets& ts) {
      ts.erase(std::remove_if(ts.begin(), ts.end(),
                              [&](const Triplet& tr) { return free_[tr.row()] == 0.0 || free_[tr.col()] == 0.0; }),
               ts.end());
    };
    drop(dfdx_t_);
    drop(dfdv_t_);
  }
  const int n = num_dofs();
  dfdx.resize(n, n);
  dfdv.resize(n, n);
  dfdx.setFromTriplets(dfdx_t_.begin(), dfdx_t_.end());
  dfdv.setFromTriplets(dfdv_t_.begin(), dfdv_t_.end());
  ++jacobian_evals_;
  return complete;
}

// ---- block Jacobians ------------------------------------------------------------

int BlockPattern::find(int i, int j) const {
  const auto b = col.begin() + row[i], e = col.begin() + row[i + 1];
  const auto it = std::lower_bound(b, e, j);
  return it != e && *it == j ? static_cast<int>(it - col.begin()) : -1;
}

// Block rows are independent: with several OpenMP threads they are shared out
// statically, so y is bitwise the same for any thread count.
void BlockJacobian::multiply(const std::vector<double>& values, const VecX& x, VecX& y) const {
  const BlockPattern& p = pattern;
  y.resize(3 * p.n);
  const double* xv = x.data();
  double* yv = y.data();
  const double* a = values.data();
  const int* row = p.row.data();
  const int* col = p.col.data();
  const int n = p.n;
#pragma omp parallel for schedule(static) if (n >= 1024 && omp_get_max_threads() > 1)
  for (int i = 0; i < n; ++i) {
    double y0 = 0.0, y1 = 0.0, y2 = 0.0;
    for (int q = row[i]; q < row[i + 1]; ++q) {
      const double* b = a + 9 * q;
      const double* xj = xv + 3 * col[q];
      y0 += b[0] * xj[0] + b[1] * xj[1] + b[2] * xj[2];
      y1 += b[3] * xj[0] + b[4] * xj[1] + b[5] * xj[2];
      y2 += b[6] * xj[0] + b[7] * xj[1] + b[8] * xj[2];
    }
    yv[3 * i] = y0, yv[3 * i + 1] = y1, yv[3 * i + 2] = y2;
  }
}

SparseMatrix BlockJacobian::to_sparse(const std::vector<double>& values) const {
  Triplets t;
  t.reserve(9 * pattern.col.size());
  for (int i = 0; i < pattern.n; ++i)
    for (int q = pattern.row[i]; q < pattern.row[i + 1]; ++q)
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) t.emplace_back(3 * i + r, 3 * pattern.col[q] + c, values[9 * q + 3 * r + c]);
  SparseMatrix m(3 * pattern.n, 3 * pattern.n);
  m.setFromTriplets(t.begin(), t.end());
  return m;
}

int JacobianAssembler::slot(int i, int j) {
  const int ri = (*rep_)[i], rj = (*rep_)[j];
  if ((*free_)[3 * ri] == 0.0 || (*free_)[3 * rj] == 0.0) return -1;
  const int q = pattern_->find(ri, rj);
  if (q >= 0) return q;
  missing_->push_back({ri, rj});
  return pattern_->blocks();  // the scratch block
}

// The pattern grows to hold `blocks` (reduced particles), their transposes
// and every diagonal block (the step matrix always has M there).
void System::grow_pattern(const std::vector<std::array<int, 2>>& blocks) {
  const int n = num_particles();
  // The old pattern is sorted row by row: only the new blocks are sorted,
  // then merged into it (the pattern of a drape holds ~10 blocks a particle,
  // and grows every time contact meets new pairs).
  const bool keep = pattern_.n == n;
  std::vector<std::array<int, 2>> add;
  add.reserve(2 * blocks.size() + (keep ? 0 : n));
  if (!keep)
    for (int i = 0; i < n; ++i) add.push_back({i, i});
  for (const auto& [i, j] : blocks) add.push_back({i, j}), add.push_back({j, i});
  std::sort(add.begin(), add.end());
  add.erase(std::unique(add.begin(), add.end()), add.end());
  BlockPattern p;
  p.n = n;
  p.row.assign(n + 1, 0);
  p.col.reserve((keep ? pattern_.col.size() : 0) + add.size());
  std::size_t a = 0;
  for (int i = 0; i < n; ++i) {
    int q = keep ? pattern_.row[i] : 0;
    const int end = keep ? pattern_.row[i + 1] : 0;
    for (;;) {
      const bool more_new = a < add.size() && add[a][0] == i;
      if (!more_new && q >= end) break;
      if (more_new && (q >= end || add[a][1] <= pattern_.col[q])) {
        if (q < end && pattern_.col[q] == add[a][1]) ++q;
        p.col.push_back(add[a++][1]);
      } else {
        p.col.push_back(pattern_.col[q++]);
      }
    }
    p.row[i + 1] = static_cast<int>(p.col.size());
  }
  // The pattern is symmetric: walking rows in order meets the blocks (i, j)
  // of column j in the order row j lists its (j, i).
  p.diag.resize(n);
  p.transpose.resize(p.col.size());
  std::vector<int> next(p.row.begin(), p.row.end() - 1);
  for (int i = 0; i < n; ++i)
    for (int q = p.row[i]; q < p.row[i + 1]; ++q) {
      if (p.col[q] == i) p.diag[i] = q;
      p.transpose[q] = next[p.col[q]]++;
    }
  p.version = ++pattern_versions_;
  pattern_ = std::move(p);
}

// One assembly pass on the current pattern; false if some block was missing
// (recorded in missing_: the caller grows the pattern and assembles again).
bool System::assemble_blocks(const Eval& e, BlockJacobian& J) {
  if (J.pattern.version != pattern_.version) J.pattern = pattern_;
  const std::size_t size = 9 * (static_cast<std::size_t>(pattern_.blocks()) + 1);
  J.dfdx.assign(size, 0.0);
  J.dfdv.assign(size, 0.0);
  missing_.clear();
  JacobianAssembler out;
  out.version_ = pattern_.version;
  out.pattern_ = &pattern_;
  out.rep_ = &rep_;
  out.free_ = &free_;
  out.dfdx_ = J.dfdx.data();
  out.dfdv_ = J.dfdv.data();
  out.missing_ = &missing_;
  bool complete = true;
  for (std::size_t i = 0; i < effects_.size(); ++i) {
    if (!active_[i]) continue;
    const auto t0 = Clock::now();
    if (block_effects_[i]) {
      complete = block_effects_[i]->add_jacobian_blocks(e, out) && complete;
    } else {
      dfdx_t_.clear();
      dfdv_t_.clear();
      complete = effects_[i]->add_jacobian(e, dfdx_t_, dfdv_t_) && complete;
      // Triplets come in runs of one block (add_block): the slot is looked up once per run.
      auto scatter = [&](const Triplets& ts, double* values) {
        int bi = -1, bj = -1, q = -1;
        for (const Triplet& tr : ts) {
          const int pi = tr.row() / 3, pj = tr.col() / 3;
          if (pi != bi || pj != bj) bi = pi, bj = pj, q = out.slot(pi, pj);
          if (q >= 0) values[9 * q + 3 * (tr.row() % 3) + tr.col() % 3] += tr.value();
        }
      };
      scatter(dfdx_t_, J.dfdx.data());
      scatter(dfdv_t_, J.dfdv.data());
    }
    profile_[i].seconds += seconds_since(t0);
  }
  return complete;
}

bool System::jacobian(double t, const VecX& x, const VecX& v, BlockJacobian& J) {
  if (merged_) {
    expand_into(x, xf_);
    expand_into(v, vf_);
  }
  const Eval e{model_, t, merged_ ? xf_ : x, merged_ ? vf_ : v};
  if (pattern_.n != num_particles()) grow_pattern({});  // first call, or after a merge
  bool complete = assemble_blocks(e, J);
  if (!missing_.empty()) {  // new blocks: grow the pattern and place everything again
    const auto blocks = missing_;
    grow_pattern(blocks);
    complete = assemble_blocks(e, J);
    VGD_ASSERT(missing_.empty(), "block Jacobian assembly: the grown pattern still misses blocks");
  }
  for (std::size_t i = 0; i < effects_.size(); ++i)
    if (active_[i]) ++profile_[i].jacobian_calls;
  ++jacobian_evals_;
  return complete;
}

// ---- prescribed motion, hooks ------------------------------------------------------

void System::apply_prescribed(State& s) const {
  if (prescribed_.empty()) return;
  if (!merged_) {
    for (const auto& e : effects_) e->prescribe(s.t, s.x, s.v);
    return;
  }
  // Effects write their (original) particles into full scratch vectors; only
  // those entries are read back. A merged particle has at most one prescribed
  // copy (apply_merges refuses others).
  px_.resize(model_.num_dofs());
  pv_.resize(model_.num_dofs());
  for (const auto& e : effects_) e->prescribe(s.t, px_, pv_);
  for (int p : prescribed_full_) {
    at(s.x, rep_[p]) = at(px_, p);
    at(s.v, rep_[p]) = at(pv_, p);
  }
}

void System::after_step(State& s) {
  State* target = &s;
  if (merged_) {
    sf_.t = s.t;
    expand_into(s.x, sf_.x);
    expand_into(s.v, sf_.v);
    target = &sf_;
  }
  for (std::size_t i = 0; i < effects_.size(); ++i) {
    if (!active_[i]) continue;
    const auto t0 = Clock::now();
    effects_[i]->after_step(model_, *target);
    profile_[i].seconds += seconds_since(t0);
    ++profile_[i].after_step_calls;
    // An effect that has done its work stops costing time.
    if (effects_[i]->finished()) active_[i] = false;
  }
  if (!merged_) return;
  // Hooks may move copies of one particle differently: the particle moves by
  // the mass-weighted mean of its copies' changes (momentum is kept). Copies
  // no hook touched contribute exactly zero, so an untouched state stays
  // bit-identical.
  VecX dx = VecX::Zero(num_dofs()), dv = VecX::Zero(num_dofs());
  for (int i = 0; i < num_particles_full(); ++i) {
    const int r = rep_[i];
    const double w = model_.mass[i] / mass_[r];
    at(dx, r) += w * (at(sf_.x, i) - at(s.x, r));
    at(dv, r) += w * (at(sf_.v, i) - at(s.v, r));
  }
  s.x += dx;
  s.v += dv;
}

// ---- merges --------------------------------------------------------------------------

bool System::apply_merges(State& s) {
  VGD_ASSERT(s.x.size() == num_dofs() && s.v.size() == num_dofs(),
             "System::apply_merges takes a state of the reduced particle set");
  const int nf = num_particles_full();
  // Requests, on the full state.
  sf_.t = s.t;
  expand_into(s.x, sf_.x);
  expand_into(s.v, sf_.v);
  std::vector<std::array<int, 2>> requests;
  for (std::size_t i = 0; i < effects_.size(); ++i)
    if (active_[i]) effects_[i]->merge_requests(model_, sf_, requests);
  for (std::size_t i = 0; i < effects_.size() && !requests.empty(); ++i)
    if (active_[i]) effects_[i]->review_merges(model_, sf_, requests);
  if (requests.empty()) return false;

  // Union with the merges so far; a class holds at most one prescribed particle.
  Sets sets{std::vector<int>(nf)};
  for (int i = 0; i < nf; ++i) sets.parent[i] = first_[rep_[i]];
  std::vector<char> pinned(nf, 0);
  for (int p : prescribed_full_) pinned[first_[rep_[p]]] = 1;  // per class root
  bool joined = false;
  for (const auto& [a, b] : requests) {
    VGD_ASSERT(a >= 0 && a < nf && b >= 0 && b < nf, "merge request names a particle outside the model");
    const int ra = sets.find(a), rb = sets.find(b);
    if (ra == rb || (pinned[ra] && pinned[rb])) continue;
    sets.unite(ra, rb);
    pinned[std::min(ra, rb)] = pinned[ra] | pinned[rb];
    joined = true;
  }
  if (!joined) return false;

  // New reduced numbering: classes in the order of their lowest particle.
  std::vector<int> rep(nf), first;
  std::vector<int> index_of_root(nf, -1);
  for (int i = 0; i < nf; ++i) {
    const int r = sets.find(i);
    if (index_of_root[r] < 0) {
      index_of_root[r] = static_cast<int>(first.size());
      first.push_back(i);
    }
    rep[i] = index_of_root[r];
  }
  const int n = static_cast<int>(first.size());

  // The state in the new coordinates: mass-weighted means of the old reduced
  // particles (their copies share position and velocity), so Σ m x and Σ m v
  // are kept; a prescribed particle's value is then overwritten by its path.
  VecX mass = VecX::Zero(n);
  for (int i = 0; i < nf; ++i) mass[rep[i]] += model_.mass[i];
  State r{s.t, VecX::Zero(3 * n), VecX::Zero(3 * n)};
  for (int old = 0; old < num_particles(); ++old) {
    const int q = rep[first_[old]];
    const double w = mass_[old] / mass[q];
    at(r.x, q) += w * at(s.x, old);
    at(r.v, q) += w * at(s.v, old);
  }

  merged_ = true;
  rep_ = std::move(rep);
  first_ = std::move(first);
  mass_ = std::move(mass);
  prescribed_.clear();
  for (int p : prescribed_full_) prescribed_.push_back(rep_[p]);
  std::sort(prescribed_.begin(), prescribed_.end());
  prescribed_.erase(std::unique(prescribed_.begin(), prescribed_.end()), prescribed_.end());
  free_ = VecX::Ones(3 * n);
  for (int p : prescribed_) at(free_, p).setZero();
  inv_mass_dof_.resize(3 * n);
  for (int i = 0; i < n; ++i) at(inv_mass_dof_, i).setConstant(1.0 / mass_[i]);
  inv_mass_dof_ = inv_mass_dof_.cwiseProduct(free_);
  s = std::move(r);
  apply_prescribed(s);

  for (const auto& e : effects_) e->particles_merged(model_, rep_);
  pattern_ = BlockPattern{};  // rebuilt on the next block Jacobian (new numbering)
  compute_stiffness();
#ifndef NDEBUG
  // The restructured mesh stays a manifold with boundary: merging never
  // creates a degenerate or duplicate triangle (collapsed ones are removed) and
  // seams join two sides, not three (three-layer seams are not supported).
  {
    const MeshCheck before = check_mesh(model_.triangles);
    const MeshCheck after = check_merged_mesh(merged_topology(model_, rep_));
    VGD_ASSERT(after.degenerate_triangles == 0 && after.duplicate_triangles <= before.duplicate_triangles &&
                   after.non_manifold_edges <= before.non_manifold_edges,
               "a seam merge left a degenerate, duplicate or non-manifold triangle in the cloth mesh");
  }
#endif
  return true;
}

// ---- energies and checks -----------------------------------------------------------

double System::kinetic_energy(const VecX& v) const {
  double e = 0.0;
  for (int i = 0; i < num_particles(); ++i) e += 0.5 * mass_[i] * at(v, i).squaredNorm();
  return e;
}

double System::potential_energy(double t, const VecX& x, const VecX& v) const {
  VecX xf, vf;
  if (merged_) expand_into(x, xf), expand_into(v, vf);
  const Eval e{model_, t, merged_ ? xf : x, merged_ ? vf : v};
  double u = 0.0;
  for (std::size_t i = 0; i < effects_.size(); ++i)
    if (active_[i]) u += effects_[i]->energy(e);
  return u;
}

void System::check_state(const State& s, double max_speed) const {
  // One cheap pass on every step (no square roots); the particle is looked up
  // only when something is wrong.
  const double limit2 = max_speed * max_speed;
  const int n = num_particles();
  const double* x = s.x.data();
  const double* v = s.v.data();
  bool ok = true;
  for (int k = 0; k < 3 * n; k += 3) {
    const double v2 = v[k] * v[k] + v[k + 1] * v[k + 1] + v[k + 2] * v[k + 2];
    // NaN fails every comparison: `!(v2 <= limit2)` also catches non-finite velocities.
    ok &= (v2 <= limit2) & std::isfinite(x[k] + x[k + 1] + x[k + 2]);
  }
  if (ok) return;
  // Messages name the original particle (the lowest of a merged one's copies).
  for (int i = 0; i < n; ++i) {
    if (!at(s.x, i).allFinite() || !at(s.v, i).allFinite())
      throw SimulationError("the simulation diverged at t = " + std::to_string(s.t) + " s: particle " +
                            std::to_string(first_[i]) + " has a non-finite position or velocity (try a smaller step, "
                            "more iterations per frame, RK4, implicit Euler or BDF)");
    const double speed = at(s.v, i).norm();
    if (speed > max_speed)
      throw SimulationError("the simulation is blowing up at t = " + std::to_string(s.t) + " s: particle " +
                            std::to_string(first_[i]) + " moves at " + std::to_string(speed) + " m/s (limit " +
                            std::to_string(max_speed) + " m/s); try a smaller step or an implicit method");
  }
}

bool System::may_rest() const {
  for (std::size_t i = 0; i < effects_.size(); ++i)
    if (active_[i] && effects_[i]->blocks_rest()) return false;
  return true;
}

}  // namespace vgd::sim
