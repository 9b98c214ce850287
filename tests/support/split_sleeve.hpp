#pragma once
// A garment for tests of sleeves cut in two along the arm (Gerber's TEESL FR
// and TEESL BK): vgd's drafted T-shirt with its sleeve split.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "vgd/pattern/draft.hpp"

namespace vgd::test {

// The drafted T-shirt with its sleeve cut in two along the arm: the left
// sleeve split at x = 0 (its centre line from the hem to the top of the cap)
// into a front half (x <= 0) and a back half (x >= 0), each cut twice; the
// drafted left and right sleeves dropped.
inline pattern::Style tee_with_split_sleeves() {
  pattern::Style s = pattern::draft_tshirt_style({pattern::tshirt_size_table()[2]});
  std::vector<pattern::Piece> kept;
  const pattern::Piece* sleeve = nullptr;
  for (const auto& p : s.pieces) {
    if (p.name == "LEFT SLEEVE") sleeve = &p;
    if (p.name.find("SLEEVE") == std::string::npos) kept.push_back(p);
  }
  if (!sleeve) throw std::runtime_error("the drafted T-shirt has no LEFT SLEEVE");
  const auto& b = sleeve->boundary;
  std::size_t apex = 0;
  for (std::size_t i = 1; i < b.size(); ++i)
    if (b[i].p.y() > b[apex].p.y()) apex = i;
  if (std::abs(b[apex].p.x()) > 1e-9) throw std::runtime_error("the drafted sleeve's cap top is off its centre line");
  pattern::Piece front = *sleeve, back = *sleeve;
  front.notches.clear(), back.notches.clear();
  front.name = "SLEEVE FRONT", back.name = "SLEEVE BACK";
  front.block = "SLEEVE_FRONT_" + s.sample_size, back.block = "SLEEVE_BACK_" + s.sample_size;
  front.quantity = back.quantity = 2;
  front.annotation = back.annotation = "";
  // Back: hem centre -> hem corner -> underarm -> cap up to the top (x >= 0).
  back.boundary = {{pattern::Vec2(0, 0), pattern::PointKind::turn}};
  for (std::size_t i = 1; i < apex; ++i) back.boundary.push_back(b[i]);
  back.boundary.push_back({b[apex].p, pattern::PointKind::turn});
  // Front: the top -> cap down to the underarm -> hem corner -> hem centre (x <= 0).
  front.boundary = {{b[apex].p, pattern::PointKind::turn}};
  for (std::size_t i = apex + 1; i < b.size(); ++i) front.boundary.push_back(b[i]);
  front.boundary.push_back(b[0]);
  front.boundary.push_back({pattern::Vec2(0, 0), pattern::PointKind::turn});
  kept.push_back(front);
  kept.push_back(back);
  s.pieces = kept;
  return s;
}


}  // namespace vgd::test
