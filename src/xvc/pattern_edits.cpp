// Edits that know what a pattern is: delete, copy, mirror; and setting a parameter.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>

#include "edit_helpers.hpp"
#include "rules.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/pattern/contour.hpp"
#include "vgd/xvc/commands.hpp"
#include "vgd/xvc/style.hpp"

namespace vgd::xvc {

using detail::require;
using Vec2 = Eigen::Vector2d;

// ---- DeletePattern -------------------------------------------------------------------

DeletePattern::DeletePattern(std::string pattern_id) : id_(std::move(pattern_id)) {}

std::string DeletePattern::label() const { return "Delete pattern " + id_; }

std::string DeletePattern::apply(Editor& edit) {
  detail::remove_with_dependents(edit, require(edit.document(), id_, "PATTERN"));
  return "";
}

// ---- CopyPattern ---------------------------------------------------------------------

namespace {
// `base`, or `base` + 2, 3, ... : the first not in `taken`.
std::string unique_name(const std::string& base, const std::set<std::string>& taken, const std::string& sep) {
  if (!taken.count(base)) return base;
  for (int n = 2;; ++n)
    if (auto s = base + sep + std::to_string(n); !taken.count(s)) return s;
}
}  // namespace

CopyPattern::CopyPattern(std::string pattern_id) : id_(std::move(pattern_id)) {}

std::string CopyPattern::label() const { return "Copy pattern " + id_; }

std::string CopyPattern::apply(Editor& edit) {
  const Document& doc = edit.document();
  const NodePath path = require(doc, id_, "PATTERN");
  Node copy = doc.at(path);
  // The view lays the copy out beside the original, not over it.
  std::erase_if(copy.children, [](const Node& c) { return c.tag == "POSITION" && c.attribute("type") == "sheet"; });
  detail::IdMaker ids(doc);
  detail::assign_ids(copy, ids, true);

  // The copy is a piece of its own: a block and a piece name nobody else uses.
  std::set<std::string> blocks, pieces;
  for (const Node* p : doc.patterns()) {
    blocks.insert(std::string(p->attribute("block")));
    pieces.insert(std::string(p->attribute("piece")));
  }
  const std::string block(copy.attribute("block")), piece(copy.attribute("piece"));
  copy.set_attribute("block", unique_name((block.empty() ? id_ : block) + "_copy", blocks, ""));
  copy.set_attribute("piece", unique_name(piece.empty() ? "copy" : piece + " copy", pieces, " "));
  const std::string copy_id(copy.id());
  const std::string size(copy.attribute("size"));
  const std::string new_piece(copy.attribute("piece"));
  edit.insert(detail::parent_of(path), path.back() + 1, std::move(copy));

  // Its own GRADATION, after the one that lists the original.
  if (const auto* grads = doc.container("GRADATIONS")) {
    const NodePath gpath = *doc.path_of(grads->id());
    std::size_t at = detail::canonical_index(*grads, "GRADATION");
    for (std::size_t i = 0; i < grads->children.size(); ++i)
      for (const auto& s : grads->children[i].children)
        if (grads->children[i].tag == "GRADATION" && s.attribute("pattern") == id_) at = i + 1;
    Node size_node{"SIZE", {{"id", ids.make("size")}, {"name", size}, {"pattern", copy_id}}, {}};
    if (grads->has_attribute("sample_size") && grads->attribute("sample_size") == size)
      size_node.set_attribute("sample", "true");
    Node grad{"GRADATION", {{"id", ids.make("grad")}, {"piece", new_piece}}, {std::move(size_node)}};
    edit.insert(gpath, at, std::move(grad));
  }
  return copy_id;
}

// ---- MirrorPattern -------------------------------------------------------------------

namespace {
Vec2 point_of(const Node& n) {
  return {parse_double(n.attribute("x")).value_or(0.0), parse_double(n.attribute("y")).value_or(0.0)};
}

void set_point(Node& n, const Vec2& p) {
  n.set_attribute("x", format_double(p.x()));
  n.set_attribute("y", format_double(p.y()));
}

// Angle in degrees brought into (-180, 180].
double normalise_deg(double a) {
  a = std::fmod(a, 360.0);
  if (a <= -180.0) a += 360.0;
  if (a > 180.0) a -= 360.0;
  return a;
}

// A reflection about a line, exact for vertical lines (x -> 2c - x) so mirroring about
// the bounding box leaves y untouched.
struct Reflection {
  bool vertical = true;
  double c = 0;        // vertical: the line x = c
  Vec2 a = Vec2::Zero();   // otherwise: a point on the line
  Vec2 u = Vec2::UnitY();  // and its unit direction
  double axis_deg = 90;

  Vec2 operator()(const Vec2& q) const {
    if (vertical) return {2 * c - q.x(), q.y()};
    const Vec2 r = q - a;
    return a + 2 * r.dot(u) * u - r;
  }
  double angle(double deg) const { return normalise_deg(2 * axis_deg - deg); }
};

const Node* grain_sequence(const Node& pattern) {
  for (const auto& c : pattern.children)
    if (c.tag == "C2DSEQ" && c.attribute("role") == "grain") return &c;
  return nullptr;
}
}  // namespace

MirrorPattern::MirrorPattern(std::string pattern_id, MirrorAxis axis) : id_(std::move(pattern_id)), axis_(axis) {}

std::string MirrorPattern::label() const { return "Mirror pattern " + id_; }

std::string MirrorPattern::apply(Editor& edit) {
  const Document& doc = edit.document();
  const NodePath path = require(doc, id_, "PATTERN");
  Node p = doc.at(path);

  // ---- the axis ----
  Reflection m;
  const Node* grain = grain_sequence(p);
  bool use_grain = axis_ == MirrorAxis::grain_line;
  if (use_grain && !grain) throw Error(doc.name(), id_, id_ + " has no grain line to mirror about", p.line);
  auto grain_length = [&] { return (point_of(grain->children.at(1)) - point_of(grain->children.at(0))).norm(); };
  // Automatic falls back to vertical when the grain line gives no direction.
  if (axis_ == MirrorAxis::automatic && grain && grain_length() > 0) use_grain = true;
  if (use_grain) {
    const Vec2 a = point_of(grain->children.at(0)), b = point_of(grain->children.at(1));
    const double len = grain_length();
    if (!(len > 0)) throw Error(doc.name(), id_, "the grain line of " + id_ + " has zero length", grain->line);
    m.vertical = false;
    m.a = a;
    m.u = (b - a) / len;
    m.axis_deg = std::atan2(m.u.y(), m.u.x()) * 180.0 / std::numbers::pi;
  } else {
    // Through the middle of the boundary's box (all points when there is no boundary).
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const bool boundary_only : {true, false}) {
      for (const auto& c : p.children)
        if (c.tag == "C2DSEQ" && (!boundary_only || detail::is_boundary_sequence(c)))
          for (const auto& q : c.children) {
            lo = std::min(lo, point_of(q).x());
            hi = std::max(hi, point_of(q).x());
          }
      if (lo <= hi) break;
    }
    if (!(lo <= hi)) throw Error(doc.name(), id_, id_ + " has no points to mirror", p.line);
    m.c = 0.5 * (lo + hi);
  }

  // ---- every point, notch and drill hole ----
  std::size_t n_boundary = 0;
  for (const auto& c : p.children)
    if (detail::is_boundary_sequence(c)) n_boundary += detail::point_count(c);
  for (auto& c : p.children) {
    if (c.tag == "C2DSEQ") {
      for (auto& q : c.children) set_point(q, m(point_of(q)));
      // A closed loop other than the outline keeps its winding sense, like the outline.
      if (!detail::is_boundary_sequence(c) && detail::parse_bool(c.attribute("closed")).value_or(false))
        std::reverse(c.children.begin(), c.children.end());
    } else if (c.tag == "POSITION" && c.attribute("type") != "sheet") {
      set_point(c, m(point_of(c)));
      if (const auto ang = parse_double(c.attribute("angle")); ang && c.has_attribute("angle"))
        c.set_attribute("angle", format_double(m.angle(*ang)));
      if (const auto v = parse_int(c.attribute("vertex")); v && n_boundary > 0)
        c.set_attribute("vertex", std::to_string((n_boundary - static_cast<std::size_t>(*v)) % n_boundary));
    }
  }

  // ---- the boundary, reversed so it stays counter-clockwise ----
  // Stretch k held [f_k .. f_{k+1}); reversed, the same edge runs f_{k+1} -> f_k, so it
  // now holds f_{k+1} followed by its own other points backwards. The stretches then
  // come in reverse order, and the contour still starts at the same vertex.
  std::vector<std::size_t> slots;
  for (std::size_t i = 0; i < p.children.size(); ++i)
    if (detail::is_boundary_sequence(p.children[i])) slots.push_back(i);
  std::vector<Node> reversed;
  for (std::size_t k = 0; k < slots.size(); ++k) {
    const Node& s = p.children[slots[k]];
    const Node& next = p.children[slots[(k + 1) % slots.size()]];
    Node r = s;
    r.children.clear();
    r.children.push_back(next.children.front());
    for (auto it = s.children.rbegin(); it + 1 < s.children.rend(); ++it) r.children.push_back(*it);
    reversed.push_back(std::move(r));
  }
  for (std::size_t i = 0; i < slots.size(); ++i) p.children[slots[i]] = std::move(reversed[slots.size() - 1 - i]);

  // ---- hems along this pattern now run the other way ----
  std::set<std::string> stretches;
  for (const auto& c : p.children)
    if (detail::is_boundary_sequence(c)) stretches.insert(std::string(c.id()));
  std::vector<NodePath> hems;
  if (const auto* seams = doc.container("SEAMS")) {
    const NodePath spath = *doc.path_of(seams->id());
    for (std::size_t i = 0; i < seams->children.size(); ++i)
      for (std::size_t j = 0; j < seams->children[i].children.size(); ++j) {
        const Node& h = seams->children[i].children[j];
        if (h.tag == "HEM" && stretches.count(std::string(h.attribute("from")))) hems.push_back({spath[0], i, j});
      }
  }
  edit.replace(path, std::move(p));
  for (const auto& hp : hems) {
    const Node& h = doc.at(hp);
    const std::string from(h.attribute("from")), to(h.attribute("to"));
    const bool reverse = h.attribute("direction") == "reverse";
    edit.set_attribute(hp, "from", to);
    edit.set_attribute(hp, "to", from);
    edit.set_attribute(hp, "direction", reverse ? "forward" : "reverse");
  }
  return id_;
}

// ---- outline points ------------------------------------------------------------------

namespace {
// Where an outline point is: the pattern's path, the C2DSEQ's child index, the C2D's
// child index in it, and the point's index along the whole boundary.
struct PointAt {
  NodePath pattern;
  std::size_t sequence = 0, child = 0, vertex = 0;
};

PointAt locate(const Document& doc, const OutlinePoint& pt) {
  PointAt at;
  at.pattern = require(doc, pt.pattern_id, "PATTERN");
  const Node& p = doc.at(at.pattern);
  std::size_t first = 0;
  for (std::size_t i = 0; i < p.children.size(); ++i) {
    const Node& c = p.children[i];
    if (!detail::is_boundary_sequence(c)) continue;
    if (c.id() != pt.sequence_id) {
      first += detail::point_count(c);
      continue;
    }
    std::size_t k = 0;
    for (std::size_t j = 0; j < c.children.size(); ++j) {
      if (c.children[j].tag != "C2D") continue;
      if (k == pt.index) {
        at.sequence = i, at.child = j, at.vertex = first + k;
        return at;
      }
      ++k;
    }
    throw Error(doc.name(), pt.sequence_id,
                pt.sequence_id + " has " + std::to_string(k) + " points, no point " + std::to_string(pt.index), c.line);
  }
  throw Error(doc.name(), pt.pattern_id, pt.pattern_id + " has no outline stretch " + pt.sequence_id, p.line);
}

std::string point_name(const OutlinePoint& pt) {
  return "point " + std::to_string(pt.index) + " of " + pt.pattern_id + "/" + pt.sequence_id;
}

NodePath child_path(NodePath path, std::size_t a) {
  path.push_back(a);
  return path;
}

void check_kind(const std::string& kind, const Document& doc, const OutlinePoint& pt) {
  if (kind != "plain" && kind != "turn" && kind != "curve")
    throw Error(doc.name(), pt.pattern_id, "a point's kind is plain, turn or curve, not '" + kind + "'");
}
}  // namespace

MovePoint::MovePoint(OutlinePoint point, double x, double y) : at_(std::move(point)), x_(x), y_(y) {}

std::string MovePoint::label() const { return "Move " + point_name(at_); }

std::string MovePoint::apply(Editor& edit) {
  const Document& doc = edit.document();
  if (!std::isfinite(x_) || !std::isfinite(y_)) throw Error(doc.name(), at_.pattern_id, "a point's x and y must be finite");
  const PointAt at = locate(doc, at_);
  const NodePath c2d = child_path(child_path(at.pattern, at.sequence), at.child);
  const Vec2 was = point_of(doc.at(c2d));
  edit.set_attribute(c2d, "x", format_double(x_));
  edit.set_attribute(c2d, "y", format_double(y_));
  // A notch on the vertex moves with it.
  const Node& p = doc.at(at.pattern);
  for (std::size_t i = 0; i < p.children.size(); ++i) {
    const Node& c = p.children[i];
    if (c.tag != "POSITION" || parse_int(c.attribute("vertex")) != std::optional<int>(static_cast<int>(at.vertex)))
      continue;
    const Vec2 q = point_of(c) + (Vec2(x_, y_) - was);
    edit.set_attribute(child_path(at.pattern, i), "x", format_double(q.x()));
    edit.set_attribute(child_path(at.pattern, i), "y", format_double(q.y()));
  }
  return at_.pattern_id;
}

InsertPoint::InsertPoint(OutlinePoint after, std::string kind, std::optional<std::array<double, 2>> xy)
    : after_(std::move(after)), kind_(std::move(kind)), xy_(xy) {}

std::string InsertPoint::label() const { return "Insert a point after " + point_name(after_); }

std::string InsertPoint::apply(Editor& edit) {
  const Document& doc = edit.document();
  check_kind(kind_, doc, after_);
  const PointAt at = locate(doc, after_);
  const Node& p = doc.at(at.pattern);
  Vec2 q;
  if (xy_) {
    q = {(*xy_)[0], (*xy_)[1]};
    if (!q.allFinite()) throw Error(doc.name(), after_.pattern_id, "a point's x and y must be finite");
  } else {
    // The middle of the edge to the next outline point (the next stretch's first
    // point after a stretch's last; the outline's first after its last).
    std::vector<Vec2> outline;
    for (const auto& c : p.children)
      if (detail::is_boundary_sequence(c))
        for (const auto& pt : c.children)
          if (pt.tag == "C2D") outline.push_back(point_of(pt));
    q = 0.5 * (outline[at.vertex] + outline[(at.vertex + 1) % outline.size()]);
  }
  Node n{"C2D", {{"x", format_double(q.x())}, {"y", format_double(q.y())}}, {}};
  if (kind_ != "plain") n.set_attribute("kind", kind_);
  detail::renumber_vertices(edit, at.pattern, at.vertex + 1, 0, 1);
  edit.insert(child_path(at.pattern, at.sequence), at.child + 1, std::move(n));
  return after_.pattern_id;
}

DeletePoint::DeletePoint(OutlinePoint point) : at_(std::move(point)) {}

std::string DeletePoint::label() const { return "Delete " + point_name(at_); }

std::string DeletePoint::apply(Editor& edit) {
  const Document& doc = edit.document();
  const PointAt at = locate(doc, at_);
  if (at_.index == 0)
    throw Error(doc.name(), at_.pattern_id,
                point_name(at_) + " is where the stretch " + at_.sequence_id +
                    " begins (seams are sewn from it): move it, or delete the stretch");
  std::size_t total = 0;
  for (const auto& c : doc.at(at.pattern).children)
    if (detail::is_boundary_sequence(c)) total += detail::point_count(c);
  if (total <= 3) throw Error(doc.name(), at_.pattern_id, "an outline keeps at least three points");
  detail::renumber_vertices(edit, at.pattern, at.vertex, 1, 0);
  edit.remove(child_path(child_path(at.pattern, at.sequence), at.child));
  return at_.pattern_id;
}

SetPointKind::SetPointKind(OutlinePoint point, std::string kind) : at_(std::move(point)), kind_(std::move(kind)) {}

std::string SetPointKind::label() const { return "Make " + point_name(at_) + " a " + kind_ + " point"; }

std::string SetPointKind::apply(Editor& edit) {
  const Document& doc = edit.document();
  check_kind(kind_, doc, at_);
  const PointAt at = locate(doc, at_);
  const NodePath c2d = child_path(child_path(at.pattern, at.sequence), at.child);
  edit.set_attribute(c2d, "kind", kind_ == "plain" ? std::nullopt : std::optional<std::string>(kind_));
  return at_.pattern_id;
}

// ---- RotatePattern -------------------------------------------------------------------

RotatePattern::RotatePattern(std::string pattern_id, double degrees) : id_(std::move(pattern_id)), degrees_(degrees) {}

std::string RotatePattern::label() const { return "Rotate pattern " + id_ + " by " + format_double(degrees_) + "°"; }

std::string RotatePattern::apply(Editor& edit) {
  const Document& doc = edit.document();
  if (!std::isfinite(degrees_)) throw Error(doc.name(), id_, "the angle must be a finite number");
  const NodePath path = require(doc, id_, "PATTERN");
  Node p = doc.at(path);
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& c : p.children)
    if (detail::is_boundary_sequence(c))
      for (const auto& q : c.children)
        if (q.tag == "C2D") lo = lo.cwiseMin(point_of(q)), hi = hi.cwiseMax(point_of(q));
  if (!(lo.x() <= hi.x())) throw Error(doc.name(), id_, id_ + " has no outline to rotate", p.line);
  const Vec2 centre = 0.5 * (lo + hi);
  const double a = degrees_ * std::numbers::pi / 180.0;
  // Quarter turns exactly (no 6e-17 where a coordinate was 0).
  double cs = std::cos(a), sn = std::sin(a);
  if (std::fmod(std::abs(degrees_), 90.0) == 0.0) cs = std::round(cs), sn = std::round(sn);
  auto turn = [&](const Vec2& q) {
    const Vec2 r = q - centre;
    return Vec2(centre.x() + cs * r.x() - sn * r.y(), centre.y() + sn * r.x() + cs * r.y());
  };
  for (auto& c : p.children) {
    if (c.tag == "C2DSEQ" && c.attribute("role") != "grain") {
      for (auto& q : c.children)
        if (q.tag == "C2D") set_point(q, turn(point_of(q)));
    } else if (c.tag == "POSITION" && c.attribute("type") != "sheet") {
      // Its point turns with the piece (an arrangement's reference point too); a
      // notch's direction with it (an arrangement's angle is round the body: kept).
      set_point(c, turn(point_of(c)));
      if (const auto ang = parse_double(c.attribute("angle")); ang && c.attribute("type") == "notch")
        c.set_attribute("angle", format_double(normalise_deg(*ang + degrees_)));
    }
  }
  edit.replace(path, std::move(p));
  return id_;
}

// ---- MoveNotch ---------------------------------------------------------------------

namespace {

// A notch on boundary vertex `vertex` of `outline`: its point, its vertex,
// its cut along the inward normal (the outline's tangent there, from its
// neighbours, turned a quarter towards the inside).
void lay_notch(Node& notch, const std::vector<pattern::ContourPoint>& outline, std::size_t vertex) {
  const std::size_t n = outline.size();
  const Vec2 t = outline[(vertex + 1) % n].p - outline[(vertex + n - 1) % n].p;
  const Vec2 inward = pattern::signed_area(outline) >= 0 ? Vec2(-t.y(), t.x()) : Vec2(t.y(), -t.x());
  set_point(notch, outline[vertex].p);
  notch.set_attribute("vertex", std::to_string(vertex));
  if (inward.norm() > 0)
    notch.set_attribute("angle", format_double(normalise_deg(std::atan2(inward.y(), inward.x()) * 180.0 / std::numbers::pi)));
}

}  // namespace

MoveNotch::MoveNotch(std::string pattern_id, std::string notch_id, std::size_t vertex)
    : pattern_(std::move(pattern_id)), notch_(std::move(notch_id)), vertex_(vertex) {}

std::string MoveNotch::label() const { return "Move notch " + notch_ + " to vertex " + std::to_string(vertex_); }

std::string MoveNotch::apply(Editor& edit) {
  const Document& doc = edit.document();
  const NodePath path = require(doc, pattern_, "PATTERN");
  Node p = doc.at(path);
  const auto outline = to_piece(doc, pattern_).boundary;  // the concatenated boundary, as `vertex` counts it
  const std::size_t n = outline.size();
  if (vertex_ >= n)
    throw Error(doc.name(), notch_, "vertex " + std::to_string(vertex_) + " is beyond the boundary of " + pattern_ +
                                        ", which has " + std::to_string(n) + " points");
  Node* notch = nullptr;
  for (auto& c : p.children)
    if (c.tag == "POSITION" && c.id() == notch_) notch = &c;
  if (!notch || notch->attribute("type") != "notch")
    throw Error(doc.name(), notch_, notch_ + " is not a notch of " + pattern_);
  lay_notch(*notch, outline, vertex_);
  edit.replace(path, std::move(p));
  return notch_;
}

// ---- AddNotch ----------------------------------------------------------------------

AddNotch::AddNotch(std::string pattern_id, std::size_t vertex) : pattern_(std::move(pattern_id)), vertex_(vertex) {}

std::string AddNotch::label() const { return "Add a notch to " + pattern_ + " at vertex " + std::to_string(vertex_); }

std::string AddNotch::apply(Editor& edit) {
  const Document& doc = edit.document();
  const NodePath path = require(doc, pattern_, "PATTERN");
  Node p = doc.at(path);
  const auto outline = to_piece(doc, pattern_).boundary;
  const std::size_t n = outline.size();
  if (vertex_ >= n)
    throw Error(doc.name(), pattern_, "vertex " + std::to_string(vertex_) + " is beyond the boundary of " + pattern_ +
                                          ", which has " + std::to_string(n) + " points");
  std::size_t at = 0;  // after the pattern's sequences, annotations and positions
  for (std::size_t i = 0; i < p.children.size(); ++i) {
    const Node& c = p.children[i];
    if (c.tag == "C2DSEQ" || c.tag == "ANNOTATION" || c.tag == "POSITION") at = i + 1;
    if (c.tag == "POSITION" && c.attribute("type") == "notch" && c.attribute("vertex") == std::to_string(vertex_))
      throw Error(doc.name(), pattern_, "vertex " + std::to_string(vertex_) + " of " + pattern_ + " has a notch already (" +
                                            std::string(c.id()) + ")");
  }
  detail::IdMaker ids(doc);
  Node notch{"POSITION", {{"id", ids.make("pos")}, {"type", "notch"}, {"length", "0.005"}}, {}};
  lay_notch(notch, outline, vertex_);
  const std::string id(notch.id());
  p.children.insert(p.children.begin() + static_cast<std::ptrdiff_t>(at), std::move(notch));
  edit.replace(path, std::move(p));
  return id;
}

// ---- AddPin -----------------------------------------------------------------------

AddPin::AddPin(std::string pattern_id, std::array<double, 2> at) : pattern_(std::move(pattern_id)), at_(at) {}

std::string AddPin::label() const { return "Pin " + pattern_; }

std::string AddPin::apply(Editor& edit) {
  const Document& doc = edit.document();
  const NodePath path = require(doc, pattern_, "PATTERN");
  const Vec2 q(at_[0], at_[1]);
  if (!q.allFinite()) throw Error(doc.name(), pattern_, "a pin's point must be finite");
  const auto outline = to_piece(doc, pattern_).boundary;
  if (!pattern::point_in_outline(outline, q) && pattern::nearest_edge(outline, q).distance > 1e-3)
    throw Error(doc.name(), pattern_,
                "the pin's point (" + format_double(q.x()) + ", " + format_double(q.y()) + ") m lies " +
                    format_fixed(1000 * pattern::nearest_edge(outline, q).distance, 1) + " mm outside the piece " +
                    pattern_ + ": a pin holds the piece's own cloth");
  Node p = doc.at(path);
  std::size_t at = 0;  // after the pattern's sequences, annotations and positions
  for (std::size_t i = 0; i < p.children.size(); ++i)
    if (p.children[i].tag == "C2DSEQ" || p.children[i].tag == "ANNOTATION" || p.children[i].tag == "POSITION") at = i + 1;
  detail::IdMaker ids(doc);
  Node pin{"POSITION", {{"id", ids.make("pos")}, {"type", "pin"}, {"x", format_double(q.x())}, {"y", format_double(q.y())}}, {}};
  const std::string id(pin.id());
  p.children.insert(p.children.begin() + static_cast<std::ptrdiff_t>(at), std::move(pin));
  edit.replace(path, std::move(p));
  return id;
}

// ---- SetGrainLine -----------------------------------------------------------------

SetGrainLine::SetGrainLine(std::string pattern_id, std::array<double, 2> a, std::array<double, 2> b)
    : id_(std::move(pattern_id)), a_(a), b_(b) {}

std::string SetGrainLine::label() const { return "Set the grain line of " + id_; }

std::string SetGrainLine::apply(Editor& edit) {
  const Document& doc = edit.document();
  const NodePath path = require(doc, id_, "PATTERN");
  const Vec2 a(a_[0], a_[1]), b(b_[0], b_[1]);
  if (!a.allFinite() || !b.allFinite()) throw Error(doc.name(), id_, "a grain line's ends must be finite");
  if ((b - a).norm() < 0.01)
    throw Error(doc.name(), id_, "a grain line must be at least 1 cm long, not " + format_double(100 * (b - a).norm()) + " cm");
  Node p = doc.at(path);
  Node* seq = nullptr;
  for (auto& c : p.children)
    if (c.tag == "C2DSEQ" && c.attribute("role") == "grain") seq = &c;
  detail::IdMaker ids(doc);
  if (!seq) {
    // After the pattern's other sequences.
    std::size_t at = 0;
    for (std::size_t i = 0; i < p.children.size(); ++i)
      if (p.children[i].tag == "C2DSEQ" || p.children[i].tag == "ANNOTATION") at = i + 1;
    auto it = p.children.insert(p.children.begin() + static_cast<std::ptrdiff_t>(at),
                                Node{"C2DSEQ", {{"id", ids.make("seq")}, {"role", "grain"}}, {}});
    seq = &*it;
  }
  seq->children.clear();
  for (const Vec2& q : {a, b}) {
    Node c{"C2D", {}, {}};
    set_point(c, q);
    seq->children.push_back(std::move(c));
  }
  edit.replace(path, std::move(p));
  return id_;
}

// ---- SetSheetPosition -----------------------------------------------------------------

std::optional<std::array<double, 2>> sheet_position(const Node& pattern) {
  for (const auto& c : pattern.children)
    if (c.tag == "POSITION" && c.attribute("type") == "sheet") {
      const auto x = parse_double(c.attribute("x")), y = parse_double(c.attribute("y"));
      if (x && y) return std::array<double, 2>{*x, *y};
    }
  return std::nullopt;
}

SetSheetPosition::SetSheetPosition(std::string pattern_id, std::optional<std::array<double, 2>> at)
    : id_(std::move(pattern_id)), at_(at) {}

std::string SetSheetPosition::label() const { return "Move pattern " + id_ + " on the sheet"; }

std::string SetSheetPosition::apply(Editor& edit) {
  const Document& doc = edit.document();
  const NodePath path = require(doc, id_, "PATTERN");
  if (at_ && !(std::isfinite((*at_)[0]) && std::isfinite((*at_)[1])))
    throw Error(doc.name(), id_, "a sheet position must be finite");
  Node p = doc.at(path);
  std::erase_if(p.children, [](const Node& c) { return c.tag == "POSITION" && c.attribute("type") == "sheet"; });
  if (at_) {
    detail::IdMaker ids(doc);
    Node pos{"POSITION",
             {{"id", ids.make("pos")}, {"type", "sheet"}, {"x", format_double((*at_)[0])}, {"y", format_double((*at_)[1])}},
             {}};
    // After the pattern's other POSITIONs (the schema's order: C2DSEQ, POSITION, ASSOCIATION).
    std::size_t at = 0;
    for (std::size_t i = 0; i < p.children.size(); ++i)
      if (p.children[i].tag == "C2DSEQ" || p.children[i].tag == "POSITION" || p.children[i].tag == "ANNOTATION") at = i + 1;
    p.children.insert(p.children.begin() + static_cast<std::ptrdiff_t>(at), std::move(pos));
  }
  edit.replace(path, std::move(p));
  return id_;
}

// ---- SetPieceMaterial ----------------------------------------------------------------

namespace {
// Content equality without ids (a pasted copy has fresh ones).
bool same_content(const Node& a, const Node& b) {
  if (a.tag != b.tag || a.children.size() != b.children.size()) return false;
  auto attrs = [](const Node& n) {
    std::vector<std::pair<std::string, std::string>> out;
    for (const auto& at : n.attributes)
      if (at.name != "id") out.emplace_back(at.name, at.value);
    return out;
  };
  if (attrs(a) != attrs(b)) return false;
  for (std::size_t i = 0; i < a.children.size(); ++i)
    if (!same_content(a.children[i], b.children[i])) return false;
  return true;
}
}  // namespace

SetPieceMaterial::SetPieceMaterial(std::string pattern_id, std::optional<Node> material)
    : id_(std::move(pattern_id)), material_(std::move(material)) {}

std::string SetPieceMaterial::label() const {
  return material_ ? "Cut " + id_ + " from " + std::string(material_->attribute("id")) : "Cut " + id_ + " from the garment's fabric";
}

std::string SetPieceMaterial::apply(Editor& edit) {
  const Document& doc = edit.document();
  const NodePath path = require(doc, id_, "PATTERN");
  if (material_ && material_->tag != "MATERIAL")
    throw Error(doc.name(), id_, "a piece is cut from a MATERIAL, not a " + material_->tag);
  const Node* mats = doc.container("MATERIALS");
  if (!mats) throw Error(doc.name(), id_, "the document has no MATERIALS to hold the piece's fabric");
  // How many pieces name each MATERIAL.
  std::map<std::string, int> named;
  for (const Node* p : doc.patterns())
    for (const auto& a : p->children)
      if (a.tag == "ASSOCIATION" && a.attribute("role") == "material") ++named[std::string(a.attribute("ref"))];
  // The fabric: a piece's own MATERIAL with the same content, else a fresh copy.
  std::string target;
  Node fabric;
  if (material_) {
    fabric = *material_;
    fabric.set_attribute("scope", "piece");
    for (const auto& m : mats->children)
      if (m.tag == "MATERIAL" && m.attribute("scope") == "piece" && same_content(m, fabric)) target = std::string(m.id());
  }
  // The pattern's present association(s) go; a MATERIAL left unnamed goes too.
  std::vector<std::string> dropped;
  const Node& p = doc.at(path);
  for (std::size_t i = p.children.size(); i-- > 0;) {
    const Node& a = p.children[i];
    if (a.tag != "ASSOCIATION" || a.attribute("role") != "material") continue;
    const std::string ref(a.attribute("ref"));
    if (ref == target) return target;  // already cut from it
    NodePath at = path;
    at.push_back(i);
    edit.remove(at);
    if (--named[ref] == 0) dropped.push_back(ref);
  }
  for (const auto& ref : dropped)
    if (const Node* m = doc.find(ref); m && m->attribute("scope") == "piece" && ref != target) edit.remove(*doc.path_of(ref));
  if (!material_) return "";
  if (target.empty()) {
    Node copy = std::move(fabric);
    detail::IdMaker ids(doc);
    detail::assign_ids(copy, ids, true);
    target = std::string(copy.id());
    const NodePath mpath = *doc.path_of(mats->id());
    edit.insert(mpath, doc.at(mpath).children.size(), std::move(copy));
  }
  detail::IdMaker ids(doc);
  Node assoc{"ASSOCIATION", {{"id", ids.make("assoc")}, {"ref", target}, {"role", "material"}}, {}};
  const Node& pat = doc.at(path);
  edit.insert(path, detail::canonical_index(pat, "ASSOCIATION"), std::move(assoc));
  return target;
}

// ---- SetParameter --------------------------------------------------------------------

SetParameter::SetParameter(std::string name, double value, std::string unit)
    : name_(std::move(name)), value_(value), unit_(std::move(unit)) {}

std::string SetParameter::label() const { return "Set " + name_; }

std::string SetParameter::apply(Editor& edit) {
  const Document& doc = edit.document();
  const auto* spec = find_parameter_spec(name_);
  std::string unit = unit_;
  // Clear messages here; check() would refuse the same values less directly.
  if (!std::isfinite(value_)) throw Error(doc.name(), name_, "the value must be a finite number");
  if (unit.empty()) {
    if (!spec) throw Error(doc.name(), name_, name_ + " is not a parameter vgd knows; give its unit");
    unit = spec->unit;
  }
  if (spec && unit != spec->unit)
    throw Error(doc.name(), name_, name_ + " is in " + std::string(spec->unit) + ", not " + unit);
  if (spec && (value_ <= spec->min || value_ > spec->max))
    throw Error(doc.name(), name_,
                name_ + " must be greater than " + format_double(spec->min) + " and at most " +
                    format_double(spec->max) + " " + std::string(spec->unit) + ", not " + format_double(value_));

  const Node& root = doc.root();
  for (std::size_t i = 0; i < root.children.size(); ++i) {
    const Node& c = root.children[i];
    if (c.tag != "PARAMETER" || c.attribute("name") != name_) continue;
    edit.set_attribute({i}, "value", format_double(value_));
    edit.set_attribute({i}, "unit", unit);
    return std::string(c.id());
  }
  const std::string id = doc.fresh_id("param");
  Node n{"PARAMETER", {{"id", id}, {"name", name_}, {"value", format_double(value_)}, {"unit", unit}}, {}};
  edit.insert({}, detail::canonical_index(root, "PARAMETER"), std::move(n));
  return id;
}


// ---- AddInternalLine, AddDrawnPattern ------------------------------------------------

namespace {
std::vector<Vec2> finite_points(const Document& doc, std::string_view where, const std::vector<std::array<double, 2>>& pts) {
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (!std::isfinite(pts[i][0]) || !std::isfinite(pts[i][1]))
      throw Error(doc.name(), std::string(where), "point " + std::to_string(i + 1) + " is not a finite coordinate");
    out.emplace_back(pts[i][0], pts[i][1]);
  }
  return out;
}
}  // namespace

AddInternalLine::AddInternalLine(std::string pattern_id, std::vector<std::array<double, 2>> points, bool closed)
    : id_(std::move(pattern_id)), points_(std::move(points)), closed_(closed) {}

std::string AddInternalLine::label() const { return "Draw a line on " + id_; }

std::string AddInternalLine::apply(Editor& edit) {
  const Document& doc = edit.document();
  const NodePath path = require(doc, id_, "PATTERN");
  const std::size_t least = closed_ ? 3 : 2;
  if (points_.size() < least)
    throw Error(doc.name(), id_, "an internal line needs at least " + std::to_string(least) + " points, not " +
                                     std::to_string(points_.size()));
  const auto pts = finite_points(doc, id_, points_);
  const pattern::Piece piece = to_piece(doc, id_);
  constexpr double kOnOutline = 0.001;  // m
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (piece.boundary.size() < 3 ||
        (!pattern::point_in_outline(piece.boundary, pts[i]) && pattern::nearest_edge(piece.boundary, pts[i]).distance > kOnOutline))
      throw Error(doc.name(), id_, "point " + std::to_string(i + 1) + " of the line (" + format_fixed(100 * pts[i].x(), 1) +
                                       ", " + format_fixed(100 * pts[i].y(), 1) + " cm) lies outside the piece");
  detail::IdMaker ids(doc);
  Node seq{"C2DSEQ", {{"id", ids.make("seq")}, {"role", "internal"}}, {}};
  if (closed_) seq.set_attribute("closed", "true");
  for (const auto& q : pts) seq.children.push_back(Node{"C2D", {{"x", format_double(q.x())}, {"y", format_double(q.y())}}, {}});
  // After the boundary and the internal lines already there.
  const Node& p = doc.at(path);
  std::size_t at = 0;
  for (std::size_t i = 0; i < p.children.size(); ++i)
    if (p.children[i].tag == "C2DSEQ" && (detail::is_boundary_sequence(p.children[i]) || p.children[i].attribute("role") == "internal"))
      at = i + 1;
  if (at == 0) at = detail::canonical_index(p, "C2DSEQ");
  edit.insert(path, at, std::move(seq));
  return id_;
}

AddDrawnPattern::AddDrawnPattern(std::string name, std::string size, std::vector<std::array<double, 2>> points,
                                 std::vector<bool> curve)
    : name_(std::move(name)), size_(std::move(size)), points_(std::move(points)), curve_(std::move(curve)) {}

std::string AddDrawnPattern::label() const { return "Draw piece " + name_; }

std::string AddDrawnPattern::apply(Editor& edit) {
  const Document& doc = edit.document();
  const std::string where = "drawn piece " + name_;
  if (points_.size() < 3)
    throw Error(doc.name(), where, "a piece needs at least 3 points, not " + std::to_string(points_.size()));
  const auto pts = finite_points(doc, where, points_);
  if (!curve_.empty() && curve_.size() != pts.size())
    throw Error(doc.name(), where, "a curve mark for each of its " + std::to_string(pts.size()) + " points, not " +
                                       std::to_string(curve_.size()));
  pattern::Piece pc;
  for (std::size_t k = 0; k < pts.size(); ++k)
    pc.boundary.push_back({pts[k], !curve_.empty() && curve_[k] ? pattern::PointKind::curve : pattern::PointKind::turn});
  if (pattern::is_self_intersecting(pc.boundary)) throw Error(doc.name(), where, "its sides cross");
  constexpr double kLeastArea = 1e-4;  // m²
  if (std::abs(pattern::signed_area(pc.boundary)) < kLeastArea)
    throw Error(doc.name(), where, "its area is under 1 cm²");
  pattern::make_counter_clockwise(pc.boundary);
  // Its first stretch begins at a corner.
  const auto corner = std::find_if(pc.boundary.begin(), pc.boundary.end(),
                                   [](const pattern::ContourPoint& c) { return c.kind == pattern::PointKind::turn; });
  if (corner != pc.boundary.end()) std::rotate(pc.boundary.begin(), corner, pc.boundary.end());
  std::set<std::string> blocks, pieces;
  for (const Node* p : doc.patterns()) {
    blocks.insert(std::string(p->attribute("block")));
    pieces.insert(std::string(p->attribute("piece")));
  }
  const auto* grads = doc.container("GRADATIONS");
  std::string size = size_;
  if (size.empty() && grads) size = std::string(grads->attribute("sample_size"));
  if (size.empty() && !doc.patterns().empty()) size = std::string(doc.patterns().front()->attribute("size"));
  if (size.empty()) size = "base";
  const std::string base = name_.empty() ? "drawn piece" : name_;
  pc.name = unique_name(base, pieces, " ");
  pc.block = unique_name(base, blocks, " ");
  pc.size = size;
  pc.quantity = 1;
  pattern::Style style;
  style.pieces.push_back(pc);
  style.sizes = {size};
  const Document one = from_style(style);
  Node node = *one.patterns().front();
  detail::IdMaker ids(doc);
  detail::assign_ids(node, ids, true);
  const std::string id(node.id());
  const Node* list = doc.container("PATTERNS");
  if (!list) throw Error(doc.name(), where, "the document has no PATTERNS to add it to");
  edit.insert(*doc.path_of(list->id()), list->children.size(), std::move(node));
  if (grads) {
    Node size_node{"SIZE", {{"id", ids.make("size")}, {"name", size}, {"pattern", id}}, {}};
    if (grads->has_attribute("sample_size") && grads->attribute("sample_size") == size) size_node.set_attribute("sample", "true");
    Node grad{"GRADATION", {{"id", ids.make("grad")}, {"piece", pc.name}}, {std::move(size_node)}};
    edit.insert(*doc.path_of(grads->id()), grads->children.size(), std::move(grad));
  }
  return id;
}

}  // namespace vgd::xvc
