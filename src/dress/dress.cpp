#include "vgd/dress/dress.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <tuple>

#include "vgd/body/landmarks.hpp"
#include "vgd/body/mannequin.hpp"
#include "vgd/body/sizes.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/dress/arrange.hpp"
#include "vgd/dress/placement.hpp"
#include "vgd/dress/prepare.hpp"
#include "vgd/xvc/arrangement.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/style.hpp"

namespace vgd::dress {

using body::Avatar;
using body::BodySegment;

namespace {

// Where a piece sewn onto `host`'s face starts: each node where the host's
// placed mesh puts the same point of the host's pattern (barycentric in the
// host triangle holding it, or the nearest), GarmentPiece::face_gap out
// along that triangle's outward normal.
std::vector<body::Vec3> on_face(const GarmentPiece& piece, const GarmentPiece& host, const PlacedPiece& placed) {
  const auto& hn = host.mesh.nodes;
  std::vector<body::Vec3> out;
  out.reserve(piece.mesh.nodes.size());
  for (const auto& q : piece.mesh.nodes) {
    const pattern::Vec2 p = piece.on_host(q);
    int best = -1;
    double best_out = std::numeric_limits<double>::infinity();
    Eigen::Vector3d w_best = Eigen::Vector3d::Zero();
    for (std::size_t t = 0; t < host.mesh.triangles.size(); ++t) {
      const auto& tr = host.mesh.triangles[t];
      const pattern::Vec2 a = hn[tr[0]], b = hn[tr[1]], c = hn[tr[2]];
      const double d = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
      if (d == 0.0) continue;
      const double w1 = ((p - a).x() * (c - a).y() - (p - a).y() * (c - a).x()) / d;
      const double w2 = ((b - a).x() * (p - a).y() - (b - a).y() * (p - a).x()) / d;
      const Eigen::Vector3d w(1.0 - w1 - w2, w1, w2);
      const double outside = -std::min(0.0, w.minCoeff());  // 0 inside
      if (outside < best_out) best_out = outside, best = static_cast<int>(t), w_best = w;
      if (outside == 0.0) break;
    }
    if (best < 0) throw Error("", piece.pattern_id, "its host " + host.name + " has no triangle to place it on");
    const auto& tr = host.mesh.triangles[best];
    const body::Vec3 &x0 = placed.positions[tr[0]], &x1 = placed.positions[tr[1]], &x2 = placed.positions[tr[2]];
    const Eigen::Vector3d w = w_best.cwiseMax(0.0) / w_best.cwiseMax(0.0).sum();
    body::Vec3 n = (x1 - x0).cross(x2 - x0);
    n = (placed.flipped ? -1.0 : 1.0) * n / std::max(n.norm(), 1e-30);
    out.push_back(w[0] * x0 + w[1] * x1 + w[2] * x2 + piece.face_gap * n);
  }
  return out;
}

}  // namespace

std::map<std::string, std::vector<xvc::Arrangement>> garment_arrangements(const xvc::Document& doc,
                                                                         const Avatar& avatar) {
  const xvc::ArrangementOptions ao = arrangement_options(avatar);
  std::map<std::string, std::vector<xvc::Arrangement>> out;
  const auto suggested = xvc::suggest_arrangements(doc, ao);
  for (const auto* p : doc.patterns()) {
    const std::string id(p->id());
    auto stored = xvc::arrangements_of(*p);
    if (!stored.empty()) {
      out[id] = std::move(stored);
      continue;
    }
    for (const auto& [pid, list] : suggested)
      if (pid == id && !list.empty()) out[id] = list;
  }
  return out;
}

std::vector<PlacedPiece> place_garment(const xvc::Document& doc, const Garment& garment,
                                       const std::map<std::string, std::vector<xvc::Arrangement>>& arrangements,
                                       const Avatar& avatar, const std::vector<Underlayer>& under, double nest) {
  // Every piece `lift` m higher than its arrangement says: a limb's height
  // runs along its axis (down a hanging leg), the trunk's is a world height;
  // a piece on a limb held level (an arm in a T-pose) keeps its place.
  const auto raised = [&](xvc::Arrangement a, double lift) {
    if (lift == 0.0) return a;
    const body::BodySegment* seg = avatar.segment(a.segment);
    if (!on_limb(a.segment)) a.height += lift;
    else if (seg && seg->axis.normalized().y() < -0.1) a.height -= lift / -seg->axis.normalized().y();
    return a;
  };
  const auto place_all = [&](double lift) {
    std::vector<PlacedPiece> out;
    for (const auto& gp : garment.pieces) {
      if (gp.host >= 0) {  // on its host's face, below
        out.emplace_back();
        continue;
      }
      const auto it = arrangements.find(gp.pattern_id);
      if (it == arrangements.end() || gp.copy >= static_cast<int>(it->second.size()))
        throw Error(doc.name(), gp.pattern_id,
                    "piece " + gp.name + " has no arrangement (where it goes round the body) and none can be "
                                         "suggested from its name: set one with 'vgd place --set " +
                        gp.name + "=torso:front:1.25'");
      const xvc::Arrangement a = raised(it->second[gp.copy], lift);
      PiecePlacement p;
      try {
        p = place_piece(gp.mesh.nodes, a, avatar, under, nest);
      } catch (const Error& e) {
        throw Error(doc.name(), gp.pattern_id, "cannot place " + gp.name + ": " + e.diagnostic().message);
      }
      PlacedPiece pp;
      pp.positions = std::move(p.points);
      pp.flipped = p.reverses_winding;
      pp.segment = a.segment;
      pp.arrangement = a.segment + " " + a.side + " at " + format_fixed(a.height, 3) + " m, " +
                       format_fixed(p.clearance * 1000, 0) + " mm clear" + (a.flip ? ", flipped" : "");
      pp.lifted = lift;
      out.push_back(std::move(pp));
    }
    for (std::size_t i = 0; i < garment.pieces.size(); ++i) {
      const GarmentPiece& gp = garment.pieces[i];
      if (gp.host < 0) continue;
      const PlacedPiece& host = out[gp.host];
      PlacedPiece pp;
      try {
        pp.positions = on_face(gp, garment.pieces[gp.host], host);
      } catch (const Error& e) {
        throw Error(doc.name(), gp.pattern_id, "cannot place " + gp.name + ": " + e.diagnostic().message);
      }
      pp.flipped = host.flipped;
      pp.segment = host.segment;
      pp.arrangement = "on the face of " + garment.pieces[gp.host].name;
      pp.lifted = lift;
      out[i] = std::move(pp);
    }
    return out;
  };
  std::vector<PlacedPiece> out = place_all(0.0);
  if (avatar.surface.vertices.empty()) return out;
  const auto lowest = [](const std::vector<PlacedPiece>& pieces) {
    double y = std::numeric_limits<double>::infinity();
    for (const auto& p : pieces)
      for (const auto& q : p.positions) y = std::min(y, q.y());
    return y;
  };
  double soles = std::numeric_limits<double>::infinity();
  for (const auto& v : avatar.surface.vertices) soles = std::min(soles, v.y());
  if (!(lowest(out) < soles + kAboveSoles - 1e-3)) return out;
  // At most three quarters of the feet's height (the ankles above the
  // soles): raised further, the garment's crotch starts above the body's and
  // does not survive the fall (Valentina's trousers raised 9.1 cm on the men's
  // 50, whose feet are 10.7 cm high: the front rise and inseams held open at
  // the crotch, the body through them; 8.0 cm raised the test trousers clean
  // on the same feet). A garment that needs more is raised that much, and
  // its pieces say what it needed.
  // The ankle as found on the surface (the legs' thinnest slice above the
  // foot, a height above the soles), on a mannequin too: its own ankle
  // landmark is the joint, 3 cm lower. Not found: the legs' last rings.
  double feet = avatar.landmarks ? avatar.landmarks->ankle : body::measure_body(avatar.surface).landmarks.ankle;
  if (!(feet > 0.0))
    for (const auto& seg : avatar.segments)
      if (seg.name.find("leg") != std::string::npos && !seg.rings.empty())
        feet = std::max(feet, seg.rings.back().centre.y() - soles);
  if (!(feet > 0.0)) return out;
  const double most = kMostOfTheFeet * feet;
  // Raised, a piece is wrapped on the body's rings at its new heights (round
  // less of the foot), so its lowest point may move by other than the lift:
  // a few rounds bring it to kAboveSoles.
  double lift = 0.0;
  for (int round = 0; round < 4; ++round) {
    const double short_by = soles + kAboveSoles - lowest(out);
    if (!(short_by > 1e-3)) break;
    if (lift + short_by > most) {
      const double needed = lift + short_by;
      if (lift < most) out = place_all(most);
      for (auto& p : out) p.too_long = needed;
      break;
    }
    lift += short_by;
    out = place_all(lift);
  }
  return out;
}

void check_fit(const std::string& document, const std::string& size, const std::vector<std::string>& segments,
               const Avatar& avatar, Diagnostics& diag, const std::string& table) {
  auto covers = [&](const char* s) { return std::find(segments.begin(), segments.end(), s) != segments.end(); };
  const bool torso = covers("torso"), hips = covers("hips");
  const std::optional<body::BodyMeasurements>& body = avatar.measurements ? avatar.measurements : avatar.measured;
  if (!body || size.empty()) return;
  body::BodyMeasurements made_for;
  try {
    made_for = body::find_size(size, table);
  } catch (const Error&) {
    return;  // a size label no table has: nothing to compare
  }
  const double too_small = kFitTooSmall, too_large = 0.12;  // m of girth
  for (const auto& [name, garment, girth] : {std::tuple{"bust", made_for.bust, body->bust},
                                             {"waist", made_for.waist, body->waist},
                                             {"hip", made_for.hip, body->hip}}) {
    const std::string what = name;
    if (girth <= 0 || !((what == "bust" && torso) || (what == "waist" && (torso || hips)) || (what == "hip" && hips)))
      continue;
    auto cm = [](double v) { return format_fixed(100 * v, 0) + " cm"; };
    const std::string figures = "size " + size + " is cut for a " + name + " of " + cm(garment) + " (" +
                                (made_for.sex == "male" ? "men's " : "women's ") + made_for.label + "); the body's is " + cm(girth);
    if (girth > garment + too_small)
      diag.warn(document, "size " + size, "the garment is too small for the body: " + figures);
    else if (girth < garment - too_large)
      diag.warn(document, "size " + size, "the garment is too large for the body: " + figures);
  }
}

namespace {

// The mesh nodes the PATTERN's pins hold (xvc::Pin): each pin's nearest node,
// which must lie within 2 cm of it (the mesh resamples the outline, so a pin
// on the cut edge is a few millimetres from the nearest node).
std::vector<std::pair<int, std::string>> pinned_nodes(const std::string& file, const xvc::Document& doc,
                                                     const GarmentPiece& gp, Diagnostics& diag) {
  std::vector<std::pair<int, std::string>> out;
  for (const auto& pin : xvc::pins_of(*doc.find(gp.pattern_id))) {
    const pattern::Vec2 q(pin.x, pin.y);
    int best = -1;
    double d = 1e300;
    for (int i = 0; i < static_cast<int>(gp.mesh.nodes.size()); ++i)
      if (const double e = (gp.mesh.nodes[i] - q).norm(); e < d) d = e, best = i;
    if (best < 0 || d > 0.02)
      throw Error(file, pin.id,
                  "the pin at (" + format_fixed(pin.x, 3) + ", " + format_fixed(pin.y, 3) + ") m is " +
                      (best < 0 ? std::string("on a piece with no cloth") : format_fixed(100 * d, 1) + " cm from the cloth of " + gp.name) +
                      ": move it onto the piece or delete it (vgd edit --delete-node " + pin.id + ")");
    out.emplace_back(best, pin.id);
    diag.info(file, pin.id, "pin: " + gp.name + " held at (" + format_fixed(pin.x, 3) + ", " + format_fixed(pin.y, 3) +
                                ") m where its arrangement puts it");
  }
  return out;
}

}  // namespace

scene::MadeCloths dress_garments(const scene::SceneDef& def, const Avatar& avatar) {
  namespace fs = std::filesystem;
  scene::MadeCloths made;
  // Two garments may both have a FRONT_38: with more than one garment the
  // pieces carry their garment's name.
  const int garments = static_cast<int>(std::count_if(def.cloth.begin(), def.cloth.end(),
                                                      [](const scene::ClothDef& x) { return x.garment.has_value(); }));
  std::vector<std::pair<int, std::vector<Underlayer>>> layers;  // each garment's placed cloth, by layer
  for (int ci = 0; ci < static_cast<int>(def.cloth.size()); ++ci) {
    const scene::ClothDef& c = def.cloth[ci];
    if (!c.garment) continue;
    const scene::GarmentDef& gd = *c.garment;
    const std::string path = "cloth[" + std::to_string(ci) + "].garment";
    const fs::path file = scene::resolve_path(def, gd.file);
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
      throw Error(def.source.string(), path + ".file", "cannot read the XVC document " + file.string() + " (no such file)");
    const xvc::Document doc = xvc::load_file(file);
    scene::MadeCloth& out = made[ci];
    const auto arrangements = garment_arrangements(doc, avatar);
    AssemblyOptions ao;
    ao.size = gd.size;
    ao.spacing = gd.spacing;
    ao.pieces = gd.pieces;
    for (const auto& [id, list] : arrangements) {
      ao.copies[id] = static_cast<int>(list.size());
      for (const auto& a : list) ao.flipped[id].push_back(a.flip);
    }
    ao.place = [&](const std::string& pattern_id, int copy, const std::vector<pattern::Vec2>& points) {
      std::vector<body::Vec3> where;
      const auto it = arrangements.find(pattern_id);
      if (it == arrangements.end() || copy >= static_cast<int>(it->second.size())) return where;
      try {
        where = place_piece(points, it->second[copy], avatar).points;
      } catch (const Error&) {
        where.clear();  // a segment the body lacks: the garment's placement says so later
      }
      return where;
    };
    const Garment g = assemble_garment(doc, ao, out.diagnostics);
    std::vector<Underlayer> under;  // the garments of lower layers placed so far
    for (const auto& [layer, cloth] : layers)
      if (layer < gd.layer) under.insert(under.end(), cloth.begin(), cloth.end());
    // Offset contact keeps the start's relations: a back and front wrapped on
    // one curve start a contact radius and a half apart where they overlap.
    const double nest = def.effects.contact ? 1.5 * def.effects.contact->radius : 0.0;
    const std::vector<PlacedPiece> placed = place_garment(doc, g, arrangements, avatar, under, nest);
    if (!placed.empty() && placed.front().lifted > 0.0) {
      const PlacedPiece& p = placed.front();
      out.diagnostics.warn(
          file.string(), "",
          "placed " + format_fixed(100 * p.lifted, 1) +
              " cm higher than arranged: it reaches the body's soles (longer than the body is), where its hems would "
              "be held open round the feet; " +
              (p.too_long > 0.0
                   ? "it needed " + format_fixed(100 * p.too_long, 1) +
                         " cm to start " + format_fixed(100 * kAboveSoles, 0) +
                         " cm above them, more than vgd raises a garment on these feet, and may not close round them: "
                         "choose a taller body (--body-size) or shorten it"
                   : "it starts " + format_fixed(100 * kAboveSoles, 0) + " cm above them and falls to its length"));
    }
    {
      std::vector<std::string> segments;
      for (const auto& p : placed) segments.push_back(p.segment);
      // The garment's size is read in the mannequin's table when the drape names one.
      const std::string table = def.avatar && def.avatar->kind == scene::AvatarDef::Kind::mannequin ? def.avatar->table : "";
      check_fit(file.string(), g.size, segments, avatar, out.diagnostics, table);
    }
    auto& mine = layers.emplace_back(gd.layer, std::vector<Underlayer>{}).second;
    std::vector<int> first(g.pieces.size(), 0);  // each piece's first particle within the cloth
    int count = 0;
    for (std::size_t k = 0; k < g.pieces.size(); ++k) {
      const GarmentPiece& gp = g.pieces[k];
      sim::Model mp;
      const int n = static_cast<int>(gp.mesh.nodes.size());
      mp.x0.resize(3 * n);
      mp.v0 = sim::VecX::Zero(3 * n);
      for (int i = 0; i < n; ++i) sim::at(mp.x0, i) = placed[k].positions[i];
      mp.uv = mesh::material_coordinates(gp.mesh);
      mp.triangles = gp.mesh.triangles;
      if (placed[k].flipped)  // keep triangles counter-clockwise seen from outside the body
        for (auto& t : mp.triangles) std::swap(t[1], t[2]);
      mine.push_back(Underlayer{placed[k].segment, placed[k].positions});
      const std::string name = gp.piece.block.empty() ? gp.name : gp.piece.block;
      out.pieces.push_back({garments > 1 && !c.name.empty() ? c.name + "/" + name : name, std::move(mp), placed[k].segment,
                            xvc::piece_material(doc, *doc.find(gp.pattern_id)), gp.layers, gp.pattern_id, gp.copy,
                            pinned_nodes(file.string(), doc, gp, out.diagnostics), placed[k].lifted, gp.face_layer});
      first[k] = count;
      count += n;
    }
    // Sleeves first (SeamsDef::sleeves_first): a seam joining a piece on an
    // arm to a piece elsewhere (a sleeve's cap to its armhole) waits for the
    // seams that close that arm's pieces on themselves (its underarm seam; a
    // two-piece sleeve's over-arm seam and a cuff's seams too), so the sleeve
    // is a tube round its arm before it is pulled along it (SeamPairs::after).
    // Legs never: the tights' rise left waiting for their inseams let the
    // body through the crotch (129 triangles, 34 mm).
    const bool order = def.effects.seams && def.effects.seams->sleeves_first;
    const int base = static_cast<int>(out.seams.size());
    std::vector<std::set<std::string>> on(g.seams.size());  // each seam's segments
    std::map<std::string, std::vector<int>> closing;        // per arm: the seams whose pieces are all on it
    if (order)
      for (std::size_t s = 0; s < g.seams.size(); ++s) {
        for (const auto& [a, b] : g.seams[s].pairs) on[s].insert(placed[a.piece].segment), on[s].insert(placed[b.piece].segment);
        if (on[s].size() == 1 && on[s].begin()->find("arm") != std::string::npos)
          closing[*on[s].begin()].push_back(base + static_cast<int>(s));
      }
    for (std::size_t s = 0; s < g.seams.size(); ++s) {
      const auto& gs = g.seams[s];
      sim::SeamPairs sp;
      sp.name = gs.name.empty() ? gs.id : gs.name;
      for (const auto& [a, b] : gs.pairs) sp.pairs.push_back({first[a.piece] + a.node, first[b.piece] + b.node});
      if (on[s].size() > 1)
        for (const auto& segment : on[s])
          if (const auto it = closing.find(segment); it != closing.end())
            sp.after.insert(sp.after.end(), it->second.begin(), it->second.end());
      out.seams.push_back(std::move(sp));
    }
  }
  return made;
}

scene::Scene build(const scene::SceneDef& def) {
  scene::validate(def);
  std::optional<Avatar> avatar;
  if (def.avatar) avatar = scene::build_avatar(def);
  scene::MadeCloths made;
  if (avatar) made = dress_garments(def, *avatar);
  return scene::build(def, std::move(avatar), made);
}

}  // namespace vgd::dress
