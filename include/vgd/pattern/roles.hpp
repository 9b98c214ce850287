#pragma once
// Piece roles: what a pattern piece is in its garment (front, sleeve, cuff,
// interfacing, ...), read from the words a CAD system writes in its piece
// name, category and annotation (docs/xvc.md, "Piece roles").
//
// The dictionary knows the words of English, Spanish, Portuguese, German,
// French and Russian pattern files, and Gerber's abbreviations (FR, BK, SL,
// SLV, CLR, CO, CUF, YK, PKT, WB, ...). Matching is on upper-case words with
// accents folded (Ärmel -> ARMEL, Puño -> PUNO; Cyrillic upper-cased):
//   - whole words, with trailing digits allowed (BACK2, WAISTBAND1);
//   - long words inside run-together names as Valentina writes them
//     (FRONTPANEL, COLLARBASEINTERFACE, SHORTSLEEVE);
//   - a few Gerber codes at the end of a style code (TEEBK1, TEESL).
// "WITH x", "NO x" (and their translations) describe the piece, they do not
// name it: FRONT_WITH_POCKET is a front.
//
// When several roles match, the most specific wins: an interfacing or lining
// of a collar is an interfacing or lining, a sleeve cuff a cuff, a collar
// stand not a collar, a pocket's front a pocket, and only then front/back.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vgd::pattern {

enum class Role {
  unknown,
  front,
  back,
  sleeve,
  leg,
  collar,
  collar_stand,
  neckband,
  hood,
  yoke,
  cuff,
  waistband,
  placket,
  facing,
  binding,
  pocket,
  pocket_flap,
  belt_loop,
  fly,
  lining,
  interfacing,
  label,
};

enum class Side { none, left, right };

// A sleeve cut in two along the arm (Gerber's TEESL FR and TEESL BK), or a
// trouser leg cut as a front and a back (FRONT LEG, TROUSER BACK): the half
// on the front of the limb or on its back.
enum class Half { none, front, back };

struct RoleGuess {
  Role role = Role::unknown;
  Side side = Side::none;
  Half half = Half::none;            // sleeves and legs only: FRONT/FR or BACK/BK beside the sleeve or leg word
  std::string word;                  // the word that decided the role ("" when unknown)
  std::vector<std::string> variant;  // the name's other words (SHORT, LONG, HALF, ...):
                                     // what tells alternatives of one role apart
};

// The role of a piece from its name, category and annotation. `style` is the
// garment's name: a Gerber piece name that starts with it ("ORILEG WB WB" in
// style "ORILEG WB") is read without it, so the style's own words do not count.
// An annotation counts only for what is cut from it: "1XINTERLINING" alone
// makes an interfacing, "1XFABRIC 1X INTERLIN" does not.
RoleGuess piece_role(std::string_view name, std::string_view category = {}, std::string_view annotation = {},
                     std::string_view style = {});

// "front", "collar stand", ... ("unknown").
std::string_view role_name(Role role);
// The role of that name (role_name's words; "collar_stand" as well), or
// nothing for a name that is none.
std::optional<Role> role_from_name(std::string_view name);
// Every role, Role::unknown first.
const std::vector<Role>& all_roles();
std::string_view side_name(Side side);  // "", "left", "right"
std::string_view half_name(Half half);  // "", "front half", "back half"

// Pieces that do not hang as cloth of their own: interfacing and fusibles
// (bonded to their host), labels, linings (a garment of their own inside).
bool drapes_as_cloth(Role role);
// Pieces sewn onto the face of a host piece rather than edge to edge round
// the body: pockets, pocket flaps, belt loops, plackets, facings, flies.
bool sewn_on_host(Role role);

// Upper case with accents folded and Cyrillic upper-cased, UTF-8 in and out
// ("Puño izquierdo" -> "PUNO IZQUIERDO"). Invalid UTF-8 bytes are kept.
std::string fold_name(std::string_view text);

}  // namespace vgd::pattern
