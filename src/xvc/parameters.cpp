// PARAMETERs: the settings later stages read from the document (meshing first).
#include <array>

#include "vgd/core/strings.hpp"
#include "vgd/xvc/commands.hpp"
#include "vgd/xvc/document.hpp"

namespace vgd::xvc {

namespace {
// Ranges are what makes physical sense, not what a mesher might prefer.
constexpr std::array<ParameterSpec, 4> kKnown{{
    {"mesh.spacing", "m", 0.0, 1.0, "target distance between resampled boundary points"},
    {"mesh.turn_angle", "deg", 0.0, 180.0,
     "a boundary vertex turning more than this is kept as a corner when resampling"},
    {"mesh.min_angle", "deg", 0.0, 33.0, "smallest triangle angle the mesher aims for (Delaunay refinement may not end above ~33.8 deg)"},
    {"mesh.max_area", "m2", 0.0, 1.0, "largest triangle area the mesher allows"},
}};

// SI only: files state the unit so a reader never guesses, and vgd never converts.
constexpr std::array<std::string_view, 15> kUnits{
    "1", "m", "m2", "m3", "deg", "kg", "kg/m2", "kg/m3", "s", "1/s", "kg/s", "N", "N/m", "N.m", "Pa"};
}  // namespace

std::span<const ParameterSpec> known_parameters() { return kKnown; }

const ParameterSpec* find_parameter_spec(std::string_view name) {
  for (const auto& s : kKnown)
    if (s.name == name) return &s;
  return nullptr;
}

std::span<const std::string_view> parameter_units() { return kUnits; }

std::optional<double> get_parameter(const Document& doc, std::string_view name) {
  for (const auto& c : doc.root().children)
    if (c.tag == "PARAMETER" && c.attribute("name") == name) return parse_double(c.attribute("value"));
  return std::nullopt;
}

void set_parameter(Document& doc, std::string_view name, double value, std::string_view unit) {
  SetParameter cmd(std::string(name), value, std::string(unit));
  execute(doc, cmd);
}

}  // namespace vgd::xvc
