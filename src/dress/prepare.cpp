#include "vgd/dress/prepare.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>

#include "vgd/body/sizes.hpp"
#include "vgd/core/data.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/pattern/contour.hpp"
#include "vgd/pattern/halves.hpp"
#include "vgd/pattern/roles.hpp"
#include "vgd/pattern/shape_roles.hpp"
#include "vgd/xvc/arrangement.hpp"
#include "vgd/xvc/commands.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/seams.hpp"
#include "vgd/xvc/style.hpp"

namespace vgd::dress {

namespace {

std::vector<std::string> tokens(const std::string& s) {
  std::vector<std::string> out;
  std::string cur;
  for (const char ch : s) {
    if (std::isalnum(static_cast<unsigned char>(ch))) {
      cur += static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    } else if (!cur.empty()) {
      out.push_back(cur);
      cur.clear();
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

bool starts(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

// Ease of a garment over the body at the girth vgd matches it by (m): a
// regular top's chest over the bust, a skirt's or trousers' hip over the hip.
constexpr double kBustEase = 0.10, kHipEase = 0.05;
// Trousers' inseam against the body's crotch height (m): 2 cm shorter.
constexpr double kInseamEase = 0.02;

// The pattern's girth (m): over the pieces given (its fronts and backs), each
// piece's widest extent across its grain line between `from` and `to` of its
// length along it (from its bottom; halves of trouser legs: from their waist,
// the wider end), times the times it is cut. 0 without a piece.
double pattern_girth(const xvc::Document& doc, const std::vector<const xvc::Node*>& patterns, double from = 0.25,
                     double to = 0.75, bool from_wider_end = false) {
  double girth = 0;
  for (const auto* node : patterns) {
    const pattern::Piece p = xvc::to_piece(doc, node->id());
    if (p.boundary.size() < 3) continue;
    pattern::Vec2 up = pattern::Vec2::UnitY();
    if (p.grain_line && (p.grain_line->b - p.grain_line->a).norm() > 0) up = (p.grain_line->b - p.grain_line->a).normalized();
    if (from_wider_end && pattern::wider_at_top(p.boundary, up)) up = -up;  // measured from the waist down
    double lo = 1e300, hi = -1e300;
    for (const auto& c : p.boundary) lo = std::min(lo, c.p.dot(up)), hi = std::max(hi, c.p.dot(up));
    double widest = 0;
    for (int k = 0; k <= 20; ++k)
      widest = std::max(widest, pattern::width_at(p.boundary, up, lo + (from + (to - from) * k / 20.0) * (hi - lo)));
    girth += std::max(1, p.quantity) * widest;
  }
  return girth;
}

// Why no seam vgd suggests sews a piece of this role: what its seam rules
// (xvc/seams.hpp) sew and what they do not yet, and what the designer can do.
std::string not_sewn_why(pattern::Role role, bool half_legs) {
  using pattern::Role;
  const std::string r(pattern::role_name(role));
  std::string why;
  switch (role) {
    case Role::collar:
      why = "vgd sews a one-piece collar (no stand) round a whole front's and a back's necklines from centre front, or a "
            "collar to the top of its stand (within 15 % of its length), where no neckband is sewn, and neither fits "
            "this one";
      break;
    case Role::collar_stand:
      why = "vgd sews a collar stand round a whole front's and a back's (or yoke's) necklines from centre front, within "
            "15 % of their length, where no neckband is sewn, and none fits this one";
      break;
    case Role::hood:
      why = "vgd does not yet suggest the seam that sews a " + r + " to the neckline";
      break;
    case Role::neckband:
      why = "no neckline vgd found (a front's and a back's outline between their shoulder seams) fits its length";
      break;
    case Role::cuff:
      why = "no sleeve vgd sews to the armholes is cut as often as it and has a hem it fits (a shirt's cuff, "
            "with its opening, is not sewn yet)";
      break;
    case Role::waistband:
      why = half_legs
                ? "on trousers cut as half legs vgd sews a waistband in two halves, one cut twice or two cut "
                  "once, each 1 cm shorter to 12 cm longer than its side's waist, and this one is not such a "
                  "half"
                : "no waist vgd found (a skirt's front and back, or whole legs) fits its length";
      break;
    case Role::binding:
      why = "vgd sews a binding round a neckline (a front's and a back's, between their shoulder seams), not yet "
            "round an armhole or another edge";
      break;
    case Role::facing:
    case Role::belt_loop:
    case Role::fly:
      why = "vgd does not yet suggest the seams of a " + r;
      break;
    default:
      why = "none of the seams vgd suggests fits it";
  }
  return why + "; sew it with 'vgd seams add' and arrange it with 'vgd place', then dress the document again";
}

// m: a chest pocket's top lies this far above the bottom of the armhole
// (the top of the side seam), its middle this share of the way from centre
// front to the side seam there, on the wearer's left.
constexpr double kPocketAboveUnderarm = 0.04;
constexpr double kPocketAcross = 0.4;
// m: a pocket flap's top edge lies this far above its pocket's.
constexpr double kFlapAbovePocket = 0.015;
// m: a placket's top end lies this far below the neckline at centre front.
constexpr double kPlacketBelowNeck = 0.005;

// Writes each piece's role (by piece name) on every size's PATTERN, as one
// undoable command named `what`.
void write_roles(xvc::Document& doc, const std::map<std::string, pattern::Role>& by_name, const std::string& what) {
  std::vector<std::unique_ptr<xvc::Command>> set;
  for (const auto* p : doc.patterns())
    if (const auto it = by_name.find(std::string(p->attribute("piece"))); it != by_name.end())
      set.push_back(std::make_unique<xvc::SetAttribute>(std::string(p->id()), "role",
                                                        std::string(pattern::role_name(it->second))));
  xvc::execute(doc, *std::make_unique<xvc::Batch>(what, std::move(set)));
}

// The box of a PATTERN's outline (m, its own frame); nothing for an outline
// of fewer than 3 points.
std::optional<std::pair<pattern::Vec2, pattern::Vec2>> outline_box(const std::vector<pattern::ContourPoint>& b) {
  if (b.size() < 3) return std::nullopt;
  pattern::Vec2 lo = b.front().p, hi = b.front().p;
  for (const auto& cp : b) lo = lo.cwiseMin(cp.p), hi = hi.cwiseMax(cp.p);
  return std::pair{lo, hi};
}
std::optional<std::pair<pattern::Vec2, pattern::Vec2>> outline_box(const xvc::Document& doc, const xvc::Node& p) {
  return outline_box(xvc::to_piece(doc, std::string(p.id())).boundary);
}

// p turned by a radians counter-clockwise.
pattern::Vec2 turned(const pattern::Vec2& p, double a) {
  return pattern::Vec2(std::cos(a) * p.x() - std::sin(a) * p.y(), std::sin(a) * p.x() + std::cos(a) * p.y());
}
// A front's outline turned upright as its arrangement turns it (by t radians).
std::vector<pattern::ContourPoint> upright_outline(const xvc::Document& doc, const xvc::Node& front,
                                                   double t) {
  std::vector<pattern::ContourPoint> up;
  for (const auto& cp : xvc::to_piece(doc, std::string(front.id())).boundary)
    up.push_back({turned(cp.p, t), pattern::PointKind::plain});
  return up;
}

// Where a patch pocket goes on a whole front (cut once, symmetric about
// centre front) when the document does not say: the front turned upright as
// its arrangement turns it, the armhole's bottom is the highest point of
// the upper half within 5 mm of its widest reach; the pocket turned the
// same way (its own +y up). Nothing for a flipped arrangement.
std::optional<xvc::FacePlacement> chest_pocket(const xvc::Document& doc, const xvc::Node& pocket, const xvc::Node& front,
                                               const xvc::Arrangement& at, std::string& said) {
  if (at.flip) return std::nullopt;
  const double t = at.angle_deg * std::numbers::pi / 180.0;
  const auto up = upright_outline(doc, front, t);
  const auto front_box = outline_box(up);
  if (!front_box) return std::nullopt;
  const auto [lo, hi] = *front_box;
  const double cf = 0.5 * (lo.x() + hi.x()), mid = 0.5 * (lo.y() + hi.y());
  double reach = -std::numeric_limits<double>::infinity();
  for (const auto& cp : up)
    if (cp.p.y() > mid) reach = std::max(reach, cp.p.x());
  double underarm = -std::numeric_limits<double>::infinity();
  for (const auto& cp : up)
    if (cp.p.y() > mid && cp.p.x() >= reach - 0.005) underarm = std::max(underarm, cp.p.y());
  if (!(reach > cf) || !std::isfinite(underarm)) return std::nullopt;
  const auto box = outline_box(doc, pocket);
  if (!box) return std::nullopt;
  const auto [plo, phi] = *box;
  const auto own = xvc::to_piece(doc, std::string(pocket.id())).boundary;
  const double across = kPocketAcross * (reach - cf);
  const pattern::Vec2 centre(cf + across, underarm + kPocketAboveUnderarm - 0.5 * (phi.y() - plo.y()));
  const pattern::Vec2 c = turned(centre, -t);
  said = "its top " + format_fixed(100 * kPocketAboveUnderarm, 1) + " cm above the bottom of the armhole, its middle " +
         format_fixed(100 * across, 1) + " cm from centre front on the wearer's left";
  // All of it on the front (in the front's upright frame).
  const pattern::Vec2 mid_own = 0.5 * (plo + phi);
  for (const auto& cp : own)
    if (!pattern::point_in_outline(up, cp.p - mid_own + centre)) {
      said = "it does not fit on " + std::string(front.attribute("piece")) + " where vgd puts a chest pocket (" + said +
             ")";
      return std::nullopt;
    }
  return xvc::FacePlacement{"", std::string(front.id()), c.x(), c.y(), -at.angle_deg};
}

// Where a placket goes on a whole front when the document does not say:
// upright along centre front (its long side up, the front turned upright as
// its arrangement turns it), its top end kPlacketBelowNeck below where the
// neckline crosses centre front (the highest point of the outline there).
// Nothing for a flipped arrangement; nothing, with `said`, where it does not fit.
std::optional<xvc::FacePlacement> centre_front_placket(const xvc::Document& doc, const xvc::Node& placket,
                                                       const xvc::Node& front, const xvc::Arrangement& at,
                                                       std::string& said) {
  if (at.flip) return std::nullopt;
  const double t = at.angle_deg * std::numbers::pi / 180.0;
  const auto up = upright_outline(doc, front, t);
  const auto front_box = outline_box(up);
  const auto box = outline_box(doc, placket);
  if (!front_box || !box) return std::nullopt;
  const double cf = 0.5 * (front_box->first.x() + front_box->second.x());
  double neck = -std::numeric_limits<double>::infinity();  // the outline's highest crossing of centre front
  for (std::size_t i = 0; i < up.size(); ++i) {
    const pattern::Vec2 &a = up[i].p, &b = up[(i + 1) % up.size()].p;
    if ((a.x() - cf) * (b.x() - cf) > 0.0 || a.x() == b.x()) continue;
    neck = std::max(neck, a.y() + (cf - a.x()) / (b.x() - a.x()) * (b.y() - a.y()));
  }
  if (!std::isfinite(neck)) return std::nullopt;
  // Its long side up: a placket drawn lying down is turned a quarter.
  const auto [plo, phi] = *box;
  const bool lying = phi.x() - plo.x() > phi.y() - plo.y();
  const double quarter = lying ? 90.0 : 0.0, length = lying ? phi.x() - plo.x() : phi.y() - plo.y();
  const pattern::Vec2 centre(cf, neck - kPlacketBelowNeck - 0.5 * length);
  said = "upright along centre front, its top " + format_fixed(100 * kPlacketBelowNeck, 1) +
         " cm below the neckline there";
  const pattern::Vec2 mid_own = 0.5 * (plo + phi);
  for (const auto& cp : xvc::to_piece(doc, std::string(placket.id())).boundary)
    if (!pattern::point_in_outline(up, turned(cp.p - mid_own, quarter * std::numbers::pi / 180.0) + centre)) {
      said = "it does not fit on " + std::string(front.attribute("piece")) + " " + said;
      return std::nullopt;
    }
  const pattern::Vec2 c = turned(centre, -t);
  return xvc::FacePlacement{"", std::string(front.id()), c.x(), c.y(), quarter - at.angle_deg};
}

}  // namespace

std::string size_table_from_name(const std::string& style_name) {
  bool men = false, women = false;
  for (const auto& t : tokens(style_name)) {
    if (t == "W" || t == "WM" || t == "WMN" || starts(t, "WOMEN") || starts(t, "LADIES") || starts(t, "FEMALE") ||
        starts(t, "WOMAN"))
      women = true;
    else if (t == "M" || t == "MEN" || t == "MENS" || t == "MAN" || starts(t, "MALE"))
      men = true;
  }
  if (men == women) return "";
  return men ? "en13402-men" : "en13402-women";
}

// The size table that holds most of a style's graded sizes, when one holds
// at least two of them and more than any other ("" otherwise: one size, or
// sizes no table tells apart). GLX4802S19's tights, graded 26-52, are
// women's sizes: 10 of them are EN 13402 women's, 5 men's.
std::string size_table_from_sizes(const std::vector<std::string>& sizes, std::string& why) {
  std::string best;
  int most = 0, second = 0;
  for (const auto& t : body::size_table_names()) {
    std::set<std::string> labels;
    for (const auto& row : body::load_size_table(body::size_table_file(t))) labels.insert(row.label);
    const int n = static_cast<int>(
        std::count_if(sizes.begin(), sizes.end(), [&](const std::string& z) { return labels.count(z) > 0; }));
    if (n > most) second = most, most = n, best = t;
    else second = std::max(second, n);
  }
  if (most < 2 || most == second) return "";
  // Numbers in their order (the document may list them in any).
  std::vector<std::string> sorted = sizes;
  const auto number = [](const std::string& z) {
    return !z.empty() && std::all_of(z.begin(), z.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
  };
  std::stable_sort(sorted.begin(), sorted.end(), [&](const std::string& a, const std::string& b) {
    const bool na = number(a), nb = number(b);
    if (na && nb) return a.size() != b.size() ? a.size() < b.size() : a < b;
    return na && !nb;
  });
  why = "the style's sizes " + sorted.front() + " to " + sorted.back() + ": " + std::to_string(most) + " of its " +
        std::to_string(sizes.size()) + " are " + best + " sizes";
  return best;
}

Preparation prepare_garment(xvc::Document& doc, const PrepareOptions& options) {
  const std::string file = doc.name();
  Preparation out;

  // Pieces written once per side (CLO's halves, a sleeve written twice) in a
  // document imported as the file wrote them: joined as vgd dress joins them
  // when it imports a DXF (pattern/halves.hpp). Only in a document that is
  // its style and nothing more (written again from its style, it is the same
  // document: no SEAM, MATERIAL, PARAMETER, arrangement, role or edit of its
  // own), which is then written again from the joined style.
  {
    pattern::Style style = xvc::to_style(doc);
    if (xvc::from_style(style) == doc) {
      const auto joined = pattern::join_pieces_written_per_side(style);
      const auto halves = pattern::unfold_top_halves(style);
      if (!joined.empty() || !halves.unfolded.empty()) {
        doc = xvc::Document(xvc::Node(xvc::from_style(style).root()), file);
        for (const auto& j : joined) out.decisions.push_back(pattern::describe(j));
        for (const auto& d : pattern::describe(halves)) out.decisions.push_back(d);
      }
    }
  }
  std::string sample;
  if (const auto* grads = doc.container("GRADATIONS")) sample = std::string(grads->attribute("sample_size"));
  const auto patterns_of = [&](const std::string& size) {
    std::vector<const xvc::Node*> v;
    for (const auto* p : doc.patterns())
      if (p->attribute("size") == size) v.push_back(p);
    return v;
  };
  out.size = !options.size.empty() ? options.size : sample;
  if (out.size.empty() && !doc.patterns().empty()) out.size = std::string(doc.patterns().front()->attribute("size"));
  const auto mine = patterns_of(out.size);
  if (mine.empty()) {
    std::vector<std::string> sizes;  // in the document's order
    for (const auto* p : doc.patterns())
      if (const std::string z(p->attribute("size")); std::find(sizes.begin(), sizes.end(), z) == sizes.end())
        sizes.push_back(z);
    std::string list;
    for (const auto& z : sizes) list += (list.empty() ? "" : ", ") + z;
    throw Error(
        file, "size " + out.size,
        "the document has no pattern of size '" + out.size + "'" +
            (sizes.empty() ? std::string(": it has no patterns")
                           : "; its sizes: " + list + (sample.empty() ? "" : " (sample " + sample + ")")));
  }

  // Quantities: a document where every pattern says 0 states none (a file
  // written with the field left at its default: mirrored.DXF): each piece is
  // cut as often as its annotation's cutting instruction says ("2XFABRIC
  // 2XINTERLINI": twice), else once. Written in the document.
  if (const auto all = doc.patterns();
      !all.empty() && std::all_of(all.begin(), all.end(), [](const xvc::Node* p) { return p->attribute("quantity") == "0"; })) {
    std::vector<std::unique_ptr<xvc::Command>> set;
    std::map<std::string, int> said;  // piece -> quantity
    for (const auto* p : doc.patterns()) {
      const std::string a = to_upper(trim(p->attribute("annotation")));
      std::size_t digits = 0;
      while (digits < a.size() && std::isdigit(static_cast<unsigned char>(a[digits]))) ++digits;
      std::size_t x = digits;
      while (x < a.size() && a[x] == ' ') ++x;
      int q = 1;
      if (digits > 0 && digits <= 2 && x < a.size() && a[x] == 'X')
        if (const auto n = parse_int(a.substr(0, digits)); n && *n >= 1) q = static_cast<int>(*n);
      said[std::string(p->attribute("piece"))] = q;
      set.push_back(std::make_unique<xvc::SetAttribute>(std::string(p->id()), "quantity", std::to_string(q)));
    }
    if (!set.empty()) {
      xvc::execute(doc, *std::make_unique<xvc::Batch>("quantities from the annotations", std::move(set)));
      std::string list;
      for (const auto& [piece, q] : said)
        if (q != 1) list += (list.empty() ? "" : ", ") + piece + " " + std::to_string(q);
      out.decisions.push_back("every piece says it is cut 0 times, which states nothing: each is cut as often as its "
                              "annotation says, else once (" + (list.empty() ? std::string("all once") : "twice or more: " + list) + ")");
    }
  }

  // Roles from the pieces' shapes, for pieces whose names say nothing (CLO's
  // numbers): pattern::roles_from_shapes at the sample size, written in the
  // document as role attributes (every size of the piece), and said.
  {
    const auto here = patterns_of(!sample.empty() && !patterns_of(sample).empty() ? sample : out.size);
    std::vector<const xvc::Node*> unknown;
    std::vector<pattern::Piece> pieces;
    for (const auto* p : here)
      if (!p->has_attribute("role") && xvc::piece_role(doc, *p).role == pattern::Role::unknown) {
        unknown.push_back(p);
        pieces.push_back(xvc::to_piece(doc, p->id()));
      }
    std::vector<const pattern::Piece*> shapes;
    for (const auto& pc : pieces) shapes.push_back(&pc);
    const auto found = pattern::roles_from_shapes(shapes);
    std::map<std::string, pattern::Role> by_name;
    std::string said, left;
    for (std::size_t i = 0; i < unknown.size(); ++i) {
      const std::string name(unknown[i]->attribute("piece"));
      if (found[i].role == pattern::Role::unknown) {
        left += (left.empty() ? "" : ", ") + name;
        continue;
      }
      by_name[name] = found[i].role;
      said += (said.empty() ? "" : ", ") + name + " " + std::string(pattern::role_name(found[i].role)) + " (" +
              found[i].why + ")";
    }
    if (!by_name.empty()) {
      write_roles(doc, by_name, "roles from shapes");
      out.decisions.push_back("roles from the pieces' shapes (their names say nothing): " + said +
                              (left.empty() ? "" : "; no role from its shape: " + left) +
                              " (role written; correct it in the document)");
    }
  }

  // Legs by elimination: a garment with a waistband and no front, back or leg piece
  // (leggings whose leg is named by a code, ORILEG's "LL", category "LENGTH OPTIONS")
  // wears its pieces cut twice that no name places as its legs. Said, and written in
  // the document as the word LEG added to their category, which the role rules read.
  {
    bool band = false, body = false;
    std::set<std::string> unknown;
    for (const auto* p : doc.patterns()) {
      const pattern::Role r = xvc::piece_role(doc, *p).role;
      band = band || r == pattern::Role::waistband;
      body = body || r == pattern::Role::front || r == pattern::Role::back || r == pattern::Role::leg;
      if (r == pattern::Role::unknown && parse_int(p->attribute("quantity")).value_or(0) >= 2)
        unknown.insert(std::string(p->attribute("piece")));
    }
    if (band && !body && !unknown.empty()) {
      std::vector<std::unique_ptr<xvc::Command>> set;
      for (const auto* p : doc.patterns())
        if (unknown.count(std::string(p->attribute("piece")))) {
          const std::string category(p->attribute("category"));
          set.push_back(std::make_unique<xvc::SetAttribute>(std::string(p->id()), "category",
                                                            category.empty() ? "LEG" : category + " LEG"));
        }
      xvc::execute(doc, *std::make_unique<xvc::Batch>("legs by elimination", std::move(set)));
      for (const auto& n : unknown)
        out.decisions.push_back("piece " + n + " read as a leg: cut twice in a garment with a waistband and no front, "
                                "back or leg (LEG added to its category)");
    }
  }

  // Trousers cut as half legs (Valentina's FRONT and BACK): in a garment for the
  // lower body (a waistband, or its name says trousers or pants) with no sleeve
  // and no leg, fronts and backs as long as a leg (at least 0.8 m along their
  // grain) and 15 % wider at one end than at the other (the waist, with the seat
  // and the crotch's extension, against the hem) are the front and back halves
  // of the legs. Written in the document as role="leg" (the name's FRONT or BACK
  // gives the half). A half cut once
  // that says no side and has no fold line is cut as a pair, left and right
  // (quantity 2): one leg's half is never a garment. Said, and written.
  {
    constexpr double kLegLength = 0.8;  // m
    bool other = false;
    std::vector<const xvc::Node*> halves;  // the sample's (or the size's) fronts and backs
    const auto here = patterns_of(!sample.empty() && !patterns_of(sample).empty() ? sample : out.size);
    for (const auto* p : here) {
      const pattern::RoleGuess g = xvc::piece_role(doc, *p);
      other = other || g.role == pattern::Role::sleeve || g.role == pattern::Role::leg;
      if ((g.role == pattern::Role::front || g.role == pattern::Role::back) && !p->has_attribute("role") &&
          p->attribute("quantity") != "0")
        halves.push_back(p);
    }
    // A lower-body garment: a waistband, or the style's name says trousers or pants.
    bool lower = false;
    for (const auto* p : here) lower = lower || xvc::piece_role(doc, *p).role == pattern::Role::waistband;
    const std::string style = to_upper(doc.root().attribute("name"));
    lower = lower || style.find("TROUSER") != std::string::npos || style.find("PANTS") != std::string::npos;
    bool legs = lower && !other && !halves.empty();
    for (const auto* p : halves) {
      if (!legs) break;
      const pattern::Piece piece = xvc::to_piece(doc, p->id());
      pattern::Vec2 up = pattern::Vec2::UnitY();
      if (piece.grain_line && (piece.grain_line->b - piece.grain_line->a).norm() > 0)
        up = (piece.grain_line->b - piece.grain_line->a).normalized();
      const pattern::EndWidths w = pattern::end_widths(piece.boundary, up);
      legs = w.length >= kLegLength && std::max(w.top, w.bottom) >= 1.15 * std::min(w.top, w.bottom);
    }
    if (legs) {
      std::set<std::string> names;
      for (const auto* p : halves) names.insert(std::string(p->attribute("piece")));
      std::vector<std::unique_ptr<xvc::Command>> set;
      std::set<std::string> paired;
      for (const auto* p : doc.patterns()) {
        const std::string name(p->attribute("piece"));
        if (!names.count(name)) continue;
        set.push_back(std::make_unique<xvc::SetAttribute>(std::string(p->id()), "role", "leg"));
        const pattern::Piece piece = xvc::to_piece(doc, p->id());
        if (p->attribute("quantity") == "1" && !piece.mirror_line && xvc::piece_role(doc, *p).side == pattern::Side::none) {
          set.push_back(std::make_unique<xvc::SetAttribute>(std::string(p->id()), "quantity", "2"));
          paired.insert(name);
        }
      }
      xvc::execute(doc, *std::make_unique<xvc::Batch>("half legs", std::move(set)));
      std::string list;
      for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
      out.decisions.push_back("pieces " + list + " read as the front and back halves of trouser legs: at least " +
                              format_fixed(kLegLength, 1) + " m long, wider at one end, no sleeve (role=\"leg\" written)");
      for (const auto& n : paired)
        out.decisions.push_back("piece " + n + " is cut as a left and a right half (quantity 2): the file cuts it once " +
                                "and names no side");
    }
  }

  // Seams: the seam file's, else vgd's suggestions when the document has none.
  if (!options.seams_file.empty()) {
    if (!xvc::list_seams(doc).empty())
      throw Error(options.seams_file, "", "the document " + file + " has seams of its own: a seam file is for a "
                                          "document without (a DXF); correct the document's SEAMs instead");
    const auto plans = xvc::parse_seam_plans(read_file(options.seams_file), options.seams_file);
    auto nodes = xvc::plan_seam_nodes(doc, plans);
    const std::size_t n = nodes.size();
    xvc::execute(doc, *std::make_unique<xvc::AddSeams>(std::move(nodes)));
    out.decisions.push_back("seams from " + options.seams_file + ": " + std::to_string(plans.size()) + " seams (" +
                            std::to_string(n) + " SEAMs over the sizes); none suggested");
  }
  if (xvc::list_seams(doc).empty()) {
    xvc::SeamOptions so;
    so.size = !sample.empty() && !patterns_of(sample).empty() ? sample : out.size;
    so.min_score = options.min_score;
    const auto suggested = xvc::suggest_seams(doc, so);
    std::vector<xvc::Node> nodes;
    for (const auto& s : suggested) {
      nodes.push_back(xvc::seam_node(s));
      std::string hems;
      for (std::size_t k = 0; k < s.hems.size(); ++k) {
        const auto* p = doc.find(s.hems[k].pattern);
        hems += (k == 0 ? "" : k == 1 ? " to " : " + ") + std::string(p ? p->attribute("piece") : s.hems[k].pattern);
      }
      out.decisions.push_back("seam '" + s.name + "' suggested at size " + so.size + ": " + hems + ", ease " +
                              format_fixed(1000 * s.ease, 1) + " mm, score " + format_fixed(s.score, 2));
    }
    if (!nodes.empty()) xvc::execute(doc, *std::make_unique<xvc::AddSeams>(std::move(nodes)));
    out.seams_added = static_cast<int>(suggested.size());
    if (suggested.empty())
      out.decisions.push_back("no SEAM in the document and none suggested at size " + so.size);
  }

  // A front or back drawn another way, named as a part: a piece whose name
  // reads as a collar, collar stand, neckband, cuff, binding or placket but
  // whose outline is as large as a front's or a back's of its size (its box
  // within kSameBox of theirs both ways, its area at least kSameArea of
  // theirs) is that front or back, cut for another version of the style
  // (Gerber's GMG1016S19-FR CO 1, category FRONT HALF CO: the front cut for
  // the half collar, its box the front's). Read after the seams are
  // suggested (they stay with the piece named front); role written, said.
  {
    constexpr double kSameBox = 0.05, kSameArea = 0.8;
    const auto here = patterns_of(!sample.empty() && !patterns_of(sample).empty() ? sample : out.size);
    struct Shape {
      const xvc::Node* p;
      double w, h, area;
    };
    const auto shape_of = [&](const xvc::Node* p) -> std::optional<Shape> {
      const auto b = xvc::to_piece(doc, std::string(p->id())).boundary;
      const auto box = outline_box(b);
      if (!box) return std::nullopt;
      const pattern::Vec2 d = box->second - box->first;
      return Shape{p, std::max(d.x(), d.y()), std::min(d.x(), d.y()), std::abs(pattern::signed_area(b))};
    };
    std::vector<Shape> bodies;
    for (const auto* p : here) {
      const pattern::Role r = xvc::piece_role(doc, *p).role;
      if ((r == pattern::Role::front || r == pattern::Role::back) && p->attribute("quantity") != "0")
        if (const auto sh = shape_of(p)) bodies.push_back(*sh);
    }
    const auto near = [](double a, double b) { return std::abs(a - b) <= kSameBox * std::max(a, b); };
    std::map<std::string, pattern::Role> by_name;
    for (const auto* p : here) {
      const pattern::Role r = xvc::piece_role(doc, *p).role;
      if (p->has_attribute("role") ||
          (r != pattern::Role::collar && r != pattern::Role::collar_stand && r != pattern::Role::neckband &&
           r != pattern::Role::cuff && r != pattern::Role::binding && r != pattern::Role::placket))
        continue;
      const auto sh = shape_of(p);
      if (!sh) continue;
      for (const Shape& b : bodies) {
        if (!near(sh->w, b.w) || !near(sh->h, b.h) || sh->area < kSameArea * b.area) continue;
        const pattern::Role body = xvc::piece_role(doc, *b.p).role;
        const std::string name(p->attribute("piece"));
        by_name[name] = body;
        out.decisions.push_back(
            "piece " + name + " read as a " + std::string(pattern::role_name(body)) + ", not a " +
            std::string(pattern::role_name(r)) + ": its outline is as large as the " +
            std::string(pattern::role_name(body)) + " " + std::string(b.p->attribute("piece")) + "'s (" +
            format_fixed(100 * sh->w, 1) + " x " + format_fixed(100 * sh->h, 1) + " cm, " +
            format_fixed(1e4 * sh->area, 0) + " cm²; the " + std::string(pattern::role_name(body)) + "'s " +
            format_fixed(100 * b.w, 1) + " x " + format_fixed(100 * b.h, 1) + " cm, " +
            format_fixed(1e4 * b.area, 0) + " cm²): the " + std::string(pattern::role_name(body)) +
            " cut for another version of the style (role written)");
        break;
      }
    }
    if (!by_name.empty()) write_roles(doc, by_name, "fronts and backs named as parts");
  }

  // Roles, as the names say.
  std::map<std::string, pattern::RoleGuess> roles;  // by piece name
  {
    std::string said;
    for (const auto* p : mine) {
      const std::string name(p->attribute("piece"));
      const pattern::RoleGuess g = xvc::piece_role(doc, *p);
      roles[name] = g;
      std::string detail = std::string(pattern::side_name(g.side));
      if (g.half != pattern::Half::none) detail += (detail.empty() ? "" : ", ") + std::string(pattern::half_name(g.half));
      said += (said.empty() ? "" : ", ") + name + " " +
              (g.role == pattern::Role::unknown ? std::string("?")
                                                : std::string(pattern::role_name(g.role)) + (detail.empty() ? "" : " (" + detail + ")"));
    }
    out.decisions.push_back("roles from the pieces' names: " + said);
  }

  // Pieces: sewn by some seam, and arranged round the body by a rule or the document.
  std::set<std::string> sewn;
  const auto seams = xvc::list_seams(doc);
  for (const auto& s : seams)
    for (const auto& h : s.hems)
      if (const auto* p = doc.find(h.pattern)) sewn.insert(std::string(p->attribute("piece")));
  // What finishes the neckline: the first neckband, collar, collar stand or
  // binding a seam sews to a front, back or yoke (piece, and the seam in words).
  const auto neck_finish = [](pattern::Role r) {
    return r == pattern::Role::neckband || r == pattern::Role::collar || r == pattern::Role::collar_stand;
  };
  std::optional<std::pair<std::string, std::string>> neck_sewn;
  for (const auto& s : seams) {
    std::string finish;
    bool body = false;
    for (const auto& h : s.hems)
      if (const auto* p = doc.find(h.pattern)) {
        const pattern::Role r = xvc::piece_role(doc, *p).role;
        if (finish.empty() && (neck_finish(r) || r == pattern::Role::binding)) finish = std::string(p->attribute("piece"));
        body = body || r == pattern::Role::front || r == pattern::Role::back || r == pattern::Role::yoke;
      }
    if (!finish.empty() && body && std::find_if(mine.begin(), mine.end(), [&](const xvc::Node* p) {
                                     return p->attribute("piece") == finish;
                                   }) != mine.end()) {
      neck_sewn = {finish, "sewn by the seam '" + s.name + "'"};
      break;
    }
  }
  std::set<std::string> arranged;
  for (const auto& [id, list] : xvc::suggest_arrangements(doc))
    if (!list.empty())
      if (const auto* p = doc.find(id)) arranged.insert(std::string(p->attribute("piece")));
  for (const auto* p : mine)
    if (!xvc::arrangements_of(*p).empty()) arranged.insert(std::string(p->attribute("piece")));
  // Trousers cut as half legs (the waistband rules sew skirts and whole legs).
  const bool half_legs = std::any_of(mine.begin(), mine.end(), [&](const xvc::Node* p) {
    const auto& g = roles[std::string(p->attribute("piece"))];
    return g.role == pattern::Role::leg && g.half != pattern::Half::none;
  });
  // A patch pocket goes on the face of a whole front (one cut once, no
  // side or half): the first pocket pattern; the others are its
  // alternatives. Where the document places it, else chest_pocket.
  const xvc::Node* pocket_host = nullptr;
  std::string first_pocket;
  std::map<std::string, xvc::FacePlacement> pocket_at;  // pattern id -> where to write it
  for (const auto* p : mine) {
    const auto& g = roles[std::string(p->attribute("piece"))];
    const std::string_view cut = p->attribute("quantity");
    if (!pocket_host && g.role == pattern::Role::front && g.side == pattern::Side::none &&
        sewn.count(std::string(p->attribute("piece"))) &&
        g.half == pattern::Half::none && (cut.empty() || cut == "1") && xvc::drape_attribute(*p) != false &&
        xvc::arrangements_of(*p).size() <= 1)
      pocket_host = p;
    if (first_pocket.empty() && g.role == pattern::Role::pocket && p->attribute("quantity") != "0" &&
        xvc::drape_attribute(*p) != false && !sewn.count(std::string(p->attribute("piece"))))
      first_pocket = std::string(p->attribute("piece"));
  }
  std::vector<const xvc::Node*> flaps;  // pocket flaps no seam sews, decided after the pockets
  std::vector<const xvc::Node*> plackets;  // plackets no seam sews, decided after the loop
  std::optional<std::pair<const xvc::Node*, xvc::FacePlacement>> placed_pocket;  // the pocket draped
  const bool has_legs = std::any_of(mine.begin(), mine.end(), [&](const xvc::Node* p) {
    return roles[std::string(p->attribute("piece"))].role == pattern::Role::leg;
  });
  const auto host_arrangement = [&]() -> std::optional<xvc::Arrangement> {
    if (!pocket_host) return std::nullopt;
    if (const auto stored = xvc::arrangements_of(*pocket_host); !stored.empty()) return stored.front();
    for (const auto& [id, list] : xvc::suggest_arrangements(doc))
      if (id == pocket_host->id() && !list.empty()) return list.front();
    return std::nullopt;
  };
  for (const auto* p : mine) {
    const std::string name(p->attribute("piece"));
    const pattern::Role role = roles[name].role;
    const std::string what = role == pattern::Role::unknown ? "" : " (" + std::string(pattern::role_name(role)) + ")";
    // missing: the garment is worn with it (not an alternative to a piece draped).
    auto leave = [&](const std::string& why, bool missing = true) {
      out.left_out.push_back(name);
      out.decisions.push_back("piece " + name + what + " left out: " + why);
      if (missing && p->attribute("quantity") != "0" && pattern::drapes_as_cloth(role))
        out.missing.push_back(name + (what.empty() ? " (role unknown)" : what));
    };
    if (role == pattern::Role::pocket_flap && xvc::drape_attribute(*p) != false && !sewn.count(name) &&
        p->attribute("quantity") != "0") {
      flaps.push_back(p);  // decided once the pocket is (below)
      continue;
    }
    if (role == pattern::Role::placket && xvc::drape_attribute(*p) != false && !sewn.count(name) &&
        p->attribute("quantity") != "0") {
      plackets.push_back(p);
      continue;
    }
    if (role == pattern::Role::pocket && !first_pocket.empty() && xvc::drape_attribute(*p) != false &&
        !sewn.count(name)) {
      if (const auto stored = xvc::face_placements_of(*p); !stored.empty()) {
        const auto* host = doc.find(stored.front().host);
        placed_pocket = {p, stored.front()};
        out.pieces.push_back(name);
        out.decisions.push_back("piece " + name + what + " sewn onto the face of " +
                                (host ? std::string(host->attribute("piece")) : stored.front().host) +
                                " where the document places it");
        continue;
      }
      if (name != first_pocket && pocket_host) {
        out.left_out.push_back(name);  // not missing: the garment has its pocket
        out.decisions.push_back("piece " + name + what + " left out: an alternative to the pocket " + first_pocket);
        continue;
      }
      std::string said;
      const auto at = host_arrangement();
      const auto f = at ? chest_pocket(doc, *p, *pocket_host, *at, said) : std::nullopt;
      if (f) {
        pocket_at[std::string(p->id())] = *f;
        placed_pocket = {p, *f};
        out.pieces.push_back(name);
        out.decisions.push_back("piece " + name + what + " sewn onto the face of " +
                                std::string(pocket_host->attribute("piece")) + ", " + said +
                                " (POSITION type=\"placement\" written in the document: move it there)");
        continue;
      }
      if (!said.empty()) {
        leave(said + "; place it with a POSITION type=\"placement\" (docs/xvc.md)");
        continue;
      }
    }
    if (xvc::drape_attribute(*p) == false) {
      out.left_out.push_back(name);
      out.decisions.push_back("piece " + name + what + " left out: the document says drape=\"false\"");
    } else if (mine.size() > 1 && !sewn.count(name)) {
      if (p->attribute("quantity") == "0")
        leave("the file cuts it 0 times (a reference or an alternative)");
      else if (!pattern::drapes_as_cloth(role))
        leave(role == pattern::Role::lining ? "a lining hangs inside the garment as a garment of its own; drape it as one"
                                            : "it is bonded to its host and does not hang as cloth of its own");
      else if (role == pattern::Role::pocket && has_legs)
        leave("a trouser pocket's pieces (bag, facing) hang inside the leg behind its pocket opening, which vgd does "
              "not drape");
      else if (role == pattern::Role::pocket)
        leave("a pocket is sewn onto the face of a whole front (one cut once), and this garment has none: place it "
              "with a POSITION type=\"placement\" (docs/xvc.md)");
      else if (pattern::sewn_on_host(role))
        leave("it is sewn onto the face of its host piece, which vgd does not drape yet");
      else if (role == pattern::Role::unknown)
        leave("its name says nothing vgd reads as a role and no seam sews it (add seams with 'vgd seams add')");
      else if (const auto alt = std::find_if(mine.begin(), mine.end(), [&](const xvc::Node* q) {
                 const std::string other(q->attribute("piece"));
                 return other != name && sewn.count(other) && roles[other].role == role &&
                        roles[other].half == roles[name].half && roles[other].side == roles[name].side;
               });
               (role == pattern::Role::sleeve || role == pattern::Role::leg || role == pattern::Role::collar ||
                role == pattern::Role::front || role == pattern::Role::back) &&
               alt != mine.end())
        leave("an alternative to the " + std::string(pattern::role_name(role)) + " " +
              std::string((*alt)->attribute("piece")) + ", whose seams fit the garment's other pieces better",
              false);
      else if (neck_finish(role) && neck_sewn)
        // One neckline, one finish: a style drawn with a rib collar and
        // three collar sets (mirrored.DXF) wears the one sewn.
        leave("an alternative finish of the neckline, which the " +
                  std::string(pattern::role_name(roles[neck_sewn->first].role)) + " " + neck_sewn->first +
                  " finishes (" + neck_sewn->second + ")",
              false);
      else
        leave("no seam sews it: " + not_sewn_why(role, half_legs));
    } else if (!arranged.count(name)) {
      leave("no rule places it round the body (give it an arrangement with 'vgd place --set \"" + name +
            "=SEGMENT:SIDE:HEIGHT\"')");
    } else {
      out.pieces.push_back(name);
    }
  }
  // Pocket flaps: over the pocket draped, the one whose name says what the
  // pocket's says beyond POCKET (POCKETFLAPROUND for POCKETROUND), else the
  // first; the others are its alternatives.
  {
    const auto beyond = [](std::string n) {
      n = to_upper(n);
      for (const char* w : {"POCKET", "FLAP", "POCHE", "RABAT", "TASCHE", "KLAPPE", "BOLSILLO", "BOLSO"})
        for (std::size_t at; (at = n.find(w)) != std::string::npos;) n.erase(at, std::string(w).size());
      std::string rest;
      for (const char c : n)
        if (std::isalnum(static_cast<unsigned char>(c))) rest += c;
      return rest;
    };
    const xvc::Node* chosen = nullptr;
    if (placed_pocket) {
      const std::string want = beyond(std::string(placed_pocket->first->attribute("piece")));
      for (const auto* f : flaps)
        if (!xvc::face_placements_of(*f).empty() || beyond(std::string(f->attribute("piece"))) == want) {
          chosen = f;
          break;
        }
      if (!chosen && !flaps.empty()) chosen = flaps.front();
    }
    const std::string pocket = placed_pocket ? std::string(placed_pocket->first->attribute("piece")) : "";
    for (const auto* f : flaps) {
      const std::string name(f->attribute("piece"));
      if (f != chosen) {
        out.left_out.push_back(name);
        out.decisions.push_back("piece " + name + " (pocket flap) left out: " +
                                (chosen ? "an alternative to the pocket flap " + std::string(chosen->attribute("piece"))
                                        : std::string("a pocket flap goes over a pocket, and no pocket is draped")));
        if (!chosen) out.missing.push_back(name + " (pocket flap)");
        continue;
      }
      const auto host_name = [&](const std::string& id) {
        const auto* h = doc.find(id);
        return h ? std::string(h->attribute("piece")) : id;
      };
      if (const auto stored = xvc::face_placements_of(*f); !stored.empty()) {
        out.pieces.push_back(name);
        out.decisions.push_back("piece " + name + " (pocket flap) sewn onto the face of " +
                                host_name(stored.front().host) + " where the document places it");
        continue;
      }
      // Its top edge kFlapAbovePocket above the pocket's, centred over it,
      // turned as the pocket is; it hangs over the pocket's mouth.
      const xvc::FacePlacement& pk = placed_pocket->second;
      const auto pocket_box = outline_box(doc, *placed_pocket->first), flap_box = outline_box(doc, *f);
      if (!pocket_box || !flap_box) {
        out.left_out.push_back(name);
        out.decisions.push_back("piece " + name + " (pocket flap) left out: its outline or its pocket's has fewer "
                                "than 3 points");
        continue;
      }
      const auto [plo, phi] = *pocket_box;
      const auto [flo, fhi] = *flap_box;
      const double a = pk.angle_deg * std::numbers::pi / 180.0;
      const pattern::Vec2 up(-std::sin(a), std::cos(a));
      const pattern::Vec2 at = pattern::Vec2(pk.x, pk.y) +
                               (0.5 * (phi.y() - plo.y()) + kFlapAbovePocket - 0.5 * (fhi.y() - flo.y())) * up;
      pocket_at[std::string(f->id())] = xvc::FacePlacement{"", pk.host, at.x(), at.y(), pk.angle_deg};
      out.pieces.push_back(name);
      out.decisions.push_back("piece " + name + " (pocket flap) sewn by its top edge onto the face of " +
                              host_name(pk.host) + ", " +
                              format_fixed(100 * kFlapAbovePocket, 1) + " cm above the top of " + pocket +
                              ", over its mouth (POSITION type=\"placement\" written in the document)");
    }
  }

  // Plackets: the one the document places, else of those whose name or
  // category does not say UNDER or LOWER (PLACKETUNDER, a polo's PLACKET
  // LOWER) the narrowest, upright along centre front of the whole front,
  // sewn by its two ends; the others lie under it, hidden by it.
  if (!plackets.empty()) {
    const xvc::Node* chosen = nullptr;
    for (const auto* f : plackets)
      if (!xvc::face_placements_of(*f).empty()) {
        chosen = f;
        break;
      }
    const auto under = [](const xvc::Node& f) {
      const std::string text =
          to_upper(std::string(f.attribute("piece")) + " " + std::string(f.attribute("category")));
      return text.find("UNDER") != std::string::npos || text.find("LOWER") != std::string::npos;
    };
    const bool any_upper =
        std::any_of(plackets.begin(), plackets.end(), [&](const xvc::Node* f) { return !under(*f); });
    if (!chosen) {
      double narrowest = std::numeric_limits<double>::infinity();
      for (const auto* f : plackets)
        if (const auto b = outline_box(doc, *f); b && !(any_upper && under(*f))) {
          const double w = std::min(b->second.x() - b->first.x(), b->second.y() - b->first.y());
          if (w < narrowest) narrowest = w, chosen = f;
        }
    }
    std::vector<const xvc::Node*> order;  // the chosen one first
    if (chosen) order.push_back(chosen);
    for (const auto* f : plackets)
      if (f != chosen) order.push_back(f);
    bool draped = false;
    for (const auto* f : order) {
      const std::string name(f->attribute("piece"));
      auto leave = [&](const std::string& why, bool missing) {
        out.left_out.push_back(name);
        out.decisions.push_back("piece " + name + " (placket) left out: " + why);
        if (missing) out.missing.push_back(name + " (placket)");
      };
      if (!chosen) {  // every outline of fewer than 3 points
        leave("its outline has fewer than 3 points", true);
        continue;
      }
      if (f != chosen) {
        if (draped)
          leave("it lies under the placket " + std::string(chosen->attribute("piece")) + ", hidden by it",
                false);
        else
          leave("it lies under a placket, and none is draped", true);
        continue;
      }
      if (const auto stored = xvc::face_placements_of(*f); !stored.empty()) {
        const auto* host = doc.find(stored.front().host);
        out.pieces.push_back(name);
        out.decisions.push_back("piece " + name + " (placket) sewn by its two ends onto the face of " +
                                (host ? std::string(host->attribute("piece")) : stored.front().host) +
                                " where the document places it");
        draped = true;
        continue;
      }
      if (!pocket_host) {
        leave("a placket is sewn onto the face of a whole front (one cut once), and this garment has none: "
              "place it with a POSITION type=\"placement\" (docs/xvc.md)",
              true);
        continue;
      }
      std::string said;
      const auto at = host_arrangement();
      const auto placed = at ? centre_front_placket(doc, *f, *pocket_host, *at, said) : std::nullopt;
      if (!placed) {
        leave((said.empty() ? "vgd finds no centre front on " + std::string(pocket_host->attribute("piece"))
                            : said) +
                  "; place it with a POSITION type=\"placement\" (docs/xvc.md)",
              true);
        continue;
      }
      pocket_at[std::string(f->id())] = *placed;
      out.pieces.push_back(name);
      out.decisions.push_back("piece " + name + " (placket) sewn by its two ends onto the face of " +
                              std::string(pocket_host->attribute("piece")) + ", " + said +
                              " (POSITION type=\"placement\" written in the document: move it there)");
      draped = true;
    }
  }

  // Alternatives: several sleeve patterns (a short and a full sleeve, a
  // one-piece and a two-piece set), several leg patterns (short and long
  // tights) are one sleeve or leg drawn several ways. Those sewn to pieces of
  // another role (a sleeve to the armholes) are the garment's; with none
  // sewn there, the one with the most seams, the first in the document of
  // those. The others are left out.
  std::set<std::string> kept;  // pieces the document says to drape: no alternatives
  for (const auto* p : mine)
    if (xvc::drape_attribute(*p) == true) kept.insert(std::string(p->attribute("piece")));
  // A sleeve or leg cut in halves has alternatives per half (three front halves
  // of a trouser leg: plain, with a pocket, with pleats).
  for (const auto& [role, half] : {std::pair{pattern::Role::sleeve, pattern::Half::none},
                                   std::pair{pattern::Role::sleeve, pattern::Half::front},
                                   std::pair{pattern::Role::sleeve, pattern::Half::back},
                                   std::pair{pattern::Role::leg, pattern::Half::none},
                                   std::pair{pattern::Role::leg, pattern::Half::front},
                                   std::pair{pattern::Role::leg, pattern::Half::back}}) {
    const std::string what = std::string(pattern::role_name(role)) +
                             (half == pattern::Half::none ? "" : "'s " + std::string(pattern::half_name(half)));
    // Copies: clang 14 cannot capture structured bindings in a lambda.
    const pattern::Role group_role = role;
    const pattern::Half group_half = half;
    const auto in_group = [&](const std::string& n) { return roles[n].role == group_role && roles[n].half == group_half; };
    std::vector<std::string> alts;  // a left and a right one are a pair, not alternatives
    for (const auto& name : out.pieces)
      if (in_group(name) && roles[name].side == pattern::Side::none && !kept.count(name)) alts.push_back(name);
    if (alts.size() < 2) continue;
    const auto is_alt = [&](const std::string& n) { return std::find(alts.begin(), alts.end(), n) != alts.end(); };
    std::set<std::string> on_body;  // with a seam to a piece of another role or half
    std::map<std::string, int> seams_of;
    for (const auto& s : xvc::list_seams(doc)) {
      std::set<std::string> names;
      for (const auto& h : s.hems)
        if (const auto* p = doc.find(h.pattern)) names.insert(std::string(p->attribute("piece")));
      const bool body = std::any_of(names.begin(), names.end(), [&](const std::string& n) { return !in_group(n); });
      for (const auto& n : names)
        if (is_alt(n)) {
          ++seams_of[n];
          if (body) on_body.insert(n);
        }
    }
    std::vector<std::string> chosen;
    for (const auto& n : alts)
      if (on_body.count(n)) chosen.push_back(n);
    if (chosen.empty())
      for (const auto& n : alts)
        if (chosen.empty() || seams_of[n] > seams_of[chosen.front()]) chosen = {n};
    std::string list;
    for (const auto& n : chosen) list += (list.empty() ? "" : ", ") + n;
    for (const auto& n : alts) {
      if (std::find(chosen.begin(), chosen.end(), n) != chosen.end()) continue;
      out.pieces.erase(std::find(out.pieces.begin(), out.pieces.end(), n));
      out.left_out.push_back(n);
      out.decisions.push_back("piece " + n + " left out: an alternative to the " + what + " " + list +
                              (!on_body.empty() ? " (sewn to the garment's other pieces)"
                                                : " (the one with the most seams, " + std::to_string(seams_of[chosen.front()]) +
                                                      ", first in the document)"));
    }
  }
  if (out.pieces.empty()) {
    std::string names;
    for (const auto* p : mine) {
      const std::string name(p->attribute("piece"));
      const pattern::Role r = roles[name].role;
      names += (names.empty() ? "" : ", ") + name + " (" +
               (r == pattern::Role::unknown ? std::string("role unknown") : std::string(pattern::role_name(r))) + ")";
    }
    throw Error(file, "size " + out.size,
                "nothing to drape: no seam vgd can find sews the pieces of this size together (" + names +
                    "); add seams with 'vgd seams add' or a seam file with 'vgd seams apply', and arrangements "
                    "with 'vgd place'");
  }

  // Where a pocket is sewn onto its front, written on the pocket's PATTERN.
  for (const auto& [id, f] : pocket_at)
    xvc::execute(doc, *std::make_unique<xvc::AddNode>(id, xvc::face_placement_node(f)));

  // Written in the document where it says nothing yet: each pattern's role
  // and whether it is draped, so that the designer corrects one and runs
  // again (the drape of the document alone leaves out drape="false").
  {
    std::vector<std::unique_ptr<xvc::Command>> set;
    const std::set<std::string> draped(out.pieces.begin(), out.pieces.end());
    for (const auto* p : doc.patterns()) {
      const std::string name(p->attribute("piece")), id(p->id());
      if (!p->has_attribute("role")) {
        const auto it = roles.find(name);
        const pattern::Role r = it != roles.end() ? it->second.role : xvc::piece_role(doc, *p).role;
        set.push_back(std::make_unique<xvc::SetAttribute>(id, "role", std::string(pattern::role_name(r))));
      }
      if (!p->has_attribute("drape"))
        set.push_back(std::make_unique<xvc::SetAttribute>(id, "drape", draped.count(name) ? "true" : "false"));
    }
    if (!set.empty()) {
      xvc::execute(doc, *std::make_unique<xvc::Batch>("roles and pieces to drape", std::move(set)));
      out.decisions.push_back("each pattern's role and whether it is draped written in the document (PATTERN "
                              "attributes role and drape): correct one there and run again");
    }
  }

  // A neckband or a cuff is cut double and folded lengthwise (a crew neck's
  // rib, a rib cuff: both raw edges sewn to the opening together): it drapes
  // as the half beside the opening, in two layers (PATTERN folded="true",
  // written where the document says nothing). One cut shorter than its
  // opening (the first SEAM that sews it to another piece: its hem over the
  // others') is stretched onto it, as a rib knit is: unless the designer
  // chose the fabric (--material) or the piece has its own, it is cut from
  // the shipped rib (a piece MATERIAL).
  const auto band_to_opening = [&](const std::string& band) -> std::optional<double> {
    for (const auto& seam : xvc::list_seams(doc)) {
      const auto* a = seam.hems.empty() ? nullptr : doc.find(seam.hems[0].pattern);
      if (!a || a->attribute("piece") != band) continue;
      double others = 0;
      for (std::size_t k = 1; k < seam.hems.size(); ++k)
        if (const auto* b = doc.find(seam.hems[k].pattern); b && b->attribute("piece") != band) others += seam.hems[k].length;
      if (others > 0) return seam.hems[0].length / others;
    }
    return std::nullopt;
  };
  // A one-piece collar (a polo's: no collar stand is draped) rolls over
  // about half way across: its fall turned down over its stand, folded the
  // same way, so it drapes folded as a neckband does.
  const bool stand = std::any_of(out.pieces.begin(), out.pieces.end(),
                                 [&](const std::string& n) { return roles[n].role == pattern::Role::collar_stand; });
  std::optional<xvc::Node> rib;  // the shipped rib's MATERIAL, read once when a band needs it
  for (const auto& name : out.pieces) {
    const pattern::Role band_role = roles[name].role;
    const bool collar = band_role == pattern::Role::collar && !stand;
    // A binding sewn round the neckline is folded over its raw edge: as a neckband.
    const bool binding = band_role == pattern::Role::binding && band_to_opening(name);
    if (band_role != pattern::Role::neckband && band_role != pattern::Role::cuff && !collar && !binding) continue;
    const std::string role_name(pattern::role_name(band_role));
    const std::string opening = band_role == pattern::Role::cuff ? "the sleeve's hem" : "the neckline";
    std::vector<std::unique_ptr<xvc::Command>> set;
    const xvc::Node* here = nullptr;
    for (const auto* p : doc.patterns()) {
      if (p->attribute("piece") != name) continue;
      if (p->attribute("size") == out.size) here = p;
      if (!p->has_attribute("folded")) set.push_back(std::make_unique<xvc::SetAttribute>(std::string(p->id()), "folded", "true"));
    }
    if (!here) continue;
    const bool said = !set.empty();
    if (said) xvc::execute(doc, *std::make_unique<xvc::Batch>(role_name + " folded", std::move(set)));
    const pattern::Piece piece = xvc::to_piece(doc, std::string(here->id()));
    double w0 = 1e300, w1 = -1e300, h0 = 1e300, h1 = -1e300;
    for (const auto& c : piece.boundary)
      w0 = std::min(w0, c.p.x()), w1 = std::max(w1, c.p.x()), h0 = std::min(h0, c.p.y()), h1 = std::max(h1, c.p.y());
    const double width = std::min(w1 - w0, h1 - h0);
    if (said && xvc::folded_attribute(*doc.find(std::string(here->id()))).value_or(false))
      out.decisions.push_back("piece " + name + " (" + role_name + ") read as " +
                              (collar ? "rolled over at half its width, its fall turned down over its stand"
                                      : "cut double and folded lengthwise") +
                              " (folded=\"true\" written in the document): it drapes as the half beside " + opening +
                              ", " + format_fixed(50 * width, 1) + " of its " + format_fixed(100 * width, 1) +
                              " cm, in two layers");
    if (options.fabric_given || !xvc::piece_material(doc, *here).empty()) continue;
    const auto ratio = band_to_opening(name);
    if (!ratio || *ratio > 0.98) continue;
    if (!rib) {
      const std::filesystem::path rib_file = data_file("materials/cotton-rib.xvc");
      const xvc::Document kdoc = xvc::load_file(rib_file);
      const auto* kmats = kdoc.container("MATERIALS");
      if (!kmats || kmats->children.empty()) throw Error(rib_file.string(), "MATERIALS", "the shipped rib has no MATERIAL");
      rib = xvc::copy_node(kdoc, kmats->children.front().id());
    }
    if (!doc.container("MATERIALS")) {
      xvc::Node container;
      container.tag = "MATERIALS";
      xvc::execute(doc, *std::make_unique<xvc::AddNode>(std::string(doc.root().id()), container));
    }
    std::vector<std::unique_ptr<xvc::Command>> cut;
    for (const auto* p : doc.patterns())
      if (p->attribute("piece") == name && xvc::piece_material(doc, *p).empty())
        cut.push_back(std::make_unique<xvc::SetPieceMaterial>(std::string(p->id()), *rib));
    xvc::execute(doc, *std::make_unique<xvc::Batch>(role_name + " cut from rib", std::move(cut)));
    out.decisions.push_back("piece " + name + " (" + role_name + ") cut from the shipped rib " +
                            std::string(rib->attribute("id")) + " (written in the document): it is " +
                            format_fixed(100 * (1 - *ratio), 0) + " % shorter than " + opening +
                            " it is sewn to and is stretched onto it, as a rib knit is; "
                            "choose another fabric for the piece in the document or with --material");
  }

  // The body: the size table from the style's name, else from its graded
  // sizes (size_table_from_sizes), the garment's size when that table has
  // it. Otherwise the body nearest the pattern: the
  // table (and, for a size no table has, the row) whose bust (tops) or hip
  // (skirts, trousers) leaves the pattern's girth the usual ease.
  if (!options.avatar.empty()) {
    out.body_size = out.size;
    out.decisions.push_back("body: " + options.avatar + " (as asked), not a mannequin");
    return out;
  }
  const std::string style(doc.root().attribute("name"));
  out.body_table = !options.body_table.empty() ? options.body_table : size_table_from_name(style);
  std::string why = !options.body_table.empty() ? "as asked" : "the style's name '" + style + "'";
  std::string table_why;  // the table from the style's sizes: why, kept when the size is then chosen by girth
  bool by_girth = false;  // the body chosen as the one nearest the pattern's girth (which says its ease)
  if (out.body_table.empty()) {
    std::vector<std::string> sizes;
    for (const auto* p : doc.patterns()) {
      const std::string z(p->attribute("size"));
      if (std::find(sizes.begin(), sizes.end(), z) == sizes.end()) sizes.push_back(z);
    }
    out.body_table = size_table_from_sizes(sizes, table_why);
    if (!out.body_table.empty()) why = table_why;
  }
  out.body_size = !options.body_size.empty() ? options.body_size : out.size;
  bool has_size = true;
  try {
    body::find_size(out.size, out.body_table);
  } catch (const Error&) {
    has_size = false;
  }
  bool lower = false;
  for (const auto& [name, g] : roles) lower = lower || g.role == pattern::Role::leg || g.role == pattern::Role::waistband;
  // Of the draped pieces in a size's patterns: the fronts and backs, and the
  // legs (halves or whole).
  const auto trunk_and_legs = [&](const std::vector<const xvc::Node*>& patterns) {
    std::pair<std::vector<const xvc::Node*>, std::vector<const xvc::Node*>> out_parts;
    for (const auto* p : patterns) {
      const std::string name(p->attribute("piece"));
      const pattern::Role r = roles[name].role;
      if (std::find(out.pieces.begin(), out.pieces.end(), name) == out.pieces.end()) continue;
      if (r == pattern::Role::front || r == pattern::Role::back) out_parts.first.push_back(p);
      if (r == pattern::Role::leg) out_parts.second.push_back(p);
    }
    return out_parts;
  };
  // Trousers: their hip is the legs' width 5-20 % of their length below the
  // waist (the seat, above the crotch's extension): halves' front and back,
  // a whole leg's both (leggings cut in one piece per leg).
  const auto girth_of = [&](const auto& parts) {
    return pattern_girth(doc, parts.first) + pattern_girth(doc, parts.second, 0.05, 0.20, true);
  };
  const auto parts = trunk_and_legs(mine);
  const auto& [trunk, legs] = parts;
  const double girth = girth_of(parts);
  if (options.body_size.empty() && (out.body_table.empty() || !has_size)) {
    // Trousers: their inseam (the longest seam named so that sews a leg) is
    // matched to the body's crotch height too, less kInseamEase (the hem clear of
    // the floor): a pattern's girth alone fits a short body with a wide hip as
    // well as a tall one, and trousers too long lie on the feet.
    double inseam = 0;
    if (!legs.empty())
      for (const auto& s : xvc::list_seams(doc)) {
        if (s.name.find("inseam") == std::string::npos || s.hems.empty()) continue;
        if (std::none_of(legs.begin(), legs.end(), [&](const xvc::Node* h) { return h->id() == s.hems[0].pattern; }))
          continue;
        inseam = std::max(inseam, s.hems[0].length);
      }
    const char* where = lower ? "hip" : "bust";
    // A size the style's table lacks (its name's or its graded sizes'): the
    // ease the style is cut with in the nearest size (by girth) that table
    // has, not the usual. Leggings are cut 11-21 cm smaller round the hip
    // than their bodies: with the usual 5 cm, size 52 went on the women's 40
    // and hung loose round its legs.
    double ease = lower ? kHipEase : kBustEase;
    std::string ease_why = format_fixed(100 * ease, 0) + " cm wanted";
    if (!out.body_table.empty() && !has_size && girth > 0) {
      double nearest = 1e300;
      for (const auto& row : body::load_size_table(body::size_table_file(out.body_table))) {
        const double g2 = girth_of(trunk_and_legs(patterns_of(row.label)));
        if (g2 <= 0 || std::abs(g2 - girth) >= nearest) continue;
        nearest = std::abs(g2 - girth);
        ease = g2 - (lower ? row.hip : row.bust);
        ease_why = format_fixed(100 * ease, 0) + " cm wanted: the style's in size " + row.label + ", the table's nearest";
      }
    }
    std::vector<std::string> tables;
    if (!out.body_table.empty()) tables = {out.body_table};
    else tables = body::size_table_names();
    struct Pick {
      std::string table, label;
      double body = 0, inseam = 0, miss = 1e300;
    } best;
    std::string others;
    for (const auto& t : tables) {
      Pick here;
      for (const auto& row : body::load_size_table(body::size_table_file(t))) {
        if (has_size && row.label != out.size) continue;
        const double b = lower ? row.hip : row.bust;
        const double miss = std::abs(girth - b - ease) + (inseam > 0 ? std::abs(inseam - row.inseam + kInseamEase) : 0.0);
        if (miss < here.miss) here = {t, row.label, b, row.inseam, miss};
      }
      if (here.table.empty()) continue;
      if (here.miss < best.miss) {
        if (!best.table.empty())
          others += "; " + best.table + " " + best.label + " leaves " + format_fixed(100 * (girth - best.body), 0) + " cm";
        best = here;
      } else {
        others += "; " + here.table + " " + here.label + " leaves " + format_fixed(100 * (girth - here.body), 0) + " cm";
      }
    }
    if (girth > 0 && !best.table.empty()) {
      out.body_table = best.table;
      out.body_size = best.label;
      by_girth = true;
      why = (table_why.empty() ? "" : table_why + ", which has no size " + out.size + "; ") +
            "nearest the pattern: its " + std::string(where) + " girth is " + format_fixed(100 * girth, 0) +
            " cm, " + format_fixed(100 * (girth - best.body), 0) + " cm of ease over the body's " +
            format_fixed(100 * best.body, 0) + " cm (" + ease_why +
            (inseam > 0 ? ", its inseam " + format_fixed(100 * inseam, 1) + " cm for a crotch height of " +
                              format_fixed(100 * best.inseam, 1) + " cm (" + format_fixed(100 * kInseamEase, 0) +
                              " cm shorter wanted)"
                        : std::string()) +
            others + "); choose with --body-table and --body-size";
    } else if (!has_size) {
      const std::string table = !out.body_table.empty() ? out.body_table : body::size_table_names().front();
      const auto rows = body::load_size_table(body::size_table_file(table));
      if (!rows.empty()) {
        out.body_size = rows[rows.size() / 2].label;
        out.body_table = table;
        why = "no table has the size '" + out.size + "' and the pattern has no front or back to measure: the "
              "middle size, choose with --body-size";
      }
    } else {
      why = "the style's name '" + style + "' says neither men nor women and the pattern has no front or back to "
            "measure; choose with --body-table";
    }
  }
  // The pattern's girth against the body chosen: said with the decision
  // (the girth's choice says it already). A garment smaller round it than
  // the body, with no fabric of the document's or the caller's, is cut for a
  // stretch fabric (below): legs smaller round the hip at all (negative ease:
  // leggings, tights), a top or skirt more than kFitTooSmall smaller round
  // the bust or hip and at least kKnitGirth of the body's (a tank graded with
  // less ease in its larger sizes: Gerber's tank with bindings has 3 cm in
  // size 36, -5 cm in size 50; in a woven its shoulders stood open with the
  // body between them). A top or skirt more than kFitTooSmall smaller that
  // is not so cut is a warning, however the body was chosen (the nearest
  // body may still be too large: a size below a table's smallest): the
  // certificate would fail it after the drape, a woven cannot close round
  // it; below kKnitGirth it is most likely a file's front and back written
  // as halves cut once that vgd did not unfold, which give half the girth.
  double body_girth = 0;
  body::BodyMeasurements chosen;
  if (girth > 0) {
    try {
      chosen = body::find_size(out.body_size, out.body_table);
      body_girth = lower ? chosen.hip : chosen.bust;
    } catch (const Error&) {
    }
  }
  const char* where = lower ? "hip" : "bust";
  const bool small = body_girth > 0 && girth < body_girth - (legs.empty() ? kFitTooSmall : 0.0);
  // (A document whose only MATERIALs are pieces' own has no fabric of its own.)
  const bool knit = small && !options.fabric_given && xvc::garment_material(doc).empty() &&
                    (!legs.empty() || girth >= kKnitGirth * body_girth);
  if (body_girth > 0) {
    if (!by_girth)
      why += "; its " + std::string(where) + " girth is " + format_fixed(100 * girth, 0) + " cm, " +
             format_fixed(100 * (girth - body_girth), 0) + " cm of ease over the body's " +
             format_fixed(100 * body_girth, 0) + " cm";
    if (small && legs.empty() && !knit)
      out.warnings.push_back("the garment is too small for the body: the pattern's " + std::string(where) +
                             " girth is " + format_fixed(100 * girth, 0) + " cm, " +
                             format_fixed(100 * (body_girth - girth), 0) + " cm less than the body's " +
                             format_fixed(100 * body_girth, 0) + " cm (" +
                             (chosen.sex == "male" ? "men's " : "women's ") + chosen.label +
                             "); a woven cannot close round it: choose the body with --body-size, or a knit "
                             "with --material");
  }
  out.decisions.push_back("body: the mannequin of size " + out.body_size + " from " +
                          (out.body_table.empty() ? std::string("the first size table that has it") : out.body_table) +
                          " (" + why + ")");

  // The shipped knit, written in the document (decided above): a woven
  // (vgd's default, shirting) would have to stretch 20-40 % to close round
  // legs cut smaller than the body, pressing on it with kilonewtons and never
  // coming to rest.
  if (knit) {
    const auto* materials = doc.container("MATERIALS");
    const xvc::Document kdoc = xvc::load_file(data_file("materials/cotton-jersey.xvc"));
    const auto* kmats = kdoc.container("MATERIALS");
    if (kmats && !kmats->children.empty()) {
      const xvc::Node material = xvc::copy_node(kdoc, kmats->children.front().id());
      std::string parent;
      if (materials) {
        parent = std::string(materials->id());
      } else {
        xvc::Node container;
        container.tag = "MATERIALS";
        xvc::execute(doc, *std::make_unique<xvc::AddNode>(std::string(doc.root().id()), container));
        parent = std::string(doc.container("MATERIALS")->id());
      }
      xvc::execute(doc, *std::make_unique<xvc::AddNode>(parent, material));
      out.fabric = std::string(material.attribute("id"));
      out.decisions.push_back(
          "fabric: the shipped knit " + out.fabric + " (written in the document): the pattern's " +
          std::string(where) + " girth is " + format_fixed(100 * girth, 0) + " cm, " +
          format_fixed(100 * (body_girth - girth), 0) + " cm less than the body's " +
          format_fixed(100 * body_girth, 0) + " cm: it is cut for a stretch fabric, which a woven is not; "
          "choose another with --material");
    }
  }
  return out;
}

}  // namespace vgd::dress
