#include "vgd/core/units.hpp"

#include "vgd/core/strings.hpp"

namespace vgd {

double metres_per(LengthUnit u) {
  switch (u) {
    case LengthUnit::millimetre: return 0.001;
    case LengthUnit::centimetre: return 0.01;
    case LengthUnit::decimetre: return 0.1;
    case LengthUnit::metre: return 1.0;
    case LengthUnit::inch: return 0.0254;
  }
  return 1.0;
}

const char* to_string(LengthUnit u) {
  switch (u) {
    case LengthUnit::millimetre: return "mm";
    case LengthUnit::centimetre: return "cm";
    case LengthUnit::decimetre: return "dm";
    case LengthUnit::metre: return "m";
    case LengthUnit::inch: return "in";
  }
  return "?";
}

std::optional<LengthUnit> parse_length_unit(std::string_view text) {
  const std::string t = to_lower(trim(text));
  if (t == "mm" || t == "millimetre" || t == "millimetres" || t == "millimeter" ||
      t == "millimeters" || t == "metric")
    return LengthUnit::millimetre;
  if (t == "cm" || t == "centimetre" || t == "centimetres" || t == "centimeter" || t == "centimeters")
    return LengthUnit::centimetre;
  if (t == "dm" || t == "decimetre" || t == "decimetres" || t == "decimeter" || t == "decimeters")
    return LengthUnit::decimetre;
  if (t == "m" || t == "metre" || t == "metres" || t == "meter" || t == "meters")
    return LengthUnit::metre;
  if (t == "in" || t == "inch" || t == "inches" || t == "\"" || t == "english" || t == "imperial")
    return LengthUnit::inch;
  return std::nullopt;
}

}  // namespace vgd
