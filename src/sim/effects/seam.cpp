// Seams that sew: a pulling force per particle pair, merge requests for the
// pairs that have closed, and the sewing progress. The law and its Jacobian
// are documented in the header; the merge itself is System::apply_merges.
#include "vgd/sim/effects/seam.hpp"

#include <cmath>
#include <functional>

#include "vgd/core/strings.hpp"

namespace vgd::sim {

namespace {

// ln cosh(x) without overflow: |x| + ln(1 + e^{−2|x|}) − ln 2.
double log_cosh(double x) {
  const double a = std::abs(x);
  return a + std::log1p(std::exp(-2.0 * a)) - std::log(2.0);
}

// φ(d) (N), φ′(d) (N/m) and φ(d)/d (N/m; its limit k at d = 0).
struct Law {
  SeamLaw law;
  double k, F;
  double phi(double d) const { return law == SeamLaw::linear ? k * d : F * std::tanh(k * d / F); }
  double dphi(double d) const {
    if (law == SeamLaw::linear) return k;
    const double t = std::tanh(k * d / F);
    return k * (1.0 - t * t);
  }
  double phi_over_d(double d) const {
    if (law == SeamLaw::linear) return k;
    const double x = k * d / F;
    return x < 1e-8 ? k : F * std::tanh(x) / d;  // tanh x / x = 1 − x²/3 + …: exact to rounding below 1e-8
  }
  // ∫₀^d φ (J).
  double energy(double d) const {
    if (law == SeamLaw::linear) return 0.5 * k * d * d;
    return k > 0.0 ? F * F / k * log_cosh(k * d / F) : 0.0;
  }
};

struct Pair {
  int a, b, seam;
};

class Seam final : public Effect {
 public:
  Seam(const Model& m, const SeamDef& d)
      : law_{d.law, d.stiffness, d.max_force}, c_(d.damping), merge_distance_(d.merge_distance),
        zip_distance_(d.zip_distance), last_distance_(d.last_stitch_distance),
        last_frames_(d.last_stitch_frames), merge_(d.merge), wait_limit_(d.wait_limit) {
    auto bad = [](const std::string& what) { throw SimulationError("seam: " + what); };
    auto check = [&](const char* field, double v, const char* unit) {
      if (!std::isfinite(v) || v < 0.0)
        bad(std::string(field) + " = " + format_significant(v, 6) + unit +
            "; it must be a finite number ≥ 0");
    };
    check("stiffness", d.stiffness, " N/m");
    check("damping", d.damping, " N·s/m");
    check("merge_distance", d.merge_distance, " m");
    check("zip_distance", d.zip_distance, " m");
    check("last_stitch_distance", d.last_stitch_distance, " m");
    check("wait_limit", d.wait_limit, " s");
    if (d.last_stitch_frames < 1) bad("last_stitch_frames = " + std::to_string(d.last_stitch_frames) + "; it must be ≥ 1");
    if (d.law == SeamLaw::saturating && !(d.max_force > 0.0 && std::isfinite(d.max_force)))
      bad("max_force = " + format_significant(d.max_force, 6) +
          " N; the saturating law needs a finite force > 0");
    const int n = m.num_particles();
    report_.seams.resize(d.seams.size());
    for (std::size_t s = 0; s < d.seams.size(); ++s) {
      const SeamPairs& seam = d.seams[s];
      const std::string who = "seam " + std::to_string(s) + (seam.name.empty() ? "" : " ('" + seam.name + "')");
      report_.seams[s].name = seam.name;
      report_.seams[s].total = static_cast<int>(seam.pairs.size());
      for (std::size_t p = 0; p < seam.pairs.size(); ++p) {
        const auto [a, b] = seam.pairs[p];
        const std::string pair = who + ", pair " + std::to_string(p);
        if (a < 0 || a >= n || b < 0 || b >= n)
          bad(pair + " names particle " + std::to_string(a < 0 || a >= n ? a : b) + ", but the model has " +
              std::to_string(n));
        if (a == b) bad(pair + " joins particle " + std::to_string(a) + " to itself");
        pairs_.push_back({a, b, static_cast<int>(s)});
      }
      for (const int w : seam.after) {
        if (w < 0 || w >= static_cast<int>(d.seams.size()))
          bad(who + " waits for seam " + std::to_string(w) + ", but the seams are 0 to " +
              std::to_string(d.seams.size() - 1));
        if (w == static_cast<int>(s)) bad(who + " waits for itself");
      }
      after_.push_back(seam.after);
      report_.seams[s].waiting = !seam.after.empty();
    }
    // No seam may wait for itself through others (depth-first, 1 = on the path).
    std::vector<int> mark(d.seams.size(), 0);
    std::function<void(int)> visit = [&](int s) {
      mark[s] = 1;
      for (const int w : d.seams[s].after) {
        if (mark[w] == 1)
          bad("seam " + std::to_string(s) + " ('" + d.seams[s].name + "') waits for seam " + std::to_string(w) +
              ", which waits for it in turn");
        if (mark[w] == 0) visit(w);
      }
      mark[s] = 2;
    };
    for (std::size_t s = 0; s < d.seams.size(); ++s)
      if (mark[s] == 0) visit(static_cast<int>(s));
    report_.total.total = static_cast<int>(pairs_.size());
    gap_.assign(pairs_.size(), 0.0);
    closed_.assign(pairs_.size(), 0);
    stalled_.assign(pairs_.size(), 0);
    for (std::size_t p = 0; p < pairs_.size(); ++p) {
      open_.push_back(static_cast<int>(p));
      gap_[p] = (at(m.x0, pairs_[p].a) - at(m.x0, pairs_[p].b)).norm();
    }
    summarise();
  }

  const char* name() const override { return "seam"; }
  const SeamReport& report() const { return report_; }

  void add_forces(const Eval& e, VecX& f) override {
    for (int p : open_) {
      if (waiting(p)) continue;
      const int a = pairs_[p].a, b = pairs_[p].b;
      const Vec3 l = at(e.x, a) - at(e.x, b);
      const Vec3 fa = -law_.phi_over_d(l.norm()) * l - c_ * (at(e.v, a) - at(e.v, b));
      at(f, a) += fa;
      at(f, b) -= fa;
    }
  }

  bool add_jacobian(const Eval& e, Triplets& dfdx, Triplets& dfdv) override {
    const Mat3 kv = -c_ * Mat3::Identity();
    for (int p : open_) {
      if (waiting(p)) continue;
      const int a = pairs_[p].a, b = pairs_[p].b;
      const Vec3 l = at(e.x, a) - at(e.x, b);
      const double d = l.norm();
      const double across = law_.phi_over_d(d);
      Mat3 kx = -across * Mat3::Identity();
      if (d > 0.0) {
        const Vec3 u = l / d;
        kx -= (law_.dphi(d) - across) * u * u.transpose();
      }
      add_block(dfdx, a, a, kx), add_block(dfdx, b, b, kx);
      add_block(dfdx, a, b, -kx), add_block(dfdx, b, a, -kx);
      if (c_ > 0.0) {
        add_block(dfdv, a, a, kv), add_block(dfdv, b, b, kv);
        add_block(dfdv, a, b, -kv), add_block(dfdv, b, a, -kv);
      }
    }
    return true;
  }

  double energy(const Eval& e) const override {
    double u = 0.0;
    for (int p : open_)
      if (!waiting(p)) u += law_.energy((at(e.x, pairs_[p].a) - at(e.x, pairs_[p].b)).norm());
    return u;
  }

  // ‖∂f_a/∂x_a‖₂ = max(φ′, φ/d) ≤ k for both laws; ‖c I‖₂ = c; twice per row
  // (a-a and a-b blocks). Waiting pairs count too: the bound holds once they pull.
  void add_stiffness_bound(const Model&, VecX& k_rows, VecX& c_rows) const override {
    for (int p : open_) {
      const int a = pairs_[p].a, b = pairs_[p].b;
      k_rows[a] += 2.0 * law_.k, k_rows[b] += 2.0 * law_.k;
      c_rows[a] += 2.0 * c_, c_rows[b] += 2.0 * c_;
    }
  }

  // Measures every open pair's gap (the progress) and asks for the close ones to merge.
  void merge_requests(const Model&, const State& full, std::vector<std::array<int, 2>>& out) override {
    release(full.t);
    // The zipper looks at the neighbours' state before this frame's merges, so
    // it advances at most one pair per seam end per frame.
    auto sewn_neighbour = [&](int p) {
      const int n = static_cast<int>(pairs_.size());
      return (p > 0 && closed_[p - 1] && pairs_[p - 1].seam == pairs_[p].seam) ||
             (p + 1 < n && closed_[p + 1] && pairs_[p + 1].seam == pairs_[p].seam);
    };
    std::vector<int> open_in_seam(report_.seams.size(), 0);
    for (int p : open_) ++open_in_seam[pairs_[p].seam];
    for (int p : open_) {
      const double before = gap_[p];
      gap_[p] = (at(full.x, pairs_[p].a) - at(full.x, pairs_[p].b)).norm();
      // Only a pair that has stopped closing (less than 2 % nearer than a frame
      // ago) zips: one still closing on its own is left to do so gently.
      const bool stalled = gap_[p] > 0.98 * before;
      stalled_[p] = stalled ? stalled_[p] + 1 : 0;
      const bool last = open_in_seam[pairs_[p].seam] == 1 && stalled_[p] >= last_frames_ && gap_[p] < last_distance_;
      if (merge_ &&
          (gap_[p] < merge_distance_ || (gap_[p] < zip_distance_ && stalled && sewn_neighbour(p)) || last))
        out.push_back({pairs_[p].a, pairs_[p].b});
    }
    summarise();
  }

  // A pair is closed once its two particles are one (by its own request or
  // through other pairs: seam crossings, corners); it then leaves the force loop.
  void particles_merged(const Model&, const std::vector<int>& rep) override {
    std::vector<int> still;
    for (int p : open_) {
      if (rep[pairs_[p].a] == rep[pairs_[p].b]) {
        closed_[p] = 1;
        gap_[p] = 0.0;
      } else {
        still.push_back(p);
      }
    }
    open_ = std::move(still);
    summarise();
    release(-1.0);
  }

  bool finished() const override { return merge_ && open_.empty(); }
  bool blocks_rest() const override { return merge_ && !open_.empty(); }

 private:
  bool waiting(int p) const { return report_.seams[pairs_[p].seam].waiting; }
  // Seams whose awaited seams have all closed, or all waiting seams once t
  // reaches the wait limit, start pulling. Called at frame boundaries only, so
  // forces and Jacobians agree within every step. t < 0: no time check.
  void release(double t) {
    const bool late = wait_limit_ > 0.0 && t >= wait_limit_;
    for (std::size_t s = 0; s < after_.size(); ++s) {
      SeamProgress& r = report_.seams[s];
      if (!r.waiting) continue;
      bool closed = true;
      for (const int w : after_[s]) closed = closed && report_.seams[w].closed == report_.seams[w].total;
      if (closed || late) r.waiting = false;
    }
  }

  void summarise() {
    std::vector<double> sum(report_.seams.size(), 0.0);
    for (auto& s : report_.seams) s.closed = 0, s.max_gap = 0.0, s.mean_gap = 0.0;
    SeamProgress& t = report_.total;
    t.closed = 0, t.max_gap = 0.0, t.mean_gap = 0.0;
    double total_sum = 0.0;
    for (std::size_t p = 0; p < pairs_.size(); ++p) {
      SeamProgress& s = report_.seams[pairs_[p].seam];
      if (closed_[p]) {
        ++s.closed, ++t.closed;
        continue;
      }
      s.max_gap = std::max(s.max_gap, gap_[p]);
      t.max_gap = std::max(t.max_gap, gap_[p]);
      sum[pairs_[p].seam] += gap_[p];
      total_sum += gap_[p];
    }
    for (std::size_t s = 0; s < report_.seams.size(); ++s) {
      const int open = report_.seams[s].total - report_.seams[s].closed;
      report_.seams[s].mean_gap = open > 0 ? sum[s] / open : 0.0;
    }
    const int open = t.total - t.closed;
    t.mean_gap = open > 0 ? total_sum / open : 0.0;
  }

  Law law_;
  double c_, merge_distance_, zip_distance_, last_distance_;
  int last_frames_;
  bool merge_;
  double wait_limit_;                   // s
  std::vector<std::vector<int>> after_;  // per seam: the seams it waits for
  std::vector<Pair> pairs_;
  std::vector<int> open_;      // pairs not yet merged
  std::vector<double> gap_;    // m, per pair, at the last frame boundary
  std::vector<char> closed_;
  std::vector<int> stalled_;  // per pair: frames in a row it has not closed by 2 %
  SeamReport report_;
};

}  // namespace

double seam_force(const SeamDef& def, double d) { return Law{def.law, def.stiffness, def.max_force}.phi(d); }

std::unique_ptr<Effect> make_seam(const Model& model, const SeamDef& def) { return std::make_unique<Seam>(model, def); }

const SeamReport* seam_report(const Effect& e) {
  const auto* s = dynamic_cast<const Seam*>(&e);
  return s ? &s->report() : nullptr;
}

}  // namespace vgd::sim
