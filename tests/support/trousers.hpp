#pragma once
// Trousers cut as half legs for tests (Valentina writes its trousers so): a
// front and a back half of the right leg's front and the left leg's back as
// drawn, each cut once, with a waist dart drawn open, a crotch extension (5 cm
// on the front, 7 cm on the back) and a back that rises 4 cm higher at centre
// back. Cropped: 62 cm inseam, the hem 2 cm narrower on each side than the
// leg's line. Metres, drawn upright (the warp along +y).
#include <map>
#include <string>
#include <vector>

#include "vgd/pattern/piece.hpp"

namespace vgd::test {

struct TrouserHalf {
  std::vector<pattern::Vec2> corners_before_rise;  // hem left, hem right, crotch point
  std::vector<pattern::Vec2> rise;                 // plain points of the crotch curve
  std::vector<pattern::Vec2> corners_after_rise;   // centre line at the waist, dart mouth, tip, mouth, waist side
  pattern::Vec2 hip;                               // plain point of the outseam
};

inline pattern::Piece trouser_half(const std::string& name, const TrouserHalf& h, int quantity) {
  pattern::Piece p;
  p.name = name;
  p.block = name + "_M";
  p.size = "M";
  p.quantity = quantity;
  p.category = "SELF";
  const auto turn = [&](const pattern::Vec2& v) { p.boundary.push_back({v, pattern::PointKind::turn}); };
  const auto plain = [&](const pattern::Vec2& v) { p.boundary.push_back({v, pattern::PointKind::plain}); };
  for (const auto& v : h.corners_before_rise) turn(v);
  for (const auto& v : h.rise) plain(v);
  for (const auto& v : h.corners_after_rise) turn(v);
  plain(h.hip);
  p.grain_line = pattern::Segment{pattern::Vec2(0.10, 0.10), pattern::Vec2(0.10, 0.60)};
  return p;
}

// Names say FRONT and BACK only (as Valentina's do) unless `named` gives the
// trouser word; `quantity` 1 as Valentina writes it.
inline pattern::Style trousers_in_halves(const std::string& front_name = "FRONT", const std::string& back_name = "BACK",
                                         int quantity = 1) {
  using V = pattern::Vec2;
  pattern::Style s;
  s.name = "TEST TROUSERS";
  s.producer = "vgd tests";
  s.flavour = "ASTM";
  s.units = "mm";
  s.sample_size = "M";
  s.sizes = {"M"};
  // Front: crotch point 5 cm beyond the leg's line, centre front at 89 cm (a 27 cm rise).
  s.pieces.push_back(trouser_half(
      front_name,
      {{V(0.02, 0), V(0.19, 0), V(0.25, 0.62)},
       {V(0.225, 0.635), V(0.208, 0.67), V(0.201, 0.72)},
       {V(0.20, 0.89), V(0.11, 0.89), V(0.10, 0.81), V(0.09, 0.89), V(-0.04, 0.89)},
       V(-0.05, 0.70)},
      quantity));
  // Back: the same inseam and outseam, crotch point 7 cm out, centre back 4 cm higher.
  s.pieces.push_back(trouser_half(
      back_name,
      {{V(0.02, 0), V(0.21, 0), V(0.27, 0.62)},
       {V(0.245, 0.63), V(0.225, 0.66), V(0.212, 0.71)},
       {V(0.20, 0.93), V(0.12, 0.92), V(0.11, 0.84), V(0.10, 0.92), V(-0.04, 0.89)},
       V(-0.05, 0.70)},
      quantity));
  return s;
}

// The seams vgd suggests for these trousers cut twice: name -> how many (a
// waist dart per half, on each leg).
inline std::map<std::string, int> trousers_seams() {
  return {{"back rise", 1},   {"front rise", 1},  {"left dart", 2},  {"left inseam", 1},
          {"left outseam", 1}, {"right dart", 2}, {"right inseam", 1}, {"right outseam", 1}};
}

}  // namespace vgd::test
