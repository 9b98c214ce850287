// The final drape as glTF 2.0 binary and as OBJ + MTL (gltf.hpp).
#include "vgd/io/vrml/gltf.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>

#include "text.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/io/vrml/vrml.hpp"

namespace vgd::io::vrml {

namespace {

int resolve(const Garment& g, int frame) {
  if (frame < 0) frame = g.frames.count() - 1;
  if (frame >= g.frames.count()) throw Error(g.name, "", "frame " + std::to_string(frame) + " does not exist");
  return frame;
}

// A piece's own vertices (glTF attributes are per vertex): the particles its
// faces use, each with its welded position and normal and its own uv.
struct PiecePrimitive {
  std::vector<float> position, normal, texcoord;
  std::vector<std::uint32_t> indices;
};

PiecePrimitive piece_primitive(const Garment& g, const OutputMesh& mesh, int piece, const std::vector<float>& x,
                               const std::vector<std::array<double, 3>>& nrm) {
  PiecePrimitive p;
  const PieceLook& look = g.look(piece);
  const bool textured = !look.texture.empty();
  const double rot = look.rotation_deg * M_PI / 180.0, cr = std::cos(rot), sr = std::sin(rot);
  std::map<int, std::uint32_t> local;  // particle -> vertex of this primitive
  const auto& faces = mesh.pieces[piece];
  for (std::size_t f = 0; f < faces.coord.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int particle = faces.tex[f][k], vertex = faces.coord[f][k];
      auto [it, fresh] = local.try_emplace(particle, static_cast<std::uint32_t>(local.size()));
      if (fresh) {
        const int src = mesh.vertex_particle[vertex];
        for (int c = 0; c < 3; ++c) p.position.push_back(x[3 * static_cast<std::size_t>(src) + c]);
        for (int c = 0; c < 3; ++c) p.normal.push_back(static_cast<float>(nrm[vertex][c]));
        double u = g.cloth.uv[particle][0], v = g.cloth.uv[particle][1];
        if (textured) {
          const double ru = cr * u - sr * v, rv = sr * u + cr * v;
          u = ru / look.repeat_u, v = rv / look.repeat_v;
        }
        p.texcoord.push_back(static_cast<float>(u));
        p.texcoord.push_back(static_cast<float>(-v));
      }
      p.indices.push_back(it->second);
    }
  return p;
}

// Appends the bytes of a float/uint array to the binary buffer, 4-byte aligned,
// and adds its bufferView and accessor; returns the accessor index.
class Buffer {
 public:
  nlohmann::json views = nlohmann::json::array(), accessors = nlohmann::json::array();
  std::string bin;

  int add_floats(const std::vector<float>& v, int components, bool bounds, int target) {
    const int view = add_view(v.data(), v.size() * sizeof(float), target);
    nlohmann::json a{{"bufferView", view},
                     {"componentType", 5126},
                     {"count", v.size() / components},
                     {"type", components == 3 ? "VEC3" : "VEC2"}};
    if (bounds) {
      std::vector<float> lo(components, 1e30f), hi(components, -1e30f);
      for (std::size_t i = 0; i < v.size(); ++i) {
        lo[i % components] = std::min(lo[i % components], v[i]);
        hi[i % components] = std::max(hi[i % components], v[i]);
      }
      a["min"] = lo, a["max"] = hi;
    }
    accessors.push_back(a);
    return static_cast<int>(accessors.size()) - 1;
  }
  int add_indices(const std::vector<std::uint32_t>& v) {
    const int view = add_view(v.data(), v.size() * sizeof(std::uint32_t), 34963);
    accessors.push_back({{"bufferView", view}, {"componentType", 5125}, {"count", v.size()}, {"type", "SCALAR"}});
    return static_cast<int>(accessors.size()) - 1;
  }

 private:
  int add_view(const void* data, std::size_t bytes, int target) {
    while (bin.size() % 4) bin.push_back('\0');
    views.push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}, {"target", target}});
    // glTF is little-endian, like every machine vgd builds on (x86-64, aarch64).
    bin.append(static_cast<const char*>(data), bytes);
    return static_cast<int>(views.size()) - 1;
  }
};

void put_u32(std::string& out, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xFF));
}

nlohmann::json material_json(const std::string& name, const Rgba& c) {
  nlohmann::json m{{"name", name},
                   {"doubleSided", true},
                   {"pbrMetallicRoughness",
                    {{"baseColorFactor", {c.r, c.g, c.b, c.a}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.9}}}};
  if (c.a < 1.0) m["alphaMode"] = "BLEND";
  return m;
}

}  // namespace

std::string glb_bytes(const Garment& g, const DrapeExportOptions& options) {
  g.validate();
  const int frame = resolve(g, options.frame);
  const auto& x = g.frames.positions[frame];
  const OutputMesh mesh = output_mesh(g.cloth, true);
  const auto nrm = vertex_normals(mesh, x);

  Buffer buf;
  nlohmann::json meshes = nlohmann::json::array(), nodes = nlohmann::json::array(),
                 materials = nlohmann::json::array(), images = nlohmann::json::array(),
                 textures = nlohmann::json::array();
  for (int p = 0; p < static_cast<int>(mesh.pieces.size()); ++p) {
    if (mesh.pieces[p].coord.empty()) continue;
    const std::string name = g.cloth.pieces.empty() ? "cloth" : g.cloth.pieces[p];
    const auto prim = piece_primitive(g, mesh, p, x, nrm);
    const PieceLook& look = g.look(p);
    nlohmann::json mat = material_json(name, look.colour);
    if (!look.texture.empty()) {
      images.push_back({{"uri", look.texture}});
      textures.push_back({{"source", images.size() - 1}});
      mat["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", textures.size() - 1}};
    }
    materials.push_back(mat);
    nlohmann::json attributes{{"POSITION", buf.add_floats(prim.position, 3, true, 34962)},
                              {"NORMAL", buf.add_floats(prim.normal, 3, false, 34962)},
                              {"TEXCOORD_0", buf.add_floats(prim.texcoord, 2, false, 34962)}};
    meshes.push_back({{"name", name},
                      {"primitives",
                       {{{"attributes", attributes},
                         {"indices", buf.add_indices(prim.indices)},
                         {"material", materials.size() - 1},
                         {"mode", 4}}}}});
    nodes.push_back({{"name", name}, {"mesh", meshes.size() - 1}});
  }
  if (options.body && g.body) {
    std::vector<float> pos;
    std::vector<std::uint32_t> idx;
    for (const auto& v : g.body->vertices)
      pos.insert(pos.end(), {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])});
    for (const auto& t : g.body->triangles)
      for (int k : t) idx.push_back(static_cast<std::uint32_t>(k));
    materials.push_back(material_json(g.body->name, g.body->colour));
    meshes.push_back({{"name", g.body->name},
                      {"primitives",
                       {{{"attributes", {{"POSITION", buf.add_floats(pos, 3, true, 34962)}}},
                         {"indices", buf.add_indices(idx)},
                         {"material", materials.size() - 1},
                         {"mode", 4}}}}});
    nodes.push_back({{"name", g.body->name}, {"mesh", meshes.size() - 1}});
  }
  while (buf.bin.size() % 4) buf.bin.push_back('\0');

  nlohmann::json scene_nodes = nlohmann::json::array();
  for (std::size_t i = 0; i < nodes.size(); ++i) scene_nodes.push_back(i);
  nlohmann::json doc{{"asset", {{"version", "2.0"}, {"generator", "vgd (docs/vrml.md)"}}},
                     {"scene", 0},
                     {"scenes", {{{"name", g.name}, {"nodes", scene_nodes}}}},
                     {"nodes", nodes},
                     {"meshes", meshes},
                     {"materials", materials},
                     {"accessors", buf.accessors},
                     {"bufferViews", buf.views},
                     {"buffers", {{{"byteLength", buf.bin.size()}}}}};
  if (!images.empty()) doc["images"] = images, doc["textures"] = textures;
  std::string json = doc.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  while (json.size() % 4) json.push_back(' ');

  // Header, JSON chunk, BIN chunk (glTF 2.0 §4.4).
  std::string out;
  put_u32(out, 0x46546C67);  // "glTF"
  put_u32(out, 2);
  put_u32(out, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + buf.bin.size()));
  put_u32(out, static_cast<std::uint32_t>(json.size()));
  put_u32(out, 0x4E4F534A);  // "JSON"
  out += json;
  put_u32(out, static_cast<std::uint32_t>(buf.bin.size()));
  put_u32(out, 0x004E4942);  // "BIN\0"
  out += buf.bin;
  return out;
}

std::string obj_text(const Garment& g, const std::string& mtl_file_name, const DrapeExportOptions& options,
                     int precision) {
  g.validate();
  const int decimals = detail::checked_decimals(precision);
  const int frame = resolve(g, options.frame);
  const auto& x = g.frames.positions[frame];
  const OutputMesh mesh = output_mesh(g.cloth, true);
  const auto nrm = vertex_normals(mesh, x);

  std::string o = "# vgd drape of '" + g.name + "', frame " + std::to_string(frame) + ": " +
                  std::to_string(mesh.vertex_particle.size()) + " vertices, " + std::to_string(mesh.face_count()) +
                  " triangles; vt = material coordinates (m)\n";
  if (!mtl_file_name.empty()) o += "mtllib " + mtl_file_name + "\n";
  for (int src : mesh.vertex_particle) {
    o += "v ";
    for (int c = 0; c < 3; ++c) append_number(o, x[3 * static_cast<std::size_t>(src) + c], decimals), o += c < 2 ? " " : "\n";
  }
  for (const auto& uv : g.cloth.uv) {
    o += "vt ", append_number(o, uv[0], decimals), o += ' ', append_number(o, uv[1], decimals), o += '\n';
  }
  for (const auto& n : nrm) {
    o += "vn ";
    for (int c = 0; c < 3; ++c) append_number(o, n[c], 4), o += c < 2 ? " " : "\n";
  }
  for (int p = 0; p < static_cast<int>(mesh.pieces.size()); ++p) {
    const auto& faces = mesh.pieces[p];
    if (faces.coord.empty()) continue;
    const std::string name = detail::def_name("", g.cloth.pieces.empty() ? "cloth" : g.cloth.pieces[p]);
    o += "g " + name + "\nusemtl " + name + "\n";
    for (std::size_t f = 0; f < faces.coord.size(); ++f) {
      o += "f";
      for (int k = 0; k < 3; ++k) {
        const std::string v = std::to_string(faces.coord[f][k] + 1);
        o += " " + v + "/" + std::to_string(faces.tex[f][k] + 1) + "/" + v;
      }
      o += "\n";
    }
  }
  if (options.body && g.body) {
    const std::size_t base = mesh.vertex_particle.size();
    o += "g avatar\nusemtl avatar\n";
    for (const auto& v : g.body->vertices) {
      o += "v ";
      for (int c = 0; c < 3; ++c) append_number(o, v[c], decimals), o += c < 2 ? " " : "\n";
    }
    for (const auto& t : g.body->triangles)
      o += "f " + std::to_string(base + t[0] + 1) + " " + std::to_string(base + t[1] + 1) + " " +
           std::to_string(base + t[2] + 1) + "\n";
  }
  return o;
}

std::string mtl_text(const Garment& g) {
  std::string o = "# vgd materials of '" + g.name + "' (from the XVC document, docs/vrml.md)\n";
  auto material = [&](const std::string& name, const Rgba& c) {
    o += "newmtl " + name + "\nKd ";
    append_number(o, c.r, 4), o += ' ', append_number(o, c.g, 4), o += ' ', append_number(o, c.b, 4);
    o += "\nKa 0 0 0\nKs 0.05 0.05 0.05\nd ", append_number(o, c.a, 4), o += "\n";
  };
  for (int p = 0; p < g.cloth.num_pieces(); ++p) {
    const PieceLook& look = g.look(p);
    material(detail::def_name("", g.cloth.pieces.empty() ? "cloth" : g.cloth.pieces[p]), look.colour);
    if (!look.texture.empty()) {
      // vt is in metres: -s scales the texture to one repeat per SCALE2D metres.
      o += "map_Kd -s ", append_number(o, look.repeat_u, 5), o += ' ', append_number(o, look.repeat_v, 5);
      o += " 1 " + look.texture + "\n";
    }
    o += "\n";
  }
  if (g.body) material("avatar", g.body->colour);
  return o;
}

}  // namespace vgd::io::vrml
