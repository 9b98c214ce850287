// Building a scene: materials resolved, pieces meshed and placed, masses
// lumped, exactly the listed effects constructed, the system assembled.
#include "vgd/scene/build.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>

#include "vgd/core/strings.hpp"
#include "vgd/mesh/mesh.hpp"
#include "vgd/sim/sdf.hpp"
#include "vgd/sim/effects/basic.hpp"
#include "vgd/sim/effects/bending.hpp"
#include "vgd/sim/effects/mass_spring.hpp"
#include "vgd/sim/effects/seam.hpp"
#include "vgd/sim/effects/strain_limit.hpp"
#include "vgd/sim/effects/strain_rosette.hpp"
#include "vgd/xvc/document.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/style.hpp"

namespace vgd::scene {

bool model_available(ClothModel m) {
  switch (m) {
    case ClothModel::mass_spring: return true;
    case ClothModel::strain_rosette: return true;
  }
  return false;
}

namespace {

namespace fs = std::filesystem;
using sim::Vec2;

std::string cloth_path(int i) { return "cloth[" + std::to_string(i) + "]"; }

// The JSON path of a material table entry (inline materials are kept under
// their own path, e.g. "cloth[0].material").
std::string material_path(const std::string& key) {
  return key.find('.') == std::string::npos ? "materials." + key : key;
}

fs::path resolve(const SceneDef& def, const fs::path& p) { return resolve_path(def, p); }

// Why a material cannot drive a cloth model ("" when it can).
std::string model_problem(const MaterialDef& m, ClothModel model) {
  return model == ClothModel::mass_spring ? mass_spring_problem(m) : orthotropic_problem(m);
}

// Everything read from other files, read once.
class Inputs {
 public:
  explicit Inputs(const SceneDef& def) : def_(def) {}

  const xvc::Document& document(const fs::path& given, const std::string& path) {
    const fs::path file = resolve(def_, given);
    auto it = docs_.find(file.string());
    if (it != docs_.end()) return it->second;
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
      throw Error(def_.source.string(), path, "cannot read the XVC document " + file.string() + " (no such file)");
    return docs_.emplace(file.string(), xvc::load_file(file)).first->second;
  }

  const MaterialDef& material(const std::string& key, ClothModel model) {
    auto it = materials_.find(key);
    if (it == materials_.end()) {
      const MaterialSource& src = def_.materials.at(key);
      MaterialDef m = src.values;
      if (!src.xvc.empty()) {
        const auto& doc = document(src.xvc, material_path(key) + ".xvc");
        m = material_from_xvc(doc, src.id, resolve(def_, src.xvc).string());
      }
      if (m.name.empty()) m.name = key;
      it = materials_.emplace(key, std::move(m)).first;
    }
    // What the model needs, named where the material came from.
    const MaterialSource& src = def_.materials.at(key);
    if (const std::string problem = model_problem(it->second, model); !problem.empty()) {
      if (!src.xvc.empty())
        throw Error(resolve(def_, src.xvc).string(), "MATERIAL " + src.id,
                    std::string("cannot be used with the ") + to_string(model) + " model: " + problem);
      throw Error(def_.source.string(), material_path(key),
                  std::string("cannot be used with the ") + to_string(model) + " model: " + problem);
    }
    return it->second;
  }

  // A MATERIAL of an XVC document (a piece's own fabric in its garment).
  const MaterialDef& xvc_material(const fs::path& given, const std::string& id, ClothModel model,
                                  const std::string& path) {
    const fs::path file = resolve(def_, given);
    const std::string key = file.string() + "#" + id;
    auto it = materials_.find(key);
    if (it == materials_.end()) it = materials_.emplace(key, material_from_xvc(document(given, path), id, file.string())).first;
    if (const std::string problem = model_problem(it->second, model); !problem.empty())
      throw Error(file.string(), "MATERIAL " + id, std::string("cannot be used with the ") + to_string(model) + " model: " + problem);
    return it->second;
  }

 private:
  const SceneDef& def_;
  std::map<std::string, xvc::Document> docs_;
  std::map<std::string, MaterialDef> materials_;
};

// The cloth's plane: unit u and unit v orthogonal to it.
std::pair<Vec3, Vec3> plane(const Placement& p) {
  const Vec3 u = p.u.normalized();
  const Vec3 v = (p.v - p.v.dot(u) * u).normalized();
  return {u, v};
}

// Appends a piece (particles, triangles, masses) to the model.
void append(sim::Model& model, const sim::Model& piece, int piece_index) {
  const int n0 = model.num_particles(), n = piece.num_particles();
  auto grow = [](sim::VecX& a, const sim::VecX& b) {
    sim::VecX c(a.size() + b.size());
    c << a, b;
    a.swap(c);
  };
  grow(model.x0, piece.x0);
  grow(model.v0, piece.v0);
  grow(model.mass, piece.mass);
  model.uv.insert(model.uv.end(), piece.uv.begin(), piece.uv.end());
  for (const auto& t : piece.triangles) {
    model.triangles.push_back({t[0] + n0, t[1] + n0, t[2] + n0});
    model.triangle_piece.push_back(piece_index);
  }
  (void)n;
}

// Masses of one piece: the mass-spring particle mass, else area x density.
void set_masses(sim::Model& piece, const MaterialDef& m, ClothModel model) {
  if (model == ClothModel::mass_spring && m.particle_mass > 0.0) {
    piece.mass = sim::VecX::Constant(static_cast<Eigen::Index>(piece.uv.size()), m.particle_mass);
  } else {
    piece.mass = sim::lump_masses(piece.uv, piece.triangles, m.density);
  }
}

// A grid piece.
sim::Model grid_piece(const ClothDef& c, const MaterialDef& m) {
  const auto& g = *c.grid;
  const auto [u, v] = plane(c.placement);
  sim::Model p = sim::make_grid(g.nu, g.nv, g.width / (g.nu - 1), g.height / (g.nv - 1), c.placement.origin, u, v, 1.0);
  set_masses(p, m, c.model);
  return p;
}

// The pieces an XVC cloth entry names, meshed and laid flat.
std::vector<std::pair<std::string, sim::Model>> xvc_pieces(const SceneDef& def, int ci, Inputs& in,
                                                           const MaterialDef& m, Diagnostics& diag) {
  const ClothDef& c = def.cloth[ci];
  const XvcPiecesDef& x = *c.xvc;
  const std::string p = cloth_path(ci) + ".xvc";
  const fs::path file = resolve(def, x.file);
  const auto& doc = in.document(x.file, p + ".file");
  const pattern::Style style = xvc::to_style(doc);

  // The size, then the pieces of that size.
  std::string size = x.size.empty() ? style.sample_size : x.size;
  if (size.empty() && !style.sizes.empty()) size = style.sizes.front();
  auto pieces = style.pieces_of_size(size);
  if (pieces.empty()) {
    std::string sizes;
    for (const auto& s : style.sizes) sizes += (sizes.empty() ? "" : ", ") + s;
    throw Error(def.source.string(), p + ".size",
                "the document " + file.string() + " has no piece in size '" + size + "'" +
                    (sizes.empty() ? "" : " (sizes: " + sizes + ")"));
  }
  if (!x.pieces.empty()) {
    std::vector<const pattern::Piece*> chosen;
    for (std::size_t k = 0; k < x.pieces.size(); ++k) {
      const auto it = std::find_if(pieces.begin(), pieces.end(), [&](const pattern::Piece* q) {
        return q->name == x.pieces[k] || q->block == x.pieces[k];
      });
      if (it == pieces.end()) {
        std::string names;
        for (const auto* q : pieces) names += (names.empty() ? "" : ", ") + q->name;
        throw Error(def.source.string(), p + ".pieces[" + std::to_string(k) + "]",
                    "no piece or block '" + x.pieces[k] + "' in size '" + size + "' of " + file.string() +
                        " (pieces: " + names + ")");
      }
      chosen.push_back(*it);
    }
    pieces = chosen;
  }

  // Mesh options: the scene's, else the document's, else the mesher's defaults.
  mesh::MeshOptions opt;
  if (const auto v = xvc::get_parameter(doc, "mesh.spacing")) opt.resample.spacing_m = *v;
  if (const auto v = xvc::get_parameter(doc, "mesh.turn_angle")) opt.resample.turn_angle_deg = *v;
  if (const auto v = xvc::get_parameter(doc, "mesh.min_angle")) opt.min_angle_deg = *v;
  if (const auto v = xvc::get_parameter(doc, "mesh.max_area")) opt.max_area_m2 = *v;
  if (x.spacing > 0.0) {
    opt.resample.spacing_m = x.spacing;
    opt.max_area_m2 = 0.0;  // follows the spacing
  }
  if (x.min_angle > 0.0) opt.min_angle_deg = x.min_angle;

  const auto [u, v] = plane(c.placement);
  std::vector<std::pair<std::string, sim::Model>> out;
  double cursor = 0.0;
  for (const auto* piece : pieces) {
    mesh::PieceMesh pm;
    try {
      const std::size_t said = diag.items().size();
      pm = mesh::mesh_piece(*piece, opt, diag);
      diag.name_file(file.string(), said);
    } catch (const Error& e) {
      throw Error(file.string(), piece->block, "cannot mesh the piece for " + cloth_path(ci) + ": " +
                                                   e.diagnostic().message);
    }
    // Lay it flat: pattern (x, y) -> origin + (x + dx) u + (y + dy) v.
    Vec2 shift = Vec2::Zero();
    if (x.layout == Layout::row) {
      Vec2 lo = pm.nodes.front(), hi = pm.nodes.front();
      for (const auto& q : pm.nodes) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
      shift = Vec2(cursor - lo.x(), -lo.y());
      cursor += hi.x() - lo.x() + x.gap;
    }
    sim::Model mp;
    const int n = static_cast<int>(pm.nodes.size());
    mp.x0.resize(3 * n);
    mp.v0 = sim::VecX::Zero(3 * n);
    for (int i = 0; i < n; ++i) {
      const Vec2 q = pm.nodes[i] + shift;
      sim::at(mp.x0, i) = c.placement.origin + q.x() * u + q.y() * v;
    }
    mp.uv = mesh::material_coordinates(pm);
    mp.triangles = pm.triangles;
    set_masses(mp, m, c.model);
    out.emplace_back(piece->block.empty() ? piece->name : piece->block, std::move(mp));
  }
  return out;
}

// A grid's named particle set (indices within the piece), or nullopt when
// the name is not one.
std::optional<std::vector<int>> grid_set(const PieceInfo& p, const std::string& name) {
  const int nu = p.nu, nv = p.nv;
  std::vector<int> s;
  auto idx = [&](int i, int j) { return j * nu + i; };
  if (name == "all") {
    for (int k = 0; k < p.count; ++k) s.push_back(k);
    return s;
  }
  if (nu == 0) return std::nullopt;  // the rest are grid sets
  if (name == "corner-u0v0") return std::vector<int>{idx(0, 0)};
  if (name == "corner-u1v0") return std::vector<int>{idx(nu - 1, 0)};
  if (name == "corner-u0v1") return std::vector<int>{idx(0, nv - 1)};
  if (name == "corner-u1v1") return std::vector<int>{idx(nu - 1, nv - 1)};
  if (name == "corners") return std::vector<int>{idx(0, 0), idx(nu - 1, 0), idx(0, nv - 1), idx(nu - 1, nv - 1)};
  if (name == "edge-u0" || name == "edge-u1") {
    for (int j = 0; j < nv; ++j) s.push_back(idx(name == "edge-u0" ? 0 : nu - 1, j));
    return s;
  }
  if (name == "edge-v0" || name == "edge-v1") {
    for (int i = 0; i < nu; ++i) s.push_back(idx(i, name == "edge-v0" ? 0 : nv - 1));
    return s;
  }
  for (const char* prefix : {"row-", "column-"}) {
    const std::string pre = prefix;
    if (name.rfind(pre, 0) != 0) continue;
    const auto k = parse_int(name.substr(pre.size()));
    const int limit = pre == "row-" ? nv : nu;
    if (!k || *k < 0 || *k >= limit) return std::nullopt;
    if (pre == "row-")
      for (int i = 0; i < nu; ++i) s.push_back(idx(i, static_cast<int>(*k)));
    else
      for (int j = 0; j < nv; ++j) s.push_back(idx(static_cast<int>(*k), j));
    return s;
  }
  return std::nullopt;
}

}  // namespace

fs::path resolve_path(const SceneDef& def, const fs::path& p) {
  if (p.is_absolute() || def.source.empty()) return p;
  return def.source.parent_path() / p;
}

sim::Model build_model(const SceneDef& def, std::vector<PieceInfo>& pieces, Diagnostics& diag, const MadeCloths& made,
                       std::vector<sim::SeamPairs>* seams) {
  Inputs in(def);
  sim::Model model;
  model.x0.resize(0);
  model.v0.resize(0);
  model.mass.resize(0);
  pieces.clear();
  for (int ci = 0; ci < static_cast<int>(def.cloth.size()); ++ci) {
    const ClothDef& c = def.cloth[ci];
    const MaterialDef& m = in.material(c.material, c.model);
    std::vector<std::pair<std::string, sim::Model>> parts;
    std::vector<std::string> segments;  // per part, made cloth only
    std::vector<double> raised;         // per part, made cloth only (MadePiece::raised)
    std::vector<int> face_layers;       // per part, made cloth only (MadePiece::face_layer)
    std::vector<const MaterialDef*> own;  // per part, made cloth only: a piece's own fabric, else nullptr
    std::deque<MaterialDef> layers_of;    // the fabrics of pieces in several layers (MadePiece::layers)
    const MadeCloth* mine = nullptr;
    if (c.grid) {
      parts.emplace_back(c.name.empty() ? cloth_path(ci) : c.name, grid_piece(c, m));
    } else if (c.xvc) {
      parts = xvc_pieces(def, ci, in, m, diag);
    } else {
      const auto it = made.find(ci);
      if (it == made.end())
        throw Error(def.source.string(), cloth_path(ci) + ".garment",
                    "a garment is dressed on the body before the scene is built (dress::build, not scene::build)");
      mine = &it->second;
      diag.append(mine->diagnostics);
      for (const auto& piece : mine->pieces) {
        const MaterialDef* pm = piece.material.empty()
                                    ? nullptr
                                    : &in.xvc_material(c.garment->file, piece.material, c.model, cloth_path(ci) + ".garment.file");
        if (piece.layers > 1) pm = &layers_of.emplace_back(layered(pm ? *pm : m, piece.layers));
        sim::Model mp = piece.model;
        set_masses(mp, pm ? *pm : m, c.model);
        parts.emplace_back(piece.name, std::move(mp));
        segments.push_back(piece.segment);
        raised.push_back(piece.raised);
        face_layers.push_back(piece.face_layer);
        own.push_back(pm);
      }
    }
    const int first_piece = static_cast<int>(pieces.size());
    for (std::size_t k = 0; k < parts.size(); ++k) {
      auto& [name, part] = parts[k];
      PieceInfo info;
      info.name = name;
      if (k < segments.size()) info.segment = segments[k];
      if (k < raised.size()) info.raised = raised[k];
      if (k < face_layers.size()) info.face_layer = face_layers[k];
      info.cloth = ci;
      info.first = model.num_particles();
      info.count = part.num_particles();
      info.first_triangle = static_cast<int>(model.triangles.size());
      info.triangles = static_cast<int>(part.triangles.size());
      if (c.grid) info.nu = c.grid->nu, info.nv = c.grid->nv;
      info.model = c.model;
      info.material = k < own.size() && own[k] ? *own[k] : m;
      append(model, part, static_cast<int>(pieces.size()));
      model.pieces.push_back(name);
      pieces.push_back(std::move(info));
    }
    if (seams && mine && !mine->pieces.empty()) {
      const int first = pieces[first_piece].first;
      const int base = static_cast<int>(seams->size());
      for (const auto& ms : mine->seams) {
        sim::SeamPairs sp;
        sp.name = ms.name;
        for (const auto& [a, b] : ms.pairs) sp.pairs.push_back({first + a, first + b});
        for (const int w : ms.after) sp.after.push_back(base + w);
        seams->push_back(std::move(sp));
      }
    }
  }
  return model;
}

std::vector<int> pin_particles(const SceneDef& def, const sim::Model& model, const std::vector<PieceInfo>& pieces,
                               const PinGroupDef& g, const std::string& path) {
  const std::string file = def.source.string();
  // The piece the group talks about: by piece name, piece (pattern) name or cloth name.
  const PieceInfo* piece = nullptr;
  if (!g.piece.empty()) {
    std::vector<const PieceInfo*> match;
    for (const auto& p : pieces)
      if (p.name == g.piece) match.push_back(&p);
    if (match.empty())
      for (const auto& p : pieces)
        if (def.cloth[p.cloth].name == g.piece) match.push_back(&p);
    if (match.empty()) {
      std::string names;
      for (const auto& p : pieces) names += (names.empty() ? "" : ", ") + p.name;
      throw Error(file, path + ".piece", "no piece called '" + g.piece + "' (pieces: " + names + ")");
    }
    if (match.size() > 1 && (!g.particles.empty() || !g.sets.empty()))
      throw Error(file, path + ".piece", "'" + g.piece + "' is " + std::to_string(match.size()) +
                                             " pieces; name one of them by its block name");
    piece = match.front();
    if (match.size() > 1) piece = nullptr;  // a region over a multi-piece cloth: filtered below
  } else if ((!g.particles.empty() || !g.sets.empty())) {
    if (pieces.size() > 1)
      throw Error(file, path + ".piece",
                  "the scene has " + std::to_string(pieces.size()) + " pieces; say which one the particles are of");
    piece = &pieces.front();
  }

  std::vector<int> out;
  for (std::size_t k = 0; k < g.particles.size(); ++k) {
    const int i = g.particles[k];
    if (i < 0 || i >= piece->count)
      throw Error(file, path + ".particles[" + std::to_string(k) + "]",
                  "particle " + std::to_string(i) + " is out of range: piece '" + piece->name + "' has " +
                      std::to_string(piece->count) + " particles (0.." + std::to_string(piece->count - 1) + ")");
    out.push_back(piece->first + i);
  }
  for (std::size_t k = 0; k < g.sets.size(); ++k) {
    const auto s = grid_set(*piece, g.sets[k]);
    if (!s)
      throw Error(file, path + ".sets[" + std::to_string(k) + "]",
                  "unknown particle set '" + g.sets[k] + "' for piece '" + piece->name + "' (" +
                      (piece->nu > 0 ? "a grid has all, corners, corner-u0v0, corner-u1v0, corner-u0v1, corner-u1v1, "
                                       "edge-u0, edge-u1, edge-v0, edge-v1, row-J (0.." +
                                           std::to_string(piece->nv - 1) + "), column-I (0.." +
                                           std::to_string(piece->nu - 1) + ")"
                                     : "a meshed piece has only all; use a region") +
                      ")");
    for (int i : *s) out.push_back(piece->first + i);
  }
  if (g.region) {
    const double tol = 1e-9;
    for (const auto& p : pieces) {
      if (!g.piece.empty() && p.name != g.piece && def.cloth[p.cloth].name != g.piece) continue;
      for (int i = p.first; i < p.first + p.count; ++i) {
        const Vec3 x = sim::at(model.x0, i);
        if ((x - g.region->min).minCoeff() >= -tol && (g.region->max - x).minCoeff() >= -tol) out.push_back(i);
      }
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  if (out.empty()) throw Error(file, path + (g.region ? ".region" : ""), "the pin group holds no particle");
  return out;
}

namespace {

// A seam between two grid sets, paired in order.
sim::SeamPairs grid_seam(const SceneDef& def, const sim::Model& model, const std::vector<PieceInfo>& pieces,
                         const GridSeamDef& g, const std::string& path) {
  const auto side = [&](const std::string& piece, const std::string& set, const std::string& key) {
    // Not pin_particles: it sorts, and a seam needs the set's own order.
    const auto it = std::find_if(pieces.begin(), pieces.end(), [&](const PieceInfo& p) { return p.name == piece; });
    if (it == pieces.end()) throw Error(def.source.string(), path + "." + key + ".piece", "no piece called '" + piece + "'");
    const auto local = grid_set(*it, set);
    if (!local) throw Error(def.source.string(), path + "." + key + ".set", "unknown grid set '" + set + "'");
    std::vector<int> out;
    for (int i : *local) out.push_back(it->first + i);
    return out;
  };
  const std::vector<int> a = side(g.piece_a, g.set_a, "a");
  std::vector<int> b = side(g.piece_b, g.set_b, "b");
  if (g.reverse) std::reverse(b.begin(), b.end());
  if (a.size() != b.size())
    throw Error(def.source.string(), path, "the two sets hold " + std::to_string(a.size()) + " and " +
                                               std::to_string(b.size()) + " particles; a seam pairs them one to one");
  sim::SeamPairs sp;
  sp.name = g.piece_a + ":" + g.set_a + " - " + g.piece_b + ":" + g.set_b;
  for (std::size_t k = 0; k < a.size(); ++k) sp.pairs.push_back({a[k], b[k]});
  (void)model;
  return sp;
}

}  // namespace

std::vector<std::string> effect_names(const SceneDef& def) {
  std::vector<std::string> names;
  bool ms = false, sr = false, bend = false;
  for (const auto& c : def.cloth) {
    ms = ms || c.model == ClothModel::mass_spring;
    sr = sr || c.model == ClothModel::strain_rosette;
    bend = bend || (c.model == ClothModel::strain_rosette && c.bending);
  }
  if (ms) names.push_back("mass-spring");
  if (sr) names.push_back("strain-rosette");
  if (bend) names.push_back("bending");
  // The yarns' lock of a fabric given by value (a fabric read from an XVC
  // document is known when the scene is built).
  for (const auto& c : def.cloth)
    if (const auto m = def.materials.find(c.material);
        m != def.materials.end() && m->second.xvc.empty() && m->second.values.strain_limit > 0.0) {
      names.push_back("strain-limit");
      break;
    }
  const auto& e = def.effects;
  if (e.gravity) names.push_back("gravity");
  if (e.viscosity) names.push_back("viscosity");
  if (e.damping) names.push_back("damping");
  if (e.wind) names.push_back("wind");
  for (std::size_t i = 0; i < e.pins.size(); ++i) names.push_back("pins");
  if (e.seams) names.push_back("seams");
  if (e.collision) names.push_back("body-collision");
  if (e.self_collision) names.push_back("self-collision");
  if (e.contact) names.push_back("contact");
  if (e.hand) names.push_back("hand");
  return names;
}

// Moves every free particle closer than `gap` to the body (or inside it) to
// `gap` out along the body's normal at its closest point (exact, TriangleBvh).
// Returns how many moved.
static int start_outside(sim::Model& model, const mesh::SurfaceMesh& body, double gap, const std::vector<int>& pinned) {
  const sim::TriangleBvh bvh(body);
  int moved = 0;
  for (int i = 0; i < model.num_particles(); ++i) {
    if (std::binary_search(pinned.begin(), pinned.end(), i)) continue;
    const auto c = bvh.closest(sim::at(model.x0, i), 0.1);  // deep inside a limb too
    if (!(c.distance < gap)) continue;
    sim::at(model.x0, i) = c.point + gap * c.normal.normalized();
    ++moved;
  }
  return moved;
}

Scene build(const SceneDef& def) {
  validate(def);
  return build(def, def.avatar ? std::optional<body::Avatar>(build_avatar(def)) : std::nullopt, {});
}

Scene build(const SceneDef& def, std::optional<body::Avatar> avatar, const MadeCloths& made) {
  validate(def);
  Scene s;
  s.name = def.name;
  s.avatar = std::move(avatar);
  sim::Model model = build_model(def, s.pieces, s.diagnostics, made, &s.seams);
  if (def.effects.seams)
    for (std::size_t i = 0; i < def.effects.seams->grid.size(); ++i)
      s.seams.push_back(grid_seam(def, model, s.pieces, def.effects.seams->grid[i],
                                  "effects.seams.grid[" + std::to_string(i) + "]"));

  // Pins first: the strain limiter must know which particles it may not move.
  std::vector<std::vector<int>> pin_groups;
  for (std::size_t i = 0; i < def.effects.pins.size(); ++i) {
    pin_groups.push_back(
        pin_particles(def, model, s.pieces, def.effects.pins[i], "effects.pins[" + std::to_string(i) + "]"));
    s.pinned.insert(s.pinned.end(), pin_groups.back().begin(), pin_groups.back().end());
  }
  // The garments' own pins (POSITION type="pin"): one still group.
  std::vector<int> document_pins;
  for (const auto& [ci, cloth] : made) {
    int k = 0;
    for (const auto& info : s.pieces) {
      if (info.cloth != ci) continue;
      if (k < static_cast<int>(cloth.pieces.size()))
        for (const auto& [i, id] : cloth.pieces[k].pinned) document_pins.push_back(info.first + i);
      ++k;
    }
  }
  std::sort(document_pins.begin(), document_pins.end());
  document_pins.erase(std::unique(document_pins.begin(), document_pins.end()), document_pins.end());
  s.pinned.insert(s.pinned.end(), document_pins.begin(), document_pins.end());
  std::sort(s.pinned.begin(), s.pinned.end());
  s.pinned.erase(std::unique(s.pinned.begin(), s.pinned.end()), s.pinned.end());
  // Offset contact keeps the start's relations (nothing through anything) and
  // cannot undo one: cloth the arrangement put inside the body or within the
  // contact radius of it starts outside it.
  if (def.effects.contact && s.avatar) start_outside(model, s.avatar->surface, 1.5 * def.effects.contact->radius, s.pinned);

  // The effects the scene lists, each constructed only when listed.
  std::vector<std::unique_ptr<sim::Effect>> effects;
  const auto uses = [&](ClothModel m) {
    return std::any_of(s.pieces.begin(), s.pieces.end(), [&](const PieceInfo& p) { return p.model == m; });
  };
  try {
    // One cloth model for all pieces (validate() refuses a mix: the engine's
    // fabric effects act on every piece of the model).
    if (uses(ClothModel::mass_spring)) {
      std::vector<sim::MassSpringMaterial> per_piece;
      for (const auto& p : s.pieces) per_piece.push_back(*p.material.mass_spring);
      sim::MassSpringOptions opt;
      opt.fixed = s.pinned;
      effects.push_back(sim::make_mass_spring(model, per_piece, opt));
    }
    if (uses(ClothModel::strain_rosette)) {
      std::vector<sim::OrthotropicMaterial> per_piece;
      for (const auto& p : s.pieces) per_piece.push_back(orthotropic_of(p.material));
      // Against a body (drapes, the contact cases) cloth is compressed as a
      // matter of course: implicit steps take the Jacobians made definite
      // (docs/fabric-model.md, 4a). Free cloth (flags, hanging cloth, the
      // accuracy studies) keeps the exact ones, and Newton's convergence.
      const bool definite = def.avatar.has_value();
      sim::RosetteOptions ro;
      ro.definite_jacobian = definite;
      effects.push_back(sim::make_strain_rosette(model, per_piece, ro));
      sim::BendingOptions bo;
      bo.definite_jacobian = definite;
      if (def.cloth.front().bending) effects.push_back(sim::make_bending(model, per_piece, bo));
    }
    // The yarns' lock, where a fabric states one: after the cloth model's own
    // hooks, before seams and contacts, which have the last word.
    if (std::any_of(s.pieces.begin(), s.pieces.end(), [](const PieceInfo& p) { return p.material.strain_limit > 0.0; })) {
      sim::StrainLimitDef sl;
      for (const auto& p : s.pieces) sl.limit.push_back(p.material.strain_limit);
      sl.fixed = s.pinned;
      effects.push_back(sim::make_strain_limit(model, sl));
    }
    const auto& e = def.effects;
    if (e.gravity) effects.push_back(sim::make_gravity(*e.gravity));
    if (e.viscosity) effects.push_back(sim::make_viscosity(*e.viscosity));
    if (e.damping) effects.push_back(sim::make_damping(model, *e.damping));
    if (e.wind) effects.push_back(sim::make_wind(*e.wind));
    if (e.hand) effects.push_back(sim::make_hand(*e.hand));
    for (std::size_t i = 0; i < pin_groups.size(); ++i)
      effects.push_back(sim::make_pins(model, {pin_groups[i], e.pins[i].velocity}));
    if (!document_pins.empty()) effects.push_back(sim::make_pins(model, {document_pins, Vec3::Zero()}));
    // The speed limit before the contacts, so their tests see limited motion.
    if (e.speed_limit) effects.push_back(sim::make_speed_limit(model, *e.speed_limit));
    // Seams, then contacts: the contact effects constrain the total force,
    // seams' pull included (seed 002 §3.2.2).
    std::vector<int> seam_particles;
    if (e.seams && !s.seams.empty()) {
      sim::SeamDef sd = e.seams->effect;
      sd.seams = s.seams;
      for (const auto& sp : sd.seams)
        for (const auto& pr : sp.pairs) seam_particles.insert(seam_particles.end(), pr.begin(), pr.end());
      effects.push_back(sim::make_seam(model, sd));
    }
    // Self-collision before the body: its corrections move particles, and the
    // body's projection after it has the last word (no particle left inside).
    // The body's effect is made first: layered self-collision reads its grid.
    std::unique_ptr<sim::Effect> body;
    if (e.collision) {
      sim::BodyCollisionDef cd = *e.collision;
      cd.body = s.avatar->surface;
      if (e.collision_seam_response != "body") cd.seam_particles = seam_particles;
      cd.seam_contact = e.collision_seam_response == "seed"    ? sim::SeamContact::seed
                        : e.collision_seam_response == "slide" ? sim::SeamContact::slide
                                                               : sim::SeamContact::glide;
      cd.fixed = s.pinned;
      body = sim::make_body_collision(model, cd);
    }
    if (e.self_collision) {
      sim::SelfCollisionDef sc = *e.self_collision;
      sc.fixed = s.pinned;
      for (const auto& sp : s.seams) sc.joined.insert(sc.joined.end(), sp.pairs.begin(), sp.pairs.end());
      // Garments worn over others keep the body's order (layer 0 innermost).
      // The order comes from the body's distance grid: with the exact (BVH)
      // query there is none, and layers stay off.
      const sim::SignedDistanceGrid* grid = body ? sim::body_collision_grid(*body) : nullptr;
      // Every garment: the corrections never leave cloth inside the body
      // (self_collision.cpp, out_of_body). The grid is in the body's frame,
      // so a moving body keeps only its own push.
      if (grid && e.collision->velocity == Vec3::Zero()) sc.body = grid;
      // A piece sewn onto another's face (a pocket) is a layer over its
      // garment's: each garment's layer holds kFaceLayers of them.
      constexpr int kFaceLayers = 3;
      if (grid && std::any_of(s.pieces.begin(), s.pieces.end(), [&](const PieceInfo& p) {
            const auto& g = def.cloth[p.cloth].garment;
            return (g && g->layer != 0) || p.face_layer != 0;
          })) {
        // The layers' order is read from the grid where the body is at rest.
        if (e.collision->velocity != Vec3::Zero())
          throw Error(def.source.string(), "effects.collision.body_velocity",
                      "garments in layers need a body at rest (the layers' order comes from its distance grid)");
        sc.body = grid;
        sc.held_distance = 1.5 * e.collision->clearance;
        sc.layer.assign(model.num_particles(), 0);
        for (const auto& p : s.pieces)
          if (const auto& g = def.cloth[p.cloth].garment)
            std::fill_n(sc.layer.begin() + p.first, p.count, kFaceLayers * g->layer + std::min(p.face_layer, kFaceLayers - 1));
      }
      // The body's push comes first: it moves cloth after the step as well,
      // and after self-collision it pushed cloth through cloth in creases
      // (an armpit) unseen (T-shirt: 7 crossing pairs at rest, 0 with this
      // order; before, self-collision projected out of the body itself
      // between its rounds, which tore the T-shirt's sleeve over a skirt).
      if (body) effects.push_back(std::move(body));
      effects.push_back(sim::make_self_collision(model, sc));
    }
    if (body) effects.push_back(std::move(body));
    // Offset contact last: its bounds cut the step's whole move, every other
    // after-step change included.
    if (e.contact) {
      sim::ContactDef cd = *e.contact;
      cd.body = s.avatar->surface;
      cd.fixed = s.pinned;
      for (const auto& sp : s.seams) cd.sewn.insert(cd.sewn.end(), sp.pairs.begin(), sp.pairs.end());
      effects.push_back(sim::make_contact(model, cd));
    }
    s.system = std::make_unique<sim::System>(std::move(model), std::move(effects));
  } catch (const sim::SimulationError& err) {
    throw Error(def.source.string(), "", std::string("cannot build the simulation: ") + err.what());
  }

  s.integrator = def.integrator.settings;
  s.integrator.step = effective_step(def);
  s.run = def.run;
  s.outputs = def.outputs;
  return s;
}

}  // namespace vgd::scene
