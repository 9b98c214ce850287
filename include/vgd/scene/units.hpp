#pragma once
// Quantities with units, as scene files and XVC MATERIAL parameters write them.
// Inside vgd everything is SI (m, kg, s, N); a file may say "4 ms", "2.5 cm",
// "0.2 N.s/m" or "180 g/m2", and the reader converts at the boundary.
//
// A unit is a product of symbols with integer powers: "N/m", "kg.m/s2",
// "N·s/m", "m^2", "1/s". Every symbol after the first '/' is in the
// denominator. Symbols: m cm mm km, g kg mg, s ms min h, N kN mN, Pa kPa MPa
// GPa, J, W, Hz, deg rad (angles are dimensionless, deg converts to rad), "%"
// (0.01) and "1".
#include <optional>
#include <string>
#include <string_view>

namespace vgd::scene {

// Powers of the base units: kg^mass · m^length · s^time.
struct Dimension {
  int mass = 0, length = 0, time = 0;
  bool operator==(const Dimension&) const = default;
};

namespace dim {
inline constexpr Dimension none{0, 0, 0};
inline constexpr Dimension length{0, 1, 0};           // m
inline constexpr Dimension area{0, 2, 0};             // m²
inline constexpr Dimension time{0, 0, 1};             // s
inline constexpr Dimension rate{0, 0, -1};            // 1/s (and Hz)
inline constexpr Dimension mass{1, 0, 0};             // kg
inline constexpr Dimension areal_density{1, -2, 0};   // kg/m²
inline constexpr Dimension density{1, -3, 0};         // kg/m³
inline constexpr Dimension velocity{0, 1, -1};        // m/s
inline constexpr Dimension acceleration{0, 1, -2};    // m/s²
inline constexpr Dimension force{1, 1, -2};           // N
inline constexpr Dimension stiffness{1, 0, -2};       // N/m (spring constants, membrane moduli)
inline constexpr Dimension damping{1, 0, -1};         // N·s/m = kg/s
inline constexpr Dimension pressure{1, -1, -2};       // Pa = N/m²
inline constexpr Dimension moment{1, 2, -2};          // N·m (bending stiffness)
inline constexpr Dimension energy{1, 2, -2};          // J (= N·m: same dimension as a moment)
inline constexpr Dimension drag{1, -3, 0};            // N·s/m³ (wind coefficient) = kg/m³
}  // namespace dim

// A value converted to SI and the dimension its unit had.
struct Quantity {
  double value = 0.0;  // SI
  Dimension dimension;
};

// The unit's factor to SI and dimension, e.g. "ms" -> {0.001, time}; nullopt
// when the text is not a unit this reader knows.
std::optional<Quantity> parse_unit(std::string_view unit);

// "4 ms", "4ms", "-9.81 m/s2", "0.2" (dimensionless); nullopt when the text is
// not a finite number followed by a known unit.
std::optional<Quantity> parse_quantity(std::string_view text);

// The SI name of a dimension: "m", "N/m", "kg/m2", "N.s/m", "1" ...
std::string si_name(const Dimension& d);

}  // namespace vgd::scene
