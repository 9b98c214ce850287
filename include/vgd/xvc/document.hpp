#pragma once
// The XVC document (seed 000 §5.1): the editable garment, held as an element tree.
//
// XVC has three layers: basicData (C2D, C2DSEQ, SCALE2D, ROTATION2D, COLORRGBA, SIZE,
// HEM, PARAMETER, ASSOCIATION, POSITION), modules built from them (PATTERN, SEAM,
// GRADATION, MATERIAL, TEXTURE, ACCESSORY) and containers of modules (PATTERNS, SEAMS,
// ...) under the GARMENT root. docs/xvc.md describes every element and attribute.
//
// The document is kept as a generic tree because the editor works on it as one (add,
// delete, copy, paste of nodes, as in the seed's VIGDES tree view) and because a tree
// saves back byte for byte. Typed views (pattern::Style, pattern::Piece) are derived
// from it in style.hpp. A Document is always valid: every way to make or change one
// runs check() (validate.hpp) and refuses a tree with errors.
//
// Ids: every element except C2D and ANNOTATION carries an `id` unique in the document.
// Ids never change once given; new elements get <prefix><n> with n above every number
// already used with that prefix (see fresh_id).
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace vgd::xvc {

// The XVC format version vgd writes; files with another major version are refused.
inline constexpr std::string_view kFormatVersion = "1.0";

struct Attribute {
  std::string name;
  std::string value;
  bool operator==(const Attribute&) const = default;
};

// One XML element: tag, attributes in file order, child elements. No text content.
struct Node {
  std::string tag;
  std::vector<Attribute> attributes;
  std::vector<Node> children;
  int line = 0;  // 1-based source line when loaded, else 0; not part of the content

  // The attribute's value, or nullptr when absent.
  const std::string* find_attribute(std::string_view name) const;
  // The attribute's value, "" when absent.
  std::string_view attribute(std::string_view name) const;
  bool has_attribute(std::string_view name) const { return find_attribute(name) != nullptr; }
  // Replaces the value in place, or appends the attribute when absent.
  void set_attribute(std::string_view name, std::string value);
  // Removes the attribute; false when it was absent.
  bool remove_attribute(std::string_view name);
  std::string_view id() const { return attribute("id"); }

  // Content equality: tag, attributes (in order) and children; line numbers ignored.
  friend bool operator==(const Node& a, const Node& b);
};

// Child indices from the root to one element; {} is the root itself.
using NodePath = std::vector<std::size_t>;

class Editor;

class Document {
 public:
  // A new, empty garment: GARMENT "garment" (version 1.0) with its six empty containers.
  Document();
  // Adopts a tree. Throws vgd::Error with the first problem check() finds (and how many
  // more there are); `name` is used in messages (the file path for loaded documents).
  explicit Document(Node root, std::string name = "");

  const Node& root() const { return root_; }
  const std::string& name() const { return name_; }

  // The element with this id, or nullptr.
  const Node* find(std::string_view id) const;
  std::optional<NodePath> path_of(std::string_view id) const;
  // The element at `path`; the path must be valid (checked).
  const Node& at(const NodePath& path) const;
  // The GARMENT child with this tag (e.g. "PATTERNS"), or nullptr.
  const Node* container(std::string_view tag) const;
  // PATTERN elements in document order.
  std::vector<const Node*> patterns() const;

  // An id not used in the document: prefix + (largest number used after prefix + 1).
  std::string fresh_id(std::string_view prefix) const;

  // Same content (names and line numbers ignored).
  friend bool operator==(const Document& a, const Document& b) { return a.root_ == b.root_; }

 private:
  friend class Editor;
  friend class Journal;
  Node& mutable_at(const NodePath& path);
  void touch() { index_valid_ = false; }
  void build_index() const;

  Node root_;
  std::string name_;
  mutable std::unordered_map<std::string, NodePath> index_;
  mutable bool index_valid_ = false;
};

// ---- element vocabulary ---------------------------------------------------------

// The id prefix vgd uses for new elements of this tag ("pattern", "seq", ...);
// "" for tags that carry no id (C2D, ANNOTATION) or are unknown.
std::string_view id_prefix(std::string_view tag);
// Attribute names that hold ids of other elements (HEM from/to, SIZE pattern, ...).
bool is_reference_attribute(std::string_view tag, std::string_view attribute);

// ---- parameters -----------------------------------------------------------------

// A parameter vgd itself reads, with its required unit and allowed range.
struct ParameterSpec {
  std::string_view name;     // e.g. "mesh.spacing"
  std::string_view unit;     // the only unit accepted, e.g. "m"
  double min = 0;            // lower bound, exclusive
  double max = 0;            // upper bound, inclusive
  std::string_view meaning;  // one sentence for docs and GUI hints
};

// mesh.spacing (m), mesh.turn_angle (deg), mesh.min_angle (deg), mesh.max_area (m2).
std::span<const ParameterSpec> known_parameters();
const ParameterSpec* find_parameter_spec(std::string_view name);

// Units a PARAMETER may state ("1" means dimensionless). SI only.
std::span<const std::string_view> parameter_units();

// The value of the GARMENT-level PARAMETER with this name, if present.
std::optional<double> get_parameter(const Document& doc, std::string_view name);

// Sets (or adds) the GARMENT-level PARAMETER. `unit` may be empty for known parameters
// (their unit is used). Throws vgd::Error, leaving `doc` unchanged, on a wrong unit, a
// value out of range or a non-finite value. The undoable form is SetParameter (commands.hpp).
void set_parameter(Document& doc, std::string_view name, double value, std::string_view unit = {});

}  // namespace vgd::xvc
