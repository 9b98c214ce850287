#include "vgd/mesh/quality.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <set>
#include <unordered_map>
#include <utility>

namespace vgd::mesh {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = 180.0 / kPi;
// Twice the area below this fraction of the longest edge squared counts as zero.
constexpr double kDegenerate = 1e-12;

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Angle at a in triangle (a, b, c), radians; atan2 stays accurate near 0 and pi.
double angle_at(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 u = b - a, v = c - a;
  return std::atan2(std::abs(cross(u, v)), u.dot(v));
}

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b))) << 32) |
         static_cast<std::uint32_t>(std::max(a, b));
}

}  // namespace

std::vector<double> interior_angles_deg(const PieceMesh& m, std::size_t c) {
  const std::vector<Vec2>& pts = m.contours.at(c).points;
  const std::size_t n = pts.size();
  std::vector<double> out(n, 180.0);
  if (n < 3) return out;
  // Walk with the piece on the left (outline CCW, holes CW); the inside angle at a
  // vertex is swept counter-clockwise from the next edge to the previous one.
  const bool forward = (c == 0) == (pattern::signed_area(pts) > 0);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& prev = pts[forward ? (i + n - 1) % n : (i + 1) % n];
    const Vec2& next = pts[forward ? (i + 1) % n : (i + n - 1) % n];
    const Vec2 u = next - pts[i], v = prev - pts[i];
    double a = std::atan2(cross(u, v), u.dot(v));
    if (a < 0) a += 2 * kPi;
    out[i] = a * kDeg;
  }
  return out;
}

QualityReport check_mesh(const PieceMesh& m, double sharp_corner_deg) {
  QualityReport r;
  const int n = static_cast<int>(m.nodes.size());
  r.nodes = m.nodes.size();
  r.triangles = m.triangles.size();
  r.boundary_edges = m.boundary.size();
  auto valid_index = [n](int v) { return v >= 0 && v < n; };

  // Sharp contour corners: triangles touching them are exempt from the angle bound.
  std::vector<char> sharp(m.nodes.size(), 0);
  for (std::size_t c = 0; c < m.contours.size() && c < m.contour_nodes.size(); ++c) {
    const auto angles = interior_angles_deg(m, c);
    for (std::size_t i = 0; i < angles.size() && i < m.contour_nodes[c].size(); ++i)
      if (angles[i] < sharp_corner_deg && valid_index(m.contour_nodes[c][i])) {
        ++r.sharp_corners;
        sharp[m.contour_nodes[c][i]] = 1;
      }
  }

  // Per triangle: orientation, degeneracy, angles, area; and directed edge uses.
  struct Uses {
    int forward = 0, backward = 0;  // as min->max, as max->min
  };
  std::unordered_map<std::uint64_t, Uses> edges;
  edges.reserve(m.triangles.size() * 2);
  std::vector<char> used(m.nodes.size(), 0);
  r.min_angle_deg = r.min_angle_away_from_sharp_deg = 180.0;
  r.min_area_m2 = m.triangles.empty() ? 0.0 : std::numeric_limits<double>::infinity();
  for (const auto& t : m.triangles) {
    if (!valid_index(t[0]) || !valid_index(t[1]) || !valid_index(t[2])) {
      ++r.bad_indices;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      used[t[k]] = 1;
      const int a = t[k], b = t[(k + 1) % 3];
      Uses& u = edges[edge_key(a, b)];
      (a < b ? u.forward : u.backward) += 1;
    }
    const Vec2 &pa = m.nodes[t[0]], &pb = m.nodes[t[1]], &pc = m.nodes[t[2]];
    const double a2 = cross(pb - pa, pc - pa);
    const double longest2 = std::max({(pb - pa).squaredNorm(), (pc - pb).squaredNorm(), (pa - pc).squaredNorm()});
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || std::abs(a2) <= kDegenerate * longest2) {
      ++r.degenerate_triangles;
    } else if (a2 < 0) {
      ++r.clockwise_triangles;
    }
    const double area = 0.5 * a2;
    r.mesh_area_m2 += area;
    r.min_area_m2 = std::min(r.min_area_m2, std::abs(area));
    r.max_area_m2 = std::max(r.max_area_m2, std::abs(area));
    const double angles[3] = {angle_at(pa, pb, pc), angle_at(pb, pc, pa), angle_at(pc, pa, pb)};
    const double lo = *std::min_element(angles, angles + 3) * kDeg;
    const double hi = *std::max_element(angles, angles + 3) * kDeg;
    r.min_angle_deg = std::min(r.min_angle_deg, lo);
    r.max_angle_deg = std::max(r.max_angle_deg, hi);
    if (!sharp[t[0]] && !sharp[t[1]] && !sharp[t[2]])
      r.min_angle_away_from_sharp_deg = std::min(r.min_angle_away_from_sharp_deg, lo);
  }
  if (m.triangles.empty()) r.min_angle_deg = 0.0;

  // Edges: interior ones used once each way, boundary ones once and listed as such.
  std::set<std::pair<int, int>> listed;
  for (const auto& e : m.boundary) {
    if (!valid_index(e.a) || !valid_index(e.b)) {
      ++r.bad_indices;
      continue;
    }
    listed.insert({e.a, e.b});
  }
  for (const auto& [key, u] : edges) {
    const int lo = static_cast<int>(key >> 32), hi = static_cast<int>(key & 0xffffffffu);
    if (u.forward > 1 || u.backward > 1) {
      ++r.non_manifold_edges;
    } else if (u.forward + u.backward == 1) {
      const std::pair<int, int> dir = u.forward ? std::pair{lo, hi} : std::pair{hi, lo};
      if (!listed.erase(dir)) ++r.boundary_mismatches;
    }
  }
  r.boundary_mismatches += static_cast<int>(listed.size());

  // Nodes: exact duplicates and nodes no triangle uses.
  std::vector<int> order(m.nodes.size());
  std::iota(order.begin(), order.end(), 0);
  auto less = [&](int a, int b) {
    return m.nodes[a].x() < m.nodes[b].x() || (m.nodes[a].x() == m.nodes[b].x() && m.nodes[a].y() < m.nodes[b].y());
  };
  std::sort(order.begin(), order.end(), less);
  for (std::size_t i = 1; i < order.size(); ++i) r.duplicate_nodes += m.nodes[order[i]] == m.nodes[order[i - 1]];
  r.unused_nodes = static_cast<int>(std::count(used.begin(), used.end(), 0));

  // Contour vertices present bit for bit; boundary nodes that are not contour vertices.
  std::vector<char> is_contour(m.nodes.size(), 0);
  for (std::size_t c = 0; c < m.contours.size(); ++c) {
    const auto& pts = m.contours[c].points;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const int v = c < m.contour_nodes.size() && i < m.contour_nodes[c].size() ? m.contour_nodes[c][i] : -1;
      if (!valid_index(v) || m.nodes[v] != pts[i]) {
        ++r.missing_contour_vertices;
      } else {
        is_contour[v] = 1;
      }
    }
  }
  std::vector<char> counted(m.nodes.size(), 0);
  for (const auto& e : m.boundary)
    for (int v : {e.a, e.b})
      if (valid_index(v) && !is_contour[v] && !counted[v]) counted[v] = 1, ++r.boundary_steiner_nodes;

  // Area against the polygon's.
  if (!m.contours.empty()) {
    r.polygon_area_m2 = std::abs(pattern::signed_area(m.contours[0].points));
    for (std::size_t c = 1; c < m.contours.size(); ++c)
      r.polygon_area_m2 -= std::abs(pattern::signed_area(m.contours[c].points));
  }
  r.area_rel_error = r.polygon_area_m2 != 0 ? std::abs(r.mesh_area_m2 - r.polygon_area_m2) / std::abs(r.polygon_area_m2)
                                            : std::abs(r.mesh_area_m2);

  // One sentence per failed check.
  auto problem = [&](int count, const char* what) {
    if (count > 0) r.problems.push_back(std::to_string(count) + " " + what);
  };
  problem(r.bad_indices, "triangle or boundary indices outside the node list");
  problem(r.degenerate_triangles, "degenerate triangles (zero area)");
  problem(r.clockwise_triangles, "clockwise triangles");
  problem(r.non_manifold_edges, "edges shared by more than two triangles or twice in the same direction");
  problem(r.boundary_mismatches, "edges where the boundary list and the triangles disagree");
  problem(r.duplicate_nodes, "duplicate nodes");
  problem(r.unused_nodes, "nodes used by no triangle");
  problem(r.missing_contour_vertices, "contour vertices missing from the nodes");
  if (m.node_markers.size() != m.nodes.size()) r.problems.push_back("node markers do not match the nodes");
  if (m.triangles.empty()) r.problems.push_back("no triangles");
  if (!(r.area_rel_error <= 1e-9))
    r.problems.push_back("mesh area differs from the polygon area by " + std::to_string(r.area_rel_error) +
                         " (relative)");
  return r;
}

}  // namespace vgd::mesh
