// The command machinery (journal, editor, undo stack) and the generic tree edits.
#include "vgd/xvc/commands.hpp"

#include <algorithm>

#include "edit_helpers.hpp"
#include "rules.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/xvc/validate.hpp"

namespace vgd::xvc {

using detail::parent_of;

// ---- Journal ----------------------------------------------------------------------

namespace {
std::vector<Attribute>::iterator attribute_at(Node& n, std::size_t position) {
  VGD_ASSERT(position <= n.attributes.size(), "journal: attribute position out of range");
  return n.attributes.begin() + static_cast<std::ptrdiff_t>(position);
}

// Puts `value` (nullopt: nothing) where the attribute `name` sits or belongs at `position`.
void put_attribute(Node& n, const std::string& name, const std::optional<std::string>& was,
                   const std::optional<std::string>& value, std::size_t position) {
  if (was && value) attribute_at(n, position)->value = *value;
  else if (was) n.attributes.erase(attribute_at(n, position));
  else if (value) n.attributes.insert(attribute_at(n, position), Attribute{name, *value});
}
}  // namespace

void Journal::undo(Document& doc) const {
  for (auto it = ops_.rbegin(); it != ops_.rend(); ++it) {
    const Op& op = *it;
    switch (op.kind) {
      case Op::insert: {
        Node& parent = doc.mutable_at(parent_of(op.path));
        parent.children.erase(parent.children.begin() + static_cast<std::ptrdiff_t>(op.path.back()));
        break;
      }
      case Op::remove: {
        Node& parent = doc.mutable_at(parent_of(op.path));
        parent.children.insert(parent.children.begin() + static_cast<std::ptrdiff_t>(op.path.back()), op.node);
        break;
      }
      case Op::set_attribute:
        put_attribute(doc.mutable_at(op.path), op.name, op.after, op.before, op.position);
        break;
    }
  }
}

void Journal::redo(Document& doc) const {
  for (const Op& op : ops_) {
    switch (op.kind) {
      case Op::insert: {
        Node& parent = doc.mutable_at(parent_of(op.path));
        parent.children.insert(parent.children.begin() + static_cast<std::ptrdiff_t>(op.path.back()), op.node);
        break;
      }
      case Op::remove: {
        Node& parent = doc.mutable_at(parent_of(op.path));
        parent.children.erase(parent.children.begin() + static_cast<std::ptrdiff_t>(op.path.back()));
        break;
      }
      case Op::set_attribute:
        put_attribute(doc.mutable_at(op.path), op.name, op.before, op.after, op.position);
        break;
    }
  }
}

// ---- Editor -----------------------------------------------------------------------

void Editor::insert(const NodePath& parent, std::size_t index, Node node) {
  Node& p = doc_.mutable_at(parent);
  VGD_ASSERT(index <= p.children.size(), "Editor::insert: index beyond the children");
  NodePath path = parent;
  path.push_back(index);
  journal_.ops_.push_back({Journal::Op::insert, path, node, {}, {}, {}, 0});
  p.children.insert(p.children.begin() + static_cast<std::ptrdiff_t>(index), std::move(node));
}

Node Editor::remove(const NodePath& path) {
  VGD_ASSERT(!path.empty(), "Editor::remove: the root cannot be removed");
  Node& p = doc_.mutable_at(parent_of(path));
  VGD_ASSERT(path.back() < p.children.size(), "Editor::remove: no such child");
  const auto it = p.children.begin() + static_cast<std::ptrdiff_t>(path.back());
  Node removed = std::move(*it);
  p.children.erase(it);
  journal_.ops_.push_back({Journal::Op::remove, path, removed, {}, {}, {}, 0});
  return removed;
}

void Editor::set_attribute(const NodePath& path, std::string_view name, std::optional<std::string> value) {
  Node& n = doc_.mutable_at(path);
  const auto it = std::find_if(n.attributes.begin(), n.attributes.end(), [&](const Attribute& a) { return a.name == name; });
  std::optional<std::string> before;
  if (it != n.attributes.end()) before = it->value;
  if (before == value) return;  // nothing to record
  const auto position = static_cast<std::size_t>(it - n.attributes.begin());  // == size() when absent
  journal_.ops_.push_back({Journal::Op::set_attribute, path, {}, std::string(name), before, value, position});
  put_attribute(n, std::string(name), before, value, position);
}

void Editor::replace(const NodePath& path, Node node) {
  remove(path);
  insert(parent_of(path), path.back(), std::move(node));
}

// ---- execute / UndoStack ----------------------------------------------------------

std::string execute(Document& doc, Command& cmd, Journal* journal) {
  Journal local;
  Journal& j = journal ? *journal : local;
  // Taking a failed command back undoes the whole journal, so it must hold only this one.
  VGD_ASSERT(j.empty(), "execute: the journal must start empty");
  Editor edit(doc, j);
  std::string result;
  try {
    result = cmd.apply(edit);
  } catch (...) {
    j.undo(doc);
    j.clear();
    throw;
  }
  // The whole document must still be valid; otherwise the command is taken back.
  const Diagnostics d = check(doc);
  if (d.has_errors()) {
    j.undo(doc);
    j.clear();
    for (const auto& item : d.items())
      if (item.severity == Severity::error) {
        Diagnostic e = item;
        e.message += " (" + cmd.label() + " refused)";
        throw Error(std::move(e));
      }
  }
  return result;
}

std::string UndoStack::execute(std::unique_ptr<Command> cmd) {
  VGD_ASSERT(cmd != nullptr, "UndoStack::execute: null command");
  Entry e{cmd->label(), {}};
  std::string result = xvc::execute(doc_, *cmd, &e.journal);
  // A command that changed nothing leaves nothing to undo.
  if (e.journal.empty()) return result;
  entries_.resize(done_);
  entries_.push_back(std::move(e));
  if (entries_.size() > limit_) entries_.erase(entries_.begin());
  done_ = entries_.size();
  return result;
}

void UndoStack::undo() {
  if (!can_undo()) return;
  entries_[--done_].journal.undo(doc_);
}

void UndoStack::redo() {
  if (!can_redo()) return;
  entries_[done_++].journal.redo(doc_);
}

std::string UndoStack::undo_label() const { return can_undo() ? entries_[done_ - 1].label : ""; }
std::string UndoStack::redo_label() const { return can_redo() ? entries_[done_].label : ""; }

// ---- generic tree edits -------------------------------------------------------------

Node copy_node(const Document& doc, std::string_view id) {
  Node n = doc.at(detail::require(doc, id));
  // A clipboard copy has no place in a file, so it forgets where it came from.
  auto clear_lines = [](auto&& self, Node& x) -> void {
    x.line = 0;
    for (auto& c : x.children) self(self, c);
  };
  clear_lines(clear_lines, n);
  return n;
}

namespace {
// Index where a new child goes: the caller's, checked, or the schema's place.
std::size_t place(const Document& doc, const NodePath& parent, const Node& child, std::optional<std::size_t> index) {
  const Node& p = doc.at(parent);
  const std::size_t canonical = detail::canonical_index(p, child.tag);  // also refuses a wrong kind
  if (!index) return canonical;
  if (*index > p.children.size())
    throw Error(doc.name(), std::string(p.id()),
                "index " + std::to_string(*index) + " is beyond the " + std::to_string(p.children.size()) +
                    " children of " + std::string(p.id()));
  return *index;
}
}  // namespace

AddNode::AddNode(std::string parent_id, Node node, std::optional<std::size_t> index)
    : parent_id_(std::move(parent_id)), node_(std::move(node)), index_(index) {}

std::string AddNode::label() const { return "Add " + node_.tag + " to " + parent_id_; }

std::string AddNode::apply(Editor& edit) {
  const Document& doc = edit.document();
  const NodePath parent = detail::require(doc, parent_id_);
  Node n = node_;
  // Ids the caller chose must be new; missing ones are made.
  auto refuse_taken = [&](auto&& self, const Node& x) -> void {
    if (x.has_attribute("id") && doc.find(x.id()))
      throw Error(doc.name(), std::string(x.id()), "id " + std::string(x.id()) + " is already used");
    for (const auto& c : x.children) self(self, c);
  };
  refuse_taken(refuse_taken, n);
  detail::IdMaker ids(doc);
  detail::assign_ids(n, ids, false);
  const std::size_t at = place(doc, parent, n, index_);
  std::string id(n.id());
  detail::insert_node(edit, parent, at, std::move(n));
  return id;
}

PasteNode::PasteNode(std::string parent_id, Node node, std::optional<std::size_t> index)
    : parent_id_(std::move(parent_id)), node_(std::move(node)), index_(index) {}

std::string PasteNode::label() const { return "Paste " + node_.tag + " into " + parent_id_; }

std::string PasteNode::apply(Editor& edit) {
  const Document& doc = edit.document();
  const NodePath parent = detail::require(doc, parent_id_);
  Node n = node_;
  detail::IdMaker ids(doc);
  detail::assign_ids(n, ids, true);
  const std::size_t at = place(doc, parent, n, index_);
  std::string id(n.id());
  detail::insert_node(edit, parent, at, std::move(n));
  return id;
}

DeleteNode::DeleteNode(std::string id) : id_(std::move(id)) {}

std::string DeleteNode::label() const { return "Delete " + id_; }

std::string DeleteNode::apply(Editor& edit) {
  const NodePath path = detail::require(edit.document(), id_);
  if (path.empty()) throw Error(edit.document().name(), id_, "the GARMENT root cannot be deleted");
  detail::remove_with_dependents(edit, path);
  return "";
}

SetAttribute::SetAttribute(std::string id, std::string name, std::optional<std::string> value)
    : id_(std::move(id)), name_(std::move(name)), value_(std::move(value)) {}

std::string SetAttribute::label() const {
  return value_ ? "Set " + name_ + " of " + id_ : "Remove " + name_ + " from " + id_;
}

std::string SetAttribute::apply(Editor& edit) {
  const NodePath path = detail::require(edit.document(), id_);
  if (name_ == "id") throw Error(edit.document().name(), id_, "ids cannot be changed; they are how others refer to " + id_);
  edit.set_attribute(path, name_, value_);
  return id_;
}

Batch::Batch(std::string label, std::vector<std::unique_ptr<Command>> commands)
    : label_(std::move(label)), commands_(std::move(commands)) {}

std::string Batch::apply(Editor& edit) {
  std::string result;
  for (auto& c : commands_) {
    VGD_ASSERT(c != nullptr, "Batch: null command");
    result = c->apply(edit);
  }
  return result;
}

}  // namespace vgd::xvc
