#include "vgd/mesh/triangle_io.hpp"

#include <string>
#include <string_view>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"

namespace vgd::mesh {

namespace {

std::filesystem::path with_ext(const std::filesystem::path& base, const char* ext) {
  return std::filesystem::path(base.string() + ext);
}

// ---- writing ----------------------------------------------------------------------

void append_line(std::string& out, std::initializer_list<std::string> fields) {
  bool first = true;
  for (const auto& f : fields) {
    if (!first) out += ' ';
    out += f;
    first = false;
  }
  out += '\n';
}

std::string num(double v) { return format_double(v); }
std::string num(int v) { return std::to_string(v); }
std::string num(std::size_t v) { return std::to_string(v); }

// ---- reading ----------------------------------------------------------------------

// The non-empty lines of one file, split into fields, comments removed.
class Lines {
 public:
  explicit Lines(const std::filesystem::path& path) : file_(path.string()) {
    const std::string text = read_file(path);
    int line = 0;
    std::size_t start = 0;
    while (start <= text.size()) {
      std::size_t end = text.find('\n', start);
      if (end == std::string::npos) end = text.size();
      ++line;
      std::string_view s(text.data() + start, end - start);
      if (const auto hash = s.find('#'); hash != std::string_view::npos) s = s.substr(0, hash);
      std::vector<std::string> fields;
      std::size_t i = 0;
      while (i < s.size()) {
        while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r' || s[i] == ',')) ++i;
        std::size_t j = i;
        while (j < s.size() && s[j] != ' ' && s[j] != '\t' && s[j] != '\r' && s[j] != ',') ++j;
        if (j > i) fields.emplace_back(s.substr(i, j - i));
        i = j;
      }
      if (!fields.empty()) rows_.push_back({line, std::move(fields)});
      start = end + 1;
    }
  }

  bool done() const { return next_ >= rows_.size(); }

  // The next line, with at least `min_fields` fields.
  const std::vector<std::string>& take(std::size_t min_fields, const char* what) {
    if (done()) throw Error(file_, "", std::string("the file ends where ") + what + " should follow");
    current_ = next_++;
    if (rows_[current_].second.size() < min_fields)
      throw Error(file_, "", std::string("too few numbers for ") + what, rows_[current_].first);
    return rows_[current_].second;
  }

  long long integer(const std::string& s, const char* what) const {
    const auto v = parse_int(s);
    if (!v) fail(std::string("expected an integer for ") + what + ", got \"" + s + "\"");
    return *v;
  }
  double real(const std::string& s, const char* what) const {
    const auto v = parse_double(s);
    if (!v) fail(std::string("expected a number for ") + what + ", got \"" + s + "\"");
    return *v;
  }
  // A node number in the file, converted to a 0-based index and checked.
  int node(const std::string& s, long long base, std::size_t count) const {
    const long long v = integer(s, "a node number") - base;
    if (v < 0 || v >= static_cast<long long>(count))
      fail("node number " + s + " is outside the " + std::to_string(count) + " nodes");
    return static_cast<int>(v);
  }
  [[noreturn]] void fail(const std::string& message) const {
    throw Error(file_, "", message, rows_.empty() ? 0 : rows_[current_].first);
  }

 private:
  std::string file_;
  std::vector<std::pair<int, std::vector<std::string>>> rows_;
  std::size_t next_ = 0, current_ = 0;
};

// A vertex list (.node file, or the head of a .poly). Returns the numbering base.
long long read_vertices(Lines& in, long long count, int attributes, int markers, TriangleData& d) {
  long long base = 0;
  for (long long k = 0; k < count; ++k) {
    const auto& f = in.take(static_cast<std::size_t>(3 + attributes + markers), "a vertex");
    const long long id = in.integer(f[0], "the vertex number");
    if (k == 0) {
      if (id != 0 && id != 1) in.fail("the first vertex must be numbered 0 or 1");
      base = id;
    } else if (id != base + k) {
      in.fail("vertices must be numbered consecutively");
    }
    d.nodes.push_back(Vec2(in.real(f[1], "x"), in.real(f[2], "y")));
    d.node_markers.push_back(markers ? static_cast<int>(in.integer(f[3 + attributes], "the boundary marker")) : 0);
  }
  return base;
}

// "<count> <dimension> <attributes> <markers>" of a .node file or .poly head.
void read_vertex_header(Lines& in, long long& count, int& attributes, int& markers) {
  const auto& f = in.take(1, "the vertex count");
  count = in.integer(f[0], "the vertex count");
  const long long dim = f.size() > 1 ? in.integer(f[1], "the dimension") : 2;
  attributes = f.size() > 2 ? static_cast<int>(in.integer(f[2], "the attribute count")) : 0;
  markers = f.size() > 3 ? static_cast<int>(in.integer(f[3], "the marker count")) : 0;
  if (count < 0 || (count > 0 && dim != 2) || attributes < 0 || markers < 0 || markers > 1)
    in.fail("bad vertex header: expected \"<vertices> 2 <attributes> <0 or 1>\"");
}

}  // namespace

TriangleData to_triangle_data(const PieceMesh& m) {
  TriangleData d;
  d.nodes = m.nodes;
  d.node_markers = m.node_markers;
  d.triangles = m.triangles;
  for (const auto& e : m.boundary) {
    d.segments.push_back({e.a, e.b});
    d.segment_markers.push_back(e.marker);
  }
  for (std::size_t c = 1; c < m.contours.size(); ++c) d.holes.push_back(interior_point(m.contours[c].points));
  return d;
}

void write_triangle_files(const TriangleData& d, const std::filesystem::path& base) {
  VGD_ASSERT(d.node_markers.empty() || d.node_markers.size() == d.nodes.size(), "one marker per node");
  VGD_ASSERT(d.segment_markers.empty() || d.segment_markers.size() == d.segments.size(), "one marker per segment");

  // .node: "<n> 2 0 1", then "<i> <x> <y> <marker>", numbered from 1 like Triangle.
  std::string node = "# nodes: number, x, y (metres), boundary marker; written by vgd\n";
  append_line(node, {num(d.nodes.size()), "2", "0", "1"});
  for (std::size_t i = 0; i < d.nodes.size(); ++i)
    append_line(node, {num(i + 1), num(d.nodes[i].x()), num(d.nodes[i].y()),
                       num(d.node_markers.empty() ? 0 : d.node_markers[i])});

  // .ele: "<t> 3 0", then "<i> <a> <b> <c>" counter-clockwise.
  std::string ele = "# triangles: number, three nodes counter-clockwise; written by vgd\n";
  append_line(ele, {num(d.triangles.size()), "3", "0"});
  for (std::size_t i = 0; i < d.triangles.size(); ++i)
    append_line(ele, {num(i + 1), num(d.triangles[i][0] + 1), num(d.triangles[i][1] + 1), num(d.triangles[i][2] + 1)});

  // .poly: vertices are in the .node file ("0 2 0 1"), then segments and holes.
  std::string poly = "# boundary segments with markers and one point per hole; vertices in the .node file\n";
  append_line(poly, {"0", "2", "0", "1"});
  append_line(poly, {num(d.segments.size()), "1"});
  for (std::size_t i = 0; i < d.segments.size(); ++i)
    append_line(poly, {num(i + 1), num(d.segments[i][0] + 1), num(d.segments[i][1] + 1),
                       num(d.segment_markers.empty() ? 0 : d.segment_markers[i])});
  append_line(poly, {num(d.holes.size())});
  for (std::size_t i = 0; i < d.holes.size(); ++i)
    append_line(poly, {num(i + 1), num(d.holes[i].x()), num(d.holes[i].y())});

  write_file_atomic(with_ext(base, ".node"), node);
  write_file_atomic(with_ext(base, ".ele"), ele);
  write_file_atomic(with_ext(base, ".poly"), poly);
}

void write_triangle_files(const PieceMesh& mesh, const std::filesystem::path& base) {
  write_triangle_files(to_triangle_data(mesh), base);
}

TriangleData read_triangle_files(const std::filesystem::path& base) {
  TriangleData d;
  long long base_index = 1;
  const auto node_path = with_ext(base, ".node"), ele_path = with_ext(base, ".ele"), poly_path = with_ext(base, ".poly");
  const bool have_node = std::filesystem::exists(node_path);

  // Nodes.
  if (have_node) {
    Lines in(node_path);
    long long count = 0;
    int attributes = 0, markers = 0;
    read_vertex_header(in, count, attributes, markers);
    base_index = read_vertices(in, count, attributes, markers, d);
  }

  // Segments and holes; the .poly may carry the vertices itself.
  if (std::filesystem::exists(poly_path)) {
    Lines in(poly_path);
    long long count = 0;
    int attributes = 0, markers = 0;
    read_vertex_header(in, count, attributes, markers);
    if (count > 0) {
      if (have_node) in.fail("vertices are listed both here and in the .node file");
      base_index = read_vertices(in, count, attributes, markers, d);
    }
    const auto& h = in.take(1, "the segment count");
    const long long segments = in.integer(h[0], "the segment count");
    const long long seg_markers = h.size() > 1 ? in.integer(h[1], "the marker count") : 0;
    if (segments < 0 || seg_markers < 0 || seg_markers > 1) in.fail("bad segment header");
    for (long long k = 0; k < segments; ++k) {
      const auto& f = in.take(static_cast<std::size_t>(3 + seg_markers), "a segment");
      d.segments.push_back({in.node(f[1], base_index, d.nodes.size()), in.node(f[2], base_index, d.nodes.size())});
      d.segment_markers.push_back(seg_markers ? static_cast<int>(in.integer(f[3], "the segment marker")) : 0);
    }
    if (!in.done()) {
      const auto& hh = in.take(1, "the hole count");
      const long long holes = in.integer(hh[0], "the hole count");
      if (holes < 0) in.fail("bad hole count");
      for (long long k = 0; k < holes; ++k) {
        const auto& f = in.take(3, "a hole");
        d.holes.push_back(Vec2(in.real(f[1], "hole x"), in.real(f[2], "hole y")));
      }
    }
  } else if (!have_node) {
    throw Error(node_path.string(), "", "file not found");
  }

  // Triangles: the first three nodes are the corners (6-node triangles list midpoints after).
  Lines in(ele_path);
  const auto& h = in.take(2, "the triangle header");
  const long long count = in.integer(h[0], "the triangle count");
  const long long per = in.integer(h[1], "nodes per triangle");
  const long long attributes = h.size() > 2 ? in.integer(h[2], "the attribute count") : 0;
  if (count < 0 || (per != 3 && per != 6) || attributes < 0) in.fail("bad triangle header: expected \"<triangles> 3 <attributes>\"");
  for (long long k = 0; k < count; ++k) {
    const auto& f = in.take(static_cast<std::size_t>(1 + per + attributes), "a triangle");
    d.triangles.push_back({in.node(f[1], base_index, d.nodes.size()), in.node(f[2], base_index, d.nodes.size()),
                           in.node(f[3], base_index, d.nodes.size())});
  }
  return d;
}

}  // namespace vgd::mesh
