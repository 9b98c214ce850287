// Arrangements of pattern pieces around the body (arrangement.hpp).
#include "vgd/xvc/arrangement.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/pattern/contour.hpp"
#include "vgd/xvc/seams.hpp"
#include "vgd/xvc/style.hpp"

namespace vgd::xvc {

namespace {

// How much further out than its stand a collar turned down over it starts (m):
// clear of the stand's cloth and its repulsion.
constexpr double kOverStand = 0.01;

bool has(const std::string& s, std::string_view w) { return s.find(w) != std::string::npos; }

pattern::Vec2 rotate(const pattern::Vec2& p, double deg) {
  const double a = deg * M_PI / 180.0, c = std::cos(a), s = std::sin(a);
  return {c * p.x() - s * p.y(), s * p.x() + c * p.y()};
}

// Rotation that turns the grain line's direction to +y (0 when there is none).
double upright_angle(const pattern::Piece& p) {
  if (!p.grain_line) return 0;
  const pattern::Vec2 d = p.grain_line->b - p.grain_line->a;
  if (d.norm() == 0) return 0;
  double a = 90.0 - std::atan2(d.y(), d.x()) * 180.0 / M_PI;
  while (a > 180) a -= 360;
  while (a <= -180) a += 360;
  return std::abs(a) < 1e-9 ? 0.0 : a;
}

// A bodice hanging from straps (a tank): within the top 5 cm of the piece turned
// upright, its cloth spans less than a quarter of its width.
bool straps(const pattern::Piece& piece, double angle_deg) {
  const std::size_t n = piece.boundary.size();
  if (n < 3) return false;
  std::vector<pattern::Vec2> q(n);
  double xmin = 1e300, xmax = -1e300, ymax = -1e300;
  for (std::size_t i = 0; i < n; ++i) {
    q[i] = rotate(piece.boundary[i].p, angle_deg);
    xmin = std::min(xmin, q[i].x()), xmax = std::max(xmax, q[i].x()), ymax = std::max(ymax, q[i].y());
  }
  // The cloth's width along a horizontal line at y: the summed lengths of the
  // intervals inside the outline (even-odd).
  auto covered = [&](double y) {
    std::vector<double> xs;
    for (std::size_t i = 0; i < n; ++i) {
      const pattern::Vec2 &a = q[i], &b = q[(i + 1) % n];
      if ((a.y() > y) != (b.y() > y)) xs.push_back(a.x() + (y - a.y()) / (b.y() - a.y()) * (b.x() - a.x()));
    }
    std::sort(xs.begin(), xs.end());
    double w = 0;
    for (std::size_t k = 0; k + 1 < xs.size(); k += 2) w += xs[k + 1] - xs[k];
    return w;
  };
  double widest = 0;
  for (const double d : {0.01, 0.02, 0.03, 0.04, 0.05}) widest = std::max(widest, covered(ymax - d));
  return widest < 0.25 * (xmax - xmin);
}

// The lowest and highest point of a piece turned by `angle_deg` (m, along its up).
std::pair<double, double> height_range(const pattern::Piece& piece, double angle_deg) {
  double lo = 1e300, hi = -1e300;
  for (const auto& c : piece.boundary) {
    const double y = rotate(c.p, angle_deg).y();
    lo = std::min(lo, y), hi = std::max(hi, y);
  }
  return piece.boundary.empty() ? std::pair{0.0, 0.0} : std::pair{lo, hi};
}

// The outline points of stretches from..to (indices in `stretches`), both
// ends' vertices included; empty when the range is not the piece's.
std::vector<pattern::Vec2> run_points(const pattern::Piece& piece, const std::vector<Stretch>& stretches,
                                      std::size_t from, std::size_t to) {
  std::vector<pattern::Vec2> out;
  const std::size_t n = piece.boundary.size();
  if (n == 0 || from >= stretches.size() || to >= stretches.size()) return out;
  const std::size_t last = to + 1 < stretches.size() ? stretches[to + 1].first : 0;  // the run's end vertex
  for (std::size_t i = stretches[from].first % n;; i = (i + 1) % n) {
    out.push_back(piece.boundary[i].p);
    if (i == last % n) break;
  }
  return out;
}

// How far below the top of its pattern (turned upright by its grain line) the
// highest point of a hem lies (m).
double hem_drop(const Document& doc, const Node& node, std::size_t from, std::size_t to) {
  const pattern::Piece piece = to_piece(doc, node.id());
  const auto run = run_points(piece, boundary_stretches(node), from, to);
  if (run.empty()) return 0;
  const double angle = upright_angle(piece);
  double hem_top = -1e300;
  for (const auto& p : run) hem_top = std::max(hem_top, rotate(p, angle).y());
  return height_range(piece, angle).second - hem_top;
}

// A hem's stretches as indices in its pattern's boundary (graded sizes have the
// sample's stretches: the same indices name the same edges in every size).
std::pair<std::size_t, std::size_t> stretch_range(const Node& pattern, const HemRef& hem) {
  const auto stretches = boundary_stretches(pattern);
  std::size_t from = 0, to = 0;
  for (std::size_t k = 0; k < stretches.size(); ++k) {
    if (stretches[k].id == hem.from) from = k;
    if (stretches[k].id == hem.to) to = k;
  }
  return {from, to};
}

}  // namespace

const std::vector<std::string_view>& arrangement_segments() {
  static const std::vector<std::string_view> v = {"neck", "torso", "hips", "left-arm", "right-arm", "left-leg", "right-leg"};
  return v;
}
const std::vector<std::string_view>& arrangement_sides() {
  static const std::vector<std::string_view> v = {"front", "back", "left", "right"};
  return v;
}

std::vector<Arrangement> arrangements_of(const Node& pattern) {
  std::vector<Arrangement> out;
  for (const auto& c : pattern.children) {
    if (c.tag != "POSITION" || c.attribute("type") != "arrangement") continue;
    Arrangement a;
    a.segment = std::string(c.attribute("segment"));
    a.side = std::string(c.attribute("side"));
    a.x = parse_double(c.attribute("x")).value_or(0);
    a.y = parse_double(c.attribute("y")).value_or(0);
    a.height = parse_double(c.attribute("height")).value_or(0);
    if (c.has_attribute("clearance")) a.clearance = parse_double(c.attribute("clearance")).value_or(0.03);
    a.angle_deg = parse_double(c.attribute("angle")).value_or(0);
    a.flip = c.attribute("flip") == "true" || c.attribute("flip") == "1";
    a.around_deg = parse_double(c.attribute("around")).value_or(0);
    out.push_back(a);
  }
  return out;
}

std::vector<Pin> pins_of(const Node& pattern) {
  std::vector<Pin> out;
  for (const auto& c : pattern.children)
    if (c.tag == "POSITION" && c.attribute("type") == "pin")
      out.push_back({std::string(c.id()), parse_double(c.attribute("x")).value_or(0),
                     parse_double(c.attribute("y")).value_or(0)});
  return out;
}

std::vector<FacePlacement> face_placements_of(const Node& pattern) {
  std::vector<FacePlacement> out;
  for (const auto& c : pattern.children)
    if (c.tag == "POSITION" && c.attribute("type") == "placement" && c.has_attribute("pattern"))
      out.push_back({std::string(c.id()), std::string(c.attribute("pattern")), parse_double(c.attribute("x")).value_or(0),
                     parse_double(c.attribute("y")).value_or(0), parse_double(c.attribute("angle")).value_or(0)});
  return out;
}

Node face_placement_node(const FacePlacement& f) {
  Node n{"POSITION", {{"type", "placement"}, {"x", format_double(f.x)}, {"y", format_double(f.y)}}, {}};
  if (f.angle_deg != 0) n.set_attribute("angle", format_double(f.angle_deg));
  n.set_attribute("pattern", f.host);
  return n;
}

Node arrangement_node(const Arrangement& a) {
  Node n{"POSITION", {{"type", "arrangement"}, {"x", format_double(a.x)}, {"y", format_double(a.y)}}, {}};
  if (a.angle_deg != 0) n.set_attribute("angle", format_double(a.angle_deg));
  n.set_attribute("segment", a.segment);
  n.set_attribute("side", a.side);
  n.set_attribute("height", format_double(a.height));
  n.set_attribute("clearance", format_double(a.clearance));
  if (a.flip) n.set_attribute("flip", "true");
  if (a.around_deg != 0) n.set_attribute("around", format_double(a.around_deg));
  return n;
}

pattern::Vec2 reference_point(const pattern::Piece& piece, double angle_deg) {
  double xmin = 1e300, xmax = -1e300, ymax = -1e300;
  for (const auto& c : piece.boundary) {
    const auto q = rotate(c.p, angle_deg);
    xmin = std::min(xmin, q.x());
    xmax = std::max(xmax, q.x());
    ymax = std::max(ymax, q.y());
  }
  if (piece.boundary.empty()) return pattern::Vec2::Zero();
  return rotate(pattern::Vec2(0.5 * (xmin + xmax), ymax), -angle_deg);
}

std::vector<Arrangement> suggest_arrangement(const pattern::Piece& piece, bool lower_body, const ArrangementOptions& opts,
                                             std::string_view style) {
  return suggest_arrangement(piece, pattern::piece_role(piece.name, piece.category, piece.annotation, style), lower_body,
                             opts);
}

std::vector<Arrangement> suggest_arrangement(const pattern::Piece& piece, const pattern::RoleGuess& role,
                                             bool lower_body, const ArrangementOptions& opts) {
  if (piece.quantity == 0) return {};  // not cut (a reference piece): nothing to place
  using pattern::Role;
  Arrangement a;
  a.clearance = opts.clearance;
  const bool band = role.role == Role::waistband || role.role == Role::neckband || role.role == Role::cuff ||
                    role.role == Role::collar || role.role == Role::collar_stand || role.role == Role::binding;
  a.angle_deg = band ? 0.0 : upright_angle(piece);
  const auto ref = reference_point(piece, a.angle_deg);
  a.x = ref.x();
  a.y = ref.y();
  double box_h = 0;
  {
    const auto [lo, hi] = height_range(piece, a.angle_deg);
    box_h = hi - lo;
  }
  // A band goes round the body lengthwise: one drawn upright is turned a
  // quarter clockwise (its right edge to the bottom, as the seam suggestions
  // expect).
  const auto turn_band = [&] {
    double w0 = 1e300, w1 = -1e300, h0 = 1e300, h1 = -1e300;
    for (const auto& c : piece.boundary)
      w0 = std::min(w0, c.p.x()), w1 = std::max(w1, c.p.x()), h0 = std::min(h0, c.p.y()), h1 = std::max(h1, c.p.y());
    if (h1 - h0 > w1 - w0) {
      a.angle_deg = -90;
      const auto top = reference_point(piece, a.angle_deg);
      a.x = top.x();
      a.y = top.y();
      box_h = w1 - w0;
    }
  };
  // A piece on each arm or leg: the left copy and the right, on the limb's outside.
  const auto both_limbs = [&](const std::string& limb) {
    Arrangement l = a, r = a;
    l.segment = "left-" + limb;
    l.side = "left";
    r.segment = "right-" + limb;
    r.side = "right";
    return std::pair{l, r};
  };
  switch (role.role) {
    case Role::sleeve: {
      a.height = opts.sleeve_drop;  // the cap top this far down the arm from its shoulder end
      a.clearance = opts.sleeve_clearance;
      Arrangement l, r;
      std::tie(l, r) = both_limbs("arm");
      if (role.half != pattern::Half::none) {
        // Half a sleeve: on the front or the back of the arm, its over-arm
        // edge (the one from the highest point, the cap's top) on the arm's
        // outside. On a limb the pattern's +u runs to the body's left (+x) on
        // the front and to its right on the back, so the over-arm edge lies on
        // +u for the left arm's front half and the right arm's back half.
        const bool front = role.half == pattern::Half::front;
        l.side = r.side = front ? "front" : "back";
        double umin = 1e300, umax = -1e300, top_u = 0, top_v = -1e300;
        for (const auto& c : piece.boundary) {
          const auto q = rotate(c.p, a.angle_deg);
          umin = std::min(umin, q.x()), umax = std::max(umax, q.x());
          if (q.y() > top_v) top_v = q.y(), top_u = q.x();
        }
        const bool over_plus = top_u > 0.5 * (umin + umax);
        l.flip = over_plus != front;
        r.flip = over_plus != !front;
      }
      if (role.side == pattern::Side::left) return {l};
      if (role.side == pattern::Side::right) return {r};
      if (role.half == pattern::Half::none) l.flip = true;  // one sleeve pattern cut twice: the left copy is the mirror
      return piece.quantity >= 2 ? std::vector<Arrangement>{r, l} : std::vector<Arrangement>{r};
    }
    case Role::leg: {
      // Upright with the wider end up (the waist), whichever way the grain line points:
      // the pattern's direction that turning by the angle brings to +y.
      if (!pattern::wider_at_top(piece.boundary, rotate(pattern::Vec2::UnitY(), -a.angle_deg)))
        a.angle_deg = a.angle_deg > 0 ? a.angle_deg - 180 : a.angle_deg + 180;
      const auto top = reference_point(piece, a.angle_deg);
      a.x = top.x();
      a.y = top.y();
      // The front half is the narrower (a leg's back is cut wider for the seat): the
      // right leg, seen from outside, has the front on its right (+x), the left leg on its left.
      double umin = 1e300, umax = -1e300;
      for (const auto& c : piece.boundary) {
        const double u = rotate(c.p, a.angle_deg).x() - rotate(top, a.angle_deg).x();
        umin = std::min(umin, u), umax = std::max(umax, u);
      }
      const bool front_at_plus = umax <= -umin;
      a.height = opts.leg_top;
      a.clearance = opts.sleeve_clearance;
      Arrangement l, r;
      std::tie(l, r) = both_limbs("leg");
      l.flip = front_at_plus;
      r.flip = !front_at_plus;
      if (role.half != pattern::Half::none) {
        // Half a trouser leg: on the front or the back of the leg, its crotch's
        // extension to the inside. The crotch side is the one reaching out
        // furthest beyond the piece's top there (the crotch point against centre
        // front or back; the outseam barely passes the waist's side at the hip).
        // On a limb the pattern's +u runs to the body's left on the front and to
        // its right on the back, so the inside lies on +u for the right leg's
        // front half and the left leg's back half.
        const bool front = role.half == pattern::Half::front;
        l.side = r.side = front ? "front" : "back";
        const double top_v = height_range(piece, a.angle_deg).second;
        double t0 = 1e300, t1 = -1e300, u0 = 1e300, u1 = -1e300;
        for (const auto& c : piece.boundary) {
          const auto q = rotate(c.p, a.angle_deg);
          u0 = std::min(u0, q.x()), u1 = std::max(u1, q.x());
          if (q.y() > top_v - 0.08) t0 = std::min(t0, q.x()), t1 = std::max(t1, q.x());
        }
        const bool crotch_plus = u1 - t1 > t0 - u0;
        r.flip = crotch_plus != front;
        l.flip = crotch_plus == front;
      }
      if (role.side == pattern::Side::left) return {l};
      if (role.side == pattern::Side::right) return {r};
      return piece.quantity >= 2 ? std::vector<Arrangement>{r, l} : std::vector<Arrangement>{r};
    }
    case Role::waistband: {
      turn_band();
      a.segment = "hips";
      a.side = "front";
      a.height = opts.waist_height + 0.5 * box_h;  // folded lengthwise: the fold sits above the waist
      return {a};
    }
    case Role::neckband:
    case Role::binding:  // one a SEAM sews round the neckline (suggest_arrangements)
      turn_band();
      a.segment = "neck";
      a.side = "front";
      a.height = opts.neck_point_height + box_h;  // its bottom edge, the one sewn, at the neck's base
      return {a};
    case Role::cuff: {
      // Round each arm lengthwise as a band, its top edge (the one sewn) at
      // the hem of the sleeve it is sewn to (suggest_arrangements moves it
      // down the arm by that sleeve's length); the left copy mirrored, as a
      // sleeve's is.
      if (piece.quantity < 2) return {};
      turn_band();
      a.height = opts.sleeve_drop;
      a.clearance = opts.sleeve_clearance;
      Arrangement l, r;
      std::tie(l, r) = both_limbs("arm");
      l.flip = true;
      return {r, l};
    }
    case Role::collar:
      // Lengthwise round the neck as a neckband, its bottom edge (the one
      // sewn) at the neck point, but centred at the back: a collar's ends
      // meet at centre front.
      turn_band();
      a.segment = "neck";
      a.side = "back";
      a.height = opts.neck_point_height + box_h;
      return {a};
    case Role::collar_stand:
      // As a collar: its bottom edge (the one sewn) at the neck point, its
      // ends meeting at centre front.
      turn_band();
      a.segment = "neck";
      a.side = "back";
      a.height = opts.neck_point_height + box_h;
      return {a};
    case Role::front:
    case Role::back:
    case Role::yoke:  // a shirt's, hung like a back; the backs sewn to it hang below it (suggest_arrangements)
      if (role.role == Role::yoke && lower_body) return {};
      a.segment = lower_body ? "hips" : "torso";
      a.side = role.role == Role::front ? "front" : "back";
      a.height = lower_body ? opts.waist_height : opts.neck_point_height + (straps(piece, a.angle_deg) ? 0.0 : opts.bodice_lift);
      return {a};
    default:
      return {};
  }
}

std::vector<std::pair<std::string, std::vector<Arrangement>>> suggest_arrangements(const Document& doc,
                                                                                   const ArrangementOptions& opts) {
  bool lower = false;
  const std::string style(doc.root().attribute("name"));
  const std::string gname = to_upper(style);
  if (has(gname, "SKIRT") || has(gname, "TROUSER") || has(gname, "PANT")) lower = true;
  for (const Node* p : doc.patterns()) {
    const std::string n = to_upper(p->attribute("piece"));
    if (piece_role(doc, *p).role == pattern::Role::waistband || has(n, "SKIRT")) lower = true;
  }
  std::vector<std::pair<std::string, std::vector<Arrangement>>> out;
  for (const Node* p : doc.patterns())
    out.emplace_back(std::string(p->id()), suggest_arrangement(to_piece(doc, p->id()), piece_role(doc, *p), lower, opts));

  // Halves of a sleeve sewn to each other: the back half goes as far up or down
  // the arm as puts the top of its longest seam with the front half level with
  // the front half's (a half that reaches past the shoulder point, hung by its
  // box top, started that much lower and was dragged up the arm). A size with
  // no seams of its own takes its sample's, at the same stretches.
  struct HalfSeam {
    std::string front, back;  // piece names
    std::pair<std::size_t, std::size_t> f, b;
  };
  std::vector<HalfSeam> half_seams;
  for (const auto& seam : list_seams(doc)) {
    if (seam.hems.size() != 2) continue;
    const Node *a = doc.find(seam.hems[0].pattern), *b = doc.find(seam.hems[1].pattern);
    if (!a || !b || a->attribute("size") != b->attribute("size")) continue;
    const auto ra = piece_role(doc, *a), rb = piece_role(doc, *b);
    if (ra.role != pattern::Role::sleeve || rb.role != pattern::Role::sleeve || ra.half == rb.half ||
        ra.half == pattern::Half::none || rb.half == pattern::Half::none)
      continue;
    const bool a_front = ra.half == pattern::Half::front;
    const Node &fp = a_front ? *a : *b, &bp = a_front ? *b : *a;
    half_seams.push_back({std::string(fp.attribute("piece")), std::string(bp.attribute("piece")),
                          stretch_range(fp, seam.hems[a_front ? 0 : 1]), stretch_range(bp, seam.hems[a_front ? 1 : 0])});
  }
  std::map<std::string, const Node*> by_piece_size;  // "piece\nsize" -> pattern
  for (const Node* p : doc.patterns())
    by_piece_size[std::string(p->attribute("piece")) + "\n" + std::string(p->attribute("size"))] = p;
  for (auto& [id, list] : out) {
    const Node* bp = doc.find(id);
    if (!bp || list.empty()) continue;
    double longest = 0, shift = 0;
    for (const auto& h : half_seams) {
      if (h.back != bp->attribute("piece")) continue;
      const auto fit = by_piece_size.find(h.front + "\n" + std::string(bp->attribute("size")));
      if (fit == by_piece_size.end()) continue;
      const auto fs = boundary_stretches(*fit->second);
      if (h.f.first >= fs.size() || h.f.second >= fs.size()) continue;
      const double length = hem_length(doc, std::string(fit->second->id()), fs[h.f.first].id, fs[h.f.second].id);
      if (length <= longest) continue;
      longest = length;
      shift = hem_drop(doc, *fit->second, h.f.first, h.f.second) - hem_drop(doc, *bp, h.b.first, h.b.second);
    }
    for (auto& a : list) a.height += shift;
  }

  // A back under a yoke of its size (a shirt's) hangs from the yoke's lowest
  // point, not from the neck: lowered by the yoke's height as arranged.
  std::map<std::string, double> yoke_drop;  // size -> the yoke's height (m)
  for (const auto& [id, list] : out) {
    const Node* p = doc.find(id);
    if (!p || list.empty() || piece_role(doc, *p).role != pattern::Role::yoke) continue;
    const auto [lo, hi] = height_range(to_piece(doc, id), list.front().angle_deg);
    if (hi > lo) yoke_drop[std::string(p->attribute("size"))] = std::max(yoke_drop[std::string(p->attribute("size"))], hi - lo);
  }
  for (auto& [id, list] : out) {
    const Node* p = doc.find(id);
    if (!p || piece_role(doc, *p).role != pattern::Role::back) continue;
    if (const auto it = yoke_drop.find(std::string(p->attribute("size"))); it != yoke_drop.end())
      for (auto& a : list) a.height -= it->second;
  }

  // A cuff goes on at the hem of the sleeve a SEAM sews it to (a seam of any
  // size: graded sizes sew with the sample's; the sleeve of the cuff's own
  // size): that sleeve's length as arranged (its top, the cap, sleeve_drop
  // down the arm) further down. A cuff no seam sews to a sleeve is not placed.
  std::map<std::string, std::string> cuff_sleeve;  // cuff piece -> sleeve piece
  for (const auto& seam : list_seams(doc))
    for (const auto& h : seam.hems) {
      const Node* c = doc.find(h.pattern);
      if (!c || piece_role(doc, *c).role != pattern::Role::cuff) continue;
      for (const auto& k : seam.hems)
        if (const Node* sl = doc.find(k.pattern); sl && piece_role(doc, *sl).role == pattern::Role::sleeve)
          cuff_sleeve[std::string(c->attribute("piece"))] = std::string(sl->attribute("piece"));
    }
  for (auto& [id, list] : out) {
    const Node* p = doc.find(id);
    if (!p || list.empty() || piece_role(doc, *p).role != pattern::Role::cuff) continue;
    const auto sleeve = cuff_sleeve.find(std::string(p->attribute("piece")));
    const Node* sl = nullptr;
    if (sleeve != cuff_sleeve.end())
      for (const Node* q : doc.patterns())
        if (q->attribute("piece") == sleeve->second && q->attribute("size") == p->attribute("size")) sl = q;
    std::vector<Arrangement> sleeve_list;
    for (const auto& [sid, slist] : out)
      if (sl && sid == sl->id()) sleeve_list = slist;
    if (sleeve_list.empty()) {
      list.clear();
      continue;
    }
    const auto [lo, hi] = height_range(to_piece(doc, sl->id()), sleeve_list.front().angle_deg);
    for (auto& a : list) a.height = sleeve_list.front().height + (hi - lo);
  }

  // A binding is arranged round the neck as a neckband when a SEAM vgd
  // suggests sews it round the neckline ("neck seam", of any size); vgd
  // places no other binding.
  std::set<std::string> neck_bindings;  // binding pieces
  for (const auto& seam : list_seams(doc))
    if (seam.name == "neck seam")
      for (const auto& h : seam.hems)
        if (const Node* b = doc.find(h.pattern); b && piece_role(doc, *b).role == pattern::Role::binding)
          neck_bindings.insert(std::string(b->attribute("piece")));
  for (auto& [id, list] : out) {
    const Node* p = doc.find(id);
    if (p && piece_role(doc, *p).role == pattern::Role::binding && !neck_bindings.count(std::string(p->attribute("piece"))))
      list.clear();
  }

  // A collar or a stand goes on by the edge a SEAM sews to the neckline (a
  // seam of any size: the same stretches in every size), whichever of its
  // long edges that is: turned half round when it would be the top as
  // arranged. A collar sewn to a stand is turned down over it about that
  // seam: its sewn edge at the stand's top, the rest hanging over the
  // stand (reflected top to bottom: its drawing's left end stays at the
  // stand's left, as the seam pairs them), `kOverStand` further out.
  struct Run {
    std::pair<std::size_t, std::size_t> stretches;
    std::string stand;  // the stand's piece, for a collar sewn to one
  };
  std::map<std::string, Run> collar_run;  // collar or stand piece -> stretches sewn
  const auto collar_like = [](pattern::Role r) { return r == pattern::Role::collar || r == pattern::Role::collar_stand; };
  for (const auto& seam : list_seams(doc))
    for (const auto& h : seam.hems) {
      const Node* c = doc.find(h.pattern);
      if (!c || !collar_like(piece_role(doc, *c).role)) continue;
      const bool is_collar = piece_role(doc, *c).role == pattern::Role::collar;
      const std::string piece(c->attribute("piece"));
      std::string other, stand;
      for (const auto& k : seam.hems)
        if (const Node* q = doc.find(k.pattern); q && q->attribute("piece") != piece) {
          other = std::string(q->attribute("piece"));
          if (is_collar && piece_role(doc, *q).role == pattern::Role::collar_stand) stand = other;
        }
      if (!other.empty()) collar_run.emplace(piece, Run{stretch_range(*c, h), stand});
    }
  // The stand's arrangement in a size (a graded stand's height differs by size).
  const auto stand_top = [&](const std::string& stand, std::string_view size) -> std::optional<Arrangement> {
    for (const auto& [sid, slist] : out)
      if (const Node* q = doc.find(sid); q && q->attribute("piece") == stand && q->attribute("size") == size && !slist.empty())
        return slist.front();
    return std::nullopt;
  };
  for (auto& [id, list] : out) {
    const Node* p = doc.find(id);
    if (!p || list.empty() || !collar_like(piece_role(doc, *p).role)) continue;
    const auto found = collar_run.find(std::string(p->attribute("piece")));
    if (found == collar_run.end()) continue;
    const pattern::Piece piece = to_piece(doc, id);
    const auto sewn = run_points(piece, boundary_stretches(*p), found->second.stretches.first, found->second.stretches.second);
    if (sewn.empty()) continue;
    const auto over = found->second.stand.empty() ? std::nullopt : stand_top(found->second.stand, p->attribute("size"));
    for (auto& a : list) {
      const auto [lo, hi] = height_range(piece, a.angle_deg);
      double mean = 0;
      for (const auto& q : sewn) mean += rotate(q, a.angle_deg).y() / static_cast<double>(sewn.size());
      const bool sewn_on_top = mean > 0.5 * (lo + hi);
      if (over) {
        // Reflected top to bottom: turned half round and flipped, or flipped only.
        if (!sewn_on_top) a.angle_deg = a.angle_deg > 0 ? a.angle_deg - 180 : a.angle_deg + 180;
        a.flip = true;
        a.height = over->height;
        a.clearance = over->clearance + kOverStand;
      } else if (sewn_on_top) {
        a.angle_deg = a.angle_deg > 0 ? a.angle_deg - 180 : a.angle_deg + 180;
      } else {
        continue;
      }
      const auto ref = reference_point(piece, a.angle_deg);
      a.x = ref.x();
      a.y = ref.y();
    }
  }

  // A half waistband (a SEAM sews its bottom edge to trouser leg halves, of
  // any size) goes round its side of the hips: the one sewn from a back half
  // (from centre back, xvc/seams.hpp) on the wearer's right, the one sewn
  // from a front half on the left; a band cut twice, sewn by both, on each.
  std::map<std::string, std::vector<std::string>> band_sides;  // band piece -> sides, in seam order
  for (const auto& seam : list_seams(doc)) {
    if (seam.hems.size() < 2) continue;
    const Node* b = doc.find(seam.hems[0].pattern);
    const Node* q = doc.find(seam.hems[1].pattern);
    if (!b || !q || piece_role(doc, *b).role != pattern::Role::waistband) continue;
    const auto rq = piece_role(doc, *q);
    if (rq.role != pattern::Role::leg || rq.half == pattern::Half::none) continue;
    auto& sides = band_sides[std::string(b->attribute("piece"))];
    const std::string side = rq.half == pattern::Half::back ? "right" : "left";
    if (std::find(sides.begin(), sides.end(), side) == sides.end()) sides.push_back(side);
  }
  for (auto& [id, list] : out) {
    const Node* p = doc.find(id);
    if (!p || list.empty() || piece_role(doc, *p).role != pattern::Role::waistband) continue;
    const auto found = band_sides.find(std::string(p->attribute("piece")));
    if (found == band_sides.end()) continue;
    std::vector<Arrangement> sided;
    for (const auto& side : found->second) {
      Arrangement a = list.front();
      a.side = side;
      sided.push_back(a);
    }
    std::sort(sided.begin(), sided.end(),
              [](const Arrangement& x, const Arrangement& y) { return x.side > y.side; });
    const int copies = std::max(1, to_piece(doc, id).quantity);
    if (static_cast<int>(sided.size()) > copies) sided.resize(copies);
    list = std::move(sided);
  }
  return out;
}

Arrangement parse_arrangement(std::string_view spec, const pattern::Piece& piece) {
  const auto parts = split(std::string(spec), ':');
  const std::string where = "arrangement '" + std::string(spec) + "'";
  if (parts.size() < 3 || parts.size() > 6)
    throw Error("", where, "expected SEGMENT:SIDE[±DEG]:HEIGHT[:CLEARANCE[:ANGLE[:flip]]], e.g. torso:front:1.25:0.03 or torso:left-20:1.25");
  Arrangement a;
  a.segment = trim(parts[0]);
  a.side = trim(parts[1]);
  // SIDE+DEG or SIDE-DEG: that far further round the segment (around).
  if (const auto sign = a.side.find_first_of("+-"); sign != std::string::npos && sign > 0) {
    const auto v = parse_double(a.side.substr(sign));
    if (!v || !std::isfinite(*v)) throw Error("", where, "the turn past the side '" + a.side.substr(sign) + "' is not a number of degrees");
    a.around_deg = *v;
    a.side = a.side.substr(0, sign);
  }
  const auto& segs = arrangement_segments();
  const auto& sides = arrangement_sides();
  if (std::find(segs.begin(), segs.end(), a.segment) == segs.end())
    throw Error("", where, "unknown segment '" + a.segment + "' (neck, torso, hips, left-arm, right-arm, left-leg, right-leg)");
  if (std::find(sides.begin(), sides.end(), a.side) == sides.end())
    throw Error("", where, "unknown side '" + a.side + "' (front, back, left, right)");
  auto number = [&](const std::string& t, const char* what) {
    const auto v = parse_double(trim(t));
    if (!v || !std::isfinite(*v)) throw Error("", where, std::string(what) + " '" + t + "' is not a number");
    return *v;
  };
  a.height = number(parts[2], "height (m)");
  if (parts.size() > 3) a.clearance = number(parts[3], "clearance (m)");
  if (a.clearance < 0) throw Error("", where, "clearance must be at least 0 m");
  if (parts.size() > 4) a.angle_deg = number(parts[4], "angle (deg)");
  if (parts.size() > 5) {
    if (trim(parts[5]) != "flip") throw Error("", where, "the sixth field can only be 'flip'");
    a.flip = true;
  }
  const auto ref = reference_point(piece, a.angle_deg);
  a.x = ref.x();
  a.y = ref.y();
  return a;
}

SetArrangements::SetArrangements(std::string pattern_id, std::vector<Arrangement> arrangements)
    : id_(std::move(pattern_id)), arrangements_(std::move(arrangements)) {}

std::string SetArrangements::label() const { return "Arrange " + id_; }

std::string SetArrangements::apply(Editor& edit) {
  const Document& doc = edit.document();
  const Node* p = doc.find(id_);
  if (!p) throw Error(doc.name(), id_, "no element with id " + id_);
  if (p->tag != "PATTERN") throw Error(doc.name(), id_, id_ + " is a " + p->tag + ", not a PATTERN");
  std::vector<std::string> old;
  for (const auto& c : p->children)
    if (c.tag == "POSITION" && c.attribute("type") == "arrangement") old.emplace_back(c.id());
  for (const auto& id : old) {
    DeleteNode del(id);
    del.apply(edit);
  }
  for (const auto& a : arrangements_) {
    AddNode add(id_, arrangement_node(a));
    add.apply(edit);
  }
  return id_;
}

}  // namespace vgd::xvc
