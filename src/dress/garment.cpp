#include "vgd/dress/garment.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <tuple>

#include "vgd/xvc/arrangement.hpp"
#include "vgd/xvc/style.hpp"

namespace vgd::dress {
namespace {

using pattern::ContourPoint;
using pattern::Vec2;

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

}  // namespace

Garment assemble_garment(const xvc::Document& doc, const AssemblyOptions& options, Diagnostics& diag) {
  const std::string file = doc.name();
  Garment g;
  g.name = std::string(doc.root().attribute("name"));

  // The size.
  std::string sample;
  if (const auto* grads = doc.container("GRADATIONS")) sample = std::string(grads->attribute("sample_size"));
  const auto patterns = doc.patterns();
  g.size = !options.size.empty() ? options.size : sample;
  if (g.size.empty() && !patterns.empty()) g.size = std::string(patterns.front()->attribute("size"));

  // Meshing settings.
  double spacing = options.spacing;
  if (spacing <= 0) spacing = xvc::get_parameter(doc, "mesh.spacing").value_or(0.015);
  double min_angle = options.min_angle;
  if (min_angle <= 0) min_angle = xvc::get_parameter(doc, "mesh.min_angle").value_or(25.0);
  const double turn_angle = xvc::get_parameter(doc, "mesh.turn_angle").value_or(30.0);

  // The pieces of the size (and of the list, when one is given): one per
  // arrangement of the PATTERN (a sleeve cut twice is placed twice), at least one.
  std::vector<std::vector<xvc::Stretch>> stretches;  // per pattern kept
  std::vector<std::vector<int>> copies;              // per pattern kept: its pieces
  std::set<std::string> left_out;                    // stretches of this size's patterns left out
  for (const auto* p : patterns) {
    if (std::string(p->attribute("size")) != g.size) continue;
    GarmentPiece gp;
    gp.pattern_id = std::string(p->id());
    gp.piece = xvc::to_piece(doc, gp.pattern_id);
    gp.name = gp.piece.name.empty() ? gp.piece.block : gp.piece.name;
    if (!options.pieces.empty() &&
        std::find_if(options.pieces.begin(), options.pieces.end(), [&](const std::string& s) {
          return s == gp.piece.name || s == gp.piece.block || s == gp.pattern_id;
        }) == options.pieces.end()) {
      for (const auto& st : xvc::boundary_stretches(*p)) left_out.insert(st.id);
      continue;
    }
    stretches.push_back(xvc::boundary_stretches(*p));
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
  // A hem sewn again goes to the pattern's next copy: (pattern, from, to) -> uses so far.
  std::map<std::tuple<int, int, int>, int> uses;

  // Seams and their hems, resolved to boundary vertex ranges.
  std::vector<Hem> hems;
  std::vector<Seam> seams;
  if (const auto* container = doc.container("SEAMS")) {
    for (const auto& s : container->children) {
      if (s.tag != "SEAM") continue;
      Seam seam{std::string(s.id()), std::string(s.attribute("name")), {}};
      bool kept = true, other_size = false;
      std::vector<Hem> mine;
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
        const int pat = f->second.first;
        const auto& st = stretches[pat];
        const int use = uses[{pat, f->second.second, t->second.second}]++;
        if (use >= static_cast<int>(copies[pat].size()))
          throw Error(file, std::string(h.id()),
                      "sews stretches " + from + ".." + to + " of " + g.pieces[copies[pat][0]].name + " " +
                          std::to_string(use + 1) + " times, but the piece is placed " +
                          std::to_string(copies[pat].size()) +
                          " time(s); give it one arrangement per copy (vgd place)");
        const int pi = copies[pat][use];
        const int n = static_cast<int>(g.pieces[pi].piece.boundary.size());
        Hem hem;
        hem.id = std::string(h.id());
        hem.piece = pi;
        hem.a = static_cast<int>(st[f->second.second].first);
        hem.b = static_cast<int>(st[(t->second.second + 1) % st.size()].first);
        hem.forward = h.attribute("direction") != "reverse";
        if (hem.a == hem.b || n < 3)
          throw Error(file, hem.id, "the hem covers the whole outline of " + g.pieces[pi].name +
                                        "; a seam needs two ends");
        mine.push_back(std::move(hem));
      }
      if (other_size) continue;  // the seam of another size
      if (!kept || mine.size() < 2) {
        diag.warn(file, seam.id, "seam '" + seam.name + "' is not sewn: one of its pieces is left out");
        continue;
      }
      for (auto& h : mine) {
        seam.hems.push_back(static_cast<int>(hems.size()));
        hems.push_back(std::move(h));
      }
      seams.push_back(std::move(seam));
    }
  }

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
    try {
      gp.mesh = mesh::mesh_piece(resampled, mo, diag);
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
      for (std::size_t q = 0; q < other.size(); ++q) out.pairs.push_back({first.at(at + q), other[q]});
      at += static_cast<int>(other.size()) - 1;
    }
    g.seams.push_back(std::move(out));
  }
  return g;
}

}  // namespace vgd::dress
