#pragma once
// Edits of an XVC document as undoable commands.
//
// The GUI draws its panels from the Document every frame and sends every change back
// as a Command (Dear ImGui style: no mirrored state), so undo and the saved XML never
// drift apart. A command changes the tree only through an Editor, which records each
// primitive change (insert, remove, set attribute) in a Journal; undo replays the
// journal backwards, so it restores the exact previous document, and redo replays it
// forwards without running the command's logic again.
//
// A command first checks its target and throws vgd::Error naming it ("no element with
// id ...", "pattern3 is a SEAM, not a PATTERN"); after it ran, the whole document is
// checked (validate.hpp) and any error undoes the command and is thrown. Either way a
// failed command leaves the document as it was.
//
// Deleting an element also deletes what would dangle: HEMs, SIZEs, ASSOCIATIONs and
// POSITIONs that name a deleted id, then SEAMs left with fewer than two HEMs and
// GRADATIONs left with no SIZE. Removing or adding a boundary C2DSEQ renumbers the
// notch vertices (POSITION vertex) of its pattern.
#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vgd/xvc/document.hpp"

namespace vgd::xvc {

// The primitive changes made by one command, replayable both ways.
class Journal {
 public:
  struct Op {
    enum Kind { insert, remove, set_attribute } kind = insert;
    NodePath path;        // insert/remove: the element's own path; set: the element's path
    Node node;            // insert: the inserted element; remove: the removed one
    std::string name;     // set: attribute name
    std::optional<std::string> before, after;  // set: values (nullopt = absent)
    std::size_t position = 0;  // set: index of the attribute in the element's list
  };
  bool empty() const { return ops_.empty(); }
  std::size_t size() const { return ops_.size(); }
  void clear() { ops_.clear(); }
  void undo(Document& doc) const;
  void redo(Document& doc) const;

 private:
  friend class Editor;
  std::vector<Op> ops_;
};

// The only way commands change a Document; each change is recorded.
class Editor {
 public:
  Editor(Document& doc, Journal& journal) : doc_(doc), journal_(journal) {}
  const Document& document() const { return doc_; }

  // Inserts `node` as child `index` of the element at `parent` (index <= child count).
  void insert(const NodePath& parent, std::size_t index, Node node);
  // Removes the element at `path` (not the root) and returns it.
  Node remove(const NodePath& path);
  // Sets an attribute; nullopt removes it.
  void set_attribute(const NodePath& path, std::string_view name, std::optional<std::string> value);
  // Replaces the element at `path` (remove + insert at the same place).
  void replace(const NodePath& path, Node node);

 private:
  Document& doc_;
  Journal& journal_;
};

class Command {
 public:
  virtual ~Command() = default;
  // Short text for an Edit menu, e.g. "Delete pattern3".
  virtual std::string label() const = 0;
  // Makes the change through `edit`. Returns the id of the element the command created
  // or changed ("" if none), so the caller can select it. Throws vgd::Error.
  virtual std::string apply(Editor& edit) = 0;
};

// Runs a command on `doc` with the checks described above; returns what apply returned.
// `journal`, when given, must be empty and receives the recorded changes.
std::string execute(Document& doc, Command& cmd, Journal* journal = nullptr);

// Do / undo / redo over one document. Undo restores the exact previous document.
class UndoStack {
 public:
  explicit UndoStack(Document& doc, std::size_t limit = 500) : doc_(doc), limit_(limit) {}
  // Runs and records `cmd`; drops anything that could be redone. Throws like execute().
  std::string execute(std::unique_ptr<Command> cmd);
  bool can_undo() const { return done_ > 0; }
  bool can_redo() const { return done_ < entries_.size(); }
  void undo();  // no-op when nothing can be undone
  void redo();  // no-op when nothing can be redone
  // Labels of the command undo/redo would act on ("" when none).
  std::string undo_label() const;
  std::string redo_label() const;
  const Document& document() const { return doc_; }

 private:
  struct Entry {
    std::string label;
    Journal journal;
  };
  Document& doc_;
  std::size_t limit_;
  std::vector<Entry> entries_;
  std::size_t done_ = 0;  // entries_[0 .. done_) are applied
};

// ---- generic tree edits (the VIGDES tree view) ----------------------------------

// A copy of the element with this id and its descendants, for a clipboard. Throws
// vgd::Error when there is no such id.
Node copy_node(const Document& doc, std::string_view id);

// Adds `node` (with its children) under the element `parent_id`, at `index` among its
// children, or when not given at the place the schema's order calls for (after the
// last sibling of the same kind). Elements without an id get a fresh one; an id
// already in the document is refused. Returns the added element's id.
class AddNode : public Command {
 public:
  AddNode(std::string parent_id, Node node, std::optional<std::size_t> index = {});
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  std::string parent_id_;
  Node node_;
  std::optional<std::size_t> index_;
};

// Like AddNode, but every element of `node` gets a fresh id, and references inside the
// pasted subtree to ids of that subtree follow the new ids. Pasting twice gives two
// independent copies. Returns the pasted element's new id.
class PasteNode : public Command {
 public:
  PasteNode(std::string parent_id, Node node, std::optional<std::size_t> index = {});
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  std::string parent_id_;
  Node node_;
  std::optional<std::size_t> index_;
};

// Deletes an element and what would dangle (see above). The root cannot be deleted.
class DeleteNode : public Command {
 public:
  explicit DeleteNode(std::string id);
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  std::string id_;
};

// Sets (or with nullopt removes) one attribute of the element with this id. The id
// attribute itself cannot be changed (ids are stable).
class SetAttribute : public Command {
 public:
  SetAttribute(std::string id, std::string name, std::optional<std::string> value);
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  std::string id_, name_;
  std::optional<std::string> value_;
};

// Several commands as one: they run in order, the document is checked once at the end
// and undo takes them back together. For edits whose steps are only valid together,
// e.g. renaming a piece in its PATTERNs and its GRADATION. Returns the last result.
class Batch : public Command {
 public:
  Batch(std::string label, std::vector<std::unique_ptr<Command>> commands);
  std::string label() const override { return label_; }
  std::string apply(Editor& edit) override;

 private:
  std::string label_;
  std::vector<std::unique_ptr<Command>> commands_;
};

// ---- pattern edits ----------------------------------------------------------------

// Deletes a PATTERN (and its hems, sizes, ... as DeleteNode does).
class DeletePattern : public Command {
 public:
  explicit DeletePattern(std::string pattern_id);
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  std::string id_;
};

// Copies a PATTERN as a new piece placed right after it: fresh ids throughout, block
// "<block>_copy" and piece "<piece> copy" (numbered when taken), and its own GRADATION.
// Returns the copy's id.
class CopyPattern : public Command {
 public:
  explicit CopyPattern(std::string pattern_id);
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  std::string id_;
};

enum class MirrorAxis {
  automatic,   // the grain line when the pattern has one, else vertical
  grain_line,  // the line through the grain line's two points
  vertical,    // the vertical line through the middle of the boundary's bounding box
};

// Mirrors a PATTERN in place. The boundary order is reversed so the outline stays
// counter-clockwise; each C2DSEQ keeps its id and still covers the same edge, so HEMs
// still name the same edges (their from/to are swapped and direction flipped). Notch
// angles are reflected and notch vertex indices follow the reversal.
class MirrorPattern : public Command {
 public:
  explicit MirrorPattern(std::string pattern_id, MirrorAxis axis = MirrorAxis::automatic);
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  std::string id_;
  MirrorAxis axis_;
};

// One point of a PATTERN's outline: the boundary C2DSEQ (one stretch of the
// outline) and the point's place among its C2D children.
struct OutlinePoint {
  std::string pattern_id, sequence_id;
  std::size_t index = 0;
};

// Moves an outline point to (x, y), m in the pattern's frame. A notch on that vertex
// moves with it; the stretches, their seams and every other point stay.
class MovePoint : public Command {
 public:
  MovePoint(OutlinePoint point, double x, double y);
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  OutlinePoint at_;
  double x_, y_;
};

// Adds a point to a stretch after `point` (at the middle of the edge to the next
// outline point when no position is given), of the kind given ("plain", "curve" or
// "turn"). Notch vertices after it follow. Returns the pattern's id.
class InsertPoint : public Command {
 public:
  InsertPoint(OutlinePoint after, std::string kind = "plain", std::optional<std::array<double, 2>> xy = {});
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  OutlinePoint after_;
  std::string kind_;
  std::optional<std::array<double, 2>> xy_;
};

// Deletes an outline point. Refused for the first point of a stretch (where the
// stretch, and the seams that sew it, begin) and when the outline would keep fewer
// than three points. Notch vertices after it follow; a notch on it keeps its place but
// no vertex.
class DeletePoint : public Command {
 public:
  explicit DeletePoint(OutlinePoint point);
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  OutlinePoint at_;
};

// Sets an outline point's kind: "plain", "turn" (an AAMA turn point, a corner) or
// "curve" (a point of a curve).
class SetPointKind : public Command {
 public:
  SetPointKind(OutlinePoint point, std::string kind);
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  OutlinePoint at_;
  std::string kind_;
};

// Turns a PATTERN by `degrees` (counter-clockwise) about the middle of its outline's
// bounding box: outline, internal lines, notches (their angles too), drill holes and
// the arrangement's reference point.
// The grain line stays as it is, so the piece is cut at another angle to the fabric's
// warp (a bias cut at 45°).
class RotatePattern : public Command {
 public:
  RotatePattern(std::string pattern_id, double degrees);
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  std::string id_;
  double degrees_;
};

// Draws an internal line on a PATTERN (a fold, a pocket's place, a dart's legs):
// a C2DSEQ role="internal" of `points` (m, in the pattern's frame; closed: a loop),
// after the pattern's boundary and internal lines. Refused for fewer than two
// points (three when closed), a non-finite coordinate, or a point outside the
// outline by more than 1 mm. Returns the pattern's id.
class AddInternalLine : public Command {
 public:
  AddInternalLine(std::string pattern_id, std::vector<std::array<double, 2>> points, bool closed = false);
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  std::string id_;
  std::vector<std::array<double, 2>> points_;
  bool closed_;
};

// Adds a piece drawn as a polygon (m): a PATTERN of `size` (empty: the sample
// size, else the first pattern's) cut once, each vertex a turn point (every side
// a stretch of its own, to be sewn) unless `curve` marks it a point on a curve
// (one per point, or empty: none; pattern::smooth_through makes such outlines),
// counter-clockwise from a turn point, with its own GRADATION. Its piece and
// block names are `name`, numbered when taken. Refused for fewer than three
// points, a non-finite coordinate, sides that cross, or an area under 1 cm².
// Returns the new PATTERN's id.
class AddDrawnPattern : public Command {
 public:
  AddDrawnPattern(std::string name, std::string size, std::vector<std::array<double, 2>> points,
                  std::vector<bool> curve = {});
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  std::string name_, size_;
  std::vector<std::array<double, 2>> points_;
  std::vector<bool> curve_;
};

// Cuts a PATTERN from a fabric of its own: `material` (a MATERIAL element, e.g.
// from a shipped fabric's document) is added to MATERIALS with fresh ids and scope
// "piece" (never the garment's fabric: xvc::garment_material), unless a piece
// MATERIAL with the same content is there already, and the pattern names it with an
// ASSOCIATION (role "material"), replacing the one it had. nullopt: the pattern is
// cut from the garment's fabric again. A piece MATERIAL no ASSOCIATION names any
// more goes; a garment one stays. Returns the MATERIAL's id ("" for nullopt).
class SetPieceMaterial : public Command {
 public:
  SetPieceMaterial(std::string pattern_id, std::optional<Node> material);
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  std::string id_;
  std::optional<Node> material_;
};

// Moves a notch (POSITION type="notch" `notch_id` of a PATTERN) onto the
// pattern's boundary vertex `vertex` (0-based over the concatenated
// boundary): its point, its vertex, and its cut square into the piece there
// (the inward normal of the outline at the vertex, from its neighbours).
// Refused for another element or a vertex beyond the boundary. Returns the
// notch's id.
class MoveNotch : public Command {
 public:
  MoveNotch(std::string pattern_id, std::string notch_id, std::size_t vertex);
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  std::string pattern_, notch_;
  std::size_t vertex_;
};

// Adds a notch to a PATTERN on its boundary vertex `vertex` (0-based over the
// concatenated boundary), laid as MoveNotch lays one (its cut square into the
// piece there), 5 mm deep: a POSITION type="notch" after the pattern's other
// positions. Refused for a vertex beyond the boundary or one that already has
// a notch. Returns the new notch's id (DeleteNode removes it).
class AddNotch : public Command {
 public:
  AddNotch(std::string pattern_id, std::size_t vertex);
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  std::string pattern_;
  std::size_t vertex_;
};

// Sets a PATTERN's grain line (the fabric's warp runs along it; the drape cuts
// the piece so) to run from `a` to `b` (m, in the pattern's frame), adding
// one when it has none. Refused for a non-finite point or a line under 1 cm.
// Returns the pattern id.
class SetGrainLine : public Command {
 public:
  SetGrainLine(std::string pattern_id, std::array<double, 2> a, std::array<double, 2> b);
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  std::string id_;
  std::array<double, 2> a_, b_;
};

// Where a PATTERN lies on the flat sheet the studio's pattern view shows:
// POSITION type="sheet" in the PATTERN, x and y (m) the sheet point its own
// origin lies on (the sheet shows the piece translated by them, never turned).
// A pattern without one is laid out by the view. It has no bearing on cutting
// or draping; rotating or mirroring the pattern keeps it, a copy has none.
std::optional<std::array<double, 2>> sheet_position(const Node& pattern);

// Adds a pin to a PATTERN (POSITION type="pin", arrangement.hpp): the cloth
// at `at` (m, in the pattern's frame) is held where the arrangement puts it
// while the garment drapes. Refused for a non-finite point or one more than
// 1 mm outside the piece's outline. Returns the new pin's id (DeleteNode
// removes it).
class AddPin : public Command {
 public:
  AddPin(std::string pattern_id, std::array<double, 2> at);
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  std::string pattern_;
  std::array<double, 2> at_;
};

// Undoable: sets the PATTERN's sheet position, or removes it (nullopt).
// Refused for a non-finite coordinate. Returns the pattern id.
class SetSheetPosition : public Command {
 public:
  SetSheetPosition(std::string pattern_id, std::optional<std::array<double, 2>> at);
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  std::string id_;
  std::optional<std::array<double, 2>> at_;
};

// Sets (or adds) a GARMENT-level PARAMETER. An empty unit means the known parameter's
// unit; unknown parameters need one. Returns the PARAMETER's id.
class SetParameter : public Command {
 public:
  SetParameter(std::string name, double value, std::string unit = "");
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  std::string name_;
  double value_;
  std::string unit_;
};

}  // namespace vgd::xvc
