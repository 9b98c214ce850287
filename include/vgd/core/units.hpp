#pragma once
// Length units met at file boundaries. Inside vgd everything is SI (metres).
#include <optional>
#include <string>
#include <string_view>

namespace vgd {

enum class LengthUnit { millimetre, centimetre, decimetre, metre, inch };

// Metres per one unit: mm 0.001, cm 0.01, dm 0.1, m 1, inch 0.0254 (exact by definition).
double metres_per(LengthUnit u);

// Short name used in files and reports: "mm", "cm", "dm", "m", "in".
const char* to_string(LengthUnit u);

// Parses unit words as CAD files write them, case-insensitively:
// "mm", "millimetre(s)", "millimeter(s)", "METRIC" (AAMA: metric = mm),
// "cm", "centimetre(s)", "m", "metre(s)", "meter(s)",
// "in", "inch", "inches", "\"", "ENGLISH" (AAMA: english = inch).
// Returns nullopt for anything else.
std::optional<LengthUnit> parse_length_unit(std::string_view text);

}  // namespace vgd
