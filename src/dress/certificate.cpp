#include "vgd/dress/certificate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <limits>
#include <numbers>
#include <optional>

#include "vgd/body/avatar.hpp"
#include "vgd/body/mannequin.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/mesh/strain.hpp"
#include "vgd/mesh/surface_checks.hpp"
#include "vgd/sim/effects/body_collision.hpp"
#include "vgd/sim/sdf.hpp"

namespace vgd::dress {
namespace {

using sim::Vec3;

Percentiles percentiles(std::vector<double> v) {
  Percentiles p;
  if (v.empty()) return p;
  std::sort(v.begin(), v.end());
  const auto at = [&](double q) { return v[static_cast<std::size_t>(std::lround(q * (v.size() - 1)))]; };
  p.min = v.front();
  p.p5 = at(0.05);
  p.p50 = at(0.5);
  p.p95 = at(0.95);
  p.max = v.back();
  return p;
}

// Strain of every triangle of one piece: deformation gradient F = [dx1 dx2]
// [du1 du2]⁻¹ (3 × 2) against the flat rest shape in (warp, weft) coordinates.
PieceStrain piece_strain(const sim::Model& m, const scene::PieceInfo& p, const sim::VecX& x) {
  std::vector<double> warp, weft, shear;
  for (int t = p.first_triangle; t < p.first_triangle + p.triangles; ++t) {
    const auto& tri = m.triangles[t];
    const auto e = mesh::triangle_strain(m.uv[tri[0]], m.uv[tri[1]], m.uv[tri[2]], sim::at(x, tri[0]),
                                         sim::at(x, tri[1]), sim::at(x, tri[2]));
    if (!e.valid) continue;
    warp.push_back(e.warp);
    weft.push_back(e.weft);
    shear.push_back(e.shear_deg);
  }
  PieceStrain s;
  s.piece = p.name;
  s.fabric = p.material.name;
  s.fabric_limit = p.material.strain_limit;
  s.warp = percentiles(warp);
  s.weft = percentiles(weft);
  s.shear_deg = percentiles(shear);
  return s;
}

// Per original particle, the lowest original particle merged with it (itself
// when unmerged): one index per sewn vertex.
std::vector<int> first_copies(const std::vector<int>& rep, int n) {
  std::vector<int> first(n);
  if (rep.empty()) {
    for (int k = 0; k < n; ++k) first[k] = k;
    return first;
  }
  std::vector<int> of_group(n, -1);
  for (int k = 0; k < n; ++k)
    if (of_group[rep[k]] < 0) of_group[rep[k]] = k;
  for (int k = 0; k < n; ++k) first[k] = of_group[rep[k]];
  return first;
}

nlohmann::json to_json(const Percentiles& p) {
  return {{"min", p.min}, {"p5", p.p5}, {"p50", p.p50}, {"p95", p.p95}, {"max", p.max}};
}

// The trunk cloth's sides left open (Certificate::open_sides).
std::vector<OpenSide> open_sides(const scene::Scene& scene, const std::vector<Vec3>& points, double limit_deg) {
  std::vector<OpenSide> out;
  if (!scene.avatar) return out;
  const body::Avatar& av = *scene.avatar;
  const sim::Model& m = scene.system->model();
  std::vector<char> trunk(points.size(), 0);
  double ymin = 1e300, ymax = -1e300;
  for (const auto& p : scene.pieces) {
    if (p.segment != "torso" && p.segment != "hips") continue;
    for (int i = p.first; i < p.first + p.count; ++i) {
      trunk[i] = 1;
      ymin = std::min(ymin, points[i].y());
      ymax = std::max(ymax, points[i].y());
    }
  }
  if (ymax <= ymin) return out;
  double top = ymax - 0.3 * (ymax - ymin);
  if (av.measurements) top = std::min(top, body::mannequin_landmarks(*av.measurements).bust);
  else if (av.landmarks && av.landmarks->bust > 0) top = std::min(top, av.landmarks->bust);
  // Above the armholes' lowest point the trunk cloth's side is the armhole,
  // which a sleeve closes (a loose shirt's armhole drops below the bust): the
  // sides are read from a slice below it, on the trunk's side of the armhole seams.
  {
    std::vector<char> arm(points.size(), 0);
    for (const auto& p : scene.pieces)
      if (p.segment == "left-arm" || p.segment == "right-arm")
        for (int i = p.first; i < p.first + p.count; ++i) arm[i] = 1;
    double underarm = 1e300;
    for (const auto& seam : scene.seams)
      for (const auto& [a, b] : seam.pairs) {
        if (a < 0 || b < 0 || a >= static_cast<int>(points.size()) || b >= static_cast<int>(points.size())) continue;
        if (trunk[a] && arm[b]) underarm = std::min(underarm, points[a].y());
        if (trunk[b] && arm[a]) underarm = std::min(underarm, points[b].y());
      }
    if (underarm < 1e300) top = std::min(top, underarm - 0.02);
  }
  // Without sleeves (a tank), the armhole ends where the side seams begin: the
  // sides are read below the highest pair of the trunk's seams that run down
  // a side (at least 10 cm tall, centred within 60° of the body's left or
  // right). A tank's armhole drops below the bust in its larger sizes, and
  // the slice at the bust was its armhole, read as a side left open. (With
  // sleeves the side seams end at the underarm found above.)
  if (const body::BodySegment* torso = av.segment("torso")) {
    double side_top = -1e300;
    for (const auto& seam : scene.seams) {
      double lo = 1e300, hi = -1e300;
      Vec3 mean = Vec3::Zero();
      int n = 0;
      for (const auto& [a, b] : seam.pairs) {
        if (a < 0 || b < 0 || a >= static_cast<int>(points.size()) || b >= static_cast<int>(points.size())) continue;
        if (!trunk[a] || !trunk[b]) continue;
        lo = std::min(lo, points[a].y());
        hi = std::max(hi, points[a].y());
        mean += points[a];
        ++n;
      }
      if (n == 0 || hi - lo < 0.10) continue;
      mean /= n;
      const Vec3 q = mean - body::ring_at(*torso, std::clamp((mean.y() - torso->start.y()) / torso->axis.y(), 0.0,
                                                               torso->length)).centre;
      const double angle = std::atan2(q.dot(torso->side()), q.dot(torso->front)) * 180.0 / std::numbers::pi;
      if (std::abs(std::abs(angle) - 90.0) <= 60.0) side_top = std::max(side_top, hi);
    }
    if (side_top > -1e300) top = std::min(top, side_top - 0.02);
  }
  const double bottom = ymin + 0.08;
  OpenSide sides[2] = {{"left", 0, 0, 0}, {"right", 0, 0, 0}};
  for (double h = top; h >= bottom; h -= 0.02) {
    // The body's axis at this height: the trunk segment (torso, then hips) spanning it.
    const body::BodySegment* seg = nullptr;
    double s = 0;
    for (const char* name : {"torso", "hips"}) {
      const body::BodySegment* b = av.segment(name);
      if (!b || std::abs(b->axis.y()) < 0.5) continue;
      const double t = (h - b->start.y()) / b->axis.y();
      if (t >= 0 && t <= b->length) {
        seg = b;
        s = t;
        break;
      }
    }
    if (!seg) continue;
    const Vec3 c = body::ring_at(*seg, s).centre, front = seg->front, left = seg->side();
    // Where the trunk cloth's triangle edges cross the height, as angles round the
    // body from its front (+90° its left).
    std::vector<double> angles;
    for (const auto& t : m.triangles) {
      if (!trunk[t[0]] || !trunk[t[1]] || !trunk[t[2]]) continue;
      for (int e = 0; e < 3; ++e) {
        const Vec3 &a = points[t[e]], &b = points[t[(e + 1) % 3]];
        if ((a.y() - h) * (b.y() - h) >= 0) continue;
        const Vec3 q = a + (h - a.y()) / (b.y() - a.y()) * (b - a) - c;
        angles.push_back(std::atan2(q.dot(left), q.dot(front)) * 180.0 / std::numbers::pi);
      }
    }
    if (angles.size() < 3) continue;
    std::sort(angles.begin(), angles.end());
    double widest[2] = {0, 0};  // left, right
    for (std::size_t k = 0; k < angles.size(); ++k) {
      const double a0 = angles[k], a1 = k + 1 < angles.size() ? angles[k + 1] : angles[0] + 360.0;
      double mid = 0.5 * (a0 + a1);
      if (mid > 180) mid -= 360;
      for (int side = 0; side < 2; ++side)
        if (std::abs(mid - (side == 0 ? 90.0 : -90.0)) <= 60) widest[side] = std::max(widest[side], a1 - a0);
    }
    for (int side = 0; side < 2; ++side) {
      OpenSide& o = sides[side];
      if (widest[side] > limit_deg) {
        if (o.top == 0) o.top = h;
        o.bottom = h;
      }
      o.widest_deg = std::max(o.widest_deg, widest[side]);
    }
  }
  for (const OpenSide& o : sides)
    if (o.widest_deg > 0) out.push_back(o);  // top and bottom 0: no slice wider than the limit
  return out;
}

// How deep, as a share of a triangle's longest rest edge, a ridge of the body
// can reach between particles over intact cloth: the sag of a chord of length
// L over a surface of curvature radius R is L²/(8R), a quarter of L only where
// R ≤ L/2 (7.5 mm at the drape's 1.5 cm mesh), tighter than any part of the
// body a garment covers. Deeper, the body has passed the cloth.
constexpr double kRidgeDepth = 0.25;
// Triangles round one particle of a regular mesh: a point of the body pushed
// between particles reaches no more.
constexpr int kPointPatch = 6;

}  // namespace

std::vector<Failure> Certificate::failures() const {
  std::vector<Failure> out;
  auto pct = [](double v) { return format_fixed(100 * v, 0) + " %"; };
  if (stop_reason == "error") out.push_back({"error", stop_message});
  else if (stop_reason != "rest") {
    std::string detail = "stopped at the time limit, " + format_fixed(simulated_s, 2) + " s simulated";
    if (still_moving) {
      const StillMoving& m = *still_moving;
      detail += "; still moving: a particle " + format_fixed(100 * m.path, 1) + " cm over the last " +
                format_fixed(m.window_s, 2) + " s, at (" + format_fixed(m.at.x(), 3) + ", " + format_fixed(m.at.y(), 3) +
                ", " + format_fixed(m.at.z(), 3) + ") m";
      if (m.near.size() == 1) detail += " by the " + m.near[0];
      if (m.near.size() >= 2) detail += " between the " + m.near[0] + " and the " + m.near[1];
      std::string pieces;
      for (const auto& [piece, n] : m.pieces) pieces += (pieces.empty() ? "" : ", ") + piece + " " + std::to_string(n);
      if (!pieces.empty()) detail += " (particles moving half as far or more: " + pieces + ")";
    }
    out.push_back({"no rest", detail});
  }
  for (const auto& s : seams)
    if (s.closed != s.pairs)
      out.push_back({"seams open", s.name + ": " + std::to_string(s.closed) + "/" + std::to_string(s.pairs) +
                                       " pairs closed, widest gap " + format_fixed(1000 * s.max_gap, 1) + " mm" +
                                       (s.body_between ? ", the body between its two sides there" : "")});
  for (const auto& o : open_sides)
    if (o.widest_deg > open_limit_deg)
      out.push_back({"open side", "the garment is open at the wearer's " + o.side + " side from " + format_fixed(o.top, 2) +
                                 " m down to " + format_fixed(o.bottom, 2) + " m high: up to " +
                                 format_fixed(o.widest_deg, 0) + "° round the body without cloth (limit " +
                                 format_fixed(open_limit_deg, 0) + "°); its front and back are not sewn there"});
  if (max_penetration > penetration_limit)
    out.push_back({"penetration", format_fixed(1000 * max_penetration, 2) + " mm inside the body (limit " +
                                      format_fixed(1000 * penetration_limit, 1) + " mm), " +
                                      std::to_string(particles_inside) + " particles inside"});
  if (body_through_opening > 0) {
    std::string where;
    for (const auto& [piece, n] : body_through_opening_by_piece) where += (where.empty() ? "" : ", ") + piece + " " + std::to_string(n);
    out.push_back({"penetration", "the body passes through the cloth: " + std::to_string(body_through_opening) +
                                      " triangles over a hole or opening of it, up to " +
                                      format_fixed(1000 * max_body_through, 1) + " mm (" + where + ")"});
  }
  if (body_through_cloth > 0 && max_body_through > body_through_limit)
    out.push_back({"penetration", body_through_text() + " (limit " + format_fixed(1000 * body_through_limit, 1) + " mm)"});
  if (triangle_intersections > 0) {
    std::string where;
    for (const auto& [pieces, n] : crossings_by_pieces) where += (where.empty() ? "" : ", ") + pieces + " " + std::to_string(n);
    out.push_back({"self-intersection", std::to_string(triangle_intersections) + " crossing triangle pairs (" + where + ")"});
  }
  for (const auto& s : strain) {
    // A fabric that states where its yarns lock cannot be stretched further.
    const double limit = s.fabric_limit > 0.0 ? s.fabric_limit : strain_limit;
    for (const auto& [dir, p] : {std::pair{"warp", s.warp}, {"weft", s.weft}})
      if (p.p95 > limit)
        out.push_back({"over-stretched", s.piece + ": " + dir + " strain p95 " + pct(p.p95) + " (limit " + pct(limit) +
                                             (s.fabric_limit > 0.0 ? ", the fabric's strain_limit" : "") + ")"});
  }
  for (const auto& w : placement)
    if (w.moved.norm() > displacement_limit)
      out.push_back({"displaced", w.piece + ": its centre moved " + format_fixed(100 * w.moved.norm(), 1) + " cm (" +
                                      format_fixed(100 * w.moved.y(), 1) + " cm up) from where it was placed on the " +
                                      w.segment + " (limit " + format_fixed(100 * displacement_limit, 0) + " cm)"});
  return out;
}

std::string Certificate::body_through_text() const {
  std::string where;
  for (const auto& [piece, n] : body_through_by_piece) where += (where.empty() ? "" : ", ") + piece + " " + std::to_string(n);
  std::string text = "the body passes through " + std::to_string(body_through_cloth) + " cloth triangles, up to " +
                     format_fixed(1000 * max_body_through, 2) + " mm inside it between their particles (" + where + ")";
  if (body_through_at) {
    const Vec3& a = *body_through_at;
    text += ", the deepest at (" + format_fixed(a.x(), 3) + ", " + format_fixed(a.y(), 3) + ", " + format_fixed(a.z(), 3) +
            ") m";
    if (body_through_near.size() == 1) text += " by the " + body_through_near[0];
    if (body_through_near.size() >= 2) text += " between the " + body_through_near[0] + " and the " + body_through_near[1];
  }
  return text;
}

std::vector<Failure> Certificate::warnings() const {
  std::vector<Failure> out;
  if (body_through_cloth > 0 && max_body_through <= body_through_limit)
    out.push_back({"body through cloth", body_through_text()});
  return out;
}

bool Certificate::passed() const { return failures().empty(); }

std::optional<std::string> caught_at_armpit(const Certificate& c) {
  // An arm and the torso among the segments beside a point.
  auto armpit = [](const std::vector<std::string>& near) {
    const bool arm = std::any_of(near.begin(), near.end(), [](const std::string& s) {
      return s == "left-arm" || s == "right-arm";
    });
    return arm && std::find(near.begin(), near.end(), "torso") != near.end();
  };
  auto where = [](const std::vector<std::string>& near, const Vec3& a) {
    return "the " + near[0] + " and the " + near[1] + ", at (" + format_fixed(a.x(), 3) + ", " +
           format_fixed(a.y(), 3) + ", " + format_fixed(a.z(), 3) + ") m";
  };
  const std::vector<Failure> failed = c.failures();
  if (failed.empty()) return std::nullopt;
  std::optional<std::string> at;
  for (const Failure& f : failed) {
    if (f.kind == "no rest" && c.stop_reason == "time limit" && c.still_moving && armpit(c.still_moving->near)) {
      at = where(c.still_moving->near, c.still_moving->at);
      continue;
    }
    if (f.kind == "penetration" && c.max_penetration <= c.penetration_limit && c.body_through_opening == 0 &&
        c.body_through_at && armpit(c.body_through_near)) {
      if (!at) at = where(c.body_through_near, *c.body_through_at);
      continue;
    }
    return std::nullopt;  // something else failed too
  }
  return at;
}

Certificate::SeamTotals Certificate::seam_totals() const {
  SeamTotals t;
  for (const auto& s : seams) t.closed += s.closed, t.pairs += s.pairs;
  return t;
}

void measure_state(const scene::Scene& scene, const sim::VecX& x, double merge_distance, double contact_distance,
                   bool intersections, Certificate& out) {
  const sim::Model& m = scene.system->model();
  out.particles = m.num_particles();
  out.triangles = static_cast<int>(m.triangles.size());
  std::vector<Vec3> points(m.num_particles());
  for (int i = 0; i < m.num_particles(); ++i) points[i] = sim::at(x, i);

  // Penetration: exact, against the body's triangles.
  out.max_penetration = 0;
  out.particles_inside = 0;
  if (scene.avatar) {
    const std::vector<double> depth = mesh::penetration_depths(scene.avatar->surface, points);
    for (std::size_t i = 0; i < depth.size(); ++i) {
      const double d = depth[i];
      if (d > out.max_penetration) out.deepest_at = points[i];
      out.max_penetration = std::max(out.max_penetration, d);
      out.particles_inside += d > 0;
    }
  }
  // Crossings in the sewn topology: a merged particle's copies are one vertex,
  // so triangles meeting across a closed seam share it and do not count.
  if (intersections) {
    const std::vector<int> first = first_copies(scene.system->representative(), m.num_particles());
    std::vector<std::array<int, 3>> sewn;
    std::vector<int> original;  // the model triangle of each sewn one
    sewn.reserve(m.triangles.size());
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      std::array<int, 3> q = m.triangles[t];
      for (int& k : q) k = first[k];
      if (q[0] != q[1] && q[1] != q[2] && q[0] != q[2]) {
        sewn.push_back(q);
        original.push_back(static_cast<int>(t));
      }
    }
    const auto crossing = mesh::find_triangle_intersections(points, sewn);
    out.triangle_intersections = static_cast<int>(crossing.size());
    // Where: per pair of pieces (a piece with itself: a fold through itself).
    auto piece_of = [&](int t) -> std::string {
      for (const auto& p : scene.pieces)
        if (t >= p.first_triangle && t < p.first_triangle + p.triangles) return p.name;
      return "?";
    };
    out.crossings_by_pieces.clear();
    for (const auto& [a, b] : crossing) {
      std::string pa = piece_of(original[a]), pb = piece_of(original[b]);
      if (pb < pa) std::swap(pa, pb);
      ++out.crossings_by_pieces[pa + " / " + pb];
    }
    // The body through the cloth: a triangle whose centre or edge midpoints
    // lie inside the body deeper than the particles may (a body ridge poking
    // between particles that are all outside it).
    out.body_through_by_piece.clear();
    out.body_through_opening_by_piece.clear();
    out.body_through_cloth = 0;
    out.body_through_opening = 0;
    out.max_body_through = 0;
    out.body_through_at.reset();
    out.body_through_near.clear();
    if (scene.avatar) {
      std::vector<Vec3> probes;
      probes.reserve(4 * sewn.size());
      for (const auto& t : sewn) {
        const Vec3 &a = points[t[0]], &b = points[t[1]], &c = points[t[2]];
        probes.push_back((a + b + c) / 3.0);
        probes.push_back(0.5 * (a + b)), probes.push_back(0.5 * (b + c)), probes.push_back(0.5 * (c + a));
      }
      const std::vector<double> depth = mesh::penetration_depths(scene.avatar->surface, probes);
      std::vector<std::size_t> deep;   // deeper than a ridge can be
      std::vector<bool> opening(sewn.size(), false);
      for (std::size_t t = 0; t < sewn.size(); ++t) {
        const double d = std::max({depth[4 * t], depth[4 * t + 1], depth[4 * t + 2], depth[4 * t + 3]});
        if (d > out.max_body_through && d > out.penetration_limit) {
          const std::size_t deepest = 4 * t + (std::max_element(depth.begin() + 4 * t, depth.begin() + 4 * t + 4) -
                                               (depth.begin() + 4 * t));
          out.body_through_at = probes[deepest];
        }
        out.max_body_through = std::max(out.max_body_through, d);
        if (d > out.penetration_limit) ++out.body_through_cloth, ++out.body_through_by_piece[piece_of(original[t])];
        if (m.uv.size() == static_cast<std::size_t>(m.num_particles())) {
          const auto& q = m.triangles[original[t]];
          double size = 0;
          for (int e = 0; e < 3; ++e) size = std::max(size, (m.uv[q[e]] - m.uv[q[(e + 1) % 3]]).norm());
          // Deeper than the triangle is long: the body through an opening
          // (a slit gaping, a strap or a sleeve with the body beside it).
          if (d > size) opening[t] = true;
          if (d > kRidgeDepth * size) deep.push_back(t);
        }
      }
      // Deeper than a ridge, over a patch wider than the triangles round one
      // particle: not a point of the body pushed between particles (a local
      // miss of the contact, in an armpit's crease) but the body showing
      // through a hole (a crotch between the seams' ends).
      std::vector<int> parent(points.size());
      for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<int>(i);
      const auto root = [&](int i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
      };
      for (const std::size_t t : deep) parent[root(sewn[t][1])] = root(sewn[t][0]), parent[root(sewn[t][2])] = root(sewn[t][0]);
      std::map<int, int> patch;  // root -> triangles
      for (const std::size_t t : deep) ++patch[root(sewn[t][0])];
      for (const std::size_t t : deep)
        if (patch[root(sewn[t][0])] > kPointPatch) opening[t] = true;
      for (std::size_t t = 0; t < sewn.size(); ++t)
        if (opening[t]) ++out.body_through_opening, ++out.body_through_opening_by_piece[piece_of(original[t])];
      if (out.body_through_at)
        out.body_through_near = body::segments_beside(*scene.avatar, *out.body_through_at, kNearCrease);
    }
  } else {
    out.triangle_intersections = -1;
    out.body_through_cloth = -1;
    out.body_through_opening = -1;
  }

  // Seams: a pair is closed when its two particles are one (merged) or as close.
  out.seams.clear();
  const auto& rep = scene.system->representative();
  std::vector<Vec3> between;              // points between open seams' sides
  std::vector<std::size_t> between_seam;  // the seam each is of
  for (const auto& sp : scene.seams) {
    SeamState st;
    st.name = sp.name;
    st.pairs = static_cast<int>(sp.pairs.size());
    double sum = 0;
    std::array<int, 2> widest{-1, -1};
    for (const auto& [a, b] : sp.pairs) {
      const bool merged = !rep.empty() && rep[a] == rep[b];
      const double gap = merged ? 0.0 : (points[a] - points[b]).norm();
      st.closed += merged || gap <= merge_distance;
      if (gap > st.max_gap) st.widest_at = 0.5 * (points[a] + points[b]), widest = {a, b};
      st.max_gap = std::max(st.max_gap, gap);
      sum += gap;
    }
    st.mean_gap = st.pairs ? sum / st.pairs : 0.0;
    // Seven points of the straight line between the widest open pair, looked
    // up in the body with every other open seam's (one query).
    if (scene.avatar && st.closed < st.pairs && st.max_gap > merge_distance && widest[0] >= 0)
      for (int k = 1; k < 8; ++k) {
        between.push_back(points[widest[0]] + (k / 8.0) * (points[widest[1]] - points[widest[0]]));
        between_seam.push_back(out.seams.size());
      }
    out.seams.push_back(st);
  }
  if (!between.empty()) {
    const std::vector<double> depth = mesh::penetration_depths(scene.avatar->surface, between);
    for (std::size_t i = 0; i < depth.size(); ++i) out.seams[between_seam[i]].body_between |= depth[i] > 0.002;
  }

  // Strain per piece.
  out.strain.clear();
  for (const auto& p : scene.pieces) out.strain.push_back(piece_strain(m, p, x));

  // Where each piece placed round the body ended.
  out.placement.clear();
  for (const auto& p : scene.pieces) {
    if (p.segment.empty() || p.count == 0) continue;
    Vec3 then = Vec3::Zero(), now = Vec3::Zero();
    for (int i = p.first; i < p.first + p.count; ++i) then += sim::at(m.x0, i), now += points[i];
    out.placement.push_back({p.name, p.segment, (now - then) / p.count, p.raised});
  }

  out.open_sides = open_sides(scene, points, out.open_limit_deg);

  // Contact pressure: at rest the body carries what pushes each touching
  // particle into it, the inward normal part of every force but the contact's.
  out.contact = ContactState{};
  if (scene.avatar) {
    const sim::VecX v = sim::VecX::Zero(x.size());
    sim::VecX f = sim::VecX::Zero(x.size());
    const sim::Eval e{m, 0.0, x, v};
    for (const auto& eff : scene.system->effects()) {
      const std::string name = eff->name();
      if (name != "body-collision" && name != "self-collision" && name != "contact") eff->add_forces(e, f);
    }
    // Each particle's cloth area: a third of each of its triangles (flat rest shape).
    std::vector<double> part(m.num_particles(), 0.0);
    for (const auto& t : m.triangles) {
      const sim::Vec2 a = m.uv[t[1]] - m.uv[t[0]], b = m.uv[t[2]] - m.uv[t[0]];
      const double A = 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
      for (int k : t) part[k] += A / 3.0;
    }
    // The collision effect's grid when there is one (building one costs 0.1–0.3 s).
    std::optional<sim::SignedDistanceGrid> own;
    const sim::SignedDistanceGrid* grid = nullptr;
    for (const auto& eff : scene.system->effects())
      if (!grid) grid = sim::body_collision_grid(*eff);
    if (!grid) grid = &own.emplace(scene.avatar->surface);
    const sim::SignedDistanceGrid& sdf = *grid;
    std::vector<double> pressure;
    out.contact.particle_pressure.assign(m.num_particles(), 0.0);
    for (int i = 0; i < m.num_particles(); ++i) {
      Vec3 n;
      if (sdf.sample(points[i], n) > contact_distance) continue;
      const double fn = std::max(0.0, -sim::at(f, i).dot(n.normalized()));
      ++out.contact.particles;
      out.contact.area += part[i];
      out.contact.force += fn;
      pressure.push_back(part[i] > 0 ? fn / part[i] : 0.0);
      out.contact.particle_pressure[i] = pressure.back();
    }
    out.contact.pressure = percentiles(pressure);
  }
}

std::string to_json(const Certificate& c) {
  using nlohmann::json;
  json j;
  j["vgd_version"] = c.version;
  json inputs = json::object();
  for (const auto& [k, v] : c.inputs) inputs[k] = v;
  j["inputs"] = inputs;
  json settings = json::object();
  for (const auto& [k, v] : c.settings) settings[k] = v;
  j["settings"] = settings;
  j["stop"] = {{"reason", c.stop_reason}, {"message", c.stop_message}, {"simulated_s", c.simulated_s},
               {"wall_s", c.wall_s}, {"frames", c.frames}, {"frames_on_fewer_threads", c.frames_on_fewer_threads}};
  if (c.still_moving) {
    const StillMoving& m = *c.still_moving;
    json pieces = json::object();
    for (const auto& [piece, n] : m.pieces) pieces[piece] = n;
    j["still_moving"] = {{"window_s", m.window_s}, {"path_m", m.path}, {"at_m", {m.at.x(), m.at.y(), m.at.z()}},
                         {"pieces", pieces}, {"near", m.near}};
  }
  json stages = json::array();
  for (const auto& s : c.stages) stages.push_back({{"name", s.name}, {"wall_s", s.wall_s}, {"simulated_s", s.simulated_s}});
  j["stages"] = stages;
  json prof = json::object();
  for (const auto& [name, sec] : c.effect_seconds) prof[name] = prof.value(name, 0.0) + sec;
  j["profile"] = {{"effect_seconds", prof},
                  {"steps", c.steps},
                  {"force_evaluations", c.force_evaluations},
                  {"linear_iterations", c.linear_iterations}};
  if (c.self_detections >= 0)
    j["profile"]["self_collision"] = {
        {"detections", c.self_detections}, {"pairs", c.self_pairs}, {"reverted_particles", c.self_reverted},
        {"untangling_moves", c.self_untangled}};
  if (c.contact_detections >= 0)
    j["profile"]["contact"] = {{"detections", c.contact_detections},
                               {"cut", c.contact_cut},
                               {"unfinished", c.contact_unfinished},
                               {"merges_held", c.contact_merges_held}};
  j["cloth"] = {{"particles", c.particles}, {"triangles", c.triangles}};
  j["penetration"] = {{"max_m", c.max_penetration}, {"particles_inside", c.particles_inside},
                      {"deepest_at_m", json::array({c.deepest_at.x(), c.deepest_at.y(), c.deepest_at.z()})},
                      {"limit_m", c.penetration_limit}};
  if (c.body_through_cloth >= 0) {
    j["body_through_cloth"] = c.body_through_cloth;
    j["body_through_cloth_max_m"] = c.max_body_through;
    if (!c.body_through_by_piece.empty()) j["body_through_cloth_by_piece"] = c.body_through_by_piece;
    if (c.body_through_at) {
      const Vec3& a = *c.body_through_at;
      j["body_through_cloth_at_m"] = {a.x(), a.y(), a.z()};
      j["body_through_cloth_near"] = c.body_through_near;
    }
    j["body_through_opening"] = c.body_through_opening;
    if (!c.body_through_opening_by_piece.empty()) j["body_through_opening_by_piece"] = c.body_through_opening_by_piece;
  }
  if (c.triangle_intersections >= 0) {
    j["triangle_intersections"] = c.triangle_intersections;
    if (!c.crossings_by_pieces.empty()) j["triangle_intersections_by_pieces"] = c.crossings_by_pieces;
  }
  json seams = json::array();
  for (const auto& s : c.seams) {
    seams.push_back({{"name", s.name}, {"pairs", s.pairs}, {"closed", s.closed}, {"max_gap_m", s.max_gap},
                     {"mean_gap_m", s.mean_gap}});
    if (s.max_gap > 0) seams.back()["widest_at_m"] = json::array({s.widest_at.x(), s.widest_at.y(), s.widest_at.z()});
    if (s.body_between) seams.back()["body_between"] = true;
  }
  j["seams"] = seams;
  json strain = json::array();
  for (const auto& s : c.strain) {
    strain.push_back({{"piece", s.piece}, {"fabric", s.fabric}, {"warp", to_json(s.warp)}, {"weft", to_json(s.weft)},
                      {"shear_deg", to_json(s.shear_deg)}});
    if (s.fabric_limit > 0.0) strain.back()["fabric_strain_limit"] = s.fabric_limit;
  }
  j["strain"] = strain;
  json where = json::array();
  for (const auto& w : c.placement) {
    where.push_back({{"piece", w.piece}, {"segment", w.segment},
                     {"moved_m", json::array({w.moved.x(), w.moved.y(), w.moved.z()})}});
    if (w.raised > 0.0) where.back()["raised_m"] = w.raised;
  }
  j["placement"] = where;
  json open = json::array();
  for (const auto& o : c.open_sides)
    open.push_back({{"side", o.side}, {"top_m", o.top}, {"bottom_m", o.bottom}, {"widest_deg", o.widest_deg}});
  j["open_sides"] = open;
  j["limits"] = {{"penetration_m", c.penetration_limit}, {"strain_p95", c.strain_limit},
                 {"displacement_m", c.displacement_limit}, {"open_side_deg", c.open_limit_deg},
                 {"body_through_m", c.body_through_limit}};
  json failures = json::array();
  for (const auto& f : c.failures()) failures.push_back({{"class", f.kind}, {"detail", f.detail}});
  j["failures"] = failures;
  json warnings = json::array();
  for (const auto& f : c.warnings()) warnings.push_back({{"class", f.kind}, {"detail", f.detail}});
  j["warnings"] = warnings;
  j["contact"] = {{"particles", c.contact.particles}, {"area_m2", c.contact.area}, {"force_n", c.contact.force},
                  {"pressure_pa", to_json(c.contact.pressure)}};
  j["kinetic_energy"] = {{"unit", "J per particle"}, {"times_s", c.times}, {"values", c.kinetic_energy}};
  j["passed"] = c.passed();
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

namespace {

// certificate_from_json's reading of one field: `path` names it in errors.
struct Reader {
  const std::string& source;
  using json = nlohmann::json;

  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw Error(source, path, what + " (not a certificate written by vgd)");
  }
  const json& at(const json& j, const std::string& key, const std::string& path) const {
    if (!j.is_object()) fail(path, "expected an object");
    const auto it = j.find(key);
    if (it == j.end()) fail(path.empty() ? key : path + "." + key, "missing");
    return *it;
  }
  double number(const json& j, const std::string& path) const {
    if (!j.is_number()) fail(path, "expected a number");
    return j.get<double>();
  }
  long long integer(const json& j, const std::string& path) const {
    if (!j.is_number_integer()) fail(path, "expected an integer");
    return j.get<long long>();
  }
  int int32(const json& j, const std::string& path) const {
    const long long v = integer(j, path);
    if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max()) fail(path, "out of range");
    return static_cast<int>(v);
  }
  std::string text(const json& j, const std::string& path) const {
    if (!j.is_string()) fail(path, "expected a string");
    return j.get<std::string>();
  }
  const json& array(const json& j, const std::string& path) const {
    if (!j.is_array()) fail(path, "expected an array");
    return j;
  }
  Vec3 vec3(const json& j, const std::string& path) const {
    if (!j.is_array() || j.size() != 3) fail(path, "expected [x, y, z]");
    return {number(j[0], path), number(j[1], path), number(j[2], path)};
  }
  Percentiles percentiles(const json& j, const std::string& path) const {
    Percentiles p;
    p.min = number(at(j, "min", path), path + ".min");
    p.p5 = number(at(j, "p5", path), path + ".p5");
    p.p50 = number(at(j, "p50", path), path + ".p50");
    p.p95 = number(at(j, "p95", path), path + ".p95");
    p.max = number(at(j, "max", path), path + ".max");
    return p;
  }
  std::map<std::string, int> counts(const json& j, const std::string& path) const {
    if (!j.is_object()) fail(path, "expected an object");
    std::map<std::string, int> out;
    for (const auto& [k, v] : j.items()) out[k] = int32(v, path + "." + k);
    return out;
  }
  std::vector<double> numbers(const json& j, const std::string& path) const {
    std::vector<double> out;
    for (std::size_t i = 0; i < array(j, path).size(); ++i) out.push_back(number(j[i], path + "[" + std::to_string(i) + "]"));
    return out;
  }
};

}  // namespace

Certificate certificate_from_json(std::string_view text, const std::string& source) {
  using nlohmann::json;
  const json j = json::parse(text, nullptr, false);
  if (j.is_discarded()) throw Error(source, "", "not JSON (a certificate.json is)");
  const Reader r{source};
  if (!j.is_object()) r.fail("", "expected an object");
  Certificate c;
  c.version = r.text(r.at(j, "vgd_version", ""), "vgd_version");
  const auto pairs = [&](const char* key) {
    std::vector<std::pair<std::string, std::string>> out;
    const json& o = r.at(j, key, "");
    if (!o.is_object()) r.fail(key, "expected an object");
    for (const auto& [k, v] : o.items()) out.emplace_back(k, r.text(v, std::string(key) + "." + k));
    return out;
  };
  c.inputs = pairs("inputs");
  c.settings = pairs("settings");
  const json& stop = r.at(j, "stop", "");
  c.stop_reason = r.text(r.at(stop, "reason", "stop"), "stop.reason");
  c.stop_message = r.text(r.at(stop, "message", "stop"), "stop.message");
  c.simulated_s = r.number(r.at(stop, "simulated_s", "stop"), "stop.simulated_s");
  c.wall_s = r.number(r.at(stop, "wall_s", "stop"), "stop.wall_s");
  c.frames = r.int32(r.at(stop, "frames", "stop"), "stop.frames");
  c.frames_on_fewer_threads = r.int32(r.at(stop, "frames_on_fewer_threads", "stop"), "stop.frames_on_fewer_threads");
  if (j.contains("still_moving")) {
    const json& m = j["still_moving"];
    const std::string p = "still_moving";
    StillMoving sm;
    sm.window_s = r.number(r.at(m, "window_s", p), p + ".window_s");
    sm.path = r.number(r.at(m, "path_m", p), p + ".path_m");
    sm.at = r.vec3(r.at(m, "at_m", p), p + ".at_m");
    const json& pieces = r.at(m, "pieces", p);
    if (!pieces.is_object()) r.fail(p + ".pieces", "expected an object");
    for (const auto& [k, v] : pieces.items()) sm.pieces.emplace_back(k, r.int32(v, p + ".pieces." + k));
    std::stable_sort(sm.pieces.begin(), sm.pieces.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
    const json& near = r.array(r.at(m, "near", p), p + ".near");
    for (std::size_t i = 0; i < near.size(); ++i) sm.near.push_back(r.text(near[i], p + ".near[" + std::to_string(i) + "]"));
    c.still_moving = std::move(sm);
  }
  const json& stages = r.array(r.at(j, "stages", ""), "stages");
  for (std::size_t i = 0; i < stages.size(); ++i) {
    const std::string p = "stages[" + std::to_string(i) + "]";
    c.stages.push_back({r.text(r.at(stages[i], "name", p), p + ".name"), r.number(r.at(stages[i], "wall_s", p), p + ".wall_s"),
                        r.number(r.at(stages[i], "simulated_s", p), p + ".simulated_s")});
  }
  const json& prof = r.at(j, "profile", "");
  const json& eff = r.at(prof, "effect_seconds", "profile");
  if (!eff.is_object()) r.fail("profile.effect_seconds", "expected an object");
  for (const auto& [k, v] : eff.items()) c.effect_seconds.emplace_back(k, r.number(v, "profile.effect_seconds." + k));
  c.steps = static_cast<long>(r.integer(r.at(prof, "steps", "profile"), "profile.steps"));
  c.force_evaluations = static_cast<long>(r.integer(r.at(prof, "force_evaluations", "profile"), "profile.force_evaluations"));
  c.linear_iterations = static_cast<long>(r.integer(r.at(prof, "linear_iterations", "profile"), "profile.linear_iterations"));
  if (prof.contains("self_collision")) {
    const json& s = prof["self_collision"];
    const std::string p = "profile.self_collision";
    c.self_detections = static_cast<long>(r.integer(r.at(s, "detections", p), p + ".detections"));
    c.self_pairs = static_cast<long>(r.integer(r.at(s, "pairs", p), p + ".pairs"));
    c.self_reverted = static_cast<long>(r.integer(r.at(s, "reverted_particles", p), p + ".reverted_particles"));
    c.self_untangled = static_cast<long>(r.integer(r.at(s, "untangling_moves", p), p + ".untangling_moves"));
  }
  if (prof.contains("contact")) {
    const json& s = prof["contact"];
    const std::string p = "profile.contact";
    c.contact_detections = static_cast<long>(r.integer(r.at(s, "detections", p), p + ".detections"));
    c.contact_cut = static_cast<long>(r.integer(r.at(s, "cut", p), p + ".cut"));
    c.contact_unfinished = static_cast<long>(r.integer(r.at(s, "unfinished", p), p + ".unfinished"));
    c.contact_merges_held = static_cast<long>(r.integer(r.at(s, "merges_held", p), p + ".merges_held"));
  }
  const json& cloth = r.at(j, "cloth", "");
  c.particles = r.int32(r.at(cloth, "particles", "cloth"), "cloth.particles");
  c.triangles = r.int32(r.at(cloth, "triangles", "cloth"), "cloth.triangles");
  const json& pen = r.at(j, "penetration", "");
  c.max_penetration = r.number(r.at(pen, "max_m", "penetration"), "penetration.max_m");
  c.particles_inside = r.int32(r.at(pen, "particles_inside", "penetration"), "penetration.particles_inside");
  c.deepest_at = r.vec3(r.at(pen, "deepest_at_m", "penetration"), "penetration.deepest_at_m");
  c.penetration_limit = r.number(r.at(pen, "limit_m", "penetration"), "penetration.limit_m");
  if (j.contains("body_through_cloth")) {
    c.body_through_cloth = r.int32(j["body_through_cloth"], "body_through_cloth");
    c.max_body_through = r.number(r.at(j, "body_through_cloth_max_m", ""), "body_through_cloth_max_m");
    if (j.contains("body_through_cloth_by_piece"))
      c.body_through_by_piece = r.counts(j["body_through_cloth_by_piece"], "body_through_cloth_by_piece");
    if (j.contains("body_through_cloth_at_m")) {
      c.body_through_at = r.vec3(j["body_through_cloth_at_m"], "body_through_cloth_at_m");
      const json& near = r.array(r.at(j, "body_through_cloth_near", ""), "body_through_cloth_near");
      for (std::size_t i = 0; i < near.size(); ++i)
        c.body_through_near.push_back(r.text(near[i], "body_through_cloth_near[" + std::to_string(i) + "]"));
    }
    c.body_through_opening = r.int32(r.at(j, "body_through_opening", ""), "body_through_opening");
    if (j.contains("body_through_opening_by_piece"))
      c.body_through_opening_by_piece = r.counts(j["body_through_opening_by_piece"], "body_through_opening_by_piece");
  }
  if (j.contains("triangle_intersections")) {
    c.triangle_intersections = r.int32(j["triangle_intersections"], "triangle_intersections");
    if (j.contains("triangle_intersections_by_pieces"))
      c.crossings_by_pieces = r.counts(j["triangle_intersections_by_pieces"], "triangle_intersections_by_pieces");
  }
  const json& seams = r.array(r.at(j, "seams", ""), "seams");
  for (std::size_t i = 0; i < seams.size(); ++i) {
    const std::string p = "seams[" + std::to_string(i) + "]";
    SeamState s;
    s.name = r.text(r.at(seams[i], "name", p), p + ".name");
    s.pairs = r.int32(r.at(seams[i], "pairs", p), p + ".pairs");
    s.closed = r.int32(r.at(seams[i], "closed", p), p + ".closed");
    s.max_gap = r.number(r.at(seams[i], "max_gap_m", p), p + ".max_gap_m");
    s.mean_gap = r.number(r.at(seams[i], "mean_gap_m", p), p + ".mean_gap_m");
    if (seams[i].contains("widest_at_m")) s.widest_at = r.vec3(seams[i]["widest_at_m"], p + ".widest_at_m");
    if (seams[i].contains("body_between")) {
      if (!seams[i]["body_between"].is_boolean()) r.fail(p + ".body_between", "expected true or false");
      s.body_between = seams[i]["body_between"].get<bool>();
    }
    c.seams.push_back(std::move(s));
  }
  const json& strain = r.array(r.at(j, "strain", ""), "strain");
  for (std::size_t i = 0; i < strain.size(); ++i) {
    const std::string p = "strain[" + std::to_string(i) + "]";
    c.strain.push_back({r.text(r.at(strain[i], "piece", p), p + ".piece"),
                        strain[i].contains("fabric") ? r.text(strain[i]["fabric"], p + ".fabric") : std::string(),
                        r.percentiles(r.at(strain[i], "warp", p), p + ".warp"),
                        r.percentiles(r.at(strain[i], "weft", p), p + ".weft"),
                        r.percentiles(r.at(strain[i], "shear_deg", p), p + ".shear_deg")});
    if (strain[i].contains("fabric_strain_limit"))
      c.strain.back().fabric_limit = r.number(strain[i]["fabric_strain_limit"], p + ".fabric_strain_limit");
  }
  const json& where = r.array(r.at(j, "placement", ""), "placement");
  for (std::size_t i = 0; i < where.size(); ++i) {
    const std::string p = "placement[" + std::to_string(i) + "]";
    c.placement.push_back({r.text(r.at(where[i], "piece", p), p + ".piece"),
                           r.text(r.at(where[i], "segment", p), p + ".segment"),
                           r.vec3(r.at(where[i], "moved_m", p), p + ".moved_m")});
    if (where[i].contains("raised_m")) c.placement.back().raised = r.number(where[i]["raised_m"], p + ".raised_m");
  }
  const json& open = r.array(r.at(j, "open_sides", ""), "open_sides");
  for (std::size_t i = 0; i < open.size(); ++i) {
    const std::string p = "open_sides[" + std::to_string(i) + "]";
    c.open_sides.push_back({r.text(r.at(open[i], "side", p), p + ".side"), r.number(r.at(open[i], "top_m", p), p + ".top_m"),
                            r.number(r.at(open[i], "bottom_m", p), p + ".bottom_m"),
                            r.number(r.at(open[i], "widest_deg", p), p + ".widest_deg")});
  }
  const json& limits = r.at(j, "limits", "");
  c.strain_limit = r.number(r.at(limits, "strain_p95", "limits"), "limits.strain_p95");
  c.displacement_limit = r.number(r.at(limits, "displacement_m", "limits"), "limits.displacement_m");
  c.open_limit_deg = r.number(r.at(limits, "open_side_deg", "limits"), "limits.open_side_deg");
  // Certificates written before the limit was a check have none: the default.
  if (limits.contains("body_through_m"))
    c.body_through_limit = r.number(limits["body_through_m"], "limits.body_through_m");
  const json& contact = r.at(j, "contact", "");
  c.contact.particles = r.int32(r.at(contact, "particles", "contact"), "contact.particles");
  c.contact.area = r.number(r.at(contact, "area_m2", "contact"), "contact.area_m2");
  c.contact.force = r.number(r.at(contact, "force_n", "contact"), "contact.force_n");
  c.contact.pressure = r.percentiles(r.at(contact, "pressure_pa", "contact"), "contact.pressure_pa");
  const json& ke = r.at(j, "kinetic_energy", "");
  c.times = r.numbers(r.at(ke, "times_s", "kinetic_energy"), "kinetic_energy.times_s");
  c.kinetic_energy = r.numbers(r.at(ke, "values", "kinetic_energy"), "kinetic_energy.values");
  return c;
}

std::string contact_pressure_json(const Certificate& c) {
  nlohmann::json j;
  j["unit"] = "Pa";
  j["values"] = c.contact.particle_pressure;
  return j.dump() + "\n";
}

std::vector<double> contact_pressure_from_json(std::string_view text, const std::string& source) {
  using nlohmann::json;
  const json j = json::parse(text, nullptr, false);
  if (j.is_discarded()) throw Error(source, "", "not JSON (a contact-pressure.json is)");
  if (!j.is_object()) throw Error(source, "", "expected an object with \"unit\" and \"values\"");
  const auto unit = j.find("unit");
  if (unit == j.end() || !unit->is_string() || unit->get<std::string>() != "Pa")
    throw Error(source, "unit", "expected \"Pa\" (vgd writes pressures in pascals)");
  const auto values = j.find("values");
  if (values == j.end() || !values->is_array()) throw Error(source, "values", "expected an array of pressures, Pa");
  std::vector<double> out;
  out.reserve(values->size());
  for (std::size_t i = 0; i < values->size(); ++i) {
    const json& v = (*values)[i];
    if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < 0.0)
      throw Error(source, "values[" + std::to_string(i) + "]", "expected a finite pressure >= 0, Pa");
    out.push_back(v.get<double>());
  }
  return out;
}

}  // namespace vgd::dress
