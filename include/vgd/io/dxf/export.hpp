#pragma once
// AAMA DXF export (R12 / AC1009, the dialect every apparel CAD system reads):
// one BLOCK per piece and size with the AAMA layers, an INSERT per block, and
// model-space texts for style name, sample size and units. Import -> export ->
// import keeps pieces, sizes, attributes and geometry (tests/io/dxf).
#include <filesystem>
#include <optional>
#include <string>

#include "vgd/core/units.hpp"
#include "vgd/pattern/piece.hpp"

namespace vgd::dxf {

struct ExportOptions {
  LengthUnit units = LengthUnit::millimetre;  // AAMA: METRIC (mm) or ENGLISH (inch)
  std::optional<std::string> size;            // only this size; all sizes when empty
};

// DXF text of the style.
std::string export_string(const pattern::Style& style, const ExportOptions& opts = {});

// Writes the file atomically (the old file stays intact if anything fails).
void export_file(const pattern::Style& style, const std::filesystem::path& path, const ExportOptions& opts = {});

}  // namespace vgd::dxf
