#pragma once
// Seams of an XVC document: reading them, writing planned ones, and suggesting them.
//
// SEAM semantics (docs/xvc.md, "SEAM suggestions"): a SEAM's first HEM is sewn to the
// concatenation of the others, in document order, each run in its own direction; with
// two HEMs that is simply hem 1 to hem 2. Points are matched by arc-length fraction.
// So a sleeve cap (one HEM) sews to the back armhole followed by the front armhole.
//
// Directions: pieces are laid face up (outer side up, outline counter-clockwise).
// Two pieces sewn edge to edge and opened flat lie on opposite sides of the seam
// line, so their counter-clockwise contours run along it in opposite directions (as
// two faces sharing an edge in an oriented mesh). Hence a seam that does not twist
// has one side forward and the other reverse: vgd's suggestions make the first HEM
// forward and every other HEM reverse. Two forward hems would sew the face of one
// piece to the back of the other (a twisted seam).
//
// Units: metres.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vgd/pattern/draft.hpp"
#include "vgd/xvc/commands.hpp"
#include "vgd/xvc/document.hpp"

namespace vgd::xvc {

// What a sewer eases in without a mark, m: a seam's hems this much apart in
// length sew as equal (suggestions score them alike; dress::assemble_garment
// trims a binding only when it is longer than its opening by more).
inline constexpr double kSewingSlack = 0.002;

// One HEM: the boundary stretches from..to (C2DSEQ ids, inclusive) of one PATTERN.
struct HemRef {
  std::string pattern;       // PATTERN id
  std::string from, to;      // boundary C2DSEQ ids
  bool reverse = false;      // sewn against the contour
  double length = 0;         // m, along the outline
  int notches = 0;           // notch marks on it (a pair within 15 mm counts once)
};

// Length (m) of the boundary from the first vertex of `from` to the first vertex of
// the stretch after `to`, along the contour. Throws vgd::Error for unknown ids.
double hem_length(const Document& doc, const std::string& pattern_id, const std::string& from, const std::string& to);

// The SEAMs of the document as HemRefs (lengths and notch counts filled in).
struct SeamInfo {
  std::string id, name;
  std::vector<HemRef> hems;
};
std::vector<SeamInfo> list_seams(const Document& doc);

// A proposed seam. hems[0] is hem A; hems[1..] together are hem B.
struct SeamSuggestion {
  std::string name;           // e.g. "side seam", "sleeve cap to armhole"
  std::string size;           // the size of the patterns sewn
  std::vector<HemRef> hems;
  double length_a = 0;        // m: hems[0]
  double length_b = 0;        // m: hems[1..] summed
  double ease = 0;            // m: length_a - length_b
  int notches_a = 0, notches_b = 0;
  int notches_matched = 0;    // marks of A with a mark (or a junction of B's hems) within 3 % of its arc
  double score = 0;           // in [0, 1]: length agreement × shape × notch agreement
  std::string reason;         // one sentence: which rule and why
};

struct SeamOptions {
  double min_score = 0.5;        // suggestions below are dropped
  std::string size;              // only patterns of this size; "" = every size
  double max_cap_ease = 0.05;    // m: sleeve cap minus armhole accepted up to this
  double merge_angle_deg = 20;   // stretches meeting at a turn turning less than this form one edge
};

// Pairs pieces by role (pattern/roles.hpp: front/back: side seams and shoulders; sleeve
// with front+back: cap to armhole, and the sleeve's underarm seam; waistband to the
// skirt waist, or in two halves to the waists of trousers cut as half legs, each side's
// from centre back or front; neckband round the neckline between the shoulders, its ends together;
// a one-piece collar round the neckline from centre front, its ends open; a cuff
// round each copy's sleeve hem, its ends together) and
// stretches by length, shape and notches; best first within each size. Patterns with
// quantity 0 are skipped. See docs/xvc.md for the rules.
std::vector<SeamSuggestion> suggest_seams(const Document& doc, const SeamOptions& opts = {});

// A SEAM element (no ids: AddNode gives them) for a suggestion.
Node seam_node(const SeamSuggestion& s);
Node seam_node(const std::string& name, const std::vector<HemRef>& hems);

// A seam plan by piece name and stretch index (pattern::SeamPlan: the drafter's own
// seams, and the seam files in tests/data) as SEAM nodes for every size of the document
// (or only `size`). Stretch k is the k-th boundary C2DSEQ of the piece's PATTERN.
// Throws vgd::Error naming the plan, piece or stretch that is missing.
std::vector<Node> plan_seam_nodes(const Document& doc, const std::vector<pattern::SeamPlan>& plans,
                                  const std::string& size = "");

// The seam-plan file format (JSON; docs/xvc.md, "Seam files"):
//   {"seams": [{"name": "left side seam",
//               "hems": [{"piece": "FRONT", "from": 1, "to": 1, "direction": "forward"}, ...]}]}
std::vector<pattern::SeamPlan> parse_seam_plans(std::string_view json_text, const std::string& file_name);
std::string seam_plans_to_json(const std::vector<pattern::SeamPlan>& plans);
// The plan of existing SEAMs (piece names, stretch indices), e.g. to save suggestions.
std::vector<pattern::SeamPlan> seams_as_plans(const Document& doc, const std::string& size = "");

// Undoable: adds SEAM elements (one Batch, one undo step; each SEAM stays its own element,
// deletable with DeleteNode). Returns the last SEAM's id.
class AddSeams : public Command {
 public:
  explicit AddSeams(std::vector<Node> seams);
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  std::vector<Node> seams_;
};

// Undoable: sews a SEAM's hem B the other way along hem A (a twisted seam
// untwisted, or the reverse): its HEMs after the first in reverse order, each
// with its direction flipped. Flipping twice gives the SEAM back. Returns the
// SEAM's id.
class FlipSeam : public Command {
 public:
  explicit FlipSeam(std::string seam_id);
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  std::string id_;
};

}  // namespace vgd::xvc
