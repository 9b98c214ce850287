#include "vgd/xvc/document.hpp"

#include <algorithm>
#include <charconv>

#include "vgd/core/diagnostics.hpp"
#include "vgd/xvc/validate.hpp"

namespace vgd::xvc {

// ---- Node -------------------------------------------------------------------------

const std::string* Node::find_attribute(std::string_view n) const {
  for (const auto& a : attributes)
    if (a.name == n) return &a.value;
  return nullptr;
}

std::string_view Node::attribute(std::string_view n) const {
  const auto* v = find_attribute(n);
  return v ? std::string_view(*v) : std::string_view{};
}

void Node::set_attribute(std::string_view n, std::string value) {
  for (auto& a : attributes)
    if (a.name == n) {
      a.value = std::move(value);
      return;
    }
  attributes.push_back({std::string(n), std::move(value)});
}

bool Node::remove_attribute(std::string_view n) {
  const auto it = std::find_if(attributes.begin(), attributes.end(), [&](const Attribute& a) { return a.name == n; });
  if (it == attributes.end()) return false;
  attributes.erase(it);
  return true;
}

bool operator==(const Node& a, const Node& b) {
  return a.tag == b.tag && a.attributes == b.attributes && a.children == b.children;
}

// ---- Document -----------------------------------------------------------------------

namespace {
Node empty_garment() {
  Node g{"GARMENT", {{"id", "garment"}, {"version", std::string(kFormatVersion)}}, {}};
  // The six containers are always written so an editor has somewhere to add modules.
  for (const char* tag : {"PATTERNS", "SEAMS", "GRADATIONS", "MATERIALS", "TEXTURES", "ACCESSORIES"}) {
    std::string id(tag);
    std::transform(id.begin(), id.end(), id.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    g.children.push_back(Node{tag, {{"id", id}}, {}});
  }
  return g;
}
}  // namespace

Document::Document() : root_(empty_garment()) {}

Document::Document(Node root, std::string name) : root_(std::move(root)), name_(std::move(name)) {
  const Diagnostics d = check(root_, name_);
  if (!d.has_errors()) return;
  // Throw the first error; say how many more there are so the user runs validate.
  const auto& items = d.items();
  const auto first = std::find_if(items.begin(), items.end(), [](const Diagnostic& x) { return x.severity == Severity::error; });
  Diagnostic e = *first;
  if (const auto more = d.count(Severity::error) - 1; more > 0)
    e.message += " (and " + std::to_string(more) + " more problem" + (more > 1 ? "s" : "") +
                 "; 'vgd validate' lists them all)";
  throw Error(std::move(e));
}

void Document::build_index() const {
  index_.clear();
  NodePath path;
  // Depth-first walk recording the path of every element that has an id.
  auto walk = [&](auto&& self, const Node& n) -> void {
    if (const auto* id = n.find_attribute("id")) index_.emplace(*id, path);
    for (std::size_t i = 0; i < n.children.size(); ++i) {
      path.push_back(i);
      self(self, n.children[i]);
      path.pop_back();
    }
  };
  walk(walk, root_);
  index_valid_ = true;
}

std::optional<NodePath> Document::path_of(std::string_view id) const {
  if (!index_valid_) build_index();
  const auto it = index_.find(std::string(id));
  if (it == index_.end()) return std::nullopt;
  return it->second;
}

const Node* Document::find(std::string_view id) const {
  const auto p = path_of(id);
  return p ? &at(*p) : nullptr;
}

const Node& Document::at(const NodePath& path) const {
  const Node* n = &root_;
  for (const auto i : path) {
    VGD_ASSERT(i < n->children.size(), "Document::at: path does not name an element");
    n = &n->children[i];
  }
  return *n;
}

Node& Document::mutable_at(const NodePath& path) {
  touch();
  return const_cast<Node&>(static_cast<const Document*>(this)->at(path));
}

const Node* Document::container(std::string_view tag) const {
  for (const auto& c : root_.children)
    if (c.tag == tag) return &c;
  return nullptr;
}

std::vector<const Node*> Document::patterns() const {
  std::vector<const Node*> out;
  if (const auto* ps = container("PATTERNS"))
    for (const auto& p : ps->children)
      if (p.tag == "PATTERN") out.push_back(&p);
  return out;
}

std::string Document::fresh_id(std::string_view prefix) const {
  if (!index_valid_) build_index();
  // Above every number used with this prefix, so a deleted id is not handed out again
  // while a higher one survives (a GUI selection then never jumps to a new element).
  unsigned long long top = 0;
  for (const auto& [id, path] : index_) {
    if (id.size() <= prefix.size() || id.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string_view digits = std::string_view(id).substr(prefix.size());
    unsigned long long n = 0;
    const auto [p, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
    if (ec == std::errc() && p == digits.data() + digits.size()) top = std::max(top, n);
  }
  return std::string(prefix) + std::to_string(top + 1);
}

}  // namespace vgd::xvc
