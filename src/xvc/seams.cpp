// Seams: reading, planned seams, suggestions (seams.hpp; docs/xvc.md "SEAM suggestions").
#include "vgd/xvc/seams.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <tuple>

#include "edit_helpers.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/pattern/contour.hpp"
#include "vgd/xvc/arrangement.hpp"
#include "vgd/xvc/style.hpp"

namespace vgd::xvc {

namespace {

using pattern::Vec2;


// ---- one pattern's outline, stretches and notch marks ---------------------------------

struct Outline {
  const Node* node = nullptr;
  std::string id, piece, size, category;
  int quantity = 1;
  pattern::RoleGuess role;
  pattern::Piece shape;
  std::vector<Stretch> stretches;
  std::vector<double> cum;  // cum[i]: arc length from vertex 0 to vertex i; cum[n] = perimeter
  std::vector<double> marks;  // notch marks as arc positions (pairs within 15 mm merged)
  double perimeter() const { return cum.back(); }
};

Outline outline(const Document& doc, const Node& pat) {
  Outline o;
  o.node = &pat;
  o.id = std::string(pat.id());
  o.piece = std::string(pat.attribute("piece"));
  o.size = std::string(pat.attribute("size"));
  o.category = std::string(pat.attribute("category"));
  o.role = piece_role(doc, pat);
  if (const auto q = parse_int(pat.attribute("quantity"))) o.quantity = static_cast<int>(*q);
  o.shape = to_piece(doc, o.id);
  o.stretches = boundary_stretches(pat);
  const auto& b = o.shape.boundary;
  o.cum.assign(b.size() + 1, 0.0);
  for (std::size_t i = 0; i < b.size(); ++i) o.cum[i + 1] = o.cum[i] + (b[(i + 1) % b.size()].p - b[i].p).norm();
  std::vector<double> s;
  for (const auto& n : o.shape.notches) {
    if (b.size() < 2) break;
    const auto e = pattern::nearest_edge(b, n.position);
    const std::size_t i = static_cast<std::size_t>(e.edge);
    s.push_back(o.cum[i] + e.t * (b[(i + 1) % b.size()].p - b[i].p).norm());
  }
  std::sort(s.begin(), s.end());
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (i + 1 < s.size() && s[i + 1] - s[i] < 0.015) {
      o.marks.push_back(0.5 * (s[i] + s[i + 1]));
      ++i;
    } else {
      o.marks.push_back(s[i]);
    }
  }
  return o;
}

std::size_t stretch_index(const Outline& o, std::string_view id) {
  for (std::size_t k = 0; k < o.stretches.size(); ++k)
    if (o.stretches[k].id == id) return k;
  throw Error("", o.id, "no boundary stretch " + std::string(id) + " in this pattern");
}

// Arc range of stretches k0..k1 (inclusive, wrapping): start position and length.
std::pair<double, double> arc_range(const Outline& o, std::size_t k0, std::size_t k1) {
  const double P = o.perimeter();
  const double s0 = o.cum[o.stretches[k0].first];
  const std::size_t end_vertex = (k1 + 1 < o.stretches.size()) ? o.stretches[k1 + 1].first : 0;
  double s1 = o.cum[end_vertex];
  double len = s1 - s0;
  if (len <= 0) len += P;
  return {s0, len};
}

// Mark fractions along a hem in its direction.
std::vector<double> mark_fractions(const Outline& o, std::size_t k0, std::size_t k1, bool reverse) {
  const auto [s0, len] = arc_range(o, k0, k1);
  const double P = o.perimeter();
  std::vector<double> f;
  for (const double m : o.marks) {
    const double rel = std::fmod(m - s0 + 2 * P, P);
    if (rel <= len + 1e-9 && len > 0) f.push_back(reverse ? 1.0 - rel / len : rel / len);
  }
  std::sort(f.begin(), f.end());
  return f;
}

HemRef hem_ref(const Outline& o, std::size_t k0, std::size_t k1, bool reverse) {
  HemRef h;
  h.pattern = o.id;
  h.from = o.stretches[k0].id;
  h.to = o.stretches[k1].id;
  h.reverse = reverse;
  h.length = arc_range(o, k0, k1).second;
  h.notches = static_cast<int>(mark_fractions(o, k0, k1, reverse).size());
  return h;
}

// ---- edges: runs of stretches between real corners -------------------------------------

struct Edge {
  std::size_t k0 = 0, k1 = 0;  // stretches, inclusive
  double length = 0;
  double u_mid = 0, v_mean = 0, v_hat = 0;  // upright frame; v_hat in [0, 1] over the piece
  int side = 0;                // +1 / -1: which side of the centre line; 0: central
  Vec2 chord = Vec2::Zero();   // (u, v) of end - start
  bool curved = false;
};

struct Frame {
  Vec2 up = Vec2::UnitY(), right = Vec2::UnitX();
  double u_centre = 0, half_width = 0, v_min = 0, v_max = 0;
};

Frame upright_frame(const Outline& o, bool use_grain) {
  Frame f;
  if (use_grain && o.shape.grain_line) {
    const Vec2 d = o.shape.grain_line->b - o.shape.grain_line->a;
    if (d.norm() > 0) f.up = d.normalized();
  }
  f.right = Vec2(f.up.y(), -f.up.x());
  double umin = 1e300, umax = -1e300;
  f.v_min = 1e300;
  f.v_max = -1e300;
  for (const auto& c : o.shape.boundary) {
    const double u = c.p.dot(f.right), v = c.p.dot(f.up);
    umin = std::min(umin, u);
    umax = std::max(umax, u);
    f.v_min = std::min(f.v_min, v);
    f.v_max = std::max(f.v_max, v);
  }
  // A half piece (cut on the fold) has its centre on the fold line.
  f.u_centre = o.shape.mirror_line ? 0.5 * (o.shape.mirror_line->a + o.shape.mirror_line->b).dot(f.right) : 0.5 * (umin + umax);
  f.half_width = std::max(std::abs(umax - f.u_centre), std::abs(umin - f.u_centre));
  return f;
}

double turn_angle_deg(const std::vector<pattern::ContourPoint>& b, std::size_t i) {
  const std::size_t n = b.size();
  const Vec2 a = b[i].p - b[(i + n - 1) % n].p, c = b[(i + 1) % n].p - b[i].p;
  if (a.norm() == 0 || c.norm() == 0) return 0;
  return std::acos(std::clamp(a.normalized().dot(c.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

std::vector<Edge> edges(const Outline& o, const Frame& f, double merge_angle) {
  std::vector<Edge> out;
  const auto& st = o.stretches;
  const auto& b = o.shape.boundary;
  if (st.empty() || b.size() < 3) return out;
  // Stretch k starts a new edge when its first vertex is a real corner.
  std::vector<bool> starts(st.size());
  for (std::size_t k = 0; k < st.size(); ++k) starts[k] = turn_angle_deg(b, st[k].first) >= merge_angle;
  std::size_t first_start = 0;
  while (first_start < st.size() && !starts[first_start]) ++first_start;
  if (first_start == st.size()) { first_start = 0; starts[0] = true; }
  for (std::size_t j = 0; j < st.size();) {
    const std::size_t k0 = (first_start + j) % st.size();
    std::size_t len = 1;
    while (j + len < st.size() && !starts[(first_start + j + len) % st.size()]) ++len;
    Edge e;
    e.k0 = k0;
    e.k1 = (k0 + len - 1) % st.size();
    const auto [s0, l] = arc_range(o, e.k0, e.k1);
    e.length = l;
    // Vertices of the edge, start to end inclusive.
    const std::size_t v0 = st[e.k0].first;
    const std::size_t v_end = (e.k1 + 1 < st.size()) ? st[e.k1 + 1].first : 0;
    std::vector<Vec2> pts;
    for (std::size_t i = v0;; i = (i + 1) % b.size()) {
      pts.push_back(b[i].p);
      if (i == v_end && pts.size() > 1) break;
      if (pts.size() > b.size() + 1) break;
    }
    double usum = 0, vsum = 0, near = 1e300;
    for (const auto& p : pts) {
      usum += p.dot(f.right);
      vsum += p.dot(f.up);
      near = std::min(near, std::abs(p.dot(f.right) - f.u_centre));
    }
    e.u_mid = usum / pts.size();
    e.v_mean = vsum / pts.size();
    e.v_hat = f.v_max > f.v_min ? (e.v_mean - f.v_min) / (f.v_max - f.v_min) : 0.5;
    e.side = near < 0.15 * f.half_width ? 0 : (e.u_mid > f.u_centre ? 1 : -1);
    const Vec2 d = pts.back() - pts.front();
    e.chord = Vec2(d.dot(f.right), d.dot(f.up));
    e.curved = d.norm() > 0 && e.length / d.norm() > 1.01;
    out.push_back(e);
    j += len;
  }
  return out;
}

// The centre front or back of a piece drawn as a half with no fold line
// (Valentina's FRONTPANEL and BACKPANEL): of its straight edges along the
// grain (within 0.6 degrees) that run at least 60 % of its length with the
// whole piece on one side of them (within 1 mm), the longest, on a piece
// that is not its own mirror image across its middle (a whole piece's
// straight side seams are not centres). Such an edge is not a side seam.
std::optional<std::size_t> centre_edge_of_half(const Outline& o, const Frame& f, const std::vector<Edge>& es) {
  if (o.shape.mirror_line) return std::nullopt;
  const auto& b = o.shape.boundary;
  double umin = 1e300, umax = -1e300;
  for (const auto& c : b) umin = std::min(umin, c.p.dot(f.right)), umax = std::max(umax, c.p.dot(f.right));
  if (pattern::mirror_symmetric(b, f.up, 0.002)) return std::nullopt;
  std::optional<std::size_t> best;
  double best_len = 0;
  for (std::size_t i = 0; i < es.size(); ++i) {
    const Edge& e = es[i];
    if (e.curved || e.length < 0.6 * (f.v_max - f.v_min) || e.length <= best_len) continue;
    if (std::abs(e.chord.x()) > std::sin(0.6 * M_PI / 180.0) * e.chord.norm()) continue;
    if (umin < e.u_mid - 0.001 && umax > e.u_mid + 0.001) continue;  // cloth on both sides
    best = i;
    best_len = e.length;
  }
  return best;
}

// Two consecutive edges on one side of a piece read as one when they meet at a gentle
// turn (a waist shaped on one piece and almost straight on the other: the front's side
// seam is one edge, the back's two). At most `max_turn_deg` between them.
std::optional<Edge> joined(const Outline& o, const Edge& a, const Edge& b, double max_turn_deg) {
  const std::size_t ns = o.stretches.size();
  if ((a.k1 + 1) % ns != b.k0 || a.side == 0 || a.side != b.side || b.k1 == a.k0) return std::nullopt;
  if (turn_angle_deg(o.shape.boundary, o.stretches[b.k0].first) > max_turn_deg) return std::nullopt;
  Edge e = a;
  e.k1 = b.k1;
  e.length = a.length + b.length;
  const double wa = a.length / e.length, wb = b.length / e.length;
  e.u_mid = wa * a.u_mid + wb * b.u_mid;
  e.v_mean = wa * a.v_mean + wb * b.v_mean;
  e.v_hat = wa * a.v_hat + wb * b.v_hat;
  e.chord = a.chord + b.chord;
  e.curved = true;
  return e;
}

// ---- roles ----------------------------------------------------------------------------

enum class Role { other, front, back, sleeve, waistband, neckband, cuff, leg, yoke, collar, stand, binding };

Role role_of(const Outline& o) {
  switch (o.role.role) {
    case pattern::Role::leg: return Role::leg;
    case pattern::Role::sleeve: return Role::sleeve;
    case pattern::Role::waistband: return Role::waistband;
    case pattern::Role::neckband: return Role::neckband;
    case pattern::Role::cuff: return Role::cuff;
    case pattern::Role::front: return Role::front;
    case pattern::Role::back: return Role::back;
    case pattern::Role::yoke: return Role::yoke;
    case pattern::Role::collar: return Role::collar;
    case pattern::Role::collar_stand: return Role::stand;
    case pattern::Role::binding: return Role::binding;
    default: return Role::other;
  }
}

// ---- scoring -------------------------------------------------------------------------

struct Part {
  const Outline* o;
  std::size_t k0, k1;
  bool reverse;
};

// Notches: marks of A against marks and junctions of the concatenation B.
void score_notches(const std::vector<Part>& parts, SeamSuggestion& s, double& factor) {
  const auto a = mark_fractions(*parts[0].o, parts[0].k0, parts[0].k1, parts[0].reverse);
  std::vector<double> b, junctions;
  double total = 0;
  for (std::size_t i = 1; i < parts.size(); ++i) total += arc_range(*parts[i].o, parts[i].k0, parts[i].k1).second;
  double offset = 0;
  for (std::size_t i = 1; i < parts.size(); ++i) {
    const double len = arc_range(*parts[i].o, parts[i].k0, parts[i].k1).second;
    for (const double f : mark_fractions(*parts[i].o, parts[i].k0, parts[i].k1, parts[i].reverse)) b.push_back((offset + f * len) / total);
    offset += len;
    if (i + 1 < parts.size()) junctions.push_back(offset / total);
  }
  s.notches_a = static_cast<int>(a.size());
  s.notches_b = static_cast<int>(b.size());
  int matched = 0;
  for (const double x : a) {
    bool hit = false;
    for (const double y : b) hit = hit || std::abs(x - y) < 0.03;
    for (const double y : junctions) hit = hit || std::abs(x - y) < 0.03;
    matched += hit;
  }
  s.notches_matched = matched;
  const int want = std::max(s.notches_a, s.notches_b);
  factor = want == 0 ? 1.0 : 0.6 + 0.4 * std::min(1.0, static_cast<double>(matched) / want);
}

// How much longer a back may be than the yoke it is pleated or gathered into.
constexpr double kYokeGathers = 0.15;
// Relative length tolerance of a side seam (other seams: 0.02): a 2.5 % difference
// still scores 0.67.
constexpr double kSideSeamTolerance = 0.04;
// How much shorter than the opening it is sewn round (a neckline, a sleeve's
// hem) a neckband or a cuff may be cut (a rib is stretched onto it:
// typically 10-20 %).
constexpr double kRibShorter = 0.25;
// How much longer or shorter than the neckline a collar stand may be cut:
// its ends overlap at centre front by the button extension, and a front
// drawn with its extension, unfolded about its edge, has it in its neckline
// on both sides (Valentina's shirt: a 50.4 cm stand for 55.9 cm of
// neckline). So too how much shorter than the stand's top the collar sewn
// to it (the stand's ends reach past the collar's by the extension).
constexpr double kStandLonger = 0.15;
// How much longer than the opening it binds a binding may be cut: strips are
// cut long and trimmed where the binding meets itself (Gerber's tank: 72 cm
// for a 58.5 cm neckline, 81 cm for a 48 cm armhole).
constexpr double kBindingLonger = 1.0;
// How much longer than its side's waist a trouser's half waistband may be cut:
// past centre front it runs on as the fly's overlap or underlap (Valentina's
// trousers: 5.1 and 9.1 cm past 46.9 cm of waist).
constexpr double kWaistbandExtension = 0.12;

SeamSuggestion make(const std::string& name, const std::string& size, const std::vector<Part>& parts, double shape,
                    const std::string& reason, double ease_lo, double ease_hi, double tolerance) {
  SeamSuggestion s;
  s.name = name;
  s.size = size;
  for (const auto& p : parts) s.hems.push_back(hem_ref(*p.o, p.k0, p.k1, p.reverse));
  s.length_a = s.hems[0].length;
  for (std::size_t i = 1; i < s.hems.size(); ++i) s.length_b += s.hems[i].length;
  s.ease = s.length_a - s.length_b;
  // Length: 1 inside [ease_lo, ease_hi] widened by what a sewer eases in
  // without a mark (2 mm, at most 5 % of the hem: a graded strap 1 mm longer
  // than its partner still sews), falling off as a Gaussian of the relative
  // excess beyond.
  const double slack = std::min(kSewingSlack, 0.05 * std::min(s.length_a, s.length_b));
  const double excess = std::max(0.0, (s.ease < ease_lo ? ease_lo - s.ease : (s.ease > ease_hi ? s.ease - ease_hi : 0.0)) - slack);
  const double rel = excess / std::max(s.length_a, s.length_b);
  double notch = 1;
  score_notches(parts, s, notch);
  s.score = std::exp(-(rel / tolerance) * (rel / tolerance)) * shape * notch;
  s.reason = reason + "; lengths " + format_fixed(s.length_a * 1000, 1) + " and " + format_fixed(s.length_b * 1000, 1) +
             " mm, notches " + std::to_string(s.notches_matched) + "/" + std::to_string(std::max(s.notches_a, s.notches_b)) +
             " matched";
  return s;
}

void suggest_for_size(const std::vector<Outline>& outs, const std::string& size, const SeamOptions& opts,
                      std::vector<SeamSuggestion>& out) {
  struct PieceInfo {
    const Outline* o;
    Role role;
    Frame frame;
    std::vector<Edge> edges;
  };
  std::vector<PieceInfo> ps;
  for (const auto& o : outs) {
    if (o.size != size || o.quantity == 0 || o.stretches.empty()) continue;
    const Role r = role_of(o);
    if (r == Role::other) continue;
    PieceInfo pi{&o, r, upright_frame(o, r != Role::waistband && r != Role::neckband && r != Role::cuff && r != Role::collar &&
                                          r != Role::stand && r != Role::binding), {}};
    pi.edges = edges(o, pi.frame, opts.merge_angle_deg);
    ps.push_back(std::move(pi));
  }
  std::set<std::pair<const Outline*, std::size_t>> used;  // (pattern, edge index)
  std::map<const Outline*, std::vector<std::pair<std::size_t, std::size_t>>> shoulders;  // stretch runs sewn as shoulders
  std::vector<SeamSuggestion> found;
  // A piece's copies: +1 the wearer's left, -1 the right (a piece cut twice: the right first).
  const auto copies_of = [](const Outline& o) {
    if (o.role.side == pattern::Side::left) return std::vector<int>{1};
    if (o.role.side == pattern::Side::right) return std::vector<int>{-1};
    return o.quantity >= 2 ? std::vector<int>{-1, 1} : std::vector<int>{1};
  };

  // 0. Darts: a narrow V cut into the outline (a waist dart of trousers drawn open):
  //    two consecutive stretches of 2-15 cm, alike within 5 mm, whose shared vertex
  //    (the tip) turns back by more than 145 degrees into the piece, their outer ends
  //    at most 5 cm apart. The legs sew to each other (mouth to mouth, tip to tip),
  //    once per copy; their edges take part in no other seam. Suggested for pieces
  //    that other seams sew into the garment (not for an alternative left out).
  std::vector<SeamSuggestion> darts;
  std::map<const Outline*, std::set<std::size_t>> dart_stretches;  // the legs of every dart found
  for (const auto& p : ps) {
    const auto& o = *p.o;
    const auto& b = o.shape.boundary;
    const std::size_t ns = o.stretches.size();
    if (ns < 4 || b.size() < 3) continue;
    const double area = pattern::signed_area(b);
    for (std::size_t k = 0; k < ns; ++k) {
      const std::size_t k2 = (k + 1) % ns;
      const Vec2 a = b[o.stretches[k].first].p, tip = b[o.stretches[k2].first].p, c = b[o.stretches[(k + 2) % ns].first].p;
      const double la = arc_range(o, k, k).second, lc = arc_range(o, k2, k2).second;
      const Vec2 in = tip - a, outv = c - tip;
      if (la < 0.02 || lc < 0.02 || la > 0.15 || lc > 0.15 || std::abs(la - lc) > 0.005 || (c - a).norm() > 0.05) continue;
      if (in.norm() == 0 || outv.norm() == 0) continue;
      const double turn = std::acos(std::clamp(in.normalized().dot(outv.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
      const double cross = in.x() * outv.y() - in.y() * outv.x();
      if (turn < 145.0 || (area > 0) == (cross > 0)) continue;  // not sharp, or a spike out of the piece
      dart_stretches[p.o].insert({k, k2});
      for (const int copy : copies_of(o)) {
        auto d = make(std::string(copy > 0 ? "left " : "right ") + "dart", size, {{p.o, k, k, false}, {p.o, k2, k2, true}},
                      1.0, "dart of " + o.piece + ": a V of " + format_fixed(1000 * (c - a).norm(), 0) + " mm by " +
                               format_fixed(1000 * la, 0) + " mm cut into its outline",
                      0, 0, 0.02);
        if (o.quantity < 2 && o.role.side == pattern::Side::none) d.name = "dart";
        if (d.score >= opts.min_score) darts.push_back(d);
      }
      for (std::size_t e = 0; e < p.edges.size(); ++e) {
        const Edge& ed = p.edges[e];
        if ((ed.k0 == k || ed.k0 == k2) && (ed.k1 == k || ed.k1 == k2)) used.insert({p.o, e});
      }
    }
  }

  // 0b. A shirt's yoke, drawn like a back (its neckline up, the wearer's left on
  //     -u): its lowest edge across the middle to the highest edge across the
  //     middle of a back (the back hangs from it); on each side its highest edge
  //     (the shoulder) to a front's shoulder on the same side of the wearer, and
  //     its edge below that (the armhole's top, when it has one) continues the
  //     back's armhole in the sleeve's seam (step 1).
  std::map<int, std::pair<const Outline*, std::size_t>> yoke_armhole;  // the wearer's side -> yoke edge
  for (const auto& yk : ps) {
    if (yk.role != Role::yoke || yk.edges.size() < 4) continue;
    std::optional<std::size_t> bottom;
    for (std::size_t i = 0; i < yk.edges.size(); ++i)
      if (yk.edges[i].side == 0 && (!bottom || yk.edges[i].v_mean < yk.edges[*bottom].v_mean)) bottom = i;
    if (!bottom) continue;
    std::optional<SeamSuggestion> best;
    std::pair<const Outline*, std::size_t> top{};
    for (const auto& bk : ps) {
      if (bk.role != Role::back) continue;
      std::optional<std::size_t> t;
      for (std::size_t j = 0; j < bk.edges.size(); ++j)
        if (bk.edges[j].side == 0 && !used.count({bk.o, j}) && (!t || bk.edges[j].v_mean > bk.edges[*t].v_mean)) t = j;
      if (!t) continue;
      const Edge &ye = yk.edges[*bottom], &be = bk.edges[*t];
      // The back may be pleated or gathered into the yoke (a men's shirt's box
      // pleat at centre back: Valentina's back is 63.5 mm longer than its yoke):
      // up to kYokeGathers longer.
      auto s = make("yoke seam", size, {{yk.o, ye.k0, ye.k1, false}, {bk.o, be.k0, be.k1, true}}, 1.0,
                    "yoke seam: the lowest edge of " + yk.o->piece + " to the top of " + bk.o->piece,
                    -kYokeGathers * be.length, 0, 0.02);
      if (!best || s.score > best->score) best = s, top = {bk.o, *t};
    }
    if (!best || best->score < opts.min_score) continue;
    used.insert({yk.o, *bottom});
    used.insert(top);
    found.push_back(*best);
    for (const int sigma : {1, -1}) {  // the wearer's side: -sigma on the yoke, +sigma on a front
      std::vector<std::size_t> mine;
      for (std::size_t i = 0; i < yk.edges.size(); ++i)
        if (yk.edges[i].side == -sigma && !used.count({yk.o, i})) mine.push_back(i);
      if (mine.empty()) continue;
      std::sort(mine.begin(), mine.end(), [&](std::size_t a, std::size_t b) { return yk.edges[a].v_mean > yk.edges[b].v_mean; });
      const Edge& ys = yk.edges[mine[0]];
      std::optional<SeamSuggestion> sh;
      std::pair<const Outline*, std::size_t> fs{};
      for (const auto& fr : ps) {
        if (fr.role != Role::front) continue;
        for (std::size_t i = 0; i < fr.edges.size(); ++i) {
          const Edge& fe = fr.edges[i];
          if (fe.side != sigma || fe.curved || fe.v_hat < 0.6 || used.count({fr.o, i})) continue;
          const std::string side = sigma > 0 ? "left " : "right ";
          auto s = make(side + "shoulder", size, {{fr.o, fe.k0, fe.k1, false}, {yk.o, ys.k0, ys.k1, true}}, 1.0,
                        "shoulder of " + fr.o->piece + " and " + yk.o->piece + " on the wearer's " + side + "side", 0, 0,
                        0.02);
          if (!sh || s.score > sh->score) sh = s, fs = {fr.o, i};
        }
      }
      if (sh && sh->score >= opts.min_score) {
        used.insert({yk.o, mine[0]});
        used.insert(fs);
        found.push_back(*sh);
        shoulders[yk.o].push_back({ys.k0, ys.k1});
        for (const auto& fr : ps)
          if (fr.o == fs.first) shoulders[fr.o].push_back({fr.edges[fs.second].k0, fr.edges[fs.second].k1});
        if (mine.size() >= 2) yoke_armhole[sigma] = {yk.o, mine[1]};
      }
    }
  }

  // 1. Sleeves: cap to a front armhole and a back armhole (and a yoke's armhole
  //    between them); then the underarm seam.
  for (const auto& sl : ps) {
    if (sl.role != Role::sleeve || sl.edges.size() < 3 || sl.o->role.half != pattern::Half::none) continue;
    std::vector<int> sides;
    if (sl.o->role.side == pattern::Side::left) sides = {1};
    else if (sl.o->role.side == pattern::Side::right) sides = {-1};
    else if (sl.o->quantity >= 2) sides = {1, -1};
    else sides = {1};
    std::size_t cap = 0;
    for (std::size_t i = 1; i < sl.edges.size(); ++i)
      if (sl.edges[i].v_mean > sl.edges[cap].v_mean) cap = i;
    const Edge& ce = sl.edges[cap];
    for (const int sigma : sides) {
      std::optional<SeamSuggestion> best;
      std::pair<const Outline*, std::size_t> bf{}, bb{};
      for (const auto& fr : ps) {
        if (fr.role != Role::front) continue;
        for (const auto& bk : ps) {
          if (bk.role != Role::back) continue;
          for (std::size_t i = 0; i < fr.edges.size(); ++i) {
            const Edge& fe = fr.edges[i];
            if (fe.side != sigma || !fe.curved || used.count({fr.o, i})) continue;
            for (std::size_t j = 0; j < bk.edges.size(); ++j) {
              const Edge& be = bk.edges[j];
              if (be.side != -sigma || !be.curved || used.count({bk.o, j})) continue;
              const double balance = std::min(fe.length, be.length) / std::max(fe.length, be.length);
              const double shape = balance > 0.7 ? 1.0 : balance / 0.7;
              // The wearer's left sleeve (sigma +1) meets the back armhole first along
              // its cap's contour; the right sleeve the front one (seams.hpp).
              std::vector<Part> parts{{sl.o, ce.k0, ce.k1, false}};
              const auto yoke = yoke_armhole.find(sigma);
              const auto add_yoke = [&] {
                if (yoke == yoke_armhole.end()) return;
                const Outline* yo = yoke->second.first;
                const Edge* ye = nullptr;
                for (const auto& pi : ps)
                  if (pi.o == yo) ye = &pi.edges[yoke->second.second];
                parts.push_back({yo, ye->k0, ye->k1, true});
              };
              if (sigma > 0) {
                parts.push_back({bk.o, be.k0, be.k1, true});
                add_yoke();
                parts.push_back({fr.o, fe.k0, fe.k1, true});
              } else {
                parts.push_back({fr.o, fe.k0, fe.k1, true});
                add_yoke();
                parts.push_back({bk.o, be.k0, be.k1, true});
              }
              auto s = make(sigma > 0 ? "left armhole" : "right armhole", size, parts, shape,
                            "sleeve cap of " + sl.o->piece + " to the " + (sigma > 0 ? "left" : "right") +
                                " armholes of " + bk.o->piece + " and " + fr.o->piece,
                            -0.005, opts.max_cap_ease, 0.02);
              if (!best || s.score > best->score) {
                best = s;
                bf = {fr.o, i};
                bb = {bk.o, j};
              }
            }
          }
        }
      }
      if (best && best->score >= opts.min_score) {
        used.insert(bf);
        used.insert(bb);
        if (const auto y = yoke_armhole.find(sigma); y != yoke_armhole.end()) used.insert(y->second);
        found.push_back(*best);
      }
    }
    // Underarm: the edge after the cap (forward) to the edge before it (reverse).
    const std::size_t after = (cap + 1) % sl.edges.size(), before = (cap + sl.edges.size() - 1) % sl.edges.size();
    if (after != before) {
      const Edge &ea = sl.edges[after], &eb = sl.edges[before];
      for (const int copy : sides) {
        auto s = make(copy > 0 ? "left underarm" : "right underarm", size,
                      {{sl.o, ea.k0, ea.k1, false}, {sl.o, eb.k0, eb.k1, true}}, 1.0,
                      "underarm seam of " + sl.o->piece + ": the edges on either side of the cap", 0, 0, 0.02);
        if (sides.size() > 1) s.reason += " (copy " + std::string(copy > 0 ? "left" : "right") + ")";
        if (s.score >= opts.min_score) found.push_back(s);
      }
    }
  }

  // 1b. Sleeves cut in two along the arm (a front and a back half, TEESL FR and TEESL
  //     BK). Their edges match in parts (a half may reach past the shoulder point), so
  //     runs of stretches within an edge are matched, not whole edges. The front half's
  //     cap is its curved run that best fits a curved front armhole run on its side;
  //     then the halves' runs from their hems' ends pair, alike in length (the longer
  //     pair is the over-arm seam, the shorter the underarm), the first hem forward,
  //     the other reverse; the back half's cap is, of its runs left (not on its hem,
  //     the lowest edge, nor beside it), the one that best fits a back armhole. The
  //     hems stay open. A half cut twice sews once per copy, the right arm's first
  //     (its first arrangement).
  struct StretchRun {
    std::size_t k0, k1, edge;
    double length;
    bool curved;
  };
  const auto stretch_runs = [](const PieceInfo& p) {
    std::vector<StretchRun> runs;  // edge by edge, then by start, then by end
    const auto& o = *p.o;
    const std::size_t ns = o.stretches.size();
    for (std::size_t e = 0; e < p.edges.size(); ++e) {
      const std::size_t count = (p.edges[e].k1 + ns - p.edges[e].k0) % ns + 1;
      for (std::size_t a = 0; a < count; ++a)
        for (std::size_t b = a; b < count; ++b) {
          const std::size_t k0 = (p.edges[e].k0 + a) % ns, k1 = (p.edges[e].k0 + b) % ns;
          const auto [start, length] = arc_range(o, k0, k1);
          const std::size_t n = o.shape.boundary.size();
          const std::size_t v0 = o.stretches[k0].first, v1 = k1 + 1 < ns ? o.stretches[k1 + 1].first : 0;
          const double chord = (o.shape.boundary[v1 % n].p - o.shape.boundary[v0].p).norm();
          runs.push_back({k0, k1, e, length, chord > 0 && length / chord > 1.01});
        }
    }
    return runs;
  };
  std::vector<std::vector<StretchRun>> piece_runs;  // per piece of ps
  for (const auto& p : ps) piece_runs.push_back(stretch_runs(p));
  const auto stretch_runs_of = [&](const PieceInfo& p) -> const std::vector<StretchRun>& {
    return piece_runs[static_cast<std::size_t>(&p - ps.data())];
  };
  const auto covers = [](const Outline& o, const StretchRun& r) {
    std::set<std::size_t> ks;
    for (std::size_t k = r.k0;; k = (k + 1) % o.stretches.size()) {
      ks.insert(k);
      if (k == r.k1) break;
    }
    return ks;
  };
  std::map<const Outline*, std::set<std::size_t>> half_cap;   // the cap's stretches of each half
  std::map<const Outline*, std::set<std::size_t>> half_sewn;  // stretches sewn to the other half
  const auto disjoint = [](const std::set<std::size_t>& x, const std::set<std::size_t>& y) {
    return std::none_of(x.begin(), x.end(), [&](std::size_t k) { return y.count(k) > 0; });
  };
  // A half's cap: of its runs that `may` be one, the one that best fits an armhole run
  // (curved) on its side of the arm, scored by length (half the ease a whole cap may
  // have), notches and how much of the armhole edge the run covers; of runs fitting
  // alike, the longest pair.
  const auto sew_cap = [&](const PieceInfo& sl, const std::function<bool(const StretchRun&)>& may) {
    const bool front_half = sl.o->role.half == pattern::Half::front;
    const auto& sruns = stretch_runs_of(sl);
    std::optional<std::size_t> cap;  // index in sruns, fixed by the first copy
    for (const int sigma : copies_of(*sl.o)) {
      std::optional<SeamSuggestion> best;
      std::pair<const Outline*, std::size_t> taken{};
      std::size_t best_cap = 0;
      for (std::size_t c = 0; c < sruns.size(); ++c) {
        if ((cap && c != *cap) || (!cap && !may(sruns[c]))) continue;
        for (const auto& bp : ps) {
          if (bp.role != (front_half ? Role::front : Role::back)) continue;
          for (const auto& br : stretch_runs_of(bp)) {
            const Edge& be = bp.edges[br.edge];
            if (be.side != (front_half ? sigma : -sigma) || !br.curved || used.count({bp.o, br.edge})) continue;
            const std::string name = std::string(sigma > 0 ? "left " : "right ") + (front_half ? "front" : "back") + " armhole";
            // The shape factor: how much of the armhole edge the run covers.
            auto s = make(name, size, {{sl.o, sruns[c].k0, sruns[c].k1, false}, {bp.o, br.k0, br.k1, true}},
                          std::min(1.0, br.length / be.length),
                          "cap of the sleeve's " + std::string(front_half ? "front" : "back") + " half " + sl.o->piece +
                              " to the " + (sigma > 0 ? "left" : "right") + " armhole of " + bp.o->piece,
                          -0.005, 0.5 * opts.max_cap_ease, 0.02);
            if (!best || s.score > best->score + 1e-9 ||
                (s.score > best->score - 1e-9 && s.length_a + s.length_b > best->length_a + best->length_b))
              best = s, taken = {bp.o, br.edge}, best_cap = c;
          }
        }
      }
      if (best && best->score >= opts.min_score) {
        used.insert(taken);
        cap = best_cap;
        found.push_back(*best);
      }
    }
    if (cap) half_cap[sl.o] = covers(*sl.o, sruns[*cap]);
  };
  // A half's hem: its edge lowest down.
  const auto hem_edge = [](const PieceInfo& p) {
    std::size_t hem = 0;
    for (std::size_t i = 1; i < p.edges.size(); ++i)
      if (p.edges[i].v_mean < p.edges[hem].v_mean) hem = i;
    return hem;
  };
  // A cap is neither on the hem nor beside it: the runs from the hem's ends are the
  // over-arm and underarm seams.
  const auto off_hem = [&](const PieceInfo& p, const StretchRun& r) {
    const std::size_t h = hem_edge(p), n = p.o->stretches.size();
    const Edge& hem = p.edges[h];
    return r.edge != h && r.k0 != (hem.k1 + 1) % n && (r.k1 + 1) % n != hem.k0;
  };
  // The front halves' caps first: a curved run.
  for (const auto& sl : ps)
    if (sl.role == Role::sleeve && sl.o->role.half == pattern::Half::front)
      sew_cap(sl, [&](const StretchRun& r) { return r.curved && off_hem(sl, r); });
  // The halves to each other, hems left open.
  for (const auto& fh : ps) {
    if (fh.role != Role::sleeve || fh.o->role.half != pattern::Half::front || !half_cap.count(fh.o)) continue;
    for (const auto& bh : ps) {
      if (bh.role != Role::sleeve || bh.o->role.half != pattern::Half::back || bh.o->role.side != fh.o->role.side ||
          bh.o->quantity != fh.o->quantity)
        continue;
      struct Pair {
        SeamSuggestion s;
        std::set<std::size_t> f, b;  // stretches covered
      };
      // The runs that leave the hem at one end and reach it at the other: the
      // front half's run leaving its hem sews to the back half's run reaching
      // its own, and the other way round (each half's hem ends are the ends of
      // the two seams; lengths alone mistook a cap for an over-arm edge at
      // graded sizes).
      const Edge &fhem = fh.edges[hem_edge(fh)], &bhem = bh.edges[hem_edge(bh)];
      const std::size_t nf = fh.o->stretches.size(), nb = bh.o->stretches.size();
      std::vector<Pair> kept;
      std::set<std::size_t> bi;
      for (const bool front_leaves : {true, false}) {
        std::optional<Pair> best;
        for (const auto& fr : stretch_runs_of(fh)) {
          if (front_leaves ? fr.k0 != (fhem.k1 + 1) % nf : (fr.k1 + 1) % nf != fhem.k0) continue;
          const auto fk = covers(*fh.o, fr);
          if (!disjoint(fk, half_cap[fh.o])) continue;
          for (const auto& br : stretch_runs_of(bh)) {
            if (front_leaves ? (br.k1 + 1) % nb != bhem.k0 : br.k0 != (bhem.k1 + 1) % nb) continue;
            auto sg = make("seam", size, {{fh.o, fr.k0, fr.k1, false}, {bh.o, br.k0, br.k1, true}}, 1.0, "", 0, 0, 0.02);
            if (sg.score < opts.min_score) continue;
            if (!best || sg.score > best->s.score + 1e-9 ||
                (sg.score > best->s.score - 1e-9 && sg.length_a > best->s.length_a))
              best = Pair{std::move(sg), fk, covers(*bh.o, br)};
          }
        }
        if (best && disjoint(best->b, bi)) {
          bi.insert(best->b.begin(), best->b.end());
          kept.push_back(std::move(*best));
        }
      }
      half_sewn[bh.o].insert(bi.begin(), bi.end());
      if (kept.size() == 2 && kept[1].s.length_a > kept[0].s.length_a) std::swap(kept[0], kept[1]);
      for (const int sigma : copies_of(*fh.o))
        for (std::size_t k = 0; k < kept.size(); ++k) {
          SeamSuggestion s = kept[k].s;
          const std::string what = k == 0 && kept.size() == 2 ? "over-arm seam" : "underarm";
          s.name = std::string(sigma > 0 ? "left " : "right ") + what;
          s.reason = what + " of the sleeve halves " + fh.o->piece + " and " + bh.o->piece + s.reason;
          found.push_back(std::move(s));
        }
    }
  }
  // The back halves' caps: a run not sewn to the front half, and not on the hem.
  for (const auto& sl : ps) {
    if (sl.role != Role::sleeve || sl.o->role.half != pattern::Half::back || sl.edges.empty()) continue;
    const auto sewn = half_sewn[sl.o];
    sew_cap(sl, [&](const StretchRun& r) { return off_hem(sl, r) && disjoint(covers(*sl.o, r), sewn); });
  }

  // A leg piece's hem and waist edges: the hem at the end narrower across the grain,
  // the waist the edge furthest from it.
  auto leg_ends = [](const PieceInfo& lg) {
    const bool hem_low = pattern::wider_at_top(lg.o->shape.boundary, lg.frame.up);
    std::size_t hem = 0, waist = 0;
    for (std::size_t i = 1; i < lg.edges.size(); ++i) {
      const double v = lg.edges[i].v_mean;
      if (hem_low ? v < lg.edges[hem].v_mean : v > lg.edges[hem].v_mean) hem = i;
      if (hem_low ? v > lg.edges[waist].v_mean : v < lg.edges[waist].v_mean) waist = i;
    }
    return std::pair{hem, waist};
  };

  // A piece's top edge: of its edges across the middle, the highest.
  const auto top_edge = [](const PieceInfo& p) -> std::optional<std::size_t> {
    std::optional<std::size_t> t;
    for (std::size_t i = 0; i < p.edges.size(); ++i)
      if (p.edges[i].side == 0 && (!t || p.edges[i].v_mean > p.edges[*t].v_mean)) t = i;
    return t;
  };
  // The stretch of a run (k0..k1) after which the piece's centre line
  // crosses it: the stretch boundary nearest the centre, within 1 cm.
  const auto centre_split = [&](const PieceInfo& p, std::pair<std::size_t, std::size_t> r) {
    std::optional<std::size_t> split;
    double best_d = 0.01;
    for (std::size_t k = r.first; k != r.second; k = (k + 1) % p.o->stretches.size()) {
      const std::size_t next = (k + 1) % p.o->stretches.size();
      const Vec2 q = p.o->shape.boundary[p.o->stretches[next].first].p;
      const double d = std::abs(q.dot(p.frame.right) - p.frame.u_centre);
      if (d < best_d) {
        best_d = d;
        split = k;
      }
    }
    return split;
  };
  // The runs (k0..k1, along the contour) of a front and a back round the
  // body, for a band sewn there (a waistband to a waist, a neckband to a
  // neckline): the back's from centre back (split at the stretch boundary
  // nearest centre back when it has one, within 1 cm), the front's, the
  // back's other half on to centre back; each reversed, running from the
  // wearer's right to the left as a band's bottom edge does as it is
  // arranged. Back's +u half (the wearer's right seen from behind) runs from
  // the side to centre back along the contour; reversed it starts at centre
  // back.
  const auto split_round = [&](const PieceInfo& fr, std::pair<std::size_t, std::size_t> rf, const PieceInfo& bk,
                               std::pair<std::size_t, std::size_t> rb) {
    const auto split = centre_split(bk, rb);
    if (split)
      return std::vector<Part>{{bk.o, rb.first, *split, true},
                               {fr.o, rf.first, rf.second, true},
                               {bk.o, (*split + 1) % bk.o->stretches.size(), rb.second, true}};
    return std::vector<Part>{{fr.o, rf.first, rf.second, true}, {bk.o, rb.first, rb.second, true}};
  };
  const auto round_top = [&](const PieceInfo& fr, const PieceInfo& bk) -> std::optional<std::vector<Part>> {
    const auto tf = top_edge(fr), tb = top_edge(bk);
    if (!tf || !tb) return std::nullopt;
    return split_round(fr, {fr.edges[*tf].k0, fr.edges[*tf].k1}, bk, {bk.edges[*tb].k0, bk.edges[*tb].k1});
  };
  // A band's seam round the body: of the runs of stretches within one of the
  // band's long edges (those at least half as long as its longest; a button
  // stand split off by a turn point stays open), the one that best fits
  // `parts` (parts[0] is replaced by the run). Of runs scoring alike, the one
  // on the band's bottom edge as it is arranged round the body
  // (xvc/arrangement.hpp: a band drawn upright is turned a quarter clockwise,
  // its right edge to the bottom): that edge runs from the wearer's right to
  // the left as the parts round the body do. A cuff (`top`) is sewn by its
  // top edge as arranged on the arm, the one towards the shoulder.
  const auto sew_band = [&](const PieceInfo& band, std::vector<Part> parts, const std::string& name,
                            const std::string& reason, double ease_lo, double ease_hi, double tolerance,
                            bool top = false) -> std::optional<SeamSuggestion> {
    std::optional<SeamSuggestion> best;
    std::vector<std::pair<std::size_t, std::size_t>> runs;
    double longest = 0;
    double w0 = 1e300, w1 = -1e300, h0 = 1e300, h1 = -1e300;
    for (const auto& e : band.edges) longest = std::max(longest, e.length);
    for (const auto& c : band.o->shape.boundary)
      w0 = std::min(w0, c.p.x()), w1 = std::max(w1, c.p.x()), h0 = std::min(h0, c.p.y()), h1 = std::max(h1, c.p.y());
    const bool upright = h1 - h0 > w1 - w0;
    std::vector<double> bottomness;  // per run
    for (const auto& r : stretch_runs_of(band)) {
      const Edge& e = band.edges[r.edge];
      if (e.length < 0.5 * longest) continue;
      runs.emplace_back(r.k0, r.k1);
      bottomness.push_back((top ? -1.0 : 1.0) * (upright ? e.u_mid : -e.v_mean));
    }
    std::optional<double> best_bottom;
    for (std::size_t r = 0; r < runs.size(); ++r) {
      parts[0] = {band.o, runs[r].first, runs[r].second, false};
      auto s = make(name, size, parts, 1.0, reason, ease_lo, ease_hi, tolerance);
      const bool alike = best && std::abs(s.score - best->score) < 1e-6;
      if (!best || (!alike && s.score > best->score) || (alike && bottomness[r] > *best_bottom)) {
        best = s;
        best_bottom = bottomness[r];
      }
    }
    if (!best || best->score < opts.min_score) return std::nullopt;
    return best;
  };
  // A band closed into a loop: its two ends, the edges shorter than half its
  // longest, sewn to each other (`where`: centre back, or a cuff's under the
  // arm, where it is arranged to meet). In contour order one end runs up and
  // the other down, so the second is reversed: bottom corner to bottom corner.
  // A binding's ends are sewn whatever their lengths: the strip is trimmed
  // square to its neckline's length (dress::assemble_garment).
  const auto band_ends = [&](const PieceInfo& band, const std::string& name, const std::string& what,
                             const std::string& where = "at centre back") -> std::optional<SeamSuggestion> {
    double longest = 0;
    for (const auto& e : band.edges) longest = std::max(longest, e.length);
    std::vector<const Edge*> ends;
    for (const auto& e : band.edges)
      if (e.length < 0.5 * longest) ends.push_back(&e);
    if (ends.size() != 2) return std::nullopt;
    const bool binding = band.role == Role::binding;
    auto s = make(name, size, {{band.o, ends[0]->k0, ends[0]->k1, false}, {band.o, ends[1]->k0, ends[1]->k1, true}},
                  1.0, what + " closed into a loop: its two ends, " + where + (binding ? " (cut square when trimmed)" : ""),
                  binding ? -longest : 0.0, binding ? longest : 0.0, 0.02);
    if (s.score < opts.min_score) return std::nullopt;
    return s;
  };
  // 2. Waistband to the skirt waist: the band's best-fitting edge to the fronts' and
  //    backs' top edges (the back split at centre back when it has a turn point there);
  //    without a front and a back, to the waists of a leg cut twice (leggings): the right
  //    leg's from centre back to centre front, the left leg's on to centre back. In each
  //    copy's own terms (the left leg flipped) its waist runs the other way, so both
  //    hems are reversed.
  for (const auto& wb : ps) {
    if (wb.role != Role::waistband) continue;
    const PieceInfo* fr = nullptr;
    const PieceInfo* bk = nullptr;
    for (const auto& p : ps) {
      if (p.role == Role::front && !fr) fr = &p;
      if (p.role == Role::back && !bk) bk = &p;
    }
    const PieceInfo* lg = nullptr;
    for (const auto& p : ps)
      if (p.role == Role::leg && p.o->role.half == pattern::Half::none && p.o->quantity >= 2 && p.edges.size() >= 5 && !lg)
        lg = &p;
    std::vector<Part> parts{{wb.o, 0, 0, false}};
    if (fr && bk) {
      const auto top = round_top(*fr, *bk);
      if (!top) continue;
      parts.insert(parts.end(), top->begin(), top->end());
    } else if (lg) {
      const Edge& w = lg->edges[leg_ends(*lg).second];
      parts.push_back({lg->o, w.k0, w.k1, true});
      parts.push_back({lg->o, w.k0, w.k1, true});
    } else {
      continue;
    }
    const auto best = sew_band(wb, std::move(parts), "waist seam",
                               "waistband " + wb.o->piece + " to the waist of " +
                                   (fr && bk ? bk->o->piece + " and " + fr->o->piece : "both copies of " + lg->o->piece),
                               -0.01, 0.01, 0.03);
    if (!best) continue;
    found.push_back(*best);
    // On legs cut twice (leggings: no opening, pulled on), the band is a loop:
    // its two ends meet at centre back and are sewn to each other (left open,
    // the body showed through a slit there).
    if ((fr && bk) || wb.o->quantity != 1) continue;  // sewn to a front and a back: it has an opening
    if (auto s = band_ends(wb, "waistband ends", "waistband " + wb.o->piece)) found.push_back(*s);
  }

  // 3. Legs cut twice (tights, leggings: one piece per leg, no side seam): the hem is
  //    the edge at the narrow end, the inseam the two edges beside it, sewn to each
  //    other on each copy; the rises are the next edges out, the shorter one the front
  //    (a back rise is the longer): each copy's front rise to the other's, and the back
  //    rises likewise. The second copy is the flipped one (its hems are read on the
  //    mirrored pattern laid face up, docs/xvc.md), so the crotch point meets the
  //    crotch point when its rise is written reversed.
  for (const auto& lg : ps) {
    if (lg.role != Role::leg || lg.o->role.half != pattern::Half::none || lg.o->quantity < 2 || lg.edges.size() < 5)
      continue;
    const std::size_t n = lg.edges.size();
    const std::size_t hem = leg_ends(lg).first;
    const Edge &ia = lg.edges[(hem + 1) % n], &ib = lg.edges[(hem + n - 1) % n];
    const Edge &ra = lg.edges[(hem + 2) % n], &rb = lg.edges[(hem + n - 2) % n];
    for (const char* which : {"right inseam", "left inseam"}) {
      auto s = make(which, size, {{lg.o, ia.k0, ia.k1, false}, {lg.o, ib.k0, ib.k1, true}}, 1.0,
                    "inseam of " + lg.o->piece + ": the edges on either side of its hem", 0, 0, 0.02);
      if (s.score >= opts.min_score) found.push_back(s);
    }
    const Edge& front = ra.length <= rb.length ? ra : rb;
    const Edge& back = ra.length <= rb.length ? rb : ra;
    for (const auto& [which, e] : {std::pair<const char*, const Edge*>{"front rise", &front}, {"back rise", &back}}) {
      auto s = make(which, size, {{lg.o, e->k0, e->k1, false}, {lg.o, e->k0, e->k1, true}}, 1.0,
                    std::string("crotch seam of the two copies of ") + lg.o->piece + ": their " + which +
                        "s (the " + (e == &front ? "shorter" : "longer") + " rise)",
                    0, 0, 0.02);
      if (s.score >= opts.min_score) found.push_back(s);
    }
  }

  // 3b. Trouser legs cut as a front and a back half (role leg, half front/back, cut
  //     as a left and a right copy): each half's outline from its hem runs up one
  //     side to the waist (the outseam) and up the other to the crotch point, where
  //     the rise turns in to the centre front or back. Stretches from the hem's ends
  //     are followed while they run more along the leg than across it; of the two
  //     runs, the one reaching out furthest beyond its top end holds the crotch
  //     point (the stretch boundary reaching furthest out): the inseam below it,
  //     the rise above. The front half's outseam and inseam sew to the back
  //     half's (first forward, second reversed, per copy: the front and back of one
  //     leg are a copy as drawn and a flipped one), each copy's front rise to the
  //     other's and the back rises likewise. Of several front halves (a plain
  //     front, one with a pocket, one with pleats: alternatives) the one whose
  //     outseam and inseam fit the back's best.
  struct HalfLeg {
    std::size_t in0, in1, rise0, rise1, out0, out1;  // stretch ranges in contour order
    // The waist between the rise's top and the outseam's (none when they meet),
    // in contour order; from centre front or back to the side when
    // waist_from_centre, else from the side.
    std::optional<std::pair<std::size_t, std::size_t>> waist;
    bool waist_from_centre = false;
  };
  const auto half_leg = [&](const PieceInfo& p) -> std::optional<HalfLeg> {
    const auto& o = *p.o;
    const std::size_t ns = o.stretches.size();
    if (p.edges.size() < 4 || ns < 4) return std::nullopt;
    const auto& b = o.shape.boundary;
    const auto vertex = [&](std::size_t k) { return b[o.stretches[k % ns].first].p; };  // start of stretch k
    const auto along = [&](std::size_t k) {
      const Vec2 d = vertex(k + 1) - vertex(k);
      return std::abs(d.dot(p.frame.up)) >= std::abs(d.dot(p.frame.right));
    };
    const Edge& hem = p.edges[leg_ends(p).first];
    const double u_hem = 0.5 * (vertex(hem.k0).dot(p.frame.right) + vertex(hem.k1 + 1).dot(p.frame.right));
    // The run forward from the hem's end and the run backward from its start.
    std::vector<std::size_t> fwd, bwd;
    for (std::size_t k = (hem.k1 + 1) % ns; fwd.size() < ns && along(k) && k != hem.k0; k = (k + 1) % ns) fwd.push_back(k);
    for (std::size_t k = (hem.k0 + ns - 1) % ns; bwd.size() < ns && along(k) && k != hem.k1; k = (k + ns - 1) % ns)
      bwd.push_back(k);
    if (fwd.empty() || bwd.empty()) return std::nullopt;
    // How far out the run reaches beyond its top end, and at which stretch boundary.
    struct Reach {
      double beyond = 0;
      std::size_t at = 0;  // the run's stretches before it: 1..size-1
    };
    const auto reach = [&](const std::vector<std::size_t>& run, bool forward) {
      const auto boundary_after = [&](std::size_t i) { return forward ? run[i] + 1 : run[i]; };  // vertex index (stretch)
      const double top = vertex(boundary_after(run.size() - 1)).dot(p.frame.right);
      const double outward = vertex(boundary_after(0)).dot(p.frame.right) > u_hem ? 1.0 : -1.0;
      Reach r;
      for (std::size_t i = 0; i + 1 < run.size(); ++i) {
        const double d = outward * (vertex(boundary_after(i)).dot(p.frame.right) - top);
        if (d > r.beyond) r = {d, i + 1};
      }
      return r;
    };
    const Reach rf = reach(fwd, true), rb = reach(bwd, false);
    const bool crotch_fwd = rf.beyond > rb.beyond;
    const Reach& rc = crotch_fwd ? rf : rb;
    if (rc.at == 0 || rc.beyond < 0.03) return std::nullopt;  // no crotch's extension
    const auto& crotch = crotch_fwd ? fwd : bwd;
    const auto& side = crotch_fwd ? bwd : fwd;
    // Ranges in contour order: a forward run from its first stretch, a backward run
    // from its last.
    const auto range = [&](const std::vector<std::size_t>& run, std::size_t i0, std::size_t i1, bool forward) {
      return forward ? std::pair{run[i0], run[i1]} : std::pair{run[i1], run[i0]};
    };
    HalfLeg h{};
    std::tie(h.in0, h.in1) = range(crotch, 0, rc.at - 1, crotch_fwd);
    std::tie(h.rise0, h.rise1) = range(crotch, rc.at, crotch.size() - 1, crotch_fwd);
    std::tie(h.out0, h.out1) = range(side, 0, side.size() - 1, !crotch_fwd);
    // Contour order hem, inseam, rise, waist, outseam when the crotch's run goes
    // forward from the hem; hem, outseam, waist, rise, inseam otherwise.
    const std::size_t w0 = crotch_fwd ? (crotch.back() + 1) % ns : (side.back() + 1) % ns;
    const std::size_t after = crotch_fwd ? side.back() : crotch.back();  // the first stretch past the waist
    if (w0 != after) h.waist = std::pair{w0, (after + ns - 1) % ns};
    h.waist_from_centre = crotch_fwd;
    return h;
  };
  struct Trousers {
    const PieceInfo *fr, *bk;
    HalfLeg hf, hb;
  };
  std::vector<Trousers> trousers;  // the halves sewn into legs, a left and a right copy each
  for (const auto& bk : ps) {
    if (bk.role != Role::leg || bk.o->role.half != pattern::Half::back) continue;
    const auto hb = half_leg(bk);
    if (!hb) continue;
    struct Pick {
      const PieceInfo* fr;
      HalfLeg hf;
      SeamSuggestion out, in;
    };
    std::optional<Pick> best;
    for (const auto& fr : ps) {
      if (fr.role != Role::leg || fr.o->role.half != pattern::Half::front || fr.o->quantity != bk.o->quantity ||
          fr.o->role.side != bk.o->role.side)
        continue;
      const auto hf = half_leg(fr);
      if (!hf) continue;
      auto outseam = make("outseam", size, {{fr.o, hf->out0, hf->out1, false}, {bk.o, hb->out0, hb->out1, true}}, 1.0,
                      "outseam of the trouser leg's halves " + fr.o->piece + " and " + bk.o->piece, 0, 0, kSideSeamTolerance);
      auto inseam = make("inseam", size, {{fr.o, hf->in0, hf->in1, false}, {bk.o, hb->in0, hb->in1, true}}, 1.0,
                     "inseam of the trouser leg's halves " + fr.o->piece + " and " + bk.o->piece, 0, 0, kSideSeamTolerance);
      // Of fronts fitting alike, the plainest: the least cloth (pleats add some).
      const double fit = outseam.score * inseam.score, best_fit = best ? best->out.score * best->in.score : 0;
      if (!best || fit > best_fit + 1e-9 ||
          (fit > best_fit - 1e-9 && std::abs(pattern::signed_area(fr.o->shape.boundary)) < std::abs(pattern::signed_area(best->fr->o->shape.boundary))))
        best = Pick{&fr, *hf, outseam, inseam};
    }
    if (!best || best->out.score < opts.min_score || best->in.score < opts.min_score) continue;
    for (const int sigma : copies_of(*bk.o))
      for (const SeamSuggestion* s : {&best->out, &best->in}) {
        SeamSuggestion c = *s;
        c.name = std::string(sigma > 0 ? "left " : "right ") + c.name;
        found.push_back(std::move(c));
      }
    if (bk.o->quantity >= 2 && bk.o->role.side == pattern::Side::none) {
      trousers.push_back({best->fr, &bk, best->hf, *hb});
      const PieceInfo& fr = *best->fr;
      for (const auto& [which, piece, r0, r1] :
           {std::tuple{"front rise", &fr, best->hf.rise0, best->hf.rise1}, std::tuple{"back rise", &bk, hb->rise0, hb->rise1}}) {
        auto s = make(which, size, {{piece->o, r0, r1, false}, {piece->o, r0, r1, true}}, 1.0,
                      std::string("crotch seam of the two copies of ") + piece->o->piece + ": their rises", 0, 0, 0.02);
        if (s.score >= opts.min_score) found.push_back(s);
      }
    }
  }

  // 3c. A waistband in two halves on trousers cut as half legs (one band cut
  //     twice, or two bands cut once: the longer, whose run past centre front
  //     is the fly's underlap, on the wearer's right): each half sewn by its
  //     bottom edge to its side's waist, round the body in the sense a whole
  //     band runs (xvc/arrangement.hpp): the right half from centre back over
  //     the back's waist and on along the front's to centre front, the left
  //     from centre front to centre back; the darts' legs left to the darts.
  //     The halves' ends at centre back are sewn to each other; past centre
  //     front a half may run on by up to kWaistbandExtension (dress trims it
  //     there, docs/xvc.md).
  for (const auto& tr : trousers) {
    if (!tr.hf.waist || !tr.hb.waist) continue;
    std::vector<const PieceInfo*> bands;
    for (const auto& p : ps) {
      const bool sewn = std::any_of(found.begin(), found.end(), [&](const SeamSuggestion& f) {
        return std::any_of(f.hems.begin(), f.hems.end(),
                           [&](const HemRef& h) { return h.pattern == p.o->id; });
      });
      if (p.role == Role::waistband && !sewn && p.o->role.side == pattern::Side::none) bands.push_back(&p);
    }
    const PieceInfo *right = nullptr, *left = nullptr;
    const auto band_length = [](const PieceInfo* b) {
      double l = 0;
      for (const auto& e : b->edges) l = std::max(l, e.length);
      return l;
    };
    if (bands.size() == 1 && bands[0]->o->quantity >= 2) {
      right = left = bands[0];
    } else if (bands.size() == 2 && bands[0]->o->quantity == 1 && bands[1]->o->quantity == 1) {
      const bool first_longer = band_length(bands[0]) >= band_length(bands[1]);
      right = bands[first_longer ? 0 : 1];
      left = bands[first_longer ? 1 : 0];
    } else {
      continue;
    }
    // Whether the arrangement lays copy `sigma` (-1 the right leg's, +1 the
    // left's) flipped: a flipped copy's hems are read on the mirrored pattern
    // (docs/xvc.md), its contour running the other way.
    const auto flipped = [](const PieceInfo& p, int sigma) {
      const auto placed = suggest_arrangement(p.o->shape, p.o->role, true);
      const std::size_t copy = sigma < 0 ? 0 : 1;
      return copy < placed.size() && placed[copy].flip;
    };
    // A half leg's waist without its darts' legs, as parts from centre front
    // or back to the side (`outwards`) or back from the side, on the copy
    // `sigma` (-1 the right leg's, +1 the left's).
    const auto waist_parts = [&](const PieceInfo& p, const HalfLeg& h, bool outwards, int sigma) {
      const std::size_t ns = p.o->stretches.size();
      const auto& darts_here = dart_stretches[p.o];
      std::vector<std::pair<std::size_t, std::size_t>> runs;  // contour order
      for (std::size_t k = h.waist->first;; k = (k + 1) % ns) {
        if (!darts_here.count(k)) {
          if (!runs.empty() && runs.back().second == (k + ns - 1) % ns)
            runs.back().second = k;
          else
            runs.push_back({k, k});
        }
        if (k == h.waist->second) break;
      }
      const bool forward = outwards == h.waist_from_centre;  // along the pattern's contour as drawn
      if (!forward) std::reverse(runs.begin(), runs.end());
      std::vector<Part> parts;
      const bool flip = flipped(p, sigma);
      for (const auto& [k0, k1] : runs) parts.push_back({p.o, k0, k1, forward == flip});
      return parts;
    };
    std::optional<SeamSuggestion> sewn[2];
    for (const int sigma : {-1, 1}) {
      const PieceInfo& band = sigma < 0 ? *right : *left;
      const PieceInfo& first = sigma < 0 ? *tr.bk : *tr.fr;
      const PieceInfo& second = sigma < 0 ? *tr.fr : *tr.bk;
      std::vector<Part> parts{{band.o, 0, 0, false}};
      for (const auto& q : waist_parts(first, sigma < 0 ? tr.hb : tr.hf, true, sigma)) parts.push_back(q);
      for (const auto& q : waist_parts(second, sigma < 0 ? tr.hf : tr.hb, false, sigma)) parts.push_back(q);
      const std::string side = sigma < 0 ? "right" : "left";
      sewn[sigma < 0 ? 0 : 1] =
          sew_band(band, std::move(parts), side + " waist seam",
                   "half waistband " + band.o->piece + " to the waist of the " + side + " leg's halves " +
                       first.o->piece + " and " + second.o->piece + ", centre " +
                       (sigma < 0 ? "back to centre front" : "front to centre back"),
                   -0.01, kWaistbandExtension, 0.03);
    }
    if (!sewn[0] || !sewn[1]) continue;
    found.push_back(*sewn[0]);
    found.push_back(*sewn[1]);
    // Their ends at centre back: the right half's where its bottom edge starts,
    // the left half's where it ends, each the edge next to it, top to top.
    const auto end_edge = [](const PieceInfo& b, std::size_t k, bool before) -> const Edge* {
      const std::size_t ns = b.o->stretches.size();
      for (const auto& e : b.edges)
        if (before ? e.k1 == (k + ns - 1) % ns : e.k0 == (k + 1) % ns) return &e;
      return nullptr;
    };
    const Edge* er = end_edge(*right, stretch_index(*right->o, sewn[0]->hems[0].from), true);
    const Edge* el = end_edge(*left, stretch_index(*left->o, sewn[1]->hems[0].to), false);
    if (!er || !el || right == left) continue;  // one band cut twice: a seam cannot name which copy's end
    auto ends = make(
        "waistband ends", size, {{right->o, er->k0, er->k1, false}, {left->o, el->k0, el->k1, true}}, 1.0,
        "the half waistbands' ends at centre back: " + right->o->piece + "'s and " + left->o->piece + "'s", 0,
        0, 0.02);
    if (ends.score >= opts.min_score) found.push_back(std::move(ends));
  }

  // 4. Fronts to backs: off-centre edges on opposite sides (front +u is the wearer's
  //    left, like back -u), similar length, shape and height. Greedy, best first.
  struct Cand {
    SeamSuggestion s;
    std::vector<std::pair<const Outline*, std::size_t>> a, b;  // the edges each side covers
  };
  std::vector<Cand> cands;
  // Each piece's side edges, alone and joined with the next at a gentle turn.
  struct Run {
    Edge e;
    std::vector<std::size_t> idx;  // the edges it covers
  };
  const auto runs_of = [&](const PieceInfo& p) {
    std::vector<Run> r;
    const auto centre = centre_edge_of_half(*p.o, p.frame, p.edges);
    for (std::size_t i = 0; i < p.edges.size(); ++i) {
      if (p.edges[i].side == 0 || used.count({p.o, i}) || (centre && *centre == i)) continue;
      r.push_back({p.edges[i], {i}});
      const std::size_t j = (i + 1) % p.edges.size();
      if (j != i && !used.count({p.o, j}))
        if (const auto e = joined(*p.o, p.edges[i], p.edges[j], 45.0)) r.push_back({*e, {i, j}});
    }
    return r;
  };
  for (const auto& fr : ps) {
    if (fr.role != Role::front) continue;
    const auto fruns = runs_of(fr);
    for (const auto& bk : ps) {
      if (bk.role != Role::back) continue;
      const auto bruns = runs_of(bk);
      for (const auto& fru : fruns) {
        const Edge& fe = fru.e;
        for (const auto& bru : bruns) {
          const Edge& be = bru.e;
          if (be.side != -fe.side) continue;
          const Vec2 cf = fe.chord.normalized(), cb = Vec2(-be.chord.x(), be.chord.y()).normalized();
          const double dir = std::abs(cf.dot(cb));
          const double dv = fe.v_hat - be.v_hat;
          const double shape = dir * dir * std::exp(-(dv / 0.15) * (dv / 0.15));
          const bool vertical = std::abs(cf.y()) > 0.8;
          const std::string what = vertical ? "side seam" : (fe.v_hat > 0.6 ? "shoulder" : "seam");
          const std::string side = fe.side > 0 ? "left " : "right ";
          // A side seam tolerates more: a back cut longer at the hem than the front
          // (a dropped back hem: 12 mm over 470 mm on a Gerber shirt) is eased in.
          auto s = make(side + what, size, {{fr.o, fe.k0, fe.k1, false}, {bk.o, be.k0, be.k1, true}}, shape,
                        what + " of " + fr.o->piece + " and " + bk.o->piece + " on the wearer's " + side + "side",
                        0, 0, vertical ? kSideSeamTolerance : 0.02);
          if (s.score < opts.min_score) continue;
          Cand c{s, {}, {}};
          for (const auto i : fru.idx) c.a.push_back({fr.o, i});
          for (const auto j : bru.idx) c.b.push_back({bk.o, j});
          cands.push_back(std::move(c));
        }
      }
    }
  }
  std::stable_sort(cands.begin(), cands.end(), [](const Cand& x, const Cand& y) { return x.s.score > y.s.score; });
  for (const auto& c : cands) {
    const auto taken = [&](const auto& v) { return std::any_of(v.begin(), v.end(), [&](const auto& e) { return used.count(e) > 0; }); };
    if (taken(c.a) || taken(c.b)) continue;
    used.insert(c.a.begin(), c.a.end());
    used.insert(c.b.begin(), c.b.end());
    found.push_back(c.s);
    if (c.s.name.find("shoulder") != std::string::npos)
      for (const auto* side : {&c.a, &c.b}) {
        const Outline* o = side->front().first;
        for (const auto& p : ps)
          if (p.o == o) shoulders[o].push_back({p.edges[side->front().second].k0, p.edges[side->back().second].k1});
      }
  }

  // 5. Neckband (a crew neck's rib) to the neckline: the band's best-fitting
  //    long edge to the front's and the back's necklines, as a waistband to a
  //    waist: from centre back (the back split at the stretch boundary nearest
  //    it) round the front and back. A piece's neckline is the run of its
  //    outline between its two shoulder seams, across its top. A rib is cut
  //    shorter than the neckline it is stretched onto: up to a quarter
  //    shorter scores alike. Round a closed neckline (a front cut once: a
  //    pullover) its ends meet at centre back and are sewn to each other.
  // The length (m) of the parts a band is sewn round (all but parts[0], the band).
  const auto round_length = [](const std::vector<Part>& parts) {
    double length = 0;
    for (std::size_t i = 1; i < parts.size(); ++i) length += arc_range(*parts[i].o, parts[i].k0, parts[i].k1).second;
    return length;
  };
  const auto neckline = [&](const PieceInfo& p) -> std::optional<std::pair<std::size_t, std::size_t>> {
    const auto it = shoulders.find(p.o);
    if (it == shoulders.end() || it->second.size() != 2) return std::nullopt;
    const std::size_t ns = p.o->stretches.size();
    const auto [a0, a1] = it->second[0];
    const auto [b0, b1] = it->second[1];
    std::optional<std::pair<std::size_t, std::size_t>> best;
    double best_v = -1e300;
    for (const auto& [from, to] : {std::pair{(a1 + 1) % ns, (b0 + ns - 1) % ns}, std::pair{(b1 + 1) % ns, (a0 + ns - 1) % ns}}) {
      if (from == (to + 1) % ns) continue;  // the shoulders meet: no run between them
      double v = 0;
      int n = 0;
      for (std::size_t k = from;; k = (k + 1) % ns) {
        v += p.o->shape.boundary[p.o->stretches[k].first].p.dot(p.frame.up), ++n;
        if (k == to) break;
      }
      if (v / n > best_v) best_v = v / n, best = std::pair{from, to};
    }
    return best;
  };
  //    A binding (a strip cut to finish an edge) is sewn there the same way
  //    when no neckband or collar is, cut long (up to kBindingLonger) as
  //    well as short: of the bindings, the one whose length is nearest the
  //    neckline's.
  const auto band_to_neckline = [&](const PieceInfo& nb) -> std::vector<SeamSuggestion> {
    for (const auto& fr : ps) {
      if (fr.role != Role::front) continue;
      const auto nf = neckline(fr);
      for (const auto& bk : ps) {
        if (bk.role != Role::back) continue;
        const auto nbk = neckline(bk);
        if (!nf || !nbk) continue;
        std::vector<Part> parts{{nb.o, 0, 0, false}};
        const auto around = split_round(fr, *nf, bk, *nbk);
        parts.insert(parts.end(), around.begin(), around.end());
        const double length = round_length(parts);
        const bool binding = nb.role == Role::binding;
        const std::string what = binding ? "binding " : "neckband ";
        const auto best = sew_band(nb, std::move(parts), "neck seam",
                                   what + nb.o->piece + " to the neckline of " + bk.o->piece + " and " + fr.o->piece +
                                       (binding ? " (cut long: trimmed to the neckline when sewn)" : ""),
                                   -kRibShorter * length, binding ? kBindingLonger * length : 0.0, 0.03);
        if (!best) continue;
        std::vector<SeamSuggestion> sewn{*best};
        if (fr.o->quantity == 1 && fr.o->role.side == pattern::Side::none && nb.o->quantity == 1)
          if (auto e = band_ends(nb, what + "ends", what + nb.o->piece)) sewn.push_back(*e);
        return sewn;
      }
    }
    return {};
  };
  for (const auto& nb : ps) {
    if (nb.role != Role::neckband) continue;
    const auto s = band_to_neckline(nb);
    found.insert(found.end(), s.begin(), s.end());
  }
  const bool collared = std::any_of(outs.begin(), outs.end(), [&](const Outline& o) {
    return o.size == size && o.quantity > 0 &&
           (o.role.role == pattern::Role::collar || o.role.role == pattern::Role::collar_stand);
  });
  if (!collared &&
      std::none_of(found.begin(), found.end(), [](const SeamSuggestion& x) { return x.name == "neck seam"; })) {
    std::vector<SeamSuggestion> best;
    const auto closer = [](const SeamSuggestion& x, const SeamSuggestion& y) {
      if (std::abs(x.score - y.score) > 1e-6) return x.score > y.score;
      return std::abs(x.ease) < std::abs(y.ease);
    };
    for (const auto& nb : ps)
      if (nb.role == Role::binding)
        if (auto s = band_to_neckline(nb); !s.empty() && (best.empty() || closer(s[0], best[0]))) best = std::move(s);
    found.insert(found.end(), best.begin(), best.end());
  }

  // 6. A one-piece collar (a polo's: the garment has no collar stand) to the
  //    neckline, as a neckband but from centre front: the front's neckline
  //    split at its centre (a stretch boundary within 1 cm of it), round the
  //    back's, to centre front again, where its ends meet open (a polo's
  //    placket). Cut up to a quarter shorter, as a rib collar is. Not where
  //    a neckband is sewn, and only for a front cut once (a whole front).
  const bool stand = std::any_of(outs.begin(), outs.end(), [&](const Outline& o) {
    return o.size == size && o.quantity > 0 && o.role.role == pattern::Role::collar_stand;
  });
  const bool necked = std::any_of(found.begin(), found.end(), [](const SeamSuggestion& x) { return x.name == "neck seam"; });
  // The runs round a whole front's (cut once) neckline from centre front,
  // over the front's half, a back's neckline (or a yoke's, with `yoke`) and
  // the front's other half: parts[0] left for the band, per front and back.
  const auto from_centre_front = [&](const PieceInfo& band, bool yoke) {
    std::vector<std::vector<Part>> runs;
    for (const auto& fr : ps) {
      if (fr.role != Role::front || fr.o->quantity != 1 || fr.o->role.side != pattern::Side::none) continue;
      const auto nf = neckline(fr);
      if (!nf) continue;
      const auto split = centre_split(fr, *nf);
      if (!split) continue;
      const std::size_t nsf = fr.o->stretches.size();
      for (const auto& bk : ps) {
        if (bk.role != Role::back && !(yoke && bk.role == Role::yoke)) continue;
        const auto nbk = neckline(bk);
        if (!nbk) continue;
        runs.push_back({{band.o, 0, 0, false},
                       {fr.o, nf->first, *split, true},
                       {bk.o, nbk->first, nbk->second, true},
                       {fr.o, (*split + 1) % nsf, nf->second, true}});
      }
    }
    return runs;
  };
  for (const auto& co : ps) {
    if (co.role != Role::collar || co.o->quantity != 1 || stand || necked) continue;
    for (auto& parts : from_centre_front(co, false)) {
      const double length = round_length(parts);
      const std::string fr = parts[1].o->piece, bk = parts[2].o->piece;
      const auto best = sew_band(co, std::move(parts), "collar seam",
                                 "collar " + co.o->piece + " to the neckline of " + fr + " and " + bk + " from centre front",
                                 -kRibShorter * length, 0.0, 0.03);
      if (!best) continue;
      found.push_back(*best);
      break;
    }
  }

  // 6b. A shirt's collar on a stand. The stand's long edge that best fits
  //     the neckline, sewn from centre front round the back's neckline (or
  //     the yoke's: a shirt's back neckline is on its yoke, which carries
  //     the shoulders) to centre front, as a one-piece collar is; its ends
  //     reach past centre front by the button extension and overlap there
  //     (within kStandLonger of the neckline's length either way). Then the
  //     collar's long edge that best fits the stand's other long edge (its
  //     top), the collar's ends short of the stand's by the extension (up to
  //     kStandLonger shorter), its drawing's left end to the stand's left.
  //     Both hems forward: the collar turns down over the stand about that
  //     seam, folded flat on it rather than opened flat beside it, so its
  //     face is sewn to the stand's back (seams.hpp). Only for a
  //     front cut once (a whole front, closed at its centre as buttoned).
  for (const auto& st : ps) {
    if (st.role != Role::stand || st.o->quantity != 1 || necked) continue;
    std::optional<SeamSuggestion> to_neck;
    for (auto& parts : from_centre_front(st, true)) {
      const double length = round_length(parts);
      const std::string fr = parts[1].o->piece, bk = parts[2].o->piece;
      to_neck = sew_band(st, std::move(parts), "stand seam",
                         "collar stand " + st.o->piece + " to the neckline of " + fr + " and " + bk +
                             " from centre front (its ends overlap there)",
                         -kStandLonger * length, kStandLonger * length, 0.03);
      if (to_neck) break;
    }
    if (!to_neck) continue;
    found.push_back(*to_neck);
    // The stand's top: of its other long edges (at least half as long as its
    // longest), the highest, the whole of it (its longest run).
    double longest = 0;
    for (const auto& e : st.edges) longest = std::max(longest, e.length);
    const std::size_t s0 = stretch_index(*st.o, to_neck->hems[0].from), s1 = stretch_index(*st.o, to_neck->hems[0].to);
    std::optional<std::size_t> sewn_edge;
    for (const auto& r : stretch_runs_of(st))
      if (r.k0 == s0 && r.k1 == s1) sewn_edge = r.edge;
    std::optional<std::pair<std::size_t, std::size_t>> top;
    double top_v = -1e300, top_length = 0;
    for (const auto& r : stretch_runs_of(st)) {
      const Edge& e = st.edges[r.edge];
      if (e.length < 0.5 * longest || (sewn_edge && r.edge == *sewn_edge)) continue;
      if (e.v_mean > top_v + 1e-9 || (std::abs(e.v_mean - top_v) <= 1e-9 && r.length > top_length))
        top_v = e.v_mean, top_length = r.length, top = std::pair{r.k0, r.k1};
    }
    if (!top) continue;
    std::optional<SeamSuggestion> best;
    for (const auto& co : ps) {
      if (co.role != Role::collar || co.o->quantity != 1) continue;
      auto s = sew_band(co, {{co.o, 0, 0, false}, {st.o, top->first, top->second, false}}, "collar seam",
                        "collar " + co.o->piece + " to the top of its stand " + st.o->piece, -kStandLonger * top_length,
                        0.0, 0.03);
      if (s && (!best || s->score > best->score)) best = s;
    }
    if (best) found.push_back(*best);
  }

  // 7. Cuff -> sleeve hem (a rib cuff): a sleeve cut twice whose cap a seam
  //    sews to the armholes takes a cuff cut as often on each copy: the
  //    cuff's long edge (its top as arranged on the arm) that best fits the
  //    sleeve's hem (its lowest edge, between the underarm seam's ends; up
  //    to a quarter longer than the cuff, which a rib is stretched onto), the
  //    right sleeve's first (the copies' order, xvc/arrangement.hpp); each
  //    cuff's ends sewn to each other under the arm. Of several sleeves (a
  //    short and a full one), the one whose hem fits the cuff best.
  for (const auto& cf : ps) {
    if (cf.role != Role::cuff || cf.o->quantity < 2) continue;
    std::optional<SeamSuggestion> best;
    for (const auto& sl : ps) {
      if (sl.role != Role::sleeve || sl.o->role.half != pattern::Half::none || sl.o->quantity != cf.o->quantity ||
          sl.edges.size() < 3)
        continue;
      const bool capped = std::any_of(found.begin(), found.end(), [&](const SeamSuggestion& x) {
        return x.name.find("armhole") != std::string::npos && x.hems[0].pattern == sl.o->id;
      });
      if (!capped) continue;
      std::size_t hem = 0;
      for (std::size_t i = 1; i < sl.edges.size(); ++i)
        if (sl.edges[i].v_mean < sl.edges[hem].v_mean) hem = i;
      const Edge& he = sl.edges[hem];
      auto s = sew_band(cf, {{cf.o, 0, 0, false}, {sl.o, he.k0, he.k1, true}}, "right cuff",
                        "cuff " + cf.o->piece + " to the hem of " + sl.o->piece, -kRibShorter * he.length, 0.0, 0.03, true);
      if (s && (!best || s->score > best->score)) best = s;
    }
    if (!best) continue;
    for (const char* side : {"right ", "left "}) {
      SeamSuggestion s = *best;
      s.name = std::string(side) + "cuff";
      s.reason = std::string(side) + s.reason;
      found.push_back(std::move(s));
    }
    for (const char* side : {"right ", "left "})
      if (auto e = band_ends(cf, std::string(side) + "cuff ends", std::string(side) + "cuff " + cf.o->piece,
                             "under the arm"))
        found.push_back(*e);
  }
  {
    std::set<std::string> sewn;
    for (const auto& s : found)
      for (const auto& h : s.hems) sewn.insert(h.pattern);
    for (auto& d : darts)
      if (sewn.count(d.hems[0].pattern)) found.push_back(std::move(d));
  }
  std::stable_sort(found.begin(), found.end(), [](const SeamSuggestion& x, const SeamSuggestion& y) { return x.score > y.score; });
  for (auto& s : found) out.push_back(std::move(s));
}

}  // namespace

double hem_length(const Document& doc, const std::string& pattern_id, const std::string& from, const std::string& to) {
  const Node* p = doc.find(pattern_id);
  if (!p || p->tag != "PATTERN") throw Error(doc.name(), pattern_id, "no PATTERN with this id");
  const Outline o = outline(doc, *p);
  return arc_range(o, stretch_index(o, from), stretch_index(o, to)).second;
}

std::vector<SeamInfo> list_seams(const Document& doc) {
  std::vector<SeamInfo> out;
  const Node* seams = doc.container("SEAMS");
  if (!seams) return out;
  std::map<std::string, Outline> cache;
  for (const auto& s : seams->children) {
    if (s.tag != "SEAM") continue;
    SeamInfo info{std::string(s.id()), std::string(s.attribute("name")), {}};
    for (const auto& h : s.children) {
      if (h.tag != "HEM") continue;
      // The pattern holding `from`.
      const auto path = doc.path_of(h.attribute("from"));
      if (!path || path->size() < 2) continue;
      NodePath pp(path->begin(), path->end() - 1);
      const Node& pat = doc.at(pp);
      auto it = cache.find(std::string(pat.id()));
      if (it == cache.end()) it = cache.emplace(std::string(pat.id()), outline(doc, pat)).first;
      const Outline& o = it->second;
      info.hems.push_back(hem_ref(o, stretch_index(o, h.attribute("from")), stretch_index(o, h.attribute("to")),
                                  h.attribute("direction") == "reverse"));
    }
    out.push_back(std::move(info));
  }
  return out;
}

std::vector<SeamSuggestion> suggest_seams(const Document& doc, const SeamOptions& opts) {
  std::vector<Outline> outs;
  std::vector<std::string> sizes;
  for (const Node* p : doc.patterns()) {
    outs.push_back(outline(doc, *p));
    if (std::find(sizes.begin(), sizes.end(), outs.back().size) == sizes.end()) sizes.push_back(outs.back().size);
  }
  std::vector<SeamSuggestion> out;
  for (const auto& size : sizes)
    if (opts.size.empty() || size == opts.size) suggest_for_size(outs, size, opts, out);
  return out;
}

Node seam_node(const std::string& name, const std::vector<HemRef>& hems) {
  Node seam{"SEAM", {}, {}};
  if (!name.empty()) seam.set_attribute("name", name);
  seam.set_attribute("type", "plain");
  for (const auto& h : hems)
    seam.children.push_back(Node{"HEM", {{"from", h.from}, {"to", h.to}, {"direction", h.reverse ? "reverse" : "forward"}, {"type", "plain"}}, {}});
  return seam;
}

Node seam_node(const SeamSuggestion& s) { return seam_node(s.name, s.hems); }

std::vector<Node> plan_seam_nodes(const Document& doc, const std::vector<pattern::SeamPlan>& plans, const std::string& size) {
  std::vector<std::string> sizes;
  for (const Node* p : doc.patterns()) {
    const std::string sz(p->attribute("size"));
    if (std::find(sizes.begin(), sizes.end(), sz) == sizes.end()) sizes.push_back(sz);
  }
  std::vector<Node> out;
  for (const auto& sz : sizes) {
    if (!size.empty() && sz != size) continue;
    for (const auto& plan : plans) {
      if (plan.hems.size() < 2)
        throw Error(doc.name(), "seam '" + plan.name + "'", "a seam needs at least two hems");
      std::vector<HemRef> hems;
      for (const auto& h : plan.hems) {
        const Node* pat = nullptr;
        for (const Node* p : doc.patterns())
          if (p->attribute("piece") == h.piece && p->attribute("size") == sz) pat = p;
        if (!pat)
          throw Error(doc.name(), "seam '" + plan.name + "'", "no pattern of piece '" + h.piece + "' in size " + sz);
        const auto st = boundary_stretches(*pat);
        for (const int k : {h.from, h.to})
          if (k < 0 || static_cast<std::size_t>(k) >= st.size())
            throw Error(doc.name(), "seam '" + plan.name + "'", "piece '" + h.piece + "' size " + sz + " has " +
                                                                     std::to_string(st.size()) + " boundary stretches; there is no stretch " +
                                                                     std::to_string(k));
        HemRef r;
        r.pattern = std::string(pat->id());
        r.from = st[h.from].id;
        r.to = st[h.to].id;
        r.reverse = h.reverse;
        hems.push_back(r);
      }
      out.push_back(seam_node(plan.name, hems));
    }
  }
  return out;
}

namespace {
std::vector<pattern::SeamPlan> read_seam_plans(const nlohmann::json& j, const std::string& file);
}

std::vector<pattern::SeamPlan> parse_seam_plans(std::string_view text, const std::string& file) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    // parse_error, and out_of_range for a number too large for a double.
    throw Error(file, "", json_error_message(e.what(), "not valid JSON"));
  }
  try {
    return read_seam_plans(j, file);
  } catch (const nlohmann::json::exception& e) {
    // A value of the wrong type somewhere the checks below did not look.
    throw Error(file, "", json_error_message(e.what(), "not a seam file"));
  }
}

namespace {
std::vector<pattern::SeamPlan> read_seam_plans(const nlohmann::json& j, const std::string& file) {
  if (!j.is_object() || !j.contains("seams") || !j["seams"].is_array())
    throw Error(file, "", "a seam file is an object with an array \"seams\"");
  std::vector<pattern::SeamPlan> out;
  int k = 0;
  for (const auto& s : j["seams"]) {
    const std::string where = "seams[" + std::to_string(k++) + "]";
    if (!s.is_object() || !s.contains("hems") || !s["hems"].is_array() || s["hems"].size() < 2)
      throw Error(file, where, "a seam needs \"hems\": an array of at least two hems");
    pattern::SeamPlan plan;
    plan.name = s.value("name", "");
    for (const auto& h : s["hems"]) {
      if (!h.is_object() || !h.contains("piece") || !h["piece"].is_string() || !h.contains("from") ||
          !h["from"].is_number_integer())
        throw Error(file, where, "each hem needs \"piece\" (a name) and \"from\" (a stretch index)");
      pattern::HemPlan hp;
      hp.piece = h["piece"].get<std::string>();
      hp.from = h["from"].get<int>();
      hp.to = h.contains("to") ? h["to"].get<int>() : hp.from;
      const std::string dir = h.value("direction", "forward");
      if (dir != "forward" && dir != "reverse")
        throw Error(file, where, "direction must be \"forward\" or \"reverse\", not \"" + dir + "\"");
      hp.reverse = dir == "reverse";
      plan.hems.push_back(hp);
    }
    out.push_back(std::move(plan));
  }
  return out;
}
}  // namespace

std::string seam_plans_to_json(const std::vector<pattern::SeamPlan>& plans) {
  nlohmann::json seams = nlohmann::json::array();
  for (const auto& p : plans) {
    nlohmann::json hems = nlohmann::json::array();
    for (const auto& h : p.hems)
      hems.push_back({{"piece", h.piece}, {"from", h.from}, {"to", h.to}, {"direction", h.reverse ? "reverse" : "forward"}});
    seams.push_back({{"name", p.name}, {"hems", hems}});
  }
  return nlohmann::json{{"seams", seams}}.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::vector<pattern::SeamPlan> seams_as_plans(const Document& doc, const std::string& size) {
  std::vector<pattern::SeamPlan> out;
  for (const auto& s : list_seams(doc)) {
    pattern::SeamPlan plan{s.name, {}};
    bool keep = true;
    for (const auto& h : s.hems) {
      const Node* pat = doc.find(h.pattern);
      if (!size.empty() && pat->attribute("size") != size) keep = false;
      const auto st = boundary_stretches(*pat);
      auto index = [&](const std::string& id) {
        for (std::size_t k = 0; k < st.size(); ++k)
          if (st[k].id == id) return static_cast<int>(k);
        return -1;
      };
      plan.hems.push_back({std::string(pat->attribute("piece")), index(h.from), index(h.to), h.reverse});
    }
    if (keep) out.push_back(std::move(plan));
  }
  return out;
}

AddSeams::AddSeams(std::vector<Node> seams) : seams_(std::move(seams)) {}

std::string AddSeams::label() const {
  return seams_.size() == 1 ? "Add seam" : "Add " + std::to_string(seams_.size()) + " seams";
}

std::string AddSeams::apply(Editor& edit) {
  const Node* container = edit.document().container("SEAMS");
  if (!container) throw Error(edit.document().name(), "GARMENT", "the document has no SEAMS container to add seams to");
  const std::string parent(container->id());
  std::string last;
  for (const auto& s : seams_) {
    AddNode add(parent, s);
    last = add.apply(edit);
  }
  return last;
}

FlipSeam::FlipSeam(std::string seam_id) : id_(std::move(seam_id)) {}

std::string FlipSeam::label() const { return "Flip seam " + id_; }

std::string FlipSeam::apply(Editor& edit) {
  const Document& doc = edit.document();
  const NodePath path = detail::require(doc, id_, "SEAM");
  Node seam = doc.at(path);
  std::vector<std::size_t> hems;  // child indices of the HEMs, in order
  for (std::size_t i = 0; i < seam.children.size(); ++i)
    if (seam.children[i].tag == "HEM") hems.push_back(i);
  if (hems.size() < 2) throw Error(doc.name(), id_, id_ + " has fewer than two hems to flip", seam.line);
  std::vector<Node> b;
  for (std::size_t k = 1; k < hems.size(); ++k) {
    Node h = seam.children[hems[k]];
    h.set_attribute("direction", h.attribute("direction") == "reverse" ? "forward" : "reverse");
    b.push_back(std::move(h));
  }
  std::reverse(b.begin(), b.end());
  for (std::size_t k = 1; k < hems.size(); ++k) seam.children[hems[k]] = std::move(b[k - 1]);
  edit.replace(path, std::move(seam));
  return id_;
}

}  // namespace vgd::xvc
