#include "edit_helpers.hpp"

#include <algorithm>
#include <charconv>

#include "rules.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"

namespace vgd::xvc::detail {

NodePath require(const Document& doc, std::string_view id, std::string_view tag) {
  const auto path = doc.path_of(id);
  if (!path) throw Error(doc.name(), std::string(id), "no element with id " + std::string(id));
  const Node& n = doc.at(*path);
  if (!tag.empty() && n.tag != tag)
    throw Error(doc.name(), std::string(id),
                std::string(id) + " is a " + n.tag + ", not a " + std::string(tag), n.line);
  return *path;
}

std::size_t canonical_index(const Node& parent, std::string_view child_tag) {
  const auto* rule = find_rule(parent.tag);
  const int rank = rule ? rule->child_rank(child_tag) : -1;
  if (rank < 0) {
    const std::string owner(parent.id().empty() ? std::string_view(parent.tag) : parent.id());
    if (!find_rule(child_tag)) throw Error("", owner, "unknown element " + std::string(child_tag));
    throw Error("", owner, "a " + parent.tag + " cannot hold a " + std::string(child_tag));
  }
  // After the last child ordered at or before the new one.
  std::size_t index = 0;
  for (std::size_t i = 0; i < parent.children.size(); ++i) {
    const int r = rule->child_rank(parent.children[i].tag);
    if (r >= 0 && r <= rank) index = i + 1;
  }
  return index;
}

std::string IdMaker::make(std::string_view prefix) {
  auto it = next_.find(prefix);
  if (it == next_.end()) {
    // Start above the document's numbers for this prefix (Document::fresh_id).
    const std::string first = doc_.fresh_id(prefix);
    unsigned long long n = 1;
    std::from_chars(first.data() + prefix.size(), first.data() + first.size(), n);
    it = next_.emplace(std::string(prefix), n).first;
  }
  for (;;) {
    std::string id = std::string(prefix) + std::to_string(it->second++);
    if (!taken_.count(id) && !doc_.find(id)) {
      taken_.insert(id);
      return id;
    }
  }
}

std::map<std::string, std::string> assign_ids(Node& node, IdMaker& ids, bool renew_all) {
  std::map<std::string, std::string> renamed;
  // Ids kept as they are must not be handed out again.
  auto reserve = [&](auto&& self, const Node& n) -> void {
    if (!renew_all && n.has_attribute("id")) ids.reserve(std::string(n.id()));
    for (const auto& c : n.children) self(self, c);
  };
  reserve(reserve, node);
  // New ids, depth first, so a copy reads in the same order as its original.
  auto renew = [&](auto&& self, Node& n) -> void {
    const auto prefix = id_prefix(n.tag);
    if (!prefix.empty() && (renew_all || !n.has_attribute("id"))) {
      const std::string old(n.id());
      const std::string fresh = ids.make(prefix);
      if (!old.empty()) renamed[old] = fresh;
      // A new id goes first, where vgd writes ids.
      if (old.empty() && !n.has_attribute("id")) n.attributes.insert(n.attributes.begin(), Attribute{"id", fresh});
      else n.set_attribute("id", fresh);
    }
    for (auto& c : n.children) self(self, c);
  };
  renew(renew, node);
  // References inside the subtree follow their targets.
  auto relink = [&](auto&& self, Node& n) -> void {
    for (auto& a : n.attributes)
      if (is_reference_attribute(n.tag, a.name))
        if (const auto it = renamed.find(a.value); it != renamed.end()) a.value = it->second;
    for (auto& c : n.children) self(self, c);
  };
  relink(relink, node);
  return renamed;
}

bool is_boundary_sequence(const Node& n) {
  return n.tag == "C2DSEQ" && (!n.has_attribute("role") || n.attribute("role") == "boundary");
}

std::size_t point_count(const Node& seq) {
  return static_cast<std::size_t>(
      std::count_if(seq.children.begin(), seq.children.end(), [](const Node& c) { return c.tag == "C2D"; }));
}

void renumber_vertices(Editor& edit, const NodePath& pattern, std::size_t first, std::size_t removed,
                       std::size_t added) {
  const Node& p = edit.document().at(pattern);
  for (std::size_t i = 0; i < p.children.size(); ++i) {
    const Node& c = p.children[i];
    if (c.tag != "POSITION" || !c.has_attribute("vertex")) continue;
    const auto v = parse_int(c.attribute("vertex"));
    if (!v || *v < 0 || static_cast<std::size_t>(*v) < first) continue;
    NodePath at = pattern;
    at.push_back(i);
    const auto u = static_cast<std::size_t>(*v);
    if (u < first + removed)
      edit.set_attribute(at, "vertex", std::nullopt);
    else
      edit.set_attribute(at, "vertex", std::to_string(u - removed + added));
  }
}

namespace {

// Index of the first boundary point held by child `index` of a pattern.
std::size_t first_vertex(const Node& pattern, std::size_t index) {
  std::size_t first = 0;
  for (std::size_t i = 0; i < index && i < pattern.children.size(); ++i)
    if (is_boundary_sequence(pattern.children[i])) first += point_count(pattern.children[i]);
  return first;
}

void collect_ids(const Node& n, std::set<std::string>& out) {
  if (n.has_attribute("id")) out.insert(std::string(n.id()));
  for (const auto& c : n.children) collect_ids(c, out);
}

// Paths of elements whose references name something in `gone`, in document order,
// with the ids of their parents.
void find_dangling(const Node& n, NodePath& path, const Node* parent, const std::set<std::string>& gone,
                   std::vector<std::pair<NodePath, std::string>>& out) {
  for (const auto& a : n.attributes)
    if (is_reference_attribute(n.tag, a.name) && gone.count(a.value)) {
      out.emplace_back(path, parent ? std::string(parent->id()) : std::string());
      break;
    }
  for (std::size_t i = 0; i < n.children.size(); ++i) {
    path.push_back(i);
    find_dangling(n.children[i], path, &n, gone, out);
    path.pop_back();
  }
}

// Removes one element, keeping a pattern's notch vertices in step with its boundary.
void remove_one(Editor& edit, const NodePath& path) {
  const Node& n = edit.document().at(path);
  const NodePath parent = parent_of(path);
  const Node& owner = edit.document().at(parent);
  if (owner.tag == "PATTERN" && is_boundary_sequence(n))
    renumber_vertices(edit, parent, first_vertex(owner, path.back()), point_count(n), 0);
  edit.remove(path);
}

}  // namespace

void remove_with_dependents(Editor& edit, const NodePath& path) {
  VGD_ASSERT(!path.empty(), "remove_with_dependents: the root cannot be removed");
  const Document& doc = edit.document();
  std::set<std::string> gone;
  collect_ids(doc.at(path), gone);
  remove_one(edit, path);
  // Repeat until nothing names a removed id: a removed HEM can leave its SEAM too small,
  // whose removal may leave further references behind.
  // Each round removes every element it finds, so the loop ends.
  for (;;) {
    std::vector<std::pair<NodePath, std::string>> dangling;
    NodePath root;
    find_dangling(doc.root(), root, nullptr, gone, dangling);
    if (dangling.empty()) break;
    std::set<std::string> parents;
    // Last first, so the paths of the others stay valid.
    for (auto it = dangling.rbegin(); it != dangling.rend(); ++it) {
      collect_ids(doc.at(it->first), gone);
      remove_one(edit, it->first);
      parents.insert(it->second);
    }
    // Modules that lost what they are made of go too.
    for (const auto& pid : parents) {
      const auto p = doc.path_of(pid);
      if (!p) continue;
      const Node& m = doc.at(*p);
      const auto hems = std::count_if(m.children.begin(), m.children.end(), [](const Node& c) { return c.tag == "HEM"; });
      const bool empty_gradation = m.tag == "GRADATION" && m.children.empty();
      if ((m.tag == "SEAM" && hems < 2) || empty_gradation) {
        collect_ids(m, gone);
        remove_one(edit, *p);
      }
    }
  }
}

void insert_node(Editor& edit, const NodePath& parent, std::size_t index, Node node) {
  const Node& owner = edit.document().at(parent);
  if (owner.tag == "PATTERN" && is_boundary_sequence(node))
    renumber_vertices(edit, parent, first_vertex(owner, index), 0, point_count(node));
  edit.insert(parent, index, std::move(node));
}

}  // namespace vgd::xvc::detail
