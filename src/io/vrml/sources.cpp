// Garments from a trajectory or from a drape's OBJ (sources.hpp).
#include "vgd/io/vrml/sources.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <map>
#include <sstream>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"

namespace vgd::io::vrml {

Garment garment_from_trajectory(const trj::Trajectory& t, const std::string& name) {
  const auto& topo = t.topology;
  if (t.frames.empty()) throw Error(name, "", "the trajectory has no frame");
  if (topo.uv.size() != static_cast<std::size_t>(topo.num_particles))
    throw Error(name, "", "the trajectory has no material coordinates (uv) for its " +
                              std::to_string(topo.num_particles) + " particles");
  Garment g;
  g.name = name;
  g.cloth.triangles = topo.triangles;
  g.cloth.triangle_piece = topo.triangle_piece;
  g.cloth.pieces = topo.pieces;
  if (g.cloth.pieces.empty() && !g.cloth.triangle_piece.empty()) g.cloth.triangle_piece.clear();
  g.cloth.uv = topo.uv;
  if (!topo.merges.empty()) g.cloth.representative = topo.representatives(t.frame_count() - 1);
  g.frames.times = t.times;
  g.frames.positions = t.frames;
  g.validate();
  return g;
}

Garment garment_from_obj(const std::filesystem::path& file) {
  std::istringstream in(read_file(file));
  Garment g;
  g.name = file.stem().string();
  std::vector<std::array<double, 3>> v;
  std::string line;
  int lineno = 0;
  int piece = -1;
  auto fail = [&](const std::string& msg) { throw Error(file.string(), "", msg, lineno); };
  while (std::getline(in, line)) {
    ++lineno;
    std::istringstream ls{std::string(trim(line))};
    std::string key;
    ls >> key;
    if (key == "v") {
      std::array<double, 3> p{};
      if (!(ls >> p[0] >> p[1] >> p[2])) fail("a vertex needs x y z");
      v.push_back(p);
    } else if (key == "g" || key == "o") {
      std::string n;
      ls >> n;
      g.cloth.pieces.push_back(n.empty() ? "piece" + std::to_string(g.cloth.pieces.size() + 1) : n);
      piece = static_cast<int>(g.cloth.pieces.size()) - 1;
    } else if (key == "f") {
      std::vector<int> idx;
      std::string w;
      while (ls >> w) {
        const auto i = parse_int(split(w, '/').front());
        if (!i || *i == 0) fail("'" + w + "' is not a vertex index");
        const long long k = *i > 0 ? *i - 1 : static_cast<long long>(v.size()) + *i;
        if (k < 0 || k >= static_cast<long long>(v.size())) fail("vertex index " + w + " is out of range");
        idx.push_back(static_cast<int>(k));
      }
      if (idx.size() < 3) fail("a face needs three vertices");
      if (piece < 0) g.cloth.pieces.push_back("cloth"), piece = 0;
      for (std::size_t k = 1; k + 1 < idx.size(); ++k) {  // fans for polygons
        g.cloth.triangles.push_back({idx[0], idx[k], idx[k + 1]});
        g.cloth.triangle_piece.push_back(piece);
      }
    }
  }
  if (g.cloth.triangles.empty()) throw Error(file.string(), "", "no faces: not a garment");

  // Each piece's vertices: a copy per piece (a vertex shared by two pieces is a closed seam).
  const int np = static_cast<int>(g.cloth.pieces.size());
  std::vector<std::map<int, int>> copy(np);
  std::vector<int> source;
  for (std::size_t t = 0; t < g.cloth.triangles.size(); ++t)
    for (int& k : g.cloth.triangles[t]) {
      auto [it, fresh] = copy[g.cloth.triangle_piece[t]].try_emplace(k, static_cast<int>(source.size()));
      if (fresh) source.push_back(k);
      k = it->second;
    }
  const int n = static_cast<int>(source.size());
  std::vector<float> x(3 * static_cast<std::size_t>(n));
  // Vertices at one place (to 1 µm) are one particle: a shared OBJ vertex, or the
  // copies of a merged seam that vgd drape writes at the same position.
  std::map<std::array<long long, 3>, int> first;
  g.cloth.representative.resize(n);
  for (int i = 0; i < n; ++i) {
    std::array<long long, 3> key{};
    for (int c = 0; c < 3; ++c) {
      x[3 * i + c] = static_cast<float>(v[source[i]][c]);
      key[c] = std::llround(v[source[i]][c] * 1e6);
    }
    g.cloth.representative[i] = first.try_emplace(key, i).first->second;
  }
  // Material coordinates: the projection on each piece's best-fitting plane.
  g.cloth.uv.assign(n, {0.0, 0.0});
  for (int p = 0; p < np; ++p) {
    if (copy[p].empty()) continue;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const auto& [obj, i] : copy[p]) c += Eigen::Vector3d(v[obj][0], v[obj][1], v[obj][2]);
    c /= static_cast<double>(copy[p].size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& [obj, i] : copy[p]) {
      const Eigen::Vector3d d = Eigen::Vector3d(v[obj][0], v[obj][1], v[obj][2]) - c;
      cov += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
    Eigen::Vector3d a = es.eigenvectors().col(2), b = es.eigenvectors().col(1);  // the two largest
    if (std::abs(b.y()) > std::abs(a.y())) std::swap(a, b);                      // u: the more vertical
    if (a.y() > 0) a = -a;                                                        // u grows downwards, like a grain from the waist
    for (const auto& [obj, i] : copy[p]) {
      const Eigen::Vector3d d = Eigen::Vector3d(v[obj][0], v[obj][1], v[obj][2]) - c;
      g.cloth.uv[i] = {d.dot(a), d.dot(b)};
    }
  }
  g.frames.times = {0.0};
  g.frames.positions = {std::move(x)};
  g.validate();
  return g;
}

}  // namespace vgd::io::vrml
