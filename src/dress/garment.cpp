#include "vgd/dress/garment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <tuple>

#include "vgd/core/strings.hpp"
#include "vgd/pattern/contour.hpp"
#include "vgd/pattern/halves.hpp"
#include "vgd/xvc/arrangement.hpp"
#include "vgd/xvc/commands.hpp"
#include "vgd/xvc/seams.hpp"
#include "vgd/xvc/style.hpp"

namespace vgd::dress {
namespace {

using pattern::ContourPoint;
using pattern::Vec2;
using Vec3 = Eigen::Vector3d;

// A HEM resolved on its piece: boundary vertices [a, b] in contour order
// (cyclic; the edge runs from a on to b), sewn forward (a -> b) or reverse.
struct Hem {
  std::string id;
  int piece = -1;
  int a = 0, b = 0;
  bool forward = true;
  std::vector<int> vertices;  // new boundary indices from a to b in contour order (filled when resampled)
  int segments = 0;           // segments the seam gives it
};

struct Seam {
  std::string id, name;
  std::vector<int> hems;  // indices in the hem list
};

double dist(const Vec2& a, const Vec2& b) { return (a - b).norm(); }

// m: how far outside its host's face a piece sewn onto it starts (the seam
// pulls its edge in; the self-collision, 3 mm thick, keeps the rest off): a
// pocket, and a flap over a pocket's mouth, clear of the pocket too.
constexpr double kPocketGap = 0.005;
constexpr double kFlapGap = 0.010;

// Boundary vertices i, i+1, ..., j (cyclic, j reached), as points.
std::vector<Vec2> span_points(const std::vector<ContourPoint>& bd, int i, int j) {
  const int n = static_cast<int>(bd.size());
  std::vector<Vec2> out{bd[i].p};
  for (int k = i; k != j;) {
    k = (k + 1) % n;
    out.push_back(bd[k].p);
  }
  return out;
}

double polyline_length(const std::vector<Vec2>& p) {
  double L = 0;
  for (std::size_t k = 1; k < p.size(); ++k) L += dist(p[k - 1], p[k]);
  return L;
}

// `segments` equal arc-length pieces of a polyline: segments + 1 points, the
// ends copied exactly.
std::vector<Vec2> by_arc_length(const std::vector<Vec2>& p, int segments) {
  const double L = polyline_length(p);
  std::vector<Vec2> out{p.front()};
  std::size_t e = 1;
  double walked = 0.0;  // arc length at p[e - 1]
  for (int k = 1; k < segments; ++k) {
    const double s = L * k / segments;
    while (e + 1 < p.size() && walked + dist(p[e - 1], p[e]) < s) walked += dist(p[e - 1], p[e]), ++e;
    const double len = dist(p[e - 1], p[e]);
    const double t = len > 0 ? std::clamp((s - walked) / len, 0.0, 1.0) : 0.0;
    out.push_back(p[e - 1] + t * (p[e] - p[e - 1]));
  }
  out.push_back(p.back());
  return out;
}

// Cuts a strip short by `excess` m at the end where its long edge a..b
// (boundary vertices, contour order) ends, square across: b moves back along
// the edge, the vertex after it (c, across the strip's end) to where the
// square cut meets the strip's other long edge, and the vertices they pass
// are dropped. Only for a straight strip: a..b and the run after c straight
// (within 0.5 mm) and parallel (c's run back along a..b's line, within
// 0.5 mm of its own), long enough for the cut. Returns, per old vertex, its
// new index (-1 dropped), or nothing when the strip is not such a strip.
std::optional<std::vector<int>> trim_strip(std::vector<ContourPoint>& bd, int a, int b, double excess) {
  const int n = static_cast<int>(bd.size());
  const int c = (b + 1) % n;
  const Vec2 pa = bd[a].p, pb = bd[b].p;
  const double len = dist(pa, pb);
  if (!(excess > 0) || len <= excess + 1e-3 || c == a) return std::nullopt;
  const Vec2 u = (pb - pa) / len;
  const auto off_line = [&](const Vec2& p, const Vec2& o) { return std::abs((p - o).x() * u.y() - (p - o).y() * u.x()); };
  for (int v = a; v != b; v = (v + 1) % n)
    if (off_line(bd[v].p, pa) > 5e-4) return std::nullopt;
  // The new end: b moved back by the excess, and across from it on c's line.
  const Vec2 nb = pb - excess * u;
  const Vec2 nc = nb + ((bd[c].p - pb) - (bd[c].p - pb).dot(u) * u);
  const double shift = (bd[c].p - nc).dot(u);  // how far c moves back along the other edge
  if (!(shift > 0)) return std::nullopt;
  std::vector<int> passed;  // vertices after c the new end passes
  double reach = 0;
  for (int v = (c + 1) % n; v != a && reach <= shift; v = (v + 1) % n) {
    const Vec2 d = bd[v].p - bd[c].p;
    if (off_line(bd[v].p, bd[c].p) > 5e-4 || d.dot(-u) <= 0) return std::nullopt;
    reach = d.dot(-u);
    if (reach <= shift + 1e-9) passed.push_back(v);
  }
  if (reach <= shift) return std::nullopt;
  std::vector<bool> drop(n, false);
  for (int v = (a + 1) % n; v != b; v = (v + 1) % n)
    if ((bd[v].p - pa).dot(u) >= len - excess - 1e-9) drop[v] = true;
  for (const int v : passed) drop[v] = true;
  bd[b].p = nb;
  bd[c].p = nc;
  std::vector<int> index(n, -1);
  std::vector<ContourPoint> kept;
  for (int v = 0; v < n; ++v)
    if (!drop[v]) index[v] = static_cast<int>(kept.size()), kept.push_back(bd[v]);
  bd = std::move(kept);
  return index;
}

// The same at the end where the edge a..b starts: a moves on along the edge.
std::optional<std::vector<int>> trim_strip_start(std::vector<ContourPoint>& bd, int a, int b, double excess) {
  const int n = static_cast<int>(bd.size());
  std::vector<ContourPoint> rev(bd.rbegin(), bd.rend());
  const auto index = trim_strip(rev, n - 1 - b, n - 1 - a, excess);
  if (!index) return std::nullopt;
  const int m = static_cast<int>(rev.size());
  std::reverse(rev.begin(), rev.end());
  std::vector<int> out(n);
  for (int v = 0; v < n; ++v) {
    const int r = (*index)[n - 1 - v];
    out[v] = r < 0 ? -1 : m - 1 - r;
  }
  bd = std::move(rev);
  return out;
}

// Do segments pq and rs cross (touching at an end counts)?
bool segments_meet(const Vec2& p, const Vec2& q, const Vec2& r, const Vec2& s) {
  const auto side = [](const Vec2& a, const Vec2& b, const Vec2& c) {
    const double d = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    return d > 0 ? 1 : d < 0 ? -1 : 0;
  };
  return side(p, q, r) * side(p, q, s) <= 0 && side(r, s, p) * side(r, s, q) <= 0;
}

// An ear: the unsewn outline e..s (contour order, e ≠ s) of a piece whose
// ends the garment's seams sew to one point, sticking out of the piece
// beyond the chord es: at least kEarBulge times longer than the chord, with
// the chord inside the outline, the cloth beyond it no more than
// kEarShare of the piece. It is an allowance's corner (a sleeve's back half
// with its cap's and over-arm's allowances run on to where they meet):
// sewn on the cut lines both ends of it go to one point and the cloth
// between stands off the garment as a horn. Returns the cloth beyond the
// chord (m²), 0 when e..s is no ear.
constexpr double kEarBulge = 1.5;
constexpr double kEarShare = 0.1;
double ear_area(const std::vector<ContourPoint>& bd, int e, int s) {
  const int n = static_cast<int>(bd.size());
  const std::vector<Vec2> run = span_points(bd, e, s);
  if (run.size() < 3) return 0.0;
  const double chord = dist(bd[e].p, bd[s].p);
  if (!(chord > 0) || polyline_length(run) < kEarBulge * chord) return 0.0;
  const double whole = pattern::signed_area(bd);
  const double ear = pattern::signed_area(run);  // closed by the chord
  // Cloth beyond the chord (the ear turns the way the outline does), a small share of the piece.
  if (!(ear * whole > 0) || std::abs(ear) > kEarShare * std::abs(whole)) return 0.0;
  // The chord inside: no edge of the rest of the outline meets it.
  for (int v = s; v != e; v = (v + 1) % n) {
    const int w = (v + 1) % n;
    if (v == s || w == e) continue;  // the edges at the chord's ends
    if (segments_meet(bd[e].p, bd[s].p, bd[v].p, bd[w].p)) return 0.0;
  }
  return std::abs(ear);
}

// A piece's outline renumbered (index: per old vertex its new one, -1
// dropped): its hems' ends and its notches follow.
void renumber(std::vector<Hem>& hems, int piece, GarmentPiece& gp, const std::vector<int>& index) {
  for (auto& o : hems)
    if (o.piece == piece) o.a = index[o.a], o.b = index[o.b];
  for (auto& nt : gp.piece.notches)
    nt.boundary_index = nt.boundary_index >= 0 && nt.boundary_index < static_cast<int>(index.size())
                            ? index[nt.boundary_index]
                            : -1;
}

// Corners of an outline: turn points and vertices turning by more than `deg`.
std::vector<bool> corners(const std::vector<ContourPoint>& bd, double deg) {
  const int n = static_cast<int>(bd.size());
  std::vector<bool> c(n, false);
  const double cos_limit = std::cos(deg * std::numbers::pi / 180.0);
  for (int i = 0; i < n; ++i) {
    if (bd[i].kind == pattern::PointKind::turn) {
      c[i] = true;
      continue;
    }
    const Vec2 d0 = bd[i].p - bd[(i + n - 1) % n].p, d1 = bd[(i + 1) % n].p - bd[i].p;
    const double l = d0.norm() * d1.norm();
    if (l > 0 && d0.dot(d1) / l < cos_limit) c[i] = true;
  }
  return c;
}

// Is boundary vertex v strictly inside the cyclic range (a, b)?
bool strictly_inside(int v, int a, int b, int n) {
  const int dv = (v - a + n) % n, db = (b - a + n) % n;
  return dv > 0 && dv < db;
}

// The size of each SEAM's patterns (that of its first HEM's PATTERN), in
// document order.
std::vector<std::string> seam_sizes(const xvc::Document& doc) {
  std::vector<std::string> out;
  for (const auto& s : xvc::list_seams(doc))
    if (!s.hems.empty())
      if (const auto* p = doc.find(s.hems.front().pattern)) out.emplace_back(p->attribute("size"));
  return out;
}

// A document whose SEAMs are all of other sizes than `size` gets those of
// the size that has them (the sample size first) sewn at the same stretches
// of `size`'s patterns: graded sizes correspond stretch for stretch (the DXF
// importer carries the sample's turn points to them). Said as a warning;
// an error when they do not fit.
std::optional<xvc::Document> with_seams_of_another_size(const xvc::Document& doc, const std::string& size,
                                                        const std::string& sample, Diagnostics& diag) {
  const auto sizes = seam_sizes(doc);
  if (sizes.empty() || std::find(sizes.begin(), sizes.end(), size) != sizes.end()) return std::nullopt;
  const std::string from = std::find(sizes.begin(), sizes.end(), sample) != sizes.end() ? sample : sizes.front();
  const auto plans = xvc::seams_as_plans(doc, from);
  std::vector<xvc::Node> nodes;
  try {
    // Stretch k must be the same stretch in both sizes: as many of them.
    auto stretches = [&](const std::string& piece, const std::string& at) -> int {
      for (const auto* p : doc.patterns())
        if (p->attribute("piece") == piece && p->attribute("size") == at)
          return static_cast<int>(xvc::boundary_stretches(*p).size());
      return -1;
    };
    for (const auto& plan : plans)
      for (const auto& h : plan.hems)
        if (const int a = stretches(h.piece, from), b = stretches(h.piece, size); b >= 0 && a != b)
          throw Error(doc.name(), h.piece,
                      "piece " + h.piece + " has " + std::to_string(b) + " boundary stretches in size " + size +
                          " and " + std::to_string(a) + " in size " + from);
    nodes = xvc::plan_seam_nodes(doc, plans, size);
  } catch (const Error& e) {
    throw Error(doc.name(), "size " + size,
                "the document has no SEAM for size " + size + ", and the " + std::to_string(plans.size()) +
                    " of size " + from + " do not fit its patterns (" + e.diagnostic().message +
                    "); suggest seams for it with 'vgd seams suggest --apply --size " + size + "'");
  }
  xvc::Document out = doc;
  xvc::execute(out, *std::make_unique<xvc::AddSeams>(std::move(nodes)));
  diag.warn(doc.name(), "size " + size,
            "no SEAM sews this size: the " + std::to_string(plans.size()) + " seams of size " +
                from + " are sewn at the same stretches of its patterns");
  return out;
}

}  // namespace

Garment assemble_garment(const xvc::Document& document, const AssemblyOptions& options, Diagnostics& diag) {
  const std::string file = document.name();
  Garment g;
  g.name = std::string(document.root().attribute("name"));

  // The size.
  std::string sample;
  if (const auto* grads = document.container("GRADATIONS")) sample = std::string(grads->attribute("sample_size"));
  const auto all_patterns = document.patterns();
  g.size = !options.size.empty() ? options.size : sample;
  if (g.size.empty() && !all_patterns.empty()) g.size = std::string(all_patterns.front()->attribute("size"));
  const std::optional<xvc::Document> carried = with_seams_of_another_size(document, g.size, sample, diag);
  const xvc::Document& doc = carried ? *carried : document;
  const auto patterns = doc.patterns();

  // Meshing settings.
  double spacing = options.spacing;
  if (spacing <= 0) spacing = xvc::get_parameter(doc, "mesh.spacing").value_or(0.015);
  double min_angle = options.min_angle;
  if (min_angle <= 0) min_angle = xvc::get_parameter(doc, "mesh.min_angle").value_or(25.0);
  const double turn_angle = xvc::get_parameter(doc, "mesh.turn_angle").value_or(30.0);

  // The pieces of the size (and of the list, when one is given; without a
  // list, those not marked drape="false"): one per arrangement of the
  // PATTERN (a sleeve cut twice is placed twice), at least one.
  std::vector<std::vector<xvc::Stretch>> stretches;  // per pattern kept
  std::vector<std::vector<int>> copies;              // per pattern kept: its pieces
  std::set<std::string> left_out;                    // stretches of this size's patterns left out
  std::vector<bool> folded;                          // per pattern kept: cut double, folded lengthwise
  std::vector<const xvc::Node*> kept_nodes;          // per pattern kept
  for (const auto* p : patterns) {
    if (std::string(p->attribute("size")) != g.size) continue;
    GarmentPiece gp;
    gp.pattern_id = std::string(p->id());
    gp.piece = xvc::to_piece(doc, gp.pattern_id);
    gp.name = gp.piece.name.empty() ? gp.piece.block : gp.piece.name;
    const bool listed_out = !options.pieces.empty()
                                ? std::find_if(options.pieces.begin(), options.pieces.end(), [&](const std::string& s) {
                                    return s == gp.piece.name || s == gp.piece.block || s == gp.pattern_id;
                                  }) == options.pieces.end()
                                : xvc::drape_attribute(*p) == false;
    if (listed_out) {
      for (const auto& st : xvc::boundary_stretches(*p)) left_out.insert(st.id);
      continue;
    }
    stretches.push_back(xvc::boundary_stretches(*p));
    folded.push_back(xvc::folded_attribute(*p).value_or(false));
    kept_nodes.push_back(p);
    copies.emplace_back();
    const auto listed = options.copies.find(gp.pattern_id);
    const int n = std::max<int>(1, listed != options.copies.end() ? listed->second
                                                                  : static_cast<int>(xvc::arrangements_of(*p).size()));
    for (int k = 0; k < n; ++k) {
      copies.back().push_back(static_cast<int>(g.pieces.size()));
      GarmentPiece c = gp;
      c.copy = k;
      g.pieces.push_back(std::move(c));
    }
  }
  if (g.pieces.empty()) throw Error(file, "GRADATIONS", "no pattern of size '" + g.size + "' to assemble");

  // Stretch id -> (pattern kept, stretch index).
  std::map<std::string, std::pair<int, int>> stretch_at;
  for (int pi = 0; pi < static_cast<int>(stretches.size()); ++pi)
    for (int s = 0; s < static_cast<int>(stretches[pi].size()); ++s) stretch_at[stretches[pi][s].id] = {pi, s};

  // The SEAMs of this size, their HEMs by pattern kept and stretch range.
  struct RawHem {
    std::string id;
    int pat = -1, from = 0, to = 0;  // pattern kept; stretch indices
    bool forward = true;
  };
  struct RawSeam {
    std::string id, name;
    std::vector<RawHem> hems;
  };
  std::vector<RawSeam> raw;
  if (const auto* container = doc.container("SEAMS")) {
    for (const auto& s : container->children) {
      if (s.tag != "SEAM") continue;
      RawSeam seam{std::string(s.id()), std::string(s.attribute("name")), {}};
      bool kept = true, other_size = false;
      for (const auto& h : s.children) {
        if (h.tag != "HEM") continue;
        const std::string from(h.attribute("from")), to(h.attribute("to"));
        const auto f = stretch_at.find(from), t = stretch_at.find(to);
        if (f == stretch_at.end() || t == stretch_at.end()) {
          kept = false;  // a pattern of another size, or one left out
          other_size = !left_out.count(from) && !left_out.count(to);
          break;
        }
        if (f->second.first != t->second.first)
          throw Error(file, std::string(h.id()), "from and to name stretches of different patterns");
        seam.hems.push_back({std::string(h.id()), f->second.first, f->second.second, t->second.second,
                             h.attribute("direction") != "reverse"});
      }
      if (other_size) continue;  // the seam of another size
      if (!kept || seam.hems.size() < 2) {
        diag.warn(file, seam.id, "seam '" + seam.name + "' is not sewn: one of its pieces is left out");
        continue;
      }
      raw.push_back(std::move(seam));
    }
  }

  // A piece cut double and folded lengthwise (a rib) hangs as the half beside
  // the longest edge a seam sews (both raw edges are sewn there together), in
  // two layers: pattern::fold_lengthwise about that edge's chord.
  for (int pi = 0; pi < static_cast<int>(stretches.size()); ++pi) {
    if (!folded[pi]) continue;
    const auto& st = stretches[pi];
    const auto& bd = g.pieces[copies[pi][0]].piece.boundary;
    const int n = static_cast<int>(bd.size());
    double longest = 0;
    std::pair<int, int> edge{-1, -1};
    for (const auto& seam : raw)
      for (const auto& h : seam.hems) {
        if (h.pat != pi || n < 3) continue;
        const int a = static_cast<int>(st[h.from].first), b = static_cast<int>(st[(h.to + 1) % st.size()].first);
        const double len = polyline_length(span_points(bd, a, b));
        if (a != b && len > longest) longest = len, edge = {a, b};
      }
    const std::string& name = g.pieces[copies[pi][0]].name;
    if (edge.first < 0)
      throw Error(file, g.pieces[copies[pi][0]].pattern_id,
                  "piece " + name + " is folded (folded=\"true\"), but no seam sews it: the fold is about the edge sewn");
    const Vec2 a = bd[edge.first].p, b = bd[edge.second].p;
    if (!((b - a).norm() > 1e-6))
      throw Error(file, g.pieces[copies[pi][0]].pattern_id,
                  "piece " + name + " is folded (folded=\"true\"), but the edge its seam sews ends where it "
                  "starts: there is no line to fold about");
    for (const int c : copies[pi]) {
      pattern::fold_lengthwise(g.pieces[c].piece, a, b - a);
      g.pieces[c].layers = 2;
    }
  }

  // Which copy of a piece cut more than once each HEM sews: a hem sewn again
  // goes to the pattern's next copy, in document order; with `place`, the
  // seams that sew the same stretches of such a piece to pieces cut once (a
  // sleeve cap to each armhole) take the copies whose placed hems lie
  // nearest their partners: a left armhole gets the left sleeve whatever
  // the order of the SEAMs.
  std::vector<std::vector<int>> copy_of(raw.size());  // per seam, per hem
  {
    std::map<std::tuple<int, int, int>, int> uses;  // (pattern, from, to) -> uses so far
    for (std::size_t si = 0; si < raw.size(); ++si)
      for (const auto& h : raw[si].hems) copy_of[si].push_back(uses[{h.pat, h.from, h.to}]++);
    for (std::size_t si = 0; si < raw.size(); ++si)
      for (std::size_t hi = 0; hi < raw[si].hems.size(); ++hi) {
        const RawHem& h = raw[si].hems[hi];
        if (copy_of[si][hi] >= static_cast<int>(copies[h.pat].size()))
          throw Error(file, h.id,
                      "sews stretches " + stretches[h.pat][h.from].id + ".." + stretches[h.pat][h.to].id + " of " +
                          g.pieces[copies[h.pat][0]].name + " " + std::to_string(copy_of[si][hi] + 1) +
                          " times, but the piece is placed " + std::to_string(copies[h.pat].size()) +
                          " time(s); give it one arrangement per copy (vgd place)");
      }
    if (options.place) {
      // Each copy's boundary placed round the body, once, its edges cut into
      // pieces of at most kDense (a band's straight edge wrapped half round
      // the body is a curve, not its chord); dense[pat][v]: where boundary
      // vertex v is among the points placed.
      constexpr double kDense = 0.01;  // m
      std::map<std::pair<int, int>, std::vector<Vec3>> placed;
      std::map<int, std::vector<int>> dense;
      auto boundary_3d = [&](int pat, int copy) -> const std::vector<Vec3>& {
        auto it = placed.find({pat, copy});
        if (it != placed.end()) return it->second;
        const GarmentPiece& gp = g.pieces[copies[pat][copy]];
        const auto& bd = gp.piece.boundary;
        const int n = static_cast<int>(bd.size());
        std::vector<Vec2> pts;
        std::vector<int>& at = dense[pat];
        at.assign(n, 0);
        for (int v = 0; v < n; ++v) {
          at[v] = static_cast<int>(pts.size());
          const Vec2 p = bd[v].p, q = bd[(v + 1) % n].p;
          const int parts = std::max(1, static_cast<int>(std::ceil(dist(p, q) / kDense)));
          for (int k = 0; k < parts; ++k) pts.push_back(p + (q - p) * (static_cast<double>(k) / parts));
        }
        std::vector<Vec3> out = options.place(gp.pattern_id, copy, pts);
        if (out.size() != pts.size()) out.clear();
        return placed.emplace(std::pair{pat, copy}, std::move(out)).first->second;
      };
      // The middle of a hem, placed: the centroid of its placed outline by
      // length; nullopt when unplaced.
      auto middle = [&](const RawHem& h, int copy) -> std::optional<Vec3> {
        const auto& pts = boundary_3d(h.pat, copy);
        if (pts.empty()) return std::nullopt;
        const auto& st = stretches[h.pat];
        const int n = static_cast<int>(pts.size());
        const int a = dense[h.pat][st[h.from].first], b = dense[h.pat][st[(h.to + 1) % st.size()].first];
        Vec3 sum = Vec3::Zero();
        double length = 0;
        for (int v = a; v != b; v = (v + 1) % n) {
          const Vec3 &p = pts[v], &q = pts[(v + 1) % n];
          const double l = (q - p).norm();
          sum += 0.5 * l * (p + q);
          length += l;
        }
        if (!(length > 0)) return pts[a];
        return sum / length;
      };
      std::map<std::tuple<int, int, int>, std::vector<std::pair<int, int>>> users;  // key -> (seam, hem)
      for (std::size_t si = 0; si < raw.size(); ++si)
        for (std::size_t hi = 0; hi < raw[si].hems.size(); ++hi) {
          const RawHem& h = raw[si].hems[hi];
          if (copies[h.pat].size() > 1) users[{h.pat, h.from, h.to}].push_back({static_cast<int>(si), static_cast<int>(hi)});
        }
      for (const auto& [key, list] : users) {
        const int pat = std::get<0>(key);
        const int nc = static_cast<int>(copies[pat].size());
        if (list.size() < 2 || static_cast<int>(list.size()) > nc || nc > 6) continue;
        // cost[u][c]: summed distance from the hem on copy c to its seam's hems on pieces cut once.
        std::vector<std::vector<double>> cost(list.size(), std::vector<double>(nc, 0.0));
        bool usable = true;
        for (std::size_t u = 0; u < list.size() && usable; ++u) {
          const RawSeam& seam = raw[list[u].first];
          int partners = 0;
          for (int c = 0; c < nc && usable; ++c) {
            const auto mine = middle(seam.hems[list[u].second], c);
            if (!mine) usable = false;
            for (const auto& other : seam.hems) {
              if (other.pat == pat || copies[other.pat].size() != 1 || !usable) continue;
              const auto theirs = middle(other, 0);
              if (!theirs) {
                usable = false;
                break;
              }
              cost[u][c] += (*mine - *theirs).norm();
              partners += c == 0;
            }
          }
          usable = usable && partners > 0;
        }
        if (!usable) continue;
        // The cheapest assignment of distinct copies (nc ≤ 6: every permutation).
        std::vector<int> perm(nc), best;
        for (int c = 0; c < nc; ++c) perm[c] = c;
        double best_cost = std::numeric_limits<double>::infinity();
        do {
          double sum = 0;
          for (std::size_t u = 0; u < list.size(); ++u) sum += cost[u][perm[u]];
          if (sum < best_cost - 1e-12) best_cost = sum, best = perm;
        } while (std::next_permutation(perm.begin(), perm.end()));
        for (std::size_t u = 0; u < list.size(); ++u) copy_of[list[u].first][list[u].second] = best[u];
      }
    }
  }

  // Seams and their hems, resolved to boundary vertex ranges.
  std::vector<Hem> hems;
  std::vector<Seam> seams;
  for (std::size_t si = 0; si < raw.size(); ++si) {
    Seam seam{raw[si].id, raw[si].name, {}};
    for (std::size_t hi = 0; hi < raw[si].hems.size(); ++hi) {
      const RawHem& r = raw[si].hems[hi];
      const auto& st = stretches[r.pat];
      const int pi = copies[r.pat][copy_of[si][hi]];
      const int n = static_cast<int>(g.pieces[pi].piece.boundary.size());
      Hem hem;
      hem.id = r.id;
      hem.piece = pi;
      hem.a = static_cast<int>(st[r.from].first);
      hem.b = static_cast<int>(st[(r.to + 1) % st.size()].first);
      const auto fl = options.flipped.find(g.pieces[pi].pattern_id);
      const bool flipped = fl != options.flipped.end() && copy_of[si][hi] < static_cast<int>(fl->second.size()) &&
                           fl->second[copy_of[si][hi]];
      hem.forward = r.forward != flipped;
      if (hem.a == hem.b || n < 3)
        throw Error(file, hem.id, "the hem covers the whole outline of " + g.pieces[pi].name + "; a seam needs two ends");
      seam.hems.push_back(static_cast<int>(hems.size()));
      hems.push_back(std::move(hem));
    }
    seams.push_back(std::move(seam));
  }

  if (seams.empty() && g.pieces.size() > 1)
    diag.warn(file, "size " + g.size,
              "no SEAM sews the " + std::to_string(g.pieces.size()) +
                  " pieces of this size: each drapes as a loose piece of cloth (suggest seams with "
                  "'vgd seams suggest --apply')");

  // Hems on one piece must not overlap.
  for (std::size_t i = 0; i < hems.size(); ++i)
    for (std::size_t j = i + 1; j < hems.size(); ++j) {
      if (hems[i].piece != hems[j].piece) continue;
      const int n = static_cast<int>(g.pieces[hems[i].piece].piece.boundary.size());
      const auto overlap = [n](const Hem& x, const Hem& y) {
        return strictly_inside(y.a, x.a, x.b, n) || strictly_inside(y.b, x.a, x.b, n) ||
               (x.a == y.a && x.b == y.b);
      };
      if (overlap(hems[i], hems[j]) || overlap(hems[j], hems[i]))
        throw Error(file, hems[j].id, "hem overlaps hem " + hems[i].id + " on " + g.pieces[hems[i].piece].name +
                                          "; a stretch of outline can be sewn once");
    }

  // A binding cut long is trimmed to the opening it binds (strips are cut
  // long and cut off where the binding meets itself): where a seam's hem on
  // a binding is longer than its other hems together (on other pieces: not
  // the seam that sews its ends to each other), the strip is cut short,
  // square, at the end where that hem ends (its ends, when a seam sews them
  // to each other, then meet square). So is a half waistband of trousers at
  // centre front, where it runs on past the waist as the fly's overlap or
  // underlap: at the end of its hem sewn next to a front half (a waist seam
  // starts or ends there, xvc/seams.hpp); left on, the two runs would start
  // in one place, crossed.
  const auto front_half = [&](const Hem& o) {
    const auto* n = doc.find(g.pieces[o.piece].pattern_id);
    if (!n) return false;
    const auto r = xvc::piece_role(doc, *n);
    return r.role == pattern::Role::leg && r.half == pattern::Half::front;
  };
  for (const auto& s : seams) {
    if (s.hems.size() < 2) continue;
    Hem& h = hems[s.hems[0]];
    GarmentPiece& gp = g.pieces[h.piece];
    const auto* node = doc.find(gp.pattern_id);
    if (!node) continue;
    const auto role = xvc::piece_role(doc, *node).role;
    // For a half waistband: +1 cut where its hem ends, -1 where it starts, 0 not one.
    int front_end = 0;
    if (role == pattern::Role::waistband) {
      const bool at_first = front_half(hems[s.hems[1]]), at_last = front_half(hems[s.hems.back()]);
      if (at_first != at_last) front_end = (at_last == h.forward) ? 1 : -1;
    }
    if (role != pattern::Role::binding && front_end == 0) continue;
    double rest = 0;
    bool ends = false;
    for (std::size_t k = 1; k < s.hems.size(); ++k) {
      const Hem& o = hems[s.hems[k]];
      ends = ends || o.piece == h.piece;
      rest += polyline_length(span_points(g.pieces[o.piece].piece.boundary, o.a, o.b));
    }
    if (ends) continue;
    auto& bd = gp.piece.boundary;
    const double mine = polyline_length(span_points(bd, h.a, h.b));
    if (mine <= rest + xvc::kSewingSlack) continue;
    auto trimmed = bd;
    const auto index = front_end < 0 ? trim_strip_start(trimmed, h.a, h.b, mine - rest)
                                     : trim_strip(trimmed, h.a, h.b, mine - rest);
    bool fits = index.has_value();
    for (int k = 0; fits && k < static_cast<int>(hems.size()); ++k)
      fits = hems[k].piece != h.piece || ((*index)[hems[k].a] >= 0 && (*index)[hems[k].b] >= 0);
    const std::string what = front_end != 0 ? "half waistband " : "binding ";
    if (!fits) {
      diag.warn(file, gp.pattern_id,
                what + gp.name + " is " + format_fixed(100 * (mine - rest), 1) + " cm longer than the " +
                    (front_end != 0 ? "waist it is sewn to" : "opening it binds") +
                    " and is not a straight strip vgd can trim: it is eased in");
      continue;
    }
    renumber(hems, h.piece, gp, *index);
    bd = std::move(trimmed);
    diag.info(
        file, gp.pattern_id,
        what + gp.name + " trimmed by " + format_fixed(100 * (mine - rest), 1) + " cm to the " +
            format_fixed(100 * rest, 1) +
            (front_end != 0
                 ? " cm of waist it is sewn to, at centre front (the fly's overlap or underlap left off)"
                 : " cm it binds"));
  }

  // Ears cut off (ear_area). Where each hem's ends go is found from the
  // seams: a seam sews its first hem's first vertex to its second hem's
  // first and its first hem's last to its last hem's last (distance 0), and
  // an unsewn run of outline under kEarGap between two hems of a piece
  // (a notch's allowance at a shoulder point) keeps its ends that close. On
  // each piece the unsewn outline between two hems whose ends the garment
  // brings within half its chord of each other is cut along that chord when
  // it is an ear.
  {
    constexpr double kEarGap = 0.025;  // m
    using End = std::pair<int, int>;   // (piece, boundary vertex)
    std::map<End, std::vector<std::pair<End, double>>> links;
    const auto link = [&](End x, End y, double d) {
      links[x].push_back({y, d});
      links[y].push_back({x, d});
    };
    const auto first = [](const Hem& h) { return End{h.piece, h.forward ? h.a : h.b}; };
    const auto last = [](const Hem& h) { return End{h.piece, h.forward ? h.b : h.a}; };
    for (const auto& s : seams) {
      if (s.hems.size() < 2) continue;
      link(first(hems[s.hems[0]]), first(hems[s.hems[1]]), 0.0);
      link(last(hems[s.hems[0]]), last(hems[s.hems.back()]), 0.0);
    }
    // Per piece, its hems in contour order and the runs between them.
    const auto hems_of = [&](int pi) {
      std::vector<int> mine;
      for (int h = 0; h < static_cast<int>(hems.size()); ++h)
        if (hems[h].piece == pi) mine.push_back(h);
      std::sort(mine.begin(), mine.end(), [&](int x, int y) { return hems[x].a < hems[y].a; });
      return mine;
    };
    for (int pi = 0; pi < static_cast<int>(g.pieces.size()); ++pi) {
      const auto mine = hems_of(pi);
      const auto& bd = g.pieces[pi].piece.boundary;
      for (std::size_t k = 0; k < mine.size() && mine.size() > 1; ++k) {
        const int e = hems[mine[k]].b, s = hems[mine[(k + 1) % mine.size()]].a;
        if (e == s) continue;
        if (const double run = polyline_length(span_points(bd, e, s)); run < kEarGap) link({pi, e}, {pi, s}, run);
      }
    }
    // How far apart the garment holds two ends at most (shortest path; infinity when not linked).
    const auto apart = [&](End from, End to) {
      std::map<End, double> best{{from, 0.0}};
      std::set<std::pair<double, End>> open{{0.0, from}};
      while (!open.empty()) {
        const auto [d, at] = *open.begin();
        open.erase(open.begin());
        if (at == to) return d;
        const auto it = links.find(at);
        if (it == links.end()) continue;
        for (const auto& [next, w] : it->second)
          if (const auto b = best.find(next); b == best.end() || d + w < b->second) {
            if (b != best.end()) open.erase({b->second, next});
            best[next] = d + w;
            open.insert({d + w, next});
          }
      }
      return std::numeric_limits<double>::infinity();
    };
    const auto seam_of = [&](int h) -> std::string {
      for (const auto& s : seams)
        if (std::find(s.hems.begin(), s.hems.end(), h) != s.hems.end()) return s.name.empty() ? s.id : s.name;
      return hems[h].id;
    };
    for (int pi = 0; pi < static_cast<int>(g.pieces.size()); ++pi) {
      const auto mine = hems_of(pi);
      GarmentPiece& gp = g.pieces[pi];
      auto& bd = gp.piece.boundary;
      const int n = static_cast<int>(bd.size());
      std::vector<bool> cut(n, false);
      bool any = false;
      for (std::size_t k = 0; k < mine.size() && mine.size() > 1; ++k) {
        const int h = mine[k], next = mine[(k + 1) % mine.size()];
        const int e = hems[h].b, s = hems[next].a;
        if (e == s) continue;
        const double area = ear_area(bd, e, s);
        const double run = polyline_length(span_points(bd, e, s)), chord = dist(bd[e].p, bd[s].p);
        if (area <= 0 || run < kEarGap) continue;
        const double d = apart({pi, e}, {pi, s});
        if (!(d <= 0.5 * chord)) continue;
        for (int v = (e + 1) % n; v != s; v = (v + 1) % n) cut[v] = true;
        any = true;
        diag.info(file, gp.pattern_id,
                  gp.name + ": the " + format_fixed(100 * run, 1) + " cm of outline between seams '" + seam_of(h) +
                      "' and '" + seam_of(next) + "', whose ends are sewn " +
                      (d > 0 ? "within " + format_fixed(100 * d, 1) + " cm of each other" : std::string("to one point")) +
                      ", cut off along its " + format_fixed(100 * chord, 1) + " cm chord (" +
                      format_fixed(1e4 * area, 1) + " cm² of an allowance's corner, which would stand off the garment)");
      }
      if (!any) continue;
      std::vector<int> index(n, -1);
      std::vector<ContourPoint> kept;
      for (int v = 0; v < n; ++v)
        if (!cut[v]) index[v] = static_cast<int>(kept.size()), kept.push_back(bd[v]);
      renumber(hems, pi, gp, index);
      bd = std::move(kept);
    }
  }

  // Pieces sewn onto another's face (xvc::FacePlacement): each gets a hem
  // along its outline but its mouth (in no SEAM), sewn to a line of its
  // host where that outline lies.
  struct FaceSeam {
    int hem = -1;   // in `hems`
    int host = -1;  // the host piece
    int line = -1;  // its line on the host (index in lines[host])
    std::string id, name;
  };
  std::vector<FaceSeam> face_seams;
  for (std::size_t k = 0; k < kept_nodes.size(); ++k) {
    const auto placements = xvc::face_placements_of(*kept_nodes[k]);
    for (std::size_t c = 0; c < copies[k].size() && c < placements.size(); ++c) {
      const xvc::FacePlacement& f = placements[c];
      const int pi = copies[k][c];
      GarmentPiece& gp = g.pieces[pi];
      int host = -1;
      for (std::size_t h = 0; h < kept_nodes.size(); ++h)
        if (kept_nodes[h]->id() == f.host) host = copies[h][0];
      if (host < 0 || host == pi)
        throw Error(file, f.id,
                    gp.name + " is sewn onto the face of " + f.host + ", which is " +
                        (host == pi ? "itself" : "not a pattern of size " + g.size + " that is draped"));
      for (const auto& h : hems)
        if (h.piece == pi)
          throw Error(file, f.id, gp.name + " is sewn onto the face of " + g.pieces[host].name +
                                      " and by seams as well (hem " + h.id + "); a piece sewn onto a face has no other seam");
      // Its mouth: the stretch whose ends' middle lies highest in its own frame.
      const auto& st = stretches[k];
      const auto& bd = gp.piece.boundary;
      const int ns = static_cast<int>(st.size());
      if (ns < 2) throw Error(file, f.id, gp.name + " needs a mouth and an outline to sew: its outline is one stretch");
      int mouth = 0;
      double top = -std::numeric_limits<double>::infinity();
      for (int q = 0; q < ns; ++q) {
        const double y = 0.5 * (bd[st[q].first].p.y() + bd[st[(q + 1) % ns].first].p.y());
        if (y > top) top = y, mouth = q;
      }
      Vec2 lo = bd[0].p, hi = bd[0].p;
      for (const auto& cp : bd) lo = lo.cwiseMin(cp.p), hi = hi.cwiseMax(cp.p);
      const double t = f.angle_deg * std::numbers::pi / 180.0;
      gp.host = host;
      gp.to_host_rotation << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
      gp.to_host_from = 0.5 * (lo + hi);
      gp.to_host_at = Vec2(f.x, f.y);
      // A pocket is sewn all round but its mouth; a flap by its top edge
      // only, hanging over its pocket; a placket by its two ends (the
      // stretches whose middles lie farthest along its long side), each a
      // seam of its own.
      const pattern::Role role = xvc::piece_role(doc, *kept_nodes[k]).role;
      const bool flap = role == pattern::Role::pocket_flap;
      gp.face_gap = flap ? kFlapGap : kPocketGap;
      gp.face_layer = flap ? 2 : 1;
      if (role == pattern::Role::placket) {
        const bool lying = hi.x() - lo.x() > hi.y() - lo.y();
        int lower = 0, upper = 0;
        double least = std::numeric_limits<double>::infinity(), most = -least;
        for (int q = 0; q < ns; ++q) {
          const Vec2 mid = 0.5 * (bd[st[q].first].p + bd[st[(q + 1) % ns].first].p);
          const double v = lying ? mid.x() : mid.y();
          if (v < least) least = v, lower = q;
          if (v > most) most = v, upper = q;
        }
        if (upper == lower)
          throw Error(file, f.id, gp.name + " needs two ends to sew: its outline is one stretch");
        for (const auto& [q, end] : {std::pair{upper, "top"}, std::pair{lower, "bottom"}}) {
          Hem hem;
          hem.id = f.id + "-" + end;
          hem.piece = pi;
          hem.a = static_cast<int>(st[q].first);
          hem.b = static_cast<int>(st[(q + 1) % ns].first);
          face_seams.push_back({static_cast<int>(hems.size()), host, -1, hem.id,
                                gp.name + " on " + g.pieces[host].name + " (" + end + ")"});
          hems.push_back(std::move(hem));
        }
        continue;
      }
      Hem hem;
      hem.id = f.id;
      hem.piece = pi;
      hem.a = static_cast<int>(st[flap ? mouth : (mouth + 1) % ns].first);
      hem.b = static_cast<int>(st[flap ? (mouth + 1) % ns : mouth].first);
      face_seams.push_back({static_cast<int>(hems.size()), host, -1, f.id, gp.name + " on " + g.pieces[host].name});
      hems.push_back(std::move(hem));
    }
  }

  // Segments per hem: a seam's first hem gets n, the others share n by length.
  for (const auto& s : seams) {
    std::vector<double> len;
    for (int h : s.hems) {
      const auto& bd = g.pieces[hems[h].piece].piece.boundary;
      len.push_back(polyline_length(span_points(bd, hems[h].a, hems[h].b)));
    }
    double rest = 0;
    for (std::size_t k = 1; k < len.size(); ++k) rest += len[k];
    const int n = std::max<int>(static_cast<int>(s.hems.size()) - 1,
                                static_cast<int>(std::ceil(std::max(len[0], rest) / spacing - 1e-9)));
    hems[s.hems[0]].segments = std::max(1, n);
    int left = n;
    double left_len = rest;
    for (std::size_t k = 1; k < s.hems.size(); ++k) {
      const int remaining = static_cast<int>(s.hems.size() - 1 - k);
      int nk = k + 1 == s.hems.size() ? left
                                      : static_cast<int>(std::lround(left * (left_len > 0 ? len[k] / left_len : 0)));
      nk = std::clamp(nk, 1, left - remaining);
      hems[s.hems[k]].segments = nk;
      left -= nk;
      left_len -= len[k];
    }
  }

  // A face seam's hem gets ceil(length / spacing) segments, and its line
  // the same points where they lie on the host, inside its outline.
  std::vector<std::vector<std::vector<Vec2>>> lines(g.pieces.size());
  for (auto& fs : face_seams) {
    Hem& h = hems[fs.hem];
    const GarmentPiece& gp = g.pieces[h.piece];
    const auto run = span_points(gp.piece.boundary, h.a, h.b);
    h.segments = std::max(1, static_cast<int>(std::ceil(polyline_length(run) / spacing - 1e-9)));
    std::vector<Vec2> line;
    for (const Vec2& p : by_arc_length(run, h.segments)) line.push_back(gp.on_host(p));
    for (const Vec2& p : line)
      if (!pattern::point_in_outline(g.pieces[fs.host].piece.boundary, p))
        throw Error(file, fs.id,
                    gp.name + " placed on " + g.pieces[fs.host].name + " reaches past its outline at (" +
                        format_fixed(p.x(), 3) + ", " + format_fixed(p.y(), 3) + ") m; move it (POSITION " + fs.id +
                        ": x, y, angle)");
    fs.line = static_cast<int>(lines[fs.host].size());
    lines[fs.host].push_back(std::move(line));
  }

  // Resample and mesh every piece.
  for (int pi = 0; pi < static_cast<int>(g.pieces.size()); ++pi) {
    GarmentPiece& gp = g.pieces[pi];
    const auto& bd = gp.piece.boundary;
    const int n = static_cast<int>(bd.size());
    std::vector<int> mine;
    for (int h = 0; h < static_cast<int>(hems.size()); ++h)
      if (hems[h].piece == pi) mine.push_back(h);

    // Break points: corners, notch vertices and hem ends, none inside a hem.
    std::vector<bool> brk = corners(bd, turn_angle);
    for (const auto& nt : gp.piece.notches)
      if (nt.boundary_index >= 0 && nt.boundary_index < n) brk[nt.boundary_index] = true;
    std::vector<int> hem_starting(n, -1);
    for (int h : mine) {
      brk[hems[h].a] = brk[hems[h].b] = true;
      hem_starting[hems[h].a] = h;
    }
    for (int h : mine)
      for (int v = 0; v < n; ++v)
        if (strictly_inside(v, hems[h].a, hems[h].b, n)) brk[v] = false;
    std::vector<int> breaks;
    for (int v = 0; v < n; ++v)
      if (brk[v]) breaks.push_back(v);
    // Break points closer than a fifth of the spacing along the outline (a
    // real file's two turn points 25 µm apart) would leave a boundary edge
    // that short and a sliver triangle on it, stiff enough that no step can
    // follow it: of such a pair the one that ends no hem goes.
    {
      std::vector<bool> hem_end(n, false);
      for (int h : mine) hem_end[hems[h].a] = hem_end[hems[h].b] = true;
      std::vector<double> arc(n + 1, 0.0);
      for (int v = 0; v < n; ++v) arc[v + 1] = arc[v] + dist(bd[v].p, bd[(v + 1) % n].p);
      const double min_side = 0.2 * spacing;
      std::vector<int> kept;
      for (const int v : breaks) {
        if (!kept.empty() && arc[v] - arc[kept.back()] < min_side) {
          if (hem_end[v] && hem_end[kept.back()]) kept.push_back(v);  // two hems' ends: both stay
          else if (hem_end[v]) kept.back() = v;                         // a hem's end wins over a corner
          continue;                                                     // else the corner goes
        }
        kept.push_back(v);
      }
      if (kept.size() > 1 && arc[n] - arc[kept.back()] + arc[kept.front()] < min_side) {
        if (!hem_end[kept.back()]) kept.pop_back();
        else if (!hem_end[kept.front()]) kept.erase(kept.begin());
      }
      breaks = std::move(kept);
    }
    if (breaks.empty()) breaks.push_back(0);

    // Walk the sides from break to break.
    std::vector<ContourPoint> out;
    std::vector<int> new_index(n, -1);  // kept break vertices
    for (std::size_t k = 0; k < breaks.size(); ++k) {
      const int a = breaks[k], b = breaks[(k + 1) % breaks.size()];
      const std::vector<Vec2> side = span_points(bd, a, b == a ? (a + n - 1) % n : b);
      std::vector<Vec2> pts;
      const int h = hem_starting[a];
      if (h >= 0) {
        pts = by_arc_length(side, hems[h].segments);
      } else {
        std::vector<Vec2> closed = side;
        if (b == a) closed.push_back(bd[a].p);  // one side round the whole outline
        pts = by_arc_length(closed, std::max(1, static_cast<int>(std::ceil(polyline_length(closed) / spacing - 1e-9))));
      }
      new_index[a] = static_cast<int>(out.size());
      if (h >= 0) hems[h].vertices.clear();
      for (std::size_t q = 0; q + 1 < pts.size(); ++q) {
        if (h >= 0) hems[h].vertices.push_back(static_cast<int>(out.size()));
        ContourPoint cp{pts[q], q == 0 ? bd[a].kind : pattern::PointKind::plain};
        if (q == 0 && brk[a] && cp.kind == pattern::PointKind::plain) cp.kind = pattern::PointKind::turn;
        out.push_back(cp);
      }
    }
    // Each hem ends where the next side starts.
    for (int h : mine) hems[h].vertices.push_back(new_index[hems[h].b]);

    pattern::Piece resampled = gp.piece;
    resampled.boundary = std::move(out);
    for (auto& nt : resampled.notches)
      nt.boundary_index = nt.boundary_index >= 0 && nt.boundary_index < n ? new_index[nt.boundary_index] : -1;

    mesh::MeshOptions mo;
    mo.resample_contour = false;
    mo.split_boundary = false;  // Steiner points on a hem would break the pairing
    mo.min_angle_deg = min_angle;
    mo.max_area_m2 = (1.0 + std::sqrt(2.0)) / 4.0 * spacing * spacing;
    mo.resample.spacing_m = spacing;
    mo.lines = lines[pi];
    try {
      const std::size_t said = diag.items().size();
      gp.mesh = mesh::mesh_piece(resampled, mo, diag);
      diag.name_file(file, said);
    } catch (const Error& e) {
      throw Error(file, gp.pattern_id, "cannot mesh " + gp.name + ": " + e.diagnostic().message);
    }
    if (gp.mesh.contour_nodes.empty() || gp.mesh.contour_nodes[0].size() != resampled.boundary.size())
      throw Error(file, gp.pattern_id, "the mesher changed the outline of " + gp.name + " (internal error)");
    gp.piece = std::move(resampled);
  }

  // Seams as node pairs.
  const auto sewing_order = [&](const Hem& h) {
    std::vector<PieceNode> nodes;
    for (int v : h.vertices) nodes.push_back({h.piece, g.pieces[h.piece].mesh.contour_nodes[0][v]});
    if (!h.forward) std::reverse(nodes.begin(), nodes.end());
    return nodes;
  };
  for (const auto& s : seams) {
    GarmentSeam out{s.id, s.name, {}, 0.0, 0.0};
    const std::vector<PieceNode> first = sewing_order(hems[s.hems[0]]);
    const auto hem_length = [&](const Hem& h) {
      return polyline_length(span_points(g.pieces[h.piece].piece.boundary, h.vertices.front(), h.vertices.back()));
    };
    out.length_a = hem_length(hems[s.hems[0]]);
    int at = 0;
    for (std::size_t k = 1; k < s.hems.size(); ++k) {
      const Hem& h = hems[s.hems[k]];
      out.length_b += hem_length(h);
      const std::vector<PieceNode> other = sewing_order(h);
      // A dart's legs share its tip: that node is sewn already.
      for (std::size_t q = 0; q < other.size(); ++q)
        if (!(first.at(at + q) == other[q])) out.pairs.push_back({first.at(at + q), other[q]});
      at += static_cast<int>(other.size()) - 1;
    }
    g.seams.push_back(std::move(out));
  }
  for (const auto& fs : face_seams) {
    const Hem& h = hems[fs.hem];
    const auto& pocket = g.pieces[h.piece];
    const auto& on = g.pieces[fs.host].mesh.line_nodes.at(fs.line);
    GarmentSeam out{fs.id, fs.name, {}, 0.0, 0.0};
    for (std::size_t i = 0; i < h.vertices.size() && i < on.size(); ++i)
      out.pairs.push_back({PieceNode{h.piece, pocket.mesh.contour_nodes[0][h.vertices[i]]}, PieceNode{fs.host, on[i]}});
    out.length_a = out.length_b =
        polyline_length(span_points(pocket.piece.boundary, h.vertices.front(), h.vertices.back()));
    g.seams.push_back(std::move(out));
  }
  return g;
}

}  // namespace vgd::dress
