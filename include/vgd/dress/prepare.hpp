#pragma once
// Getting a pattern document ready to drape, deciding what the designer did
// not say (docs/drape.md, "vgd dress"):
//
//   seams     none in the document: vgd's suggestions at the sample size are
//             added (graded sizes sew with them: dress/garment.hpp);
//   roles     each piece's role from its name (pattern/roles.hpp), said;
//   pieces    those of the size that a seam sews, and that a rule can arrange
//             round the body; the others are left out, each with its reason:
//             interfacings and labels (bonded, not cloth of their own),
//             linings (a garment of their own), pockets, flaps and plackets
//             (sewn onto a face, which vgd does not drape yet), pieces cut 0
//             times, pieces no seam sews; of several sleeve (or leg) patterns
//             (a short and a full sleeve) the one sewn to the armholes, else
//             the one with the most seams;
//   bands     a neckband or a cuff read as cut double and folded lengthwise
//             (a crew neck's rib, a rib cuff), and a one-piece collar with no
//             stand draped read as rolled over at half its width: folded="true"
//             written on its patterns; one shorter than its neckline or sleeve hem cut from
//             the shipped rib (a piece MATERIAL), unless it has its own or the
//             caller gives the fabric;
//   quantities a document where every piece says it is cut 0 times: each
//             as often as its annotation says ("2XFABRIC"), else once;
//   legs      in a garment with a waistband and no front, back or leg, a
//             piece cut twice whose name says nothing is the leg (LEG added
//             to its category);
//   body      the size table of the garment's own sizes: men's when the
//             style's name says men (MEN, MENS, MAN, MALE, or an M between
//             separators as in "SS17_M POLO"), women's when it says women;
//             otherwise, and for a size no table has (Valentina's "base"),
//             the table and size whose bust (tops) or hip (skirts,
//             trousers, legs) leaves the pattern's girth the usual ease;
//             without a front or back to measure, the first table with the
//             size, or the middle size of the first table. A body file
//             given instead of a mannequin is said, and no table chosen.
//
// Every decision is a sentence in Preparation::decisions, and the SEAMs it
// adds are in the document, so the designer can read, correct and re-run.
#include <string>
#include <vector>

#include "vgd/xvc/document.hpp"

namespace vgd::dress {

struct PrepareOptions {
  std::string size;        // the garment's size; "" = the document's sample size
  std::string body_table;  // size table of the mannequin; "" = from the style's name
  std::string body_size;   // the mannequin's size; "" = the garment's, or the size nearest the pattern
  std::string avatar;      // a body file draped on instead of a mannequin: said, no table chosen
  double min_score = 0.5;  // seam suggestions below are not added
  // A seam file (JSON, docs/xvc.md "Seam files": pieces by name, stretches by
  // index) sewing the pieces as they are once joined: its seams are added for
  // every size instead of vgd's suggestions. Refused (vgd::Error) for a
  // document with SEAMs of its own.
  std::string seams_file;
  // The caller drapes in a fabric of its own (vgd dress --material): no
  // fabric is chosen for the document.
  bool fabric_given = false;
};

// m of girth: a garment more than this smaller round a girth than the body
// is too small for it (prepare_garment's check of the pattern's girth, and
// check_fit's of its size's measurements).
inline constexpr double kFitTooSmall = 0.04;
// A top or skirt smaller than that round the bust or hip, and at least this
// fraction of the body's, is cut for a knit (prepare_garment's fabric decision).
inline constexpr double kKnitGirth = 0.75;

struct Preparation {
  std::string size;                    // the size to drape
  std::vector<std::string> pieces;     // piece names to drape, document order
  std::vector<std::string> left_out;   // piece names left out (each also in decisions)
  // Of those, the pieces the garment is worn with, "NAME (role)": not the
  // ones cut 0 times, alternatives, interfacings, labels or linings. A drape
  // without them is of an incomplete garment (a tee without its sleeves).
  std::vector<std::string> missing;
  std::string body_table;              // "" = the default search order
  std::string body_size;               // the mannequin's size (the garment's unless no table has it)
  int seams_added = 0;
  // The MATERIAL id written in the document when it had none and the pattern
  // has less girth than the body (cut for a stretch fabric: the shipped
  // knit); "" when none was written.
  std::string fabric;
  std::vector<std::string> decisions;  // one sentence each, in the order taken
  // What the user should know before the drape (a top whose pattern has less
  // girth than the body chosen), one sentence each.
  std::vector<std::string> warnings;
};

// Adds SEAMs to `doc` when it has none. Throws vgd::Error naming the document
// when nothing can be draped: no pattern of the size, or several pieces and
// no seam between any of them.
Preparation prepare_garment(xvc::Document& doc, const PrepareOptions& options = {});

// The size table a style's name points to ("en13402-men", "en13402-women"),
// or "" when it says neither.
std::string size_table_from_name(const std::string& style_name);

}  // namespace vgd::dress
