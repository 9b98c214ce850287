#include "rules.hpp"

#include <algorithm>
#include <climits>
#include <cmath>

#include "vgd/core/strings.hpp"
#include "vgd/pattern/roles.hpp"
#include "vgd/xvc/document.hpp"

namespace vgd::xvc::detail {

namespace {
using VT = ValueType;

// Attribute rules repeated by many elements.
const AttributeRule kId{"id", VT::id, true};

std::vector<ElementRule> make_rules() {
  const std::vector<std::string_view> roles = {"boundary", "internal", "cutout", "sew",
                                               "grain",    "mirror",   "grade"};
  std::vector<std::string_view> piece_roles;  // pattern/roles.hpp
  for (const pattern::Role r : pattern::all_roles()) piece_roles.push_back(pattern::role_name(r));
  return {
      // ---- GARMENT and its containers ----
      {"GARMENT", "garment",
       {kId, {"version", VT::version, true}, {"name"}, {"producer"}, {"flavour"}, {"units"}},
       {{"PARAMETER"}, {"PATTERNS", 0, 1}, {"SEAMS", 0, 1}, {"GRADATIONS", 0, 1}, {"MATERIALS", 0, 1},
        {"TEXTURES", 0, 1}, {"ACCESSORIES", 0, 1}}},
      {"PATTERNS", "patterns", {kId}, {{"PATTERN"}}},
      {"SEAMS", "seams", {kId}, {{"SEAM"}}},
      {"GRADATIONS", "gradations", {kId, {"sample_size"}}, {{"SIZE"}, {"GRADATION"}}},
      {"MATERIALS", "materials", {kId}, {{"MATERIAL"}}},
      {"TEXTURES", "textures", {kId}, {{"TEXTURE"}}},
      {"ACCESSORIES", "accessories", {kId}, {{"ACCESSORY"}}},
      // ---- modules ----
      {"PATTERN", "pattern",
       {kId, {"block"}, {"piece"}, {"size"}, {"quantity", VT::count}, {"flipped", VT::count}, {"category"},
        {"fabric"}, {"annotation"}, {"closed", VT::boolean}, {"self_intersecting", VT::boolean},
        {"role", VT::choice, false, piece_roles}, {"drape", VT::boolean}, {"folded", VT::boolean}},
       {{"ANNOTATION"}, {"C2DSEQ"}, {"POSITION"}, {"ASSOCIATION"}}},
      {"SEAM", "seam", {kId, {"name"}, {"type", VT::name}}, {{"HEM", 2, -1}, {"ASSOCIATION"}}},
      {"GRADATION", "grad", {kId, {"piece", VT::text, true}}, {{"SIZE"}}},
      {"MATERIAL", "material", {kId, {"name"}, {"scope", VT::choice, false, {"garment", "piece"}}},
       {{"PARAMETER"}, {"COLORRGBA", 0, 1}}},
      {"TEXTURE", "texture", {kId, {"name"}, {"file", VT::text, true}}, {{"SCALE2D", 0, 1}, {"ROTATION2D", 0, 1}}},
      {"ACCESSORY", "accessory", {kId, {"name"}, {"type"}},
       {{"COLORRGBA", 0, 1}, {"POSITION"}, {"ASSOCIATION"}}},
      // ---- basicData ----
      {"C2DSEQ", "seq", {kId, {"role", VT::choice, false, roles}, {"closed", VT::boolean}}, {{"C2D"}}},
      {"C2D", "",
       {{"x", VT::finite, true}, {"y", VT::finite, true}, {"kind", VT::choice, false, {"plain", "turn", "curve"}}},
       {}},
      {"POSITION", "pos",
       {kId,
        {"type", VT::choice, true, {"notch", "drill", "placement", "arrangement", "sheet", "pin"}},
        {"x", VT::finite, true},
        {"y", VT::finite, true},
        {"angle", VT::finite},
        {"length", VT::nonnegative},
        {"width", VT::nonnegative},
        {"notch_type", VT::count},
        {"vertex", VT::count},
        {"pattern", VT::ref},
        // arrangement only (arrangement.hpp)
        {"segment", VT::choice, false, {"neck", "torso", "hips", "left-arm", "right-arm", "left-leg", "right-leg"}},
        {"side", VT::choice, false, {"front", "back", "left", "right"}},
        {"height", VT::finite},
        {"clearance", VT::nonnegative},
        {"flip", VT::boolean},
        {"around", VT::finite}},
       {}},
      {"ANNOTATION", "", {{"key"}, {"text", VT::text, true}}, {}},
      {"HEM", "hem",
       {kId,
        {"from", VT::ref, true},
        {"to", VT::ref, true},
        {"direction", VT::choice, false, {"forward", "reverse"}},
        {"type", VT::name}},
       {}},
      {"SIZE", "size", {kId, {"name", VT::text, true}, {"pattern", VT::ref}, {"sample", VT::boolean}}, {}},
      {"PARAMETER", "param",
       {kId, {"name", VT::name, true}, {"value", VT::finite, true}, {"unit", VT::unit, true}},
       {}},
      {"ASSOCIATION", "assoc",
       {kId, {"ref", VT::ref, true}, {"role", VT::choice, true, {"material", "texture", "accessory", "pattern"}}},
       {}},
      {"COLORRGBA", "color",
       {kId,
        {"r", VT::unit_interval, true},
        {"g", VT::unit_interval, true},
        {"b", VT::unit_interval, true},
        {"a", VT::unit_interval}},
       {}},
      {"SCALE2D", "scale", {kId, {"x", VT::positive, true}, {"y", VT::positive, true}}, {}},
      {"ROTATION2D", "rot", {kId, {"angle", VT::finite, true}}, {}},
  };
}

const std::vector<ElementRule>& rules() {
  static const std::vector<ElementRule> r = make_rules();
  return r;
}

bool is_name_start(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_'; }
bool is_name_char(char c) { return is_name_start(c) || (c >= '0' && c <= '9') || c == '.' || c == '-'; }
}  // namespace

const AttributeRule* ElementRule::attribute(std::string_view n) const {
  for (const auto& a : attributes)
    if (a.name == n) return &a;
  return nullptr;
}

int ElementRule::child_rank(std::string_view child) const {
  for (std::size_t i = 0; i < children.size(); ++i)
    if (children[i].tag == child) return static_cast<int>(i);
  return -1;
}

const ElementRule* find_rule(std::string_view tag) {
  for (const auto& r : rules())
    if (r.tag == tag) return &r;
  return nullptr;
}

bool is_id_text(std::string_view s) {
  return !s.empty() && is_name_start(s.front()) && std::all_of(s.begin(), s.end(), is_name_char);
}

std::optional<bool> parse_bool(std::string_view s) {
  s = trim(s);
  if (s == "true" || s == "1") return true;
  if (s == "false" || s == "0") return false;
  return std::nullopt;
}

std::string text_problem(std::string_view text) {
  // Decode UTF-8 by hand: overlong forms, surrogates and characters outside XML 1.0's
  // Char production (most C0 controls, U+FFFE/U+FFFF) cannot be written to a file.
  std::size_t i = 0;
  while (i < text.size()) {
    const auto b0 = static_cast<unsigned char>(text[i]);
    char32_t cp = 0;
    std::size_t len = 0;
    if (b0 < 0x80) {
      cp = b0, len = 1;
    } else if ((b0 & 0xE0) == 0xC0) {
      cp = b0 & 0x1F, len = 2;
    } else if ((b0 & 0xF0) == 0xE0) {
      cp = b0 & 0x0F, len = 3;
    } else if ((b0 & 0xF8) == 0xF0) {
      cp = b0 & 0x07, len = 4;
    } else {
      return "is not valid UTF-8";
    }
    if (i + len > text.size()) return "is not valid UTF-8";
    for (std::size_t k = 1; k < len; ++k) {
      const auto b = static_cast<unsigned char>(text[i + k]);
      if ((b & 0xC0) != 0x80) return "is not valid UTF-8";
      cp = (cp << 6) | (b & 0x3F);
    }
    const bool overlong = (len == 2 && cp < 0x80) || (len == 3 && cp < 0x800) || (len == 4 && cp < 0x10000);
    if (overlong || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return "is not valid UTF-8";
    const bool xml_char = cp == 0x9 || cp == 0xA || cp == 0xD || (cp >= 0x20 && cp <= 0xD7FF) ||
                          (cp >= 0xE000 && cp <= 0xFFFD) || cp >= 0x10000;
    if (!xml_char) return "holds a control character XML cannot store (code " + std::to_string(cp) + ")";
    i += len;
  }
  return "";
}

std::string value_problem(const AttributeRule& rule, std::string_view value) {
  auto number = [&]() { return parse_double(value); };
  switch (rule.type) {
    case VT::id:
    case VT::ref:
      if (!is_id_text(value)) return "is not an id (a letter or '_' first, then letters, digits, '_', '.', '-')";
      return "";
    case VT::name:
      if (!is_id_text(value)) return "is not a name (a letter or '_' first, then letters, digits, '_', '.', '-')";
      return "";
    case VT::text:
      return "";
    case VT::version: {
      const auto dot = value.find('.');
      const auto digits = [](std::string_view s) {
        return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
      };
      if (dot == std::string_view::npos || !digits(value.substr(0, dot)) || !digits(value.substr(dot + 1)))
        return "is not a version number like 1.0";
      return "";
    }
    case VT::finite:
      return number() ? "" : "is not a finite number";
    case VT::nonnegative: {
      const auto v = number();
      if (!v) return "is not a finite number";
      return *v < 0 ? "is negative; it must be 0 or more" : "";
    }
    case VT::positive: {
      const auto v = number();
      if (!v) return "is not a finite number";
      return *v <= 0 ? "must be greater than 0" : "";
    }
    case VT::unit_interval: {
      const auto v = number();
      if (!v) return "is not a finite number";
      return (*v < 0 || *v > 1) ? "must lie between 0 and 1" : "";
    }
    case VT::count: {
      const auto v = parse_int(value);
      if (!v) return "is not a whole number";
      if (*v < 0) return "is negative; it must be 0 or more";
      return *v > INT_MAX ? "is too large" : "";
    }
    case VT::boolean:
      return parse_bool(value) ? "" : "must be true or false";
    case VT::choice: {
      if (std::find(rule.choices.begin(), rule.choices.end(), value) != rule.choices.end()) return "";
      std::string list;
      for (auto c : rule.choices) list += (list.empty() ? "" : ", ") + std::string(c);
      return "must be one of " + list;
    }
    case VT::unit: {
      const auto units = parameter_units();
      if (std::find(units.begin(), units.end(), value) != units.end()) return "";
      std::string list;
      for (auto u : units) list += (list.empty() ? "" : ", ") + std::string(u);
      return "is not a unit vgd knows (SI only: " + list + ")";
    }
  }
  return "";
}

}  // namespace vgd::xvc::detail

namespace vgd::xvc {

std::string_view id_prefix(std::string_view tag) {
  const auto* r = detail::find_rule(tag);
  return r ? r->id_prefix : std::string_view{};
}

bool is_reference_attribute(std::string_view tag, std::string_view attribute) {
  const auto* r = detail::find_rule(tag);
  const auto* a = r ? r->attribute(attribute) : nullptr;
  return a && a->type == detail::ValueType::ref;
}

}  // namespace vgd::xvc
