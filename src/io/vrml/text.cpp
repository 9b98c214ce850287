// Numbers, names and the shared parts of every VRML flavour.
#include "text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "vgd/core/diagnostics.hpp"
#include "vgd/io/vrml/vrml.hpp"

namespace vgd::io::vrml {

void append_number(std::string& out, double v, int decimals) {
  char buf[64];
  if (!std::isfinite(v)) v = 0.0;  // never reaches here from a checked garment; keeps the file parseable
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, decimals);
  char* end = r.ptr;
  // Trailing zeros and a trailing point go: 1.2500 -> 1.25, 2.000 -> 2.
  if (decimals > 0) {
    while (end > buf && end[-1] == '0') --end;
    if (end > buf && end[-1] == '.') --end;
  }
  std::string_view s(buf, static_cast<std::size_t>(end - buf));
  if (s == "-0") s = "0";
  out.append(s);
}

namespace detail {

void Box::add(double x, double y, double z) {
  const double p[3] = {x, y, z};
  for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
}

Box garment_box(const Garment& g, int frame) {
  Box b;
  const auto& x = g.frames.positions[frame];
  for (std::size_t i = 0; i + 2 < x.size(); i += 3) b.add(x[i], x[i + 1], x[i + 2]);
  if (b.empty()) b.add(0, 0, 0);
  return b;
}

std::string quoted(std::string_view s) {
  std::string q = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') q += '\\';
    q += (static_cast<unsigned char>(c) < 32) ? ' ' : c;
  }
  return q + "\"";
}

std::string def_name(std::string_view prefix, std::string_view s) {
  std::string n(prefix);
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    // VRML97 IdRestChars exclude control characters, space, " # ' + , - . [ \ ] { }.
    const bool bad = u <= 32 || c == '"' || c == '#' || c == '\'' || c == '+' || c == ',' || c == '-' || c == '.' ||
                     c == '[' || c == '\\' || c == ']' || c == '{' || c == '}' || u >= 127;
    n += bad ? '_' : c;
  }
  if (n.empty() || (n[0] >= '0' && n[0] <= '9')) n = "_" + n;
  return n;
}

int checked_decimals(int decimals) {
  VGD_ASSERT(decimals >= 0 && decimals <= 9, "VRML precision must be 0 to 9 decimals");
  return decimals;
}

std::string preamble(const std::string& title, const std::vector<std::string>& comments, const Box& box,
                     bool side_view) {
  std::string o = "#VRML V2.0 utf8\n";
  for (const auto& c : comments) o += "# " + c + "\n";
  o += "WorldInfo { title " + detail::quoted(title) + " info [ \"written by vgd, docs/vrml.md\" ] }\n";
  o += "NavigationInfo { type [ \"EXAMINE\" \"ANY\" ] headlight TRUE }\n";
  o += "Background { skyColor [ 0.93 0.94 0.96 ] }\n";
  // A view framing the box with the default 45° field of view.
  const double c[3] = {0.5 * (box.lo[0] + box.hi[0]), 0.5 * (box.lo[1] + box.hi[1]), 0.5 * (box.lo[2] + box.hi[2])};
  const int across = side_view ? 2 : 0, depth = side_view ? 0 : 2;
  const double w = box.hi[across] - box.lo[across], h = box.hi[1] - box.lo[1];
  const double d = 1.3 * 0.5 * std::max({w, h, 0.1}) / std::tan(0.5 * 0.785398) + box.hi[depth] - c[depth];
  double p[3] = {c[0], c[1], c[2]};
  p[depth] += d;
  o += std::string("Viewpoint { description \"") + (side_view ? "side" : "front") +
       "\" fieldOfView 0.785398 position ";
  append_number(o, p[0], 3), o += ' ', append_number(o, p[1], 3), o += ' ', append_number(o, p[2], 3);
  if (side_view) o += " orientation 0 1 0 1.5708";
  o += " }\n";
  o += "DirectionalLight { direction -0.3 -0.5 -0.8 intensity 0.6 }\n";
  return o;
}

namespace {

// "material Material { ... }" in a colour.
std::string material(const Rgba& c) {
  std::string o = "material Material { diffuseColor ";
  append_number(o, c.r, 3), o += ' ', append_number(o, c.g, 3), o += ' ', append_number(o, c.b, 3);
  o += " specularColor 0.08 0.08 0.08 shininess 0.1";
  if (c.a < 1.0) o += " transparency ", append_number(o, 1.0 - c.a, 3);
  return o + " }";
}

}  // namespace

std::string appearance(const Rgba& c, int indent) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  return "Appearance {\n" + pad + "  " + material(c) + "\n" + pad + "}";
}

std::string appearance(const PieceLook& look, int indent) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  std::string o = "Appearance {\n" + pad + "  " + material(look.colour) + "\n";
  if (!look.texture.empty()) {
    // Texture coordinates are metres of fabric: scaled to repeats, turned by the document's angle.
    o += pad + "  texture ImageTexture { url " + detail::quoted(look.texture) + " }\n";
    o += pad + "  textureTransform TextureTransform { scale ";
    append_number(o, 1.0 / std::max(look.repeat_u, 1e-6), 4), o += ' ';
    append_number(o, 1.0 / std::max(look.repeat_v, 1e-6), 4);
    if (look.rotation_deg != 0.0) o += " rotation ", append_number(o, look.rotation_deg * M_PI / 180.0, 5);
    o += " }\n";
  }
  return o + pad + "}";
}

void append_point_lines(std::string& out, const std::vector<float>& x, const std::vector<int>& particles,
                        int decimals, int indent) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  int on_line = 0;
  for (std::size_t k = 0; k < particles.size(); ++k) {
    if (on_line == 0) out += pad;
    const std::size_t i = 3 * static_cast<std::size_t>(particles[k]);
    append_number(out, x[i], decimals), out += ' ';
    append_number(out, x[i + 1], decimals), out += ' ';
    append_number(out, x[i + 2], decimals);
    if (++on_line == 6 || k + 1 == particles.size()) out += ",\n", on_line = 0;
    else out += ", ";
  }
}

void append_points(std::string& out, const std::vector<float>& x, const std::vector<int>& particles, int decimals,
                   int indent) {
  out += "[\n";
  append_point_lines(out, x, particles, decimals, indent);
  out += std::string(static_cast<std::size_t>(std::max(indent - 2, 0)), ' ') + "]";
}

void append_faces(std::string& out, const std::vector<std::array<int, 3>>& faces, int indent) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  out += "[\n";
  int on_line = 0;
  for (std::size_t k = 0; k < faces.size(); ++k) {
    if (on_line == 0) out += pad;
    const auto& f = faces[k];
    out += std::to_string(f[0]) + ' ' + std::to_string(f[1]) + ' ' + std::to_string(f[2]) + " -1";
    if (++on_line == 8 || k + 1 == faces.size()) out += "\n", on_line = 0;
    else out += ' ';
  }
  out += pad.substr(0, pad.size() >= 2 ? pad.size() - 2 : 0) + "]";
}

void append_uv(std::string& out, const std::vector<std::array<double, 2>>& uv, int decimals, int indent) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  out += "[\n";
  int on_line = 0;
  for (std::size_t k = 0; k < uv.size(); ++k) {
    if (on_line == 0) out += pad;
    append_number(out, uv[k][0], decimals), out += ' ', append_number(out, uv[k][1], decimals);
    if (++on_line == 8 || k + 1 == uv.size()) out += ",\n", on_line = 0;
    else out += ", ";
  }
  out += pad.substr(0, pad.size() >= 2 ? pad.size() - 2 : 0) + "]";
}

std::string body_shape(const Body& body, int precision) {
  std::string o = "DEF " + def_name("", body.name.empty() ? "Avatar" : body.name) + " Shape {\n";
  o += "  appearance " + appearance(body.colour, 2) + "\n";
  o += "  geometry IndexedFaceSet {\n    coord Coordinate { point ";
  std::vector<float> x;
  x.reserve(body.vertices.size() * 3);
  for (const auto& v : body.vertices) x.insert(x.end(), {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])});
  std::vector<int> all(body.vertices.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  append_points(o, x, all, checked_decimals(precision), 6);
  o += " }\n    coordIndex ";
  append_faces(o, body.triangles, 6);
  o += "\n    solid FALSE\n    creaseAngle ";
  append_number(o, crease_angle(median_edge_length(body)), 3);
  o += "\n  }\n}\n";
  return o;
}

}  // namespace detail
}  // namespace vgd::io::vrml
