// Scene helpers: colours, bounds, smooth normals, checks.
#include "vgd/render/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <unordered_map>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"

namespace vgd::render {

namespace {

using V3 = std::array<float, 3>;

V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Exact position as a hash key (seam partners are written with identical coordinates).
struct PositionKey {
  std::uint32_t bits[3];
  bool operator==(const PositionKey& o) const { return std::memcmp(bits, o.bits, sizeof bits) == 0; }
};
struct PositionHash {
  std::size_t operator()(const PositionKey& k) const {
    return (static_cast<std::size_t>(k.bits[0]) * 73856093u) ^ (static_cast<std::size_t>(k.bits[1]) * 19349663u) ^
           (static_cast<std::size_t>(k.bits[2]) * 83492791u);
  }
};
PositionKey key_of(const V3& p) {
  PositionKey k;
  for (int i = 0; i < 3; ++i) {
    const float v = p[i] == 0.0f ? 0.0f : p[i];  // -0 and +0 alike
    std::memcpy(&k.bits[i], &v, sizeof v);
  }
  return k;
}

struct NamedColour {
  const char* name;
  Colour colour;
};
// A few names a designer types; anything else as #rrggbb.
constexpr NamedColour kNames[] = {
    {"blue", kFabric},
    {"navy", {0.12f, 0.16f, 0.33f}},
    {"red", {0.72f, 0.16f, 0.16f}},
    {"green", {0.22f, 0.52f, 0.30f}},
    {"yellow", {0.90f, 0.78f, 0.25f}},
    {"orange", {0.90f, 0.50f, 0.18f}},
    {"purple", {0.46f, 0.27f, 0.60f}},
    {"pink", {0.90f, 0.55f, 0.65f}},
    {"black", {0.08f, 0.08f, 0.09f}},
    {"white", {0.96f, 0.96f, 0.95f}},
    {"grey", {0.55f, 0.55f, 0.55f}},
    {"gray", {0.55f, 0.55f, 0.55f}},
    {"denim", {0.26f, 0.36f, 0.52f}},
    {"khaki", {0.76f, 0.69f, 0.50f}},
    {"skin", kBody},
};

}  // namespace

std::optional<Colour> parse_colour(std::string_view text) {
  const std::string t = to_lower(trim(text));
  for (const auto& n : kNames)
    if (t == n.name) return n.colour;
  std::string_view hex = t;
  if (!hex.empty() && hex[0] == '#') hex.remove_prefix(1);
  if (hex.size() != 6 && hex.size() != 3) return std::nullopt;
  int digits[6];
  for (std::size_t i = 0; i < hex.size(); ++i) {
    const char c = hex[i];
    if (c >= '0' && c <= '9') digits[i] = c - '0';
    else if (c >= 'a' && c <= 'f') digits[i] = c - 'a' + 10;
    else return std::nullopt;
  }
  auto channel = [&](int k) {
    const int v = hex.size() == 6 ? 16 * digits[2 * k] + digits[2 * k + 1] : 17 * digits[k];
    return static_cast<float>(v) / 255.0f;
  };
  return Colour{channel(0), channel(1), channel(2)};
}

std::string to_hex(const Colour& c) {
  auto byte = [](float v) { return static_cast<int>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", byte(c.r), byte(c.g), byte(c.b));
  return buf;
}

Colour piece_colour(int index) {
  // Muted, distinguishable fabric colours.
  static constexpr Colour palette[] = {
      {0.25f, 0.42f, 0.68f}, {0.74f, 0.33f, 0.27f}, {0.33f, 0.58f, 0.38f}, {0.83f, 0.66f, 0.28f},
      {0.52f, 0.38f, 0.66f}, {0.30f, 0.62f, 0.66f}, {0.80f, 0.47f, 0.60f}, {0.50f, 0.50f, 0.50f},
  };
  constexpr int n = static_cast<int>(sizeof palette / sizeof palette[0]);
  return palette[((index % n) + n) % n];
}

void Box::extend(const std::array<float, 3>& p) {
  for (int i = 0; i < 3; ++i) {
    min[i] = std::min(min[i], static_cast<double>(p[i]));
    max[i] = std::max(max[i], static_cast<double>(p[i]));
  }
}

void Box::extend(const Box& b) {
  if (b.empty()) return;
  for (int i = 0; i < 3; ++i) {
    min[i] = std::min(min[i], b.min[i]);
    max[i] = std::max(max[i], b.max[i]);
  }
}

Box bounds(const Scene& scene, std::optional<MeshKind> kind) {
  Box box;
  for (const auto& m : scene.meshes) {
    if (kind && m.kind != *kind) continue;
    for (const auto& t : m.triangles)
      for (int k = 0; k < 3; ++k) box.extend(m.positions[static_cast<std::size_t>(t[k])]);
  }
  return box;
}

void compute_normals(Scene& scene) {
  // 1. Per mesh: area-weighted sums of the triangle normals (cross products).
  std::vector<std::vector<std::array<double, 3>>> sums(scene.meshes.size());
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    if (!mesh.normals.empty()) continue;
    sums[m].assign(mesh.positions.size(), {0, 0, 0});
    for (const auto& t : mesh.triangles) {
      const V3 n = cross(sub(mesh.positions[t[1]], mesh.positions[t[0]]), sub(mesh.positions[t[2]], mesh.positions[t[0]]));
      for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 3; ++i) sums[m][t[k]][i] += n[i];
    }
  }
  // 2. Coincident vertices of meshes of the same kind: one shared sum, each
  //    contribution turned to agree with the first one met.
  for (const MeshKind kind : {MeshKind::garment, MeshKind::body}) {
    std::unordered_map<PositionKey, std::array<double, 3>, PositionHash> shared;
    std::unordered_map<PositionKey, int, PositionHash> count;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
      if (scene.meshes[m].kind != kind || sums[m].empty()) continue;
      for (std::size_t v = 0; v < sums[m].size(); ++v) {
        const PositionKey k = key_of(scene.meshes[m].positions[v]);
        auto [it, fresh] = shared.try_emplace(k, sums[m][v]);
        ++count[k];
        if (fresh) continue;
        const double s = dot(it->second, sums[m][v]) < 0 ? -1.0 : 1.0;
        for (int i = 0; i < 3; ++i) it->second[i] += s * sums[m][v][i];
      }
    }
    // 3. Normalise, each vertex keeping its own mesh's orientation.
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
      Mesh& mesh = scene.meshes[m];
      if (mesh.kind != kind || sums[m].empty()) continue;
      mesh.normals.resize(mesh.positions.size());
      for (std::size_t v = 0; v < sums[m].size(); ++v) {
        const PositionKey k = key_of(mesh.positions[v]);
        std::array<double, 3> n = count[k] > 1 ? shared[k] : sums[m][v];
        if (dot(n, sums[m][v]) < 0) n = {-n[0], -n[1], -n[2]};
        const double len = std::sqrt(dot(n, n));
        mesh.normals[v] = len > 0 ? V3{static_cast<float>(n[0] / len), static_cast<float>(n[1] / len),
                                       static_cast<float>(n[2] / len)}
                                  : V3{0, 1, 0};
      }
    }
  }
}

void check_scene(const Scene& scene) {
  for (const auto& m : scene.meshes) {
    const std::string name = m.name.empty() ? "mesh" : m.name;
    for (const auto& p : m.positions)
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        throw Error("", name, "a vertex position is not a finite number");
    for (const auto& t : m.triangles)
      for (int k = 0; k < 3; ++k)
        if (t[k] < 0 || static_cast<std::size_t>(t[k]) >= m.positions.size())
          throw Error("", name, "triangle vertex index " + std::to_string(t[k]) + " is out of range (" +
                                    std::to_string(m.positions.size()) + " vertices)");
    if (!m.normals.empty() && m.normals.size() != m.positions.size())
      throw Error("", name, "has " + std::to_string(m.normals.size()) + " normals for " +
                                std::to_string(m.positions.size()) + " vertices");
    if (!m.uv.empty() && m.uv.size() != m.positions.size())
      throw Error("", name, "has " + std::to_string(m.uv.size()) + " texture coordinates for " +
                                std::to_string(m.positions.size()) + " vertices");
    for (const auto& c : m.uv)
      if (!std::isfinite(c[0]) || !std::isfinite(c[1]))
        throw Error("", name, "a texture coordinate is not a finite number");
    if (m.texture) {
      const Texture& t = *m.texture;
      if (m.uv.empty()) throw Error("", name, "has a texture but no texture coordinates");
      if (t.image.empty() || t.image.rgba.size() != static_cast<std::size_t>(t.image.width) * t.image.height * 4)
        throw Error("", name, "has an empty or malformed texture image");
      if (!(t.repeat_m[0] > 0) || !(t.repeat_m[1] > 0) || !std::isfinite(t.repeat_m[0]) ||
          !std::isfinite(t.repeat_m[1]) || !std::isfinite(t.rotation_rad))
        throw Error("", name, "the texture's repeat must be positive metres and its rotation finite");
    }
  }
}

}  // namespace vgd::render
