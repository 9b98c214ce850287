// pattern::Style <-> XVC document. docs/xvc.md ("Mapping from a style") lists where
// each field goes; attributes holding a default value are left out.
#include "vgd/xvc/style.hpp"

#include <algorithm>
#include <map>

#include "edit_helpers.hpp"
#include "rules.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"

namespace vgd::xvc {

namespace {
using pattern::ContourPoint;
using pattern::PointKind;
using pattern::Vec2;

// ---- Style -> XVC ------------------------------------------------------------------

// Sequential ids per prefix: pattern1, seq1, ... in document order.
struct Counter {
  std::map<std::string, int, std::less<>> next;
  std::string operator()(std::string_view prefix) {
    return std::string(prefix) + std::to_string(++next[std::string(prefix)]);
  }
};

Node point(const Vec2& p, PointKind kind = PointKind::plain) {
  Node n{"C2D", {{"x", format_double(p.x())}, {"y", format_double(p.y())}}, {}};
  if (kind == PointKind::turn) n.set_attribute("kind", "turn");
  if (kind == PointKind::curve) n.set_attribute("kind", "curve");
  return n;
}

Node sequence(Counter& ids, std::string_view role, const std::vector<Vec2>& pts, bool closed) {
  Node n{"C2DSEQ", {{"id", ids("seq")}, {"role", std::string(role)}}, {}};
  if (closed) n.set_attribute("closed", "true");
  for (const auto& p : pts) n.children.push_back(point(p));
  return n;
}

void put_if(Node& n, std::string_view name, const std::string& value) {
  if (!value.empty()) n.set_attribute(name, value);
}

Node pattern_node(const pattern::Piece& pc, const std::string& id, Counter& ids) {
  Node n{"PATTERN", {{"id", id}, {"block", pc.block}, {"piece", pc.name}, {"size", pc.size}}, {}};
  n.set_attribute("quantity", std::to_string(pc.quantity));
  if (pc.quantity_flipped != 0) n.set_attribute("flipped", std::to_string(pc.quantity_flipped));
  put_if(n, "category", pc.category);
  put_if(n, "fabric", pc.fabric);
  put_if(n, "annotation", pc.annotation);
  if (!pc.closed) n.set_attribute("closed", "false");
  if (pc.self_intersecting) n.set_attribute("self_intersecting", "true");

  for (const auto& [key, text] : pc.annotations) {
    Node a{"ANNOTATION", {}, {}};
    put_if(a, "key", key);
    a.set_attribute("text", text);
    n.children.push_back(std::move(a));
  }
  // The boundary, one C2DSEQ per stretch: a new one at every turn point, so a hem can
  // name the edge between two corners. The first keeps the contour's first vertex.
  for (std::size_t i = 0; i < pc.boundary.size(); ++i) {
    const ContourPoint& cp = pc.boundary[i];
    if (i == 0 || cp.kind == PointKind::turn) n.children.push_back(Node{"C2DSEQ", {{"id", ids("seq")}}, {}});
    n.children.back().children.push_back(point(cp.p, cp.kind));
  }
  for (const auto& l : pc.internal_lines) n.children.push_back(sequence(ids, "internal", l.points, l.closed));
  for (const auto& l : pc.cutouts) n.children.push_back(sequence(ids, "cutout", l.points, l.closed));
  for (const auto& l : pc.sew_lines) n.children.push_back(sequence(ids, "sew", l.points, l.closed));
  const std::pair<const char*, const std::optional<pattern::Segment>*> lines[] = {
      {"grain", &pc.grain_line}, {"mirror", &pc.mirror_line}, {"grade", &pc.grade_reference}};
  for (const auto& [role, seg] : lines)
    if (*seg) n.children.push_back(sequence(ids, role, {(*seg)->a, (*seg)->b}, false));

  for (const auto& nt : pc.notches) {
    Node pn{"POSITION",
            {{"id", ids("pos")},
             {"type", "notch"},
             {"x", format_double(nt.position.x())},
             {"y", format_double(nt.position.y())},
             {"angle", format_double(nt.angle_deg)}},
            {}};
    if (nt.length_m != 0) pn.set_attribute("length", format_double(nt.length_m));
    if (nt.width_m != 0) pn.set_attribute("width", format_double(nt.width_m));
    if (nt.type != 0) pn.set_attribute("notch_type", std::to_string(nt.type));
    if (nt.boundary_index >= 0) pn.set_attribute("vertex", std::to_string(nt.boundary_index));
    n.children.push_back(std::move(pn));
  }
  for (const auto& d : pc.drill_holes)
    n.children.push_back(
        Node{"POSITION", {{"id", ids("pos")}, {"type", "drill"}, {"x", format_double(d.x())}, {"y", format_double(d.y())}}, {}});
  return n;
}

// ---- XVC -> Style ------------------------------------------------------------------

Vec2 vec(const Node& n) {
  return {parse_double(n.attribute("x")).value_or(0.0), parse_double(n.attribute("y")).value_or(0.0)};
}

std::vector<Vec2> points(const Node& seq) {
  std::vector<Vec2> out;
  for (const auto& c : seq.children)
    if (c.tag == "C2D") out.push_back(vec(c));
  return out;
}

int count_or(const Node& n, std::string_view name, int fallback) {
  const auto v = parse_int(n.attribute(name));
  return v ? static_cast<int>(*v) : fallback;
}

double number_or(const Node& n, std::string_view name, double fallback) {
  return parse_double(n.attribute(name)).value_or(fallback);
}

pattern::Piece piece_of(const Node& n) {
  pattern::Piece pc;
  pc.block = n.attribute("block");
  pc.name = n.attribute("piece");
  pc.size = n.attribute("size");
  pc.quantity = count_or(n, "quantity", 1);
  pc.quantity_flipped = count_or(n, "flipped", 0);
  pc.category = n.attribute("category");
  pc.fabric = n.attribute("fabric");
  pc.annotation = n.attribute("annotation");
  pc.closed = detail::parse_bool(n.attribute("closed")).value_or(true);
  pc.self_intersecting = detail::parse_bool(n.attribute("self_intersecting")).value_or(false);

  for (const auto& c : n.children) {
    if (c.tag == "ANNOTATION") {
      pc.annotations.emplace_back(std::string(c.attribute("key")), std::string(c.attribute("text")));
    } else if (c.tag == "C2DSEQ") {
      const auto role = c.has_attribute("role") ? c.attribute("role") : std::string_view("boundary");
      const bool closed = detail::parse_bool(c.attribute("closed")).value_or(false);
      if (role == "boundary") {
        for (const auto& q : c.children) {
          const auto k = q.attribute("kind");
          pc.boundary.push_back({vec(q), k == "turn" ? PointKind::turn : k == "curve" ? PointKind::curve : PointKind::plain});
        }
      } else if (role == "internal") {
        pc.internal_lines.push_back({points(c), closed});
      } else if (role == "cutout") {
        pc.cutouts.push_back({points(c), closed});
      } else if (role == "sew") {
        pc.sew_lines.push_back({points(c), closed});
      } else {
        const auto pts = points(c);
        const pattern::Segment seg{pts.at(0), pts.at(1)};  // two points: check() saw to it
        if (role == "grain") pc.grain_line = seg;
        if (role == "mirror") pc.mirror_line = seg;
        if (role == "grade") pc.grade_reference = seg;
      }
    } else if (c.tag == "POSITION") {
      if (c.attribute("type") == "notch") {
        pattern::Notch nt;
        nt.position = vec(c);
        nt.angle_deg = number_or(c, "angle", 0.0);
        nt.length_m = number_or(c, "length", 0.0);
        nt.width_m = number_or(c, "width", 0.0);
        nt.type = count_or(c, "notch_type", 0);
        nt.boundary_index = count_or(c, "vertex", -1);
        pc.notches.push_back(nt);
      } else if (c.attribute("type") == "drill") {
        pc.drill_holes.push_back(vec(c));
      }
    }
  }
  return pc;
}
}  // namespace

Document from_style(const pattern::Style& style) {
  Document empty;
  Node g = empty.root();
  put_if(g, "name", style.name);
  put_if(g, "producer", style.producer);
  put_if(g, "flavour", style.flavour);
  put_if(g, "units", style.units);
  auto child = [&](std::string_view tag) -> Node& {
    return *std::find_if(g.children.begin(), g.children.end(), [&](const Node& c) { return c.tag == tag; });
  };

  // Patterns, one per block, in file order.
  Counter ids;
  std::vector<std::string> pattern_ids;
  Node& patterns = child("PATTERNS");
  for (const auto& pc : style.pieces) {
    pattern_ids.push_back(ids("pattern"));
    patterns.children.push_back(pattern_node(pc, pattern_ids.back(), ids));
  }

  // The size run, then one gradation per piece name listing the pattern of each size.
  Node& grads = child("GRADATIONS");
  put_if(grads, "sample_size", style.sample_size);
  auto size_node = [&](const std::string& name) {
    Node s{"SIZE", {{"id", ids("size")}, {"name", name}}, {}};
    return s;
  };
  for (const auto& sz : style.sizes) {
    Node s = size_node(sz);
    if (!style.sample_size.empty() && sz == style.sample_size) s.set_attribute("sample", "true");
    grads.children.push_back(std::move(s));
  }
  for (const auto& name : style.piece_names()) {
    Node gr{"GRADATION", {{"id", ids("grad")}, {"piece", name}}, {}};
    for (std::size_t i = 0; i < style.pieces.size(); ++i) {
      if (style.pieces[i].name != name) continue;
      Node s = size_node(style.pieces[i].size);
      s.set_attribute("pattern", pattern_ids[i]);
      if (!style.sample_size.empty() && style.pieces[i].size == style.sample_size) s.set_attribute("sample", "true");
      gr.children.push_back(std::move(s));
    }
    grads.children.push_back(std::move(gr));
  }
  return Document(std::move(g));
}

pattern::Style to_style(const Document& doc) {
  pattern::Style s;
  const Node& g = doc.root();
  s.name = g.attribute("name");
  s.producer = g.attribute("producer");
  s.flavour = g.attribute("flavour");
  s.units = g.attribute("units");
  if (const auto* grads = doc.container("GRADATIONS")) {
    s.sample_size = grads->attribute("sample_size");
    for (const auto& c : grads->children)
      if (c.tag == "SIZE") s.sizes.emplace_back(c.attribute("name"));
  }
  for (const Node* p : doc.patterns()) s.pieces.push_back(piece_of(*p));
  return s;
}

pattern::Piece to_piece(const Document& doc, std::string_view pattern_id) {
  return piece_of(doc.at(detail::require(doc, pattern_id, "PATTERN")));
}

std::vector<Stretch> boundary_stretches(const Node& pattern) {
  std::vector<Stretch> out;
  std::size_t first = 0;
  for (const auto& c : pattern.children) {
    if (!detail::is_boundary_sequence(c)) continue;
    const std::size_t n = detail::point_count(c);
    out.push_back({std::string(c.id()), first, n});
    first += n;
  }
  return out;
}

std::optional<bool> drape_attribute(const Node& pattern) {
  if (!pattern.has_attribute("drape")) return std::nullopt;
  return detail::parse_bool(pattern.attribute("drape"));
}

std::optional<bool> folded_attribute(const Node& pattern) {
  if (!pattern.has_attribute("folded")) return std::nullopt;
  return detail::parse_bool(pattern.attribute("folded"));
}

std::string piece_material(const Document& doc, const Node& pattern) {
  for (const auto& a : pattern.children)
    if (a.tag == "ASSOCIATION" && a.attribute("role") == "material")
      if (const Node* m = doc.find(a.attribute("ref")); m && m->tag == "MATERIAL") return std::string(m->id());
  return "";
}

std::string garment_material(const Document& doc) {
  if (const Node* mats = doc.container("MATERIALS"))
    for (const auto& m : mats->children)
      if (m.tag == "MATERIAL" && m.attribute("scope") != "piece") return std::string(m.id());
  return "";
}

pattern::RoleGuess piece_role(const Document& doc, const Node& pattern) {
  pattern::RoleGuess g = pattern::piece_role(pattern.attribute("piece"), pattern.attribute("category"),
                                             pattern.attribute("annotation"), doc.root().attribute("name"));
  if (pattern.has_attribute("role"))
    if (const auto set = pattern::role_from_name(pattern.attribute("role")); set && *set != g.role) {
      // A sleeve or leg set on a piece the name calls a front or back is that half of it.
      const pattern::Role named = g.role;
      g.role = *set;
      g.word = "role=\"" + std::string(pattern.attribute("role")) + "\"";
      if (g.role != pattern::Role::sleeve && g.role != pattern::Role::leg)
        g.half = pattern::Half::none;  // halves are of sleeves and legs only
      else if (g.half == pattern::Half::none && (named == pattern::Role::front || named == pattern::Role::back))
        g.half = named == pattern::Role::front ? pattern::Half::front : pattern::Half::back;
    }
  return g;
}

}  // namespace vgd::xvc
