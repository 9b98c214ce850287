// AAMA / ASTM D6673 interpretation of a raw DXF drawing: blocks become pieces,
// layers become outline, notches, grain line and the rest, texts become
// attributes, file units become metres. Every repair is reported.
#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <map>
#include <set>

#include "encoding.hpp"
#include "raw.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/io/dxf/import.hpp"
#include "vgd/pattern/contour.hpp"
#include "vgd/pattern/grading.hpp"

namespace vgd::dxf {

using pattern::ContourPoint;
using pattern::Piece;
using pattern::PointKind;
using pattern::Vec2;

namespace {

// ---- texts ---------------------------------------------------------------------

struct KeyValue {
  std::string key;  // lower-case, single spaces; empty when the text has no "key:"
  std::string value;
};

KeyValue split_text(std::string_view text) {
  const auto colon = text.find(':');
  if (colon == std::string_view::npos) return {"", std::string(trim(text))};
  std::string key;
  for (char c : to_lower(trim(text.substr(0, colon)))) {
    if (c == '_' || c == '\t') c = ' ';
    if (c == ' ' && (key.empty() || key.back() == ' ')) continue;
    key += c;
  }
  // "12:30" or "C:\\path" are not keyed texts: a key starts with a letter.
  if (key.empty() || !std::isalpha(static_cast<unsigned char>(key[0]))) return {"", std::string(trim(text))};
  return {key, std::string(trim(text.substr(colon + 1)))};
}

// Grade-rule labels ("# 12") sit at graded points on several layers.
bool is_grade_rule_label(std::string_view s) {
  s = trim(s);
  if (s.empty() || s[0] != '#') return false;
  return parse_int(s.substr(1)).has_value();
}

int layer_number(const std::string& layer) {
  const auto n = parse_int(layer);
  return n ? static_cast<int>(*n) : -1;
}

// ---- transforms ----------------------------------------------------------------

// Block coordinates to metres: p_m = scale * (offset + R S (p - base)).
struct Xform {
  Eigen::Matrix2d m = Eigen::Matrix2d::Identity();
  Vec2 t = Vec2::Zero();
  Vec2 apply(double x, double y) const { return m * Vec2(x, y) + t; }
  Xform then(const Xform& outer) const { return {outer.m * m, outer.m * t + outer.t}; }
  bool mirrors() const { return m.determinant() < 0; }
};

Xform insert_xform(const raw::Insert& ins, const raw::Block& blk) {
  const double a = ins.angle_deg * M_PI / 180.0;
  Eigen::Matrix2d r;
  r << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  Xform x;
  x.m = r * Eigen::Vector2d(ins.sx, ins.sy).asDiagonal();
  x.t = Vec2(ins.x, ins.y) - x.m * Vec2(blk.base_x, blk.base_y);
  return x;
}

// Polyline vertices with bulges expanded into arcs (chord angle ≤ 10°).
std::vector<Vec2> expand(const raw::Polyline& pl, const Xform& x) {
  std::vector<Vec2> out;
  const auto& v = pl.vertices;
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i) {
    out.push_back(x.apply(v[i].x, v[i].y));
    const bool has_next = i + 1 < n || pl.closed;
    if (!has_next || v[i].bulge == 0.0 || !std::isfinite(v[i].bulge)) continue;
    const auto& w = v[(i + 1) % n];
    const Vec2 p0(v[i].x, v[i].y), p1(w.x, w.y);
    const double theta = 4.0 * std::atan(v[i].bulge);  // included angle, signed
    const double chord = (p1 - p0).norm();
    if (chord == 0.0 || std::abs(theta) < 1e-9) continue;
    const double radius = chord / (2.0 * std::sin(std::abs(theta) / 2.0));
    const Vec2 mid = 0.5 * (p0 + p1);
    const Vec2 perp = Vec2(-(p1 - p0).y(), (p1 - p0).x()) / chord;
    const double h = radius * std::cos(theta / 2.0);
    const Vec2 center = mid + (theta > 0 ? 1.0 : -1.0) * h * perp * (std::abs(theta) > M_PI ? -1.0 : 1.0);
    const double a0 = std::atan2(p0.y() - center.y(), p0.x() - center.x());
    const int steps = std::max(2, static_cast<int>(std::ceil(std::abs(theta) / (10.0 * M_PI / 180.0))));
    for (int k = 1; k < steps; ++k) {
      const double a = a0 + theta * k / steps;
      const Vec2 q = center + radius * Vec2(std::cos(a), std::sin(a));
      out.push_back(x.apply(q.x(), q.y()));
    }
  }
  if (pl.closed && !out.empty()) out.push_back(out.front());
  return out;
}

// ---- one block's entities, flattened through nested INSERTs -------------------

constexpr int kMaxInsertDepth = 8;
constexpr int kMaxExpandedInserts = 10000;

struct Flat {
  std::vector<std::string> stack;  // blocks being expanded, outermost first
  int expanded = 0;                // nested INSERTs expanded so far
  bool budget_warned = false;
  std::vector<std::pair<const raw::Polyline*, Xform>> polylines;
  std::vector<std::pair<const raw::Line*, Xform>> lines;
  std::vector<std::pair<const raw::Point*, Xform>> points;
  std::vector<const raw::Text*> texts;
};

class Interpreter {
 public:
  Interpreter(const raw::Drawing& d, const std::string& name, const ImportOptions& o)
      : d_(d), name_(name), opts_(o) {
    for (const auto& b : d_.blocks) by_name_.emplace(b.name, &b);
  }

  ImportResult run();

 private:
  void flatten(const raw::Block& b, const Xform& x, Flat& f, int depth);
  void decide_units();
  void read_style_texts();
  bool import_block(const raw::Block& b, const Xform& place, Piece& piece, BlockReport& rep);
  void warn(const std::string& entity, const std::string& msg, int line = 0) {
    res_.diagnostics.warn(name_, entity, msg, line);
  }

  const raw::Drawing& d_;
  std::string name_;
  ImportOptions opts_;
  std::map<std::string, const raw::Block*> by_name_;
  ImportResult res_;
  double scale_ = 0.001;  // metres per file unit
  std::vector<std::pair<std::string, std::string>> style_texts_;
  std::set<std::string> states_quantity_;  // blocks with their own "Quantity:" text
};

void Interpreter::flatten(const raw::Block& b, const Xform& x, Flat& f, int depth) {
  for (const auto& p : b.polylines) f.polylines.emplace_back(&p, x);
  for (const auto& l : b.lines) f.lines.emplace_back(&l, x);
  for (const auto& p : b.points) f.points.emplace_back(&p, x);
  for (const auto& t : b.texts) f.texts.push_back(&t);
  for (const auto& ins : b.inserts) {
    const auto it = by_name_.find(ins.block);
    if (it == by_name_.end()) {
      warn("block " + b.name, "INSERT of unknown block '" + ins.block + "' ignored", ins.line);
      continue;
    }
    // A block that (indirectly) inserts itself would expand forever.
    if (std::find(f.stack.begin(), f.stack.end(), ins.block) != f.stack.end()) {
      warn("block " + b.name, "INSERT of '" + ins.block + "' makes a cycle; ignored", ins.line);
      continue;
    }
    // Fan-out (a block inserting another many times, nested) grows exponentially:
    // cap the expansion so a hostile file cannot exhaust memory.
    if (depth >= kMaxInsertDepth || f.expanded >= kMaxExpandedInserts) {
      if (!f.budget_warned)
        warn("block " + b.name, "nested INSERTs beyond " + std::to_string(kMaxInsertDepth) + " levels or " +
                                    std::to_string(kMaxExpandedInserts) + " copies ignored", ins.line);
      f.budget_warned = true;
      continue;
    }
    ++f.expanded;
    f.stack.push_back(ins.block);
    flatten(*it->second, insert_xform(ins, *it->second).then(x), f, depth + 1);
    f.stack.pop_back();
  }
}

void Interpreter::decide_units() {
  std::optional<LengthUnit> unit;
  std::string how;
  // A "Units:" text anywhere (AAMA puts it in model space).
  auto scan_texts = [&](const raw::Block& b) {
    for (const auto& t : b.texts) {
      const auto kv = split_text(t.value);
      if (kv.key != "units" || unit) continue;
      if (auto u = parse_length_unit(kv.value)) {
        unit = u;
        how = "stated by the text '" + std::string(trim(t.value)) + "'";
      } else {
        warn("", "unknown units '" + kv.value + "' in the text '" + std::string(trim(t.value)) + "'", t.line);
      }
    }
  };
  scan_texts(d_.model);
  for (const auto& b : d_.blocks) scan_texts(b);
  if (!unit) {
    if (auto it = d_.header.find("$INSUNITS"); it != d_.header.end()) {
      const auto v = parse_int(it->second).value_or(0);
      if (v == 1) unit = LengthUnit::inch;
      if (v == 4) unit = LengthUnit::millimetre;
      if (v == 5) unit = LengthUnit::centimetre;
      if (v == 6) unit = LengthUnit::metre;
      if (unit) how = "stated by $INSUNITS = " + it->second;
    }
  }
  if (!unit) {
    if (auto it = d_.header.find("$MEASUREMENT"); it != d_.header.end()) {
      unit = parse_int(it->second).value_or(1) == 0 ? LengthUnit::inch : LengthUnit::millimetre;
      how = "implied by $MEASUREMENT = " + it->second;
    }
  }
  if (opts_.units) {
    unit = opts_.units;
    how = "given on the command line";
  } else if (!unit) {
    unit = opts_.default_units;
    how = "not stated in the file; read as the default";
    warn("", std::string("the file states no units; reading it as ") + to_string(*unit) +
                 " (override with --units mm|cm|in)");
  }
  scale_ = metres_per(*unit);
  res_.style.units = to_string(*unit);
  res_.diagnostics.info(name_, "", std::string("units: ") + to_string(*unit) + ", " + how);
}

void Interpreter::read_style_texts() {
  std::string author, product, version;
  bool astm = false;
  for (const auto& t : d_.model.texts) {
    const auto kv = split_text(t.value);
    if (to_lower(t.value).find("astm") != std::string::npos || t.value.find("6673") != std::string::npos)
      astm = true;
    if (kv.key == "style name") res_.style.name = kv.value;
    else if (kv.key == "sample size") res_.style.sample_size = kv.value;
    else if (kv.key == "author") author = kv.value;
    else if (kv.key == "product") product = kv.value;
    else if (kv.key == "version") version = kv.value;
    if (!kv.key.empty() && kv.key != "units") style_texts_.emplace_back(kv.key, kv.value);
  }
  // Producer: what the file says about itself.
  std::string producer = author;
  for (const auto* s : {&product, &version})
    if (!s->empty() && producer.find(*s) == std::string::npos) producer += (producer.empty() ? "" : " / ") + *s;
  if (producer.empty())
    for (const auto& c : d_.comments)
      if (!trim(c).empty()) { producer = std::string(trim(c)); break; }
  res_.style.producer = producer.empty() ? "unknown" : producer;
  // Flavour: ASTM D6673 files say so, or carry the 80-87 quality-validation layers.
  std::string evidence = astm ? "a text names ASTM D6673" : "";
  if (!astm) {
    for (const auto& b : d_.blocks) {
      auto check = [&](const std::string& layer) {
        const int n = layer_number(layer);
        if (n >= 80 && n <= 87 && !astm) {
          astm = true;
          evidence = "layer " + layer + " (ASTM-only) is used in block " + b.name;
        }
      };
      for (const auto& p : b.polylines) check(p.layer);
      for (const auto& p : b.points) check(p.layer);
    }
  }
  res_.style.flavour = astm ? "ASTM" : "AAMA";
  res_.diagnostics.info(name_, "", "flavour: " + res_.style.flavour +
                                       (evidence.empty() ? " (no ASTM marks found)" : " (" + evidence + ")"));
}

bool Interpreter::import_block(const raw::Block& b, const Xform& place, Piece& piece, BlockReport& rep) {
  const std::string entity = "block " + b.name;
  Flat f;
  f.stack.push_back(b.name);
  flatten(b, place, f, 0);

  // ---- texts: attributes -------------------------------------------------------
  std::string piece_name, size, quantity;
  std::vector<std::string> layer15;
  for (const auto* t : f.texts) {
    if (is_grade_rule_label(t->value)) continue;
    const auto kv = split_text(t->value);
    if (kv.key == "piece name") piece_name = kv.value;
    else if (kv.key == "size") size = kv.value;
    else if (kv.key == "quantity") quantity = kv.value;
    else if (kv.key == "category") piece.category = kv.value;
    else if (kv.key == "fabric") piece.fabric = kv.value;
    else if (kv.key == "annotation") piece.annotation = kv.value;
    else if (!kv.key.empty()) piece.annotations.emplace_back(kv.key, kv.value);
    else if (t->layer == "1" || t->layer == "15") {
      if (!kv.value.empty()) piece.annotations.emplace_back("", kv.value);
      if (t->layer == "15") layer15.push_back(kv.value);
    }
  }
  piece.block = b.name;
  piece.name = !piece_name.empty() ? piece_name : b.name;
  piece.size = !size.empty() ? size : res_.style.sample_size;
  if (!quantity.empty()) {
    // AAMA writes the total; ASTM writes "normal,flipped".
    const auto parts = split(quantity, ',');
    int total = 0;
    bool ok = !parts.empty();
    for (const auto& p : parts) {
      const auto v = parse_int(p);
      if (!v || *v < 0) { ok = false; break; }
      total += static_cast<int>(*v);
    }
    if (ok) {
      states_quantity_.insert(b.name);
      piece.quantity = total;
      if (parts.size() == 2) piece.quantity_flipped = static_cast<int>(*parse_int(parts[1]));
    } else {
      warn(entity, "quantity '" + quantity + "' is not a number; using 1");
    }
  }

  // ---- coordinates: finite and in range -----------------------------------------
  auto in_range = [&](const Vec2& p) {
    return std::isfinite(p.x()) && std::isfinite(p.y()) && std::abs(p.x()) <= opts_.max_coordinate_m &&
           std::abs(p.y()) <= opts_.max_coordinate_m;
  };
  auto check = [&](const Vec2& p, int line) {
    if (in_range(p)) return true;
    res_.diagnostics.error(name_, entity,
                           "coordinate (" + format_double(p.x()) + ", " + format_double(p.y()) +
                               ") m is out of range (limit ±" + format_double(opts_.max_coordinate_m) +
                               " m): wrong units or a corrupt file; block dropped",
                           line);
    return false;
  };

  // ---- boundary: layer 1, chained -------------------------------------------------
  std::vector<std::vector<Vec2>> parts;
  int parts_line = 0;
  auto collect = [&](const std::string& layer) {
    for (const auto& [pl, x] : f.polylines) {
      if (pl->layer != layer) continue;
      auto pts = expand(*pl, x);
      for (auto& p : pts) {
        p *= scale_;
        if (!check(p, pl->line)) return false;
      }
      if (!parts_line) parts_line = pl->line;
      parts.push_back(std::move(pts));
    }
    for (const auto& [l, x] : f.lines) {
      if (l->layer != layer) continue;
      std::vector<Vec2> pts{x.apply(l->x1, l->y1) * scale_, x.apply(l->x2, l->y2) * scale_};
      for (auto& p : pts)
        if (!check(p, l->line)) return false;
      parts.push_back(std::move(pts));
    }
    return true;
  };
  if (!collect("1")) return false;
  if (parts.empty()) {
    if (!collect("84")) return false;
    if (!parts.empty())
      warn(entity, "no boundary on layer 1; using the ASTM quality-validation outline (layer 84)", b.line);
  }
  if (parts.empty()) {
    res_.diagnostics.error(name_, entity, "no boundary: the block has no polyline on layer 1; block dropped",
                           b.line);
    return false;
  }
  const std::size_t raw_parts = parts.size();
  pattern::ChainOptions copt{opts_.join_tolerance_m, opts_.repair_gap_m};
  auto chain = pattern::chain_parts(std::move(parts), copt);
  for (const auto& p : chain.outline) piece.boundary.push_back({p, PointKind::plain});
  const int dups = pattern::remove_duplicate_vertices(piece.boundary, opts_.join_tolerance_m);
  if (chain.parts_duplicate > 0)
    warn(entity, std::to_string(chain.parts_duplicate) + " duplicate boundary part(s) dropped");
  if (chain.joins_bridged > 0)
    warn(entity, "boundary parts joined across " + std::to_string(chain.joins_bridged) +
                     " gap(s), the largest " + format_fixed(chain.largest_bridge_m * 1000, 3) + " mm");
  if (chain.parts_unused > 0)
    warn(entity, std::to_string(chain.parts_unused) + " of " + std::to_string(raw_parts) +
                     " boundary parts could not be joined to the outline and were ignored", parts_line);
  piece.closed = chain.closed;
  if (!chain.closed)
    warn(entity, "open boundary: the outline's ends are " + format_fixed(chain.closing_gap_m * 1000, 3) +
                     " mm apart (more than the " + format_fixed(opts_.repair_gap_m * 1000, 3) +
                     " mm repair limit)", parts_line);
  else if (chain.closing_gap_m > opts_.join_tolerance_m)
    warn(entity, "closed a gap of " + format_fixed(chain.closing_gap_m * 1000, 3) + " mm in the boundary");
  if (dups > 0)
    res_.diagnostics.info(name_, entity, std::to_string(dups) + " duplicate boundary vertices removed");
  if (piece.boundary.size() < 3) {
    res_.diagnostics.error(name_, entity, "boundary has fewer than 3 distinct vertices; block dropped", parts_line);
    return false;
  }
  {
    Vec2 lo = piece.boundary.front().p, hi = lo;
    for (const auto& c : piece.boundary) lo = lo.cwiseMin(c.p), hi = hi.cwiseMax(c.p);
    const Vec2 ext = hi - lo;
    if (ext.maxCoeff() > opts_.max_piece_size_m) {
      res_.diagnostics.error(name_, entity,
                             "the piece is " + format_fixed(ext.x(), 1) + " m wide and " + format_fixed(ext.y(), 1) +
                                 " m high (limit " + format_fixed(opts_.max_piece_size_m, 0) +
                                 " m): wrong units or a corrupt block; block dropped, the others kept",
                             parts_line);
      return false;
    }
  }
  pattern::make_counter_clockwise(piece.boundary);
  if (std::abs(pattern::signed_area(piece.boundary)) == 0.0) {
    res_.diagnostics.error(name_, entity, "boundary encloses no area (all points on a line); block dropped",
                           parts_line);
    return false;
  }

  // ---- points: turn/curve markers, notches, drill holes --------------------------
  const double mark_tol = std::max(1e-5, 10 * opts_.join_tolerance_m);
  int markers_off = 0;
  for (const auto& [pt, x] : f.points) {
    const Vec2 p = x.apply(pt->x, pt->y) * scale_;
    if (!check(p, pt->line)) return false;
    const int layer = layer_number(pt->layer);
    if (layer == 2 || layer == 3) {
      const auto nv = pattern::nearest_vertex(piece.boundary, p);
      if (nv.index >= 0 && nv.distance <= mark_tol) {
        auto& k = piece.boundary[nv.index].kind;
        if (layer == 2) k = PointKind::turn;
        else if (k == PointKind::plain) k = PointKind::curve;
      } else {
        ++markers_off;  // markers of internal lines, or graded leftovers
      }
    } else if (layer == 4 || (layer >= 80 && layer <= 83)) {
      pattern::Notch n;
      n.position = p;
      n.type = layer == 4 ? 0 : layer;
      n.length_m = std::abs(pt->z) * scale_;
      n.width_m = std::abs(pt->thickness) * scale_;
      const auto ne = pattern::nearest_edge(piece.boundary, p);
      if (pt->has_angle) {
        // The stated direction is in block coordinates: carry it through the transform.
        const double a = pt->angle * M_PI / 180.0;
        const Vec2 d = x.m * Vec2(std::cos(a), std::sin(a));
        n.angle_deg = std::atan2(d.y(), d.x()) * 180.0 / M_PI;
      } else if (ne.edge >= 0) {
        // No direction stated: cut perpendicular to the boundary, inwards (CCW: left normal).
        const Vec2 e = piece.boundary[(ne.edge + 1) % piece.boundary.size()].p - piece.boundary[ne.edge].p;
        n.angle_deg = std::atan2(e.x(), -e.y()) * 180.0 / M_PI;
      }
      n.boundary_index = pattern::nearest_vertex(piece.boundary, p).index;
      if (ne.distance > 2e-3)
        warn(entity, "notch at (" + format_fixed(p.x(), 4) + ", " + format_fixed(p.y(), 4) + ") m is " +
                         format_fixed(ne.distance * 1000, 2) + " mm off the boundary", pt->line);
      piece.notches.push_back(n);
    } else if (layer == 13) {
      piece.drill_holes.push_back(p);
    }
  }
  (void)markers_off;

  // ---- lines: grade reference, mirror, grain, internal, cut-outs, sew lines -----
  auto as_segment = [&](const std::vector<Vec2>& pts) {
    return pattern::Segment{pts.front(), pts.back()};
  };
  auto add_line = [&](int layer, std::vector<Vec2> pts, bool closed, int line) {
    for (const auto& p : pts)
      if (!check(p, line)) return false;
    if (pts.size() < 2) return true;
    switch (layer) {
      case 5: if (!piece.grade_reference) piece.grade_reference = as_segment(pts); break;
      case 6:
        if (piece.mirror_line) warn(entity, "more than one mirror line; using the first", line);
        else piece.mirror_line = as_segment(pts);
        break;
      case 7:
        if (!piece.grain_line) piece.grain_line = as_segment(pts);
        break;
      case 8: piece.internal_lines.push_back({std::move(pts), closed}); break;
      case 11: piece.cutouts.push_back({std::move(pts), true}); break;
      case 14: piece.sew_lines.push_back({std::move(pts), closed}); break;
      default: break;
    }
    return true;
  };
  for (const auto& [l, x] : f.lines)
    if (!add_line(layer_number(l->layer), {x.apply(l->x1, l->y1) * scale_, x.apply(l->x2, l->y2) * scale_}, false,
                  l->line))
      return false;
  for (const auto& [pl, x] : f.polylines) {
    const int layer = layer_number(pl->layer);
    if (layer == 1 || layer == 84 || layer < 5 || (layer > 8 && layer != 11 && layer != 14)) continue;
    auto pts = expand(*pl, x);
    for (auto& p : pts) p *= scale_;
    if (pl->closed && pts.size() > 1) pts.pop_back();  // closed flag carries the closure
    if (!add_line(layer, std::move(pts), pl->closed, pl->line)) return false;
  }
  for (auto& c : piece.cutouts) {
    if (c.points.size() > 1 && (c.points.back() - c.points.front()).norm() <= opts_.join_tolerance_m)
      c.points.pop_back();
    // Holes wind clockwise so that the piece reads as outline minus holes.
    if (pattern::signed_area(c.points) > 0) std::reverse(c.points.begin(), c.points.end());
  }
  if (!piece.grain_line) warn(entity, "no grain line (layer 7); the warp is taken along +x");

  // ---- report as stored, then check crossings ------------------------------------
  piece.self_intersecting = pattern::is_self_intersecting(piece.boundary);
  rep.block = piece.block;
  rep.piece = piece.name;
  rep.size = piece.size;
  rep.quantity = piece.quantity;
  rep.boundary_vertices = static_cast<int>(piece.boundary.size());
  rep.closed = piece.closed;
  rep.area_m2 = std::abs(pattern::signed_area(piece.boundary));
  rep.perimeter_m = pattern::perimeter(piece.boundary);
  rep.grain_angle_deg = pattern::grain_angle_deg(piece);
  rep.notches = static_cast<int>(piece.notches.size());
  rep.internal_lines = static_cast<int>(piece.internal_lines.size());
  rep.drill_holes = static_cast<int>(piece.drill_holes.size());
  rep.mirror_line = piece.mirror_line.has_value();
  rep.self_intersecting = piece.self_intersecting;
  if (piece.self_intersecting) {
    std::string what = "self-intersecting boundary";
    if (opts_.repair_self_intersections) {
      auto repaired = piece.boundary;
      // Slits drawn as out-and-back spikes touch themselves; remove them first.
      const int spikes = pattern::remove_spikes(repaired, opts_.join_tolerance_m);
      if (spikes > 0) what += "; removed " + std::to_string(spikes) + " zero-width spike(s) (slits)";
      const int loops = pattern::is_self_intersecting(repaired) ? pattern::remove_small_self_loops(repaired) : 0;
      // A repair that leaves no outline (a piece made only of slits) is no repair.
      const bool usable = repaired.size() >= 3 && std::abs(pattern::signed_area(repaired)) > 0.0;
      if ((spikes > 0 || loops > 0) && usable && !pattern::is_self_intersecting(repaired)) {
        const double lost = rep.area_m2 - std::abs(pattern::signed_area(repaired));
        piece.boundary = std::move(repaired);
        piece.self_intersecting = false;
        if (loops > 0) {
          // The shoelace area of a crossing outline counts its loops with
          // signs: the difference says how much, not which way.
          const double mm2 = std::abs(lost) * 1e6;
          what += "; cut " + std::to_string(loops) + " small loop(s) (" +
                  (mm2 < 100 ? format_fixed(mm2, 1) + " mm²" : format_fixed(mm2 / 100, 1) + " cm²") + ")";
        }
        what += ": repaired";
      } else {
        what += "; not repairable automatically (the crossing encloses a large area): fix it in the CAD system";
      }
    }
    warn(entity, what, parts_line);
  }
  return true;
}

ImportResult Interpreter::run() {
  decide_units();
  read_style_texts();

  // Where each block is placed in model space. A name defined by several
  // BLOCKs (Valentina writes that) pairs its k-th BLOCK with its k-th INSERT.
  std::map<std::string, std::vector<const raw::Insert*>> placement;
  std::map<std::string, int> definitions;
  for (const auto& b : d_.blocks) ++definitions[b.name];
  std::set<std::string> nested;
  for (const auto& ins : d_.model.inserts) {
    auto& list = placement[ins.block];
    if (!list.empty() && static_cast<int>(list.size()) >= definitions[ins.block])
      warn("block " + ins.block, "inserted more than once; using the first placement", ins.line);
    else
      list.push_back(&ins);
  }
  for (const auto& b : d_.blocks)
    for (const auto& ins : b.inserts) nested.insert(ins.block);

  std::map<std::string, int> seen_blocks;
  for (const auto& b : d_.blocks) {
    // Layout blocks and anonymous blocks are not pieces.
    if (b.name.empty() || b.name[0] == '$' || b.name[0] == '*') continue;
    const auto pl = placement.find(b.name);
    // A block only used inside other blocks is a symbol, not a piece.
    if (pl == placement.end() && nested.count(b.name)) continue;
    if (pl == placement.end() && b.polylines.empty() && b.lines.empty() && b.texts.empty()) continue;
    const int occurrence = seen_blocks[b.name]++;
    Xform place;
    if (pl != placement.end())
      place = insert_xform(*pl->second[std::min<std::size_t>(occurrence, pl->second.size() - 1)], b);
    else
      place.t = -Vec2(b.base_x, b.base_y);
    Piece piece;
    BlockReport rep;
    rep.block = b.name;
    if (import_block(b, place, piece, rep)) {
      // A second BLOCK of the same name is kept under a name of its own.
      if (occurrence > 0) {
        const std::string renamed = b.name + " #" + std::to_string(occurrence + 1);
        warn("block " + b.name, "another BLOCK has this name; this one (line " + std::to_string(b.line) +
                                    ") is kept as '" + renamed + "'",
             b.line);
        if (piece.name == piece.block) piece.name = renamed;
        piece.block = rep.block = renamed;
        rep.piece = piece.name;
      }
      if (place.mirrors()) warn("block " + b.name, "placed mirrored by its INSERT; outline rewound counter-clockwise");
      res_.style.pieces.push_back(std::move(piece));
    } else {
      rep.imported = false;
    }
    res_.blocks.push_back(std::move(rep));
  }
  if (res_.style.pieces.empty()) {
    std::string why = d_.blocks.empty() ? "no pattern pieces: the file has no BLOCKs"
                                        : "no pattern pieces: no BLOCK has a usable boundary (layer 1)";
    for (const auto& d : res_.diagnostics.items())
      if (d.severity == Severity::error) {
        why += " (first problem: " + d.entity + ": " + d.message + ")";
        break;
      }
    throw Error(name_, "", why);
  }

  // Attributes stated only in the sample-size block apply to every size of the piece.
  auto& pieces = res_.style.pieces;
  for (auto& p : pieces) {
    for (const auto& q : pieces) {
      if (&p == &q || p.name != q.name) continue;
      if (p.category.empty()) p.category = q.category;
      if (p.fabric.empty()) p.fabric = q.fabric;
      if (p.annotation.empty()) p.annotation = q.annotation;
      if (!states_quantity_.count(p.block) && states_quantity_.count(q.block)) {
        p.quantity = q.quantity;
        p.quantity_flipped = q.quantity_flipped;
      }
    }
  }
  // Sizes in order of first appearance; a file without any size text is one size.
  for (auto& p : pieces) {
    if (p.size.empty()) p.size = "base";
    if (std::find(res_.style.sizes.begin(), res_.style.sizes.end(), p.size) == res_.style.sizes.end())
      res_.style.sizes.push_back(p.size);
  }
  if (res_.style.sample_size.empty()) res_.style.sample_size = res_.style.sizes.front();
  for (auto& rep : res_.blocks) {
    for (const auto& p : pieces)
      if (p.block == rep.block) {
        rep.size = p.size;
        rep.category = p.category;
        rep.quantity = p.quantity;
      }
  }
  if (res_.style.name.empty()) res_.style.name = std::filesystem::path(name_).stem().string();

  // Graded blocks carry no turn points or notches: they take the sample size's.
  {
    int carried = 0;
    for (const auto& [block, c] : pattern::carry_sample_marks(res_.style)) {
      if (c.carried) ++carried;
      else warn("block " + block, "the sample size's turn points and notches could not be carried to it: " + c.why +
                                      "; seams found at the sample size may not fit it");
    }
    if (carried > 0)
      res_.diagnostics.info(name_, "sizes", "turn points and notches of the sample size " + res_.style.sample_size +
                                                " carried to " + std::to_string(carried) + " graded blocks");
  }

  auto& s = res_.summary;
  s.producer = res_.style.producer;
  s.flavour = res_.style.flavour;
  s.style = res_.style.name;
  s.units = res_.style.units;
  s.sample_size = res_.style.sample_size;
  s.pieces = static_cast<int>(res_.style.piece_names().size());
  s.blocks = static_cast<int>(pieces.size());
  s.sizes = res_.style.sizes;

  if (opts_.unfold_mirrored) {
    for (auto& p : pieces) {
      if (!p.mirror_line) continue;
      if (!pattern::unfold_about_mirror_line(p))
        warn("block " + p.block, "cannot unfold: the mirror line's ends are not on the boundary");
      else
        for (auto& n : p.notches) n.boundary_index = pattern::nearest_vertex(p.boundary, n.position).index;
    }
  }
  if (opts_.join_per_side) res_.joined = pattern::join_pieces_written_per_side(res_.style);
  if (opts_.sew_on_sew_lines) {
    double lo = 1e300, hi = 0.0;
    for (auto& p : pieces)
      if (const auto a = pattern::sew_on_sew_line(p)) {
        ++res_.sewn_on_sew_lines;
        lo = std::min(lo, a->min), hi = std::max(hi, a->max);
      }
    if (res_.sewn_on_sew_lines > 0) res_.allowance_min = lo, res_.allowance_max = hi;
  }
  // Files that mark no turn points (Valentina) get their corners from
  // the outline, so that a piece has stretches to sew.
  for (auto& p : pieces) {
    if (std::any_of(p.boundary.begin(), p.boundary.end(), [](const pattern::ContourPoint& c) { return c.kind == PointKind::turn; }))
      continue;
    const int corners = pattern::mark_corners(p.boundary);
    res_.diagnostics.info(name_, "block " + p.block,
                          "no turn points in the file: " + std::to_string(corners) +
                              " corners found from the outline (turns of 30 degrees or more within 5 mm)");
  }
  return std::move(res_);
}

}  // namespace

ImportResult import_string(std::string_view text, const std::string& name, const ImportOptions& opts) {
  const Decoded decoded = to_utf8(text);
  const raw::Drawing drawing = raw::read(decoded.text, name);
  ImportResult r = Interpreter(drawing, name, opts).run();
  if (decoded.replaced > 0)
    r.diagnostics.warn(name, "$DWGCODEPAGE", decoded.note + "; " + std::to_string(decoded.replaced) +
                                                 " byte(s) have no character there and read as U+FFFD");
  else if (!decoded.note.empty() && decoded.note.find("names no code page") != std::string::npos)
    r.diagnostics.warn(name, "$DWGCODEPAGE", decoded.note);
  else if (!decoded.note.empty())
    r.diagnostics.info(name, "$DWGCODEPAGE", decoded.note);
  return r;
}

std::vector<std::string> import_notes(const ImportResult& r) {
  std::vector<std::string> out;
  for (const auto& j : r.joined) out.push_back(pattern::describe(j));
  if (r.sewn_on_sew_lines > 0) {
    auto cm = [](double m) { return format_fixed(100 * m, 1); };
    out.push_back(std::to_string(r.sewn_on_sew_lines) + " block(s) sewn on their sew line (layer 14): a seam allowance of " +
                  cm(r.allowance_min) + "-" + cm(r.allowance_max) + " cm cut off their outline");
  }
  return out;
}

ImportResult import_file(const std::filesystem::path& path, const ImportOptions& opts) {
  const std::string text = read_file(path);
  return import_string(text, path.string(), opts);
}

}  // namespace vgd::dxf
