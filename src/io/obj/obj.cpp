// OBJ frames: text, atomic per-frame files, and a small reader for checks.
#include "vgd/io/obj/obj.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"

namespace vgd::io::obj {

namespace {

void append_line(std::string& out, const char* fmt, double a, double b, double c) {
  char buf[96];
  const int n = std::snprintf(buf, sizeof buf, fmt, a, b, c);
  out.append(buf, static_cast<std::size_t>(n));
}

// A group name OBJ readers accept: no spaces or control characters.
std::string group_name(const std::string& s) {
  std::string g = s.empty() ? "cloth" : s;
  for (char& ch : g)
    if (static_cast<unsigned char>(ch) <= ' ') ch = '_';
  return g;
}

}  // namespace

std::string frame_text(const sim::Model& topology, double t, const sim::VecX& x) {
  const int n = static_cast<int>(x.size() / 3);
  std::string out;
  out.reserve(static_cast<std::size_t>(n) * 40 + topology.triangles.size() * 24 + 64);
  append_line(out, "# vgd frame, t = %.9g s, %.0f vertices, %.0f triangles\n", t, n,
              static_cast<double>(topology.triangles.size()));
  for (int i = 0; i < n; ++i) append_line(out, "v %.9g %.9g %.9g\n", x[3 * i], x[3 * i + 1], x[3 * i + 2]);
  // Pattern coordinates, one per particle with the particle's index: what a
  // renderer needs to lay a fabric texture on the piece along its grain.
  const bool textured = n > 0 && topology.uv.size() == static_cast<std::size_t>(n);
  if (textured)
    for (const auto& c : topology.uv) {
      char buf[64];
      const int len = std::snprintf(buf, sizeof buf, "vt %.9g %.9g\n", c.x(), c.y());
      out.append(buf, static_cast<std::size_t>(len));
    }
  // Faces grouped by piece, in triangle order within each piece.
  const bool grouped = !topology.pieces.empty() && topology.triangle_piece.size() == topology.triangles.size();
  const std::size_t groups = grouped ? topology.pieces.size() : 1;
  for (std::size_t g = 0; g < groups; ++g) {
    if (grouped) out += "g " + group_name(topology.pieces[g]) + "\n";
    for (std::size_t k = 0; k < topology.triangles.size(); ++k) {
      if (grouped && topology.triangle_piece[k] != static_cast<int>(g)) continue;
      const auto& f = topology.triangles[k];
      out += 'f';
      for (int c = 0; c < 3; ++c) {
        const std::string i = std::to_string(f[c] + 1);
        out += ' ' + (textured ? i + '/' + i : i);
      }
      out += '\n';
    }
  }
  return out;
}

std::string frame_file_name(int index, const std::string& prefix) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%04d", index);
  return prefix + buf + ".obj";
}

ObjSequenceSink::ObjSequenceSink(std::filesystem::path directory, std::string prefix)
    : directory_(std::move(directory)), prefix_(std::move(prefix)) {}

void ObjSequenceSink::begin(const sim::Model& model) {
  topology_ = sim::Model{};
  topology_.triangles = model.triangles;
  topology_.triangle_piece = model.triangle_piece;
  topology_.pieces = model.pieces;
  std::error_code ec;
  std::filesystem::create_directories(directory_, ec);
  if (ec) throw Error(directory_.string(), "", "cannot create the output folder: " + ec.message());
}

void ObjSequenceSink::frame(int index, double t, const sim::VecX& x) {
  write_file_atomic(directory_ / frame_file_name(index, prefix_), frame_text(topology_, t, x));
  ++written_;
}

ObjMesh read_obj(const std::filesystem::path& file) {
  std::istringstream in(read_file(file));
  ObjMesh m;
  std::string line;
  int lineno = 0;
  auto fail = [&](const std::string& msg) { throw Error(file.string(), "", msg, lineno); };
  while (std::getline(in, line)) {
    ++lineno;
    const auto t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    const auto parts = split(t, ' ');
    std::vector<std::string> w;
    for (const auto& p : parts)
      if (!trim(p).empty()) w.emplace_back(trim(p));
    if (w[0] == "v") {
      if (w.size() < 4) fail("a vertex needs x y z");
      std::array<double, 3> v{};
      for (int k = 0; k < 3; ++k) {
        const auto d = parse_double(w[1 + k]);
        if (!d) fail("'" + w[1 + k] + "' is not a number");
        v[k] = *d;
      }
      m.vertices.push_back(v);
    } else if (w[0] == "vt") {
      if (w.size() < 3) fail("a texture coordinate needs u v");
      std::array<double, 2> c{};
      for (int k = 0; k < 2; ++k) {
        const auto d = parse_double(w[1 + k]);
        if (!d) fail("'" + w[1 + k] + "' is not a number");
        c[k] = *d;
      }
      m.texcoords.push_back(c);
    } else if (w[0] == "f") {
      if (w.size() != 4) fail("a face with " + std::to_string(w.size() - 1) + " corners (only triangles are read)");
      // A 1-based (or negative, from the end) index among `count` so far, 0-based.
      auto index = [&](const std::string& text, std::size_t count, const char* what, const char* whats) {
        const auto idx = parse_int(text);
        if (!idx || *idx == 0) fail("'" + text + "' is not a " + what + " index");
        const long long n = static_cast<long long>(count);
        const long long i = *idx > 0 ? *idx - 1 : n + *idx;
        if (i < 0 || i >= n) fail(std::string(what) + " index " + std::to_string(*idx) + " is out of range (" +
                                  std::to_string(n) + " " + whats + " so far)");
        return static_cast<int>(i);
      };
      std::array<int, 3> f{}, ft{-1, -1, -1};
      int with_texcoords = 0;
      for (int k = 0; k < 3; ++k) {
        const auto refs = split(w[1 + k], '/');
        f[k] = index(refs.front(), m.vertices.size(), "vertex", "vertices");
        if (refs.size() > 1 && !refs[1].empty()) {
          ft[k] = index(refs[1], m.texcoords.size(), "texture coordinate", "texture coordinates");
          ++with_texcoords;
        }
      }
      if (with_texcoords != 0 && with_texcoords != 3) fail("a face with texture coordinates on some corners only");
      m.faces.push_back(f);
      m.face_texcoords.push_back(ft);
      m.face_group.push_back(static_cast<int>(m.groups.size()) - 1);
    } else if (w[0] == "g" || w[0] == "o") {
      m.groups.push_back(w.size() > 1 ? w[1] : "");
    }
  }
  return m;
}

}  // namespace vgd::io::obj
