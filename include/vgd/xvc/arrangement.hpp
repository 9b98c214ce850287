#pragma once
// Arrangements: where each pattern piece goes around the body before draping
// (docs/xvc.md, "Arrangements"; the geometry is scene/placement.hpp).
//
// Stored as POSITION type="arrangement" inside its PATTERN, one per copy of the piece
// (a SLEEVE cut twice has two: the right arm and, flipped, the left arm). Attributes:
//   x, y       m: the piece's reference point in pattern coordinates (vgd puts it at
//              the top centre of the piece's box, measured with the piece turned by angle)
//   segment    neck, torso, hips, left-arm, right-arm, left-leg, right-leg
//   side       front, back, left, right: the body direction the reference point faces
//   height     m: neck/torso/hips: the world height (y) of the reference point;
//              arms/legs: the distance s along the segment's axis from its start
//              (shoulder or hip joint) to the reference point
//   clearance  m, gap between the body and the piece (default 0.03)
//   angle      deg, counter-clockwise rotation of the pattern about the reference point
//              that turns its "up" (towards the neck, or the shoulder for sleeves) to +y
//   flip       true: the piece is mirrored (cut face down): its copy for the other side
//   around     deg, further round the segment from `side` (positive turns the piece's
//              middle from front towards left, counter-clockwise seen from the
//              pattern's up end; default 0: facing the side itself)
// Units: metres and degrees.
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "vgd/pattern/piece.hpp"
#include "vgd/pattern/roles.hpp"
#include "vgd/xvc/commands.hpp"
#include "vgd/xvc/document.hpp"

namespace vgd::xvc {

struct Arrangement {
  std::string segment = "torso";  // neck, torso, hips, left-arm, right-arm, left-leg, right-leg
  std::string side = "front";     // front, back, left, right
  double x = 0, y = 0;            // m: reference point, pattern coordinates
  double height = 0;              // m: see above
  double clearance = 0.03;        // m
  double angle_deg = 0;           // deg
  bool flip = false;
  double around_deg = 0;          // deg: further round the segment from `side`
};

// The names the schema admits.
const std::vector<std::string_view>& arrangement_segments();
const std::vector<std::string_view>& arrangement_sides();

// The arrangements stored in a PATTERN, in document order.
std::vector<Arrangement> arrangements_of(const Node& pattern);

// A pin (POSITION type="pin" in a PATTERN): the cloth at this point of the
// piece (x, y: m, in the pattern's frame) is held where the arrangement puts
// it while the garment drapes (seed 000's constrictions: a coat hanger, a
// flagstaff). Each copy of the pattern is held at its own point.
struct Pin {
  std::string id;
  double x = 0, y = 0;
};
// The pins stored in a PATTERN, in document order.
std::vector<Pin> pins_of(const Node& pattern);
// A piece sewn onto another piece's face (a patch pocket): POSITION
// type="placement" pattern="HOST" in its PATTERN. The middle of its
// outline's box lies at (x, y) (m, the host PATTERN's frame), the piece
// turned by `angle` (deg, counter-clockwise) from its own frame into the
// host's; both face up. Its top edge in its own frame (+y; the boundary
// C2DSEQ whose middle is highest) is its mouth, left open; the rest of its
// outline is sewn to the host along that outline as it lies there
// (dress::assemble_garment). A pattern cut more than once gives its k-th
// copy the k-th such POSITION; each sits on the host's first copy.
struct FacePlacement {
  std::string id;    // the POSITION's id
  std::string host;  // the PATTERN it is sewn onto
  double x = 0, y = 0, angle_deg = 0;
};
// The face placements stored in a PATTERN, in document order.
std::vector<FacePlacement> face_placements_of(const Node& pattern);
// A POSITION element for one (no id: AddNode gives one).
Node face_placement_node(const FacePlacement& f);

// A POSITION element (no id: AddNode gives one).
Node arrangement_node(const Arrangement& a);

// Body heights the suggestions use (m); defaults fit vgd's default mannequin (1.68 m).
struct ArrangementOptions {
  double neck_point_height = 1.42;  // world height of the neck point (shoulder at the neck)
  double waist_height = 1.05;       // world height of the natural waist
  double clearance = 0.03;          // m
  // Bodices hang this far above the neck point, so their shoulder edges start
  // above the body's shoulders and the shoulder seams close over them in free
  // air (started level with the neck point they had to be dragged up over the
  // shoulders against friction and stalled). Not a bodice hanging from straps
  // (within its top 5 cm its cloth spans less than a quarter of its width: a
  // tank): lifted, its straps closed above the shoulders and stood there
  // beside the neck; level with the neck point they come to rest on them.
  double bodice_lift = 0.05;        // m
  // Sleeves fit an arm closely: at 3 cm their underarm edges started in the
  // gap between arm and torso and could not meet.
  double sleeve_clearance = 0.01;   // m
  // Sleeves start this far down the arm (cap top from the arm's shoulder end),
  // clear of the bodice's shoulders: at 0 their caps started through the
  // bodice (85 crossing triangle pairs before the first step); from 6 cm on
  // nothing crosses, and the cap is pulled up into the armhole.
  double sleeve_drop = 0.06;        // m
  // Legs (tights, trousers cut as one piece per leg): the piece's top (the
  // waist) this far along the leg from its hip joint; negative: above it.
  double leg_top = -0.10;           // m
};

// From the piece's role (pattern/roles.hpp; `style` is the garment's name): front ->
// torso front, back and a top's yoke -> torso back (top edge bodice_lift above the neck
// point; suggest_arrangements hangs a back below its size's yoke), sleeve ->
// the arms (a left or right sleeve one arm; a sleeve cut twice gives the right arm and the
// left arm flipped; cap top sleeve_drop down the arm; the front or back half of a sleeve
// cut in two on that side of the arm, its over-arm edge outside, flipped as that needs),
// leg -> the legs the same way, the
// wider end up (the waist, at leg_top) and the narrower half to the front (one copy
// flipped: the right leg's front is on its pattern's +x), collar stand -> neck front,
// neckband -> neck front lengthwise, its bottom edge at the neck point, collar -> neck
// back lengthwise (its ends at centre front; suggest_arrangements turns it half round
// when the edge a SEAM sews to the neckline would be its top), a cuff
// cut twice -> each arm lengthwise (the right first, the left mirrored; placed at the
// hem of its sleeve by suggest_arrangements); in a
// lower-body garment front/back -> hips front/back with their top at the waist, and
// waistband -> hips front around the waist (a band drawn upright is turned a quarter
// clockwise, its right edge to the bottom). Empty for other roles and when the
// piece is not cut (quantity 0). The reference point and angle come from the piece's box
// and grain line.
std::vector<Arrangement> suggest_arrangement(const pattern::Piece& piece, bool lower_body,
                                             const ArrangementOptions& opts = {}, std::string_view style = {});
// The same for a piece whose role is known (a PATTERN's role attribute: xvc::piece_role).
std::vector<Arrangement> suggest_arrangement(const pattern::Piece& piece, const pattern::RoleGuess& role,
                                             bool lower_body, const ArrangementOptions& opts = {});
// Every PATTERN of the document (its role as xvc::piece_role reads it): (pattern id, its
// suggestions). A garment is lower-body when a piece is a waistband or its name says
// skirt, or the garment's says skirt, trousers or pants. A cuff goes on at the hem of
// the sleeve a SEAM sews it to: that sleeve's height down the arm plus its length
// along its upright; a cuff no seam sews to a sleeve gets none. A half waistband (a
// SEAM sews it to trouser leg halves) goes round the right of the hips when its seam
// starts at a back half, the left when at a front half.
std::vector<std::pair<std::string, std::vector<Arrangement>>> suggest_arrangements(
    const Document& doc, const ArrangementOptions& opts = {});

// "SEGMENT:SIDE[±DEG]:HEIGHT[:CLEARANCE[:ANGLE[:flip]]]", e.g. "torso:front:1.25:0.03",
// "torso:left-20:1.25" (20° back from the left towards the front: around -20).
// The reference point is filled in from `piece` (top centre). Throws vgd::Error.
Arrangement parse_arrangement(std::string_view spec, const pattern::Piece& piece);

// The reference point vgd uses: top centre of the piece's box with the piece turned by
// angle_deg (m, pattern coordinates).
pattern::Vec2 reference_point(const pattern::Piece& piece, double angle_deg);

// Undoable: replaces every arrangement of a PATTERN with the given ones (empty: removes
// them). Returns the pattern id.
class SetArrangements : public Command {
 public:
  SetArrangements(std::string pattern_id, std::vector<Arrangement> arrangements);
  std::string label() const override;
  std::string apply(Editor& edit) override;

 private:
  std::string id_;
  std::vector<Arrangement> arrangements_;
};

}  // namespace vgd::xvc
