#pragma once
// The XVC vocabulary as data: which elements exist, their attributes with value types,
// and which children they hold in which order. check() enforces it, the commands use
// it to place new elements, and schemas/xvc.xsd says the same for other XML tools
// (tests keep the two in agreement).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vgd::xvc::detail {

enum class ValueType {
  id,             // [A-Za-z_][A-Za-z0-9_.-]*, unique in the document
  ref,            // an id of another element
  text,           // any text XML can hold
  version,        // digits '.' digits
  name,           // [A-Za-z_][A-Za-z0-9_.-]* (parameter names, hem types)
  finite,         // a finite number
  nonnegative,    // a finite number >= 0
  positive,       // a finite number > 0
  unit_interval,  // a number in [0, 1]
  count,          // a whole number in [0, 2^31 - 1]
  boolean,        // true, false, 1, 0
  choice,         // one of AttributeRule::choices
  unit,           // one of parameter_units()
};

struct AttributeRule {
  std::string_view name;
  ValueType type = ValueType::text;
  bool required = false;
  std::vector<std::string_view> choices = {};
};

struct ChildRule {
  std::string_view tag;
  int min = 0;
  int max = -1;  // -1: unbounded
};

struct ElementRule {
  std::string_view tag;
  std::string_view id_prefix;  // "" when the element carries no id
  std::vector<AttributeRule> attributes;
  std::vector<ChildRule> children;  // in the order they must appear

  const AttributeRule* attribute(std::string_view name) const;
  // Index of `child` in `children`, or -1 when this element cannot hold it.
  int child_rank(std::string_view child) const;
};

// The rule for a tag, or nullptr for an unknown tag.
const ElementRule* find_rule(std::string_view tag);

// Value checks shared by check() and the commands. Each returns "" when the value is
// fine, else the problem as a phrase ("is not a number", ...).
std::string value_problem(const AttributeRule& rule, std::string_view value);
// "" when the text is valid UTF-8 made only of characters XML 1.0 can hold.
std::string text_problem(std::string_view text);
bool is_id_text(std::string_view s);
std::optional<bool> parse_bool(std::string_view s);

// Parent path of a path; the path must not be the root.
template <class Path>
Path parent_of(Path p) {
  p.pop_back();
  return p;
}

}  // namespace vgd::xvc::detail
