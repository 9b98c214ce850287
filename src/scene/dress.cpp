#include "vgd/scene/dress.hpp"

#include <cmath>

#include "vgd/core/strings.hpp"
#include "vgd/scene/mannequin.hpp"
#include "vgd/scene/placement.hpp"

namespace vgd::scene {

std::map<std::string, std::vector<xvc::Arrangement>> garment_arrangements(const xvc::Document& doc,
                                                                         const Avatar& avatar, Diagnostics& diag) {
  // Heights for the suggestions: the mannequin's landmarks, else the torso's top
  // (neck) and a waist at the usual 62 % of the height.
  xvc::ArrangementOptions ao;
  if (avatar.measurements) {
    const MannequinLandmarks l = mannequin_landmarks(*avatar.measurements);
    ao.neck_point_height = l.neck_base;
    ao.waist_height = l.waist;
  } else if (const BodySegment* torso = avatar.segment("torso")) {
    ao.neck_point_height = (torso->start + torso->length * torso->axis).y();
    ao.waist_height = 0.62 * (ao.neck_point_height / 0.845);
  }
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
    if (!out.count(id))
      diag.warn(doc.name(), id, "piece " + std::string(p->attribute("piece")) +
                                    " has no arrangement and vgd cannot suggest one from its name; "
                                    "give it one with vgd place");
  }
  return out;
}

std::vector<PlacedPiece> place_garment(const xvc::Document& doc, const Garment& garment,
                                       const std::map<std::string, std::vector<xvc::Arrangement>>& arrangements,
                                       const Avatar& avatar, const std::vector<Underlayer>& under) {
  std::vector<PlacedPiece> out;
  for (const auto& gp : garment.pieces) {
    const auto it = arrangements.find(gp.pattern_id);
    if (it == arrangements.end() || gp.copy >= static_cast<int>(it->second.size()))
      throw Error(doc.name(), gp.pattern_id,
                  "piece " + gp.name + " has no arrangement (where it goes round the body) and none can be "
                                       "suggested from its name: set one with 'vgd place --set " +
                      gp.name + "=torso:front:1.25'");
    const xvc::Arrangement& a = it->second[gp.copy];
    PiecePlacement p;
    try {
      p = place_piece(gp.mesh.nodes, a, avatar, under);
    } catch (const Error& e) {
      throw Error(doc.name(), gp.pattern_id, "cannot place " + gp.name + ": " + e.diagnostic().message);
    }
    PlacedPiece pp;
    pp.positions = std::move(p.points);
    pp.flipped = p.reverses_winding;
    pp.segment = a.segment;
    pp.arrangement = a.segment + " " + a.side + " at " + format_fixed(a.height, 3) + " m, " +
                     format_fixed(p.clearance * 1000, 0) + " mm clear" + (a.flip ? ", flipped" : "");
    out.push_back(std::move(pp));
  }
  return out;
}

}  // namespace vgd::scene
