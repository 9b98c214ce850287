#pragma once
// A shared DXF garment as `vgd dress` reads it (half pieces unfolded), as an
// XVC document, and the seam options for its sample size.
#include <string>

#include "support/test_paths.hpp"
#include "vgd/io/dxf/import.hpp"
#include "vgd/pattern/halves.hpp"
#include "vgd/xvc/seams.hpp"
#include "vgd/xvc/style.hpp"

namespace vgd::test {

struct SharedStyle {
  xvc::Document doc;
  xvc::SeamOptions sample;  // size: the file's sample size
};

inline SharedStyle shared_style(const std::string& file) {
  dxf::ImportOptions unfold;
  unfold.unfold_mirrored = true;
  const auto imported = dxf::import_file(shared_dxf(file), unfold);
  SharedStyle s{xvc::from_style(imported.style), {}};
  s.sample.size = imported.style.sample_size;
  return s;
}

// The same with a top drawn in halves unfolded as `vgd dress` unfolds it
// (pattern::unfold_top_halves: Valentina's shirt).
inline SharedStyle shared_style_halves_unfolded(const std::string& file) {
  dxf::ImportOptions unfold;
  unfold.unfold_mirrored = true;
  auto style = dxf::import_file(shared_dxf(file), unfold).style;
  pattern::unfold_top_halves(style);
  SharedStyle s{xvc::from_style(style), {}};
  s.sample.size = style.sample_size;
  return s;
}

}  // namespace vgd::test
