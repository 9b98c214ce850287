#pragma once
// Pieces shared by the commands: finding targets, placing children, fresh ids and the
// cascade that keeps references from dangling.
#include <map>
#include <set>
#include <string>
#include <string_view>

#include "vgd/xvc/commands.hpp"
#include "vgd/xvc/document.hpp"

namespace vgd::xvc::detail {

// The path of the element with `id`; throws vgd::Error when there is none or, when
// `tag` is given, when the element is of another kind.
NodePath require(const Document& doc, std::string_view id, std::string_view tag = {});

// Where a new `child_tag` goes among `parent`'s children when no index is given:
// after the last child that the schema orders at or before it. Throws vgd::Error when
// `parent` cannot hold such a child.
std::size_t canonical_index(const Node& parent, std::string_view child_tag);

// Hands out ids unused in the document and not yet handed out.
class IdMaker {
 public:
  explicit IdMaker(const Document& doc) : doc_(doc) {}
  void reserve(const std::string& id) { taken_.insert(id); }
  std::string make(std::string_view prefix);

 private:
  const Document& doc_;
  std::set<std::string> taken_;
  std::map<std::string, unsigned long long, std::less<>> next_;
};

// Gives every element of `node` that carries ids a fresh one (all of them when
// `renew_all`, else only those without an id) and rewrites references inside `node`
// that named a renewed id. Returns old -> new.
std::map<std::string, std::string> assign_ids(Node& node, IdMaker& ids, bool renew_all);

// True for a C2DSEQ that is part of a pattern's boundary.
bool is_boundary_sequence(const Node& n);

// Number of C2D in a node's children.
std::size_t point_count(const Node& seq);

// Moves the notch vertices of the pattern at `pattern` when boundary points [first,
// first + removed) disappear and `added` points appear at `first`. Vertices of removed
// points lose their vertex attribute (the notch no longer sits on a known vertex).
void renumber_vertices(Editor& edit, const NodePath& pattern, std::size_t first, std::size_t removed,
                       std::size_t added);

// Removes the element at `path` and everything that would dangle without it.
void remove_with_dependents(Editor& edit, const NodePath& path);

// Inserts `node` at `index` under `parent`, renumbering the notch vertices of the
// pattern when `node` is a boundary C2DSEQ.
void insert_node(Editor& edit, const NodePath& parent, std::size_t index, Node node);

}  // namespace vgd::xvc::detail
