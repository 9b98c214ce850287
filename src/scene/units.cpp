// Units of scene files: symbols, products, powers, conversion to SI.
#include "vgd/scene/units.hpp"

#include <array>
#include <cctype>
#include <cmath>

#include "vgd/core/strings.hpp"

namespace vgd::scene {

namespace {

struct Symbol {
  std::string_view name;
  double factor;
  Dimension dimension;
};

// Longest names first where one is a prefix of another is not needed: symbols
// are matched whole (a token is a symbol plus an optional power).
constexpr std::array<Symbol, 26> kSymbols{{
    {"m", 1.0, dim::length},       {"cm", 0.01, dim::length},   {"mm", 0.001, dim::length},
    {"km", 1000.0, dim::length},   {"kg", 1.0, dim::mass},      {"g", 0.001, dim::mass},
    {"mg", 1e-6, dim::mass},       {"s", 1.0, dim::time},       {"ms", 0.001, dim::time},
    {"min", 60.0, dim::time},      {"h", 3600.0, dim::time},    {"N", 1.0, dim::force},
    {"kN", 1000.0, dim::force},    {"mN", 0.001, dim::force},   {"Pa", 1.0, dim::pressure},
    {"kPa", 1e3, dim::pressure},   {"MPa", 1e6, dim::pressure}, {"GPa", 1e9, dim::pressure},
    {"J", 1.0, dim::moment},       {"W", 1.0, {1, 2, -3}},      {"Hz", 1.0, dim::rate},
    {"rad", 1.0, dim::none},       {"deg", M_PI / 180.0, dim::none},
    {"%", 0.01, dim::none},        {"1", 1.0, dim::none},       {"cN", 0.01, dim::force},
}};

Dimension scaled(const Dimension& d, int p) { return {d.mass * p, d.length * p, d.time * p}; }
Dimension plus(const Dimension& a, const Dimension& b) {
  return {a.mass + b.mass, a.length + b.length, a.time + b.time};
}

// One factor: a symbol and an optional integer power ("m2", "m^2", "s-1").
std::optional<Quantity> parse_factor(std::string_view tok) {
  std::size_t end = tok.size();
  while (end > 0 && (std::isdigit(static_cast<unsigned char>(tok[end - 1])) || tok[end - 1] == '-')) --end;
  std::string_view sym = tok.substr(0, end), pow_text = tok.substr(end);
  if (!sym.empty() && sym.back() == '^') sym.remove_suffix(1);
  if (sym.empty()) {  // a bare number: only "1" is allowed ("1/s")
    if (tok == "1") return Quantity{1.0, dim::none};
    return std::nullopt;
  }
  int power = 1;
  if (!pow_text.empty()) {
    const auto p = parse_int(pow_text);
    if (!p || *p == 0 || std::abs(*p) > 6) return std::nullopt;
    power = static_cast<int>(*p);
  }
  for (const auto& s : kSymbols)
    if (s.name == sym) return Quantity{std::pow(s.factor, power), scaled(s.dimension, power)};
  return std::nullopt;
}

}  // namespace

std::optional<Quantity> parse_unit(std::string_view unit) {
  unit = trim(unit);
  if (unit.empty()) return Quantity{1.0, dim::none};
  Quantity q{1.0, dim::none};
  bool denominator = false;
  std::string tok;
  auto flush = [&]() -> bool {
    if (tok.empty()) return true;
    const auto f = parse_factor(tok);
    tok.clear();
    if (!f) return false;
    q.value = denominator ? q.value / f->value : q.value * f->value;
    q.dimension = plus(q.dimension, denominator ? scaled(f->dimension, -1) : f->dimension);
    return true;
  };
  for (std::size_t i = 0; i < unit.size(); ++i) {
    const char c = unit[i];
    // "·" (U+00B7, UTF-8 C2 B7) and "*" and "." and spaces separate factors.
    if (c == '.' || c == '*' || c == ' ') {
      if (!flush()) return std::nullopt;
    } else if (c == '/') {
      if (!flush() || denominator) return std::nullopt;  // one '/' at most
      denominator = true;
    } else if (static_cast<unsigned char>(c) == 0xC2 && i + 1 < unit.size() &&
               static_cast<unsigned char>(unit[i + 1]) == 0xB7) {
      if (!flush()) return std::nullopt;
      ++i;
    } else if (static_cast<unsigned char>(c) == 0xC2 && i + 1 < unit.size() &&
               (static_cast<unsigned char>(unit[i + 1]) == 0xB2 || static_cast<unsigned char>(unit[i + 1]) == 0xB3)) {
      tok += static_cast<unsigned char>(unit[i + 1]) == 0xB2 ? '2' : '3';  // "m²", "m³"
      ++i;
    } else {
      tok += c;
    }
  }
  if (!flush()) return std::nullopt;
  return q;
}

std::optional<Quantity> parse_quantity(std::string_view text) {
  text = trim(text);
  // The number is the longest prefix that parses; the rest is the unit.
  std::size_t n = 0;
  while (n < text.size() && (std::isdigit(static_cast<unsigned char>(text[n])) || text[n] == '.' || text[n] == '-' ||
                             text[n] == '+' ||
                             ((text[n] == 'e' || text[n] == 'E') && n > 0 && n + 1 < text.size() &&
                              (std::isdigit(static_cast<unsigned char>(text[n + 1])) || text[n + 1] == '-' ||
                               text[n + 1] == '+'))))
    ++n;
  const auto number = parse_double(text.substr(0, n));
  if (!number) return std::nullopt;
  auto unit = parse_unit(text.substr(n));
  if (!unit) return std::nullopt;
  unit->value *= *number;
  if (!std::isfinite(unit->value)) return std::nullopt;
  return unit;
}

std::string si_name(const Dimension& d) {
  if (d == dim::none) return "1";
  if (d == dim::force) return "N";
  if (d == dim::stiffness) return "N/m";
  if (d == dim::damping) return "N.s/m";
  if (d == dim::pressure) return "Pa";
  if (d == dim::moment) return "N.m";
  if (d == dim::drag) return "N.s/m3";
  std::string num, den;
  auto add = [](std::string& s, const char* sym, int p) {
    if (p == 0) return;
    if (!s.empty()) s += '.';
    s += sym;
    if (std::abs(p) != 1) s += std::to_string(std::abs(p));
  };
  (d.mass > 0 ? add(num, "kg", d.mass) : add(den, "kg", d.mass));
  (d.length > 0 ? add(num, "m", d.length) : add(den, "m", d.length));
  (d.time > 0 ? add(num, "s", d.time) : add(den, "s", d.time));
  if (num.empty()) num = "1";
  return den.empty() ? num : num + "/" + den;
}

}  // namespace vgd::scene
