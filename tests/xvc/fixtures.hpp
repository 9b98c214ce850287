#pragma once
// Small garments built in code, shared by the xvc tests: a style using every field of
// pattern::Style / pattern::Piece, and documents with seams, materials and the rest.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "support/test_paths.hpp"
#include "vgd/xvc/xvc.hpp"

namespace vgd::xvc::test {

using pattern::ContourPoint;
using pattern::PointKind;
using pattern::Vec2;

// A quadrilateral-ish piece, counter-clockwise, with every optional feature filled in.
// The first vertex is a curve point, so the last stretch wraps past the contour start.
inline pattern::Piece full_piece(const std::string& name, const std::string& size, double dx) {
  pattern::Piece p;
  p.block = name + "_" + size;
  p.name = name;
  p.size = size;
  p.quantity = 2;
  p.quantity_flipped = 1;
  p.category = "SELF";
  p.fabric = "denim & co <12oz>";
  p.annotation = "say \"hi\"\ttab\nnew line, caf\xC3\xA9";
  p.annotations = {{"Comment", "keep dry"}, {"", "text without key"}, {"weird key", "  spaced  "}};
  p.boundary = {
      {Vec2(dx + 0.1, 0.0), PointKind::curve},  {Vec2(dx + 0.3, 0.0), PointKind::turn},
      {Vec2(dx + 0.3, 0.15), PointKind::plain}, {Vec2(dx + 0.3, 0.4), PointKind::turn},
      {Vec2(dx + 0.15, 0.45), PointKind::curve}, {Vec2(dx + 0.0, 0.4), PointKind::turn},
      {Vec2(dx + 0.0, 0.0), PointKind::turn},
  };
  p.closed = true;
  p.self_intersecting = false;
  p.notches = {
      {Vec2(dx + 0.3, 0.15), 180.0, 0.005, 0.001, 81, 2},
      {Vec2(dx + 0.2, 0.0), 90.0, 0.0, 0.0, 0, -1},
      {Vec2(dx + 1e-7, 0.2), -0.0, 5e-4, 0.0, 0, -1},  // numbers that need an exponent
  };
  p.grain_line = pattern::Segment{Vec2(dx + 0.15, 0.05), Vec2(dx + 0.15, 0.35)};
  p.mirror_line = pattern::Segment{Vec2(dx + 0.0, 0.0), Vec2(dx + 0.0, 0.4)};
  p.grade_reference = pattern::Segment{Vec2(dx + 0.1, 0.1), Vec2(dx + 0.2, 0.1)};
  p.internal_lines = {{{Vec2(dx + 0.05, 0.3), Vec2(dx + 0.25, 0.3)}, false},
                      {{Vec2(dx + 0.1, 0.2), Vec2(dx + 0.12, 0.2), Vec2(dx + 0.11, 0.22)}, true}};
  p.cutouts = {{{Vec2(dx + 0.2, 0.2), Vec2(dx + 0.22, 0.2), Vec2(dx + 0.22, 0.22), Vec2(dx + 0.2, 0.22)}, true}};
  p.sew_lines = {{{Vec2(dx + 0.01, 0.01), Vec2(dx + 0.29, 0.01)}, false}};
  p.drill_holes = {Vec2(dx + 0.15, 0.25), Vec2(dx + 0.16, 0.26)};
  return p;
}

// Two pieces in two sizes plus a half-filled piece; sizes listed with one no piece uses.
inline pattern::Style full_style() {
  pattern::Style s;
  s.name = "Jacket <test> & \"co\"";
  s.producer = "GERBER TECHNOLOGY / ACCUMARK 10.0.1";
  s.flavour = "AAMA";
  s.units = "mm";
  s.sample_size = "38";
  s.sizes = {"36", "38", "40"};
  s.pieces.push_back(full_piece("FRONT", "36", 0.0));
  s.pieces.push_back(full_piece("BACK", "36", 0.5));
  s.pieces.push_back(full_piece("FRONT", "38", 1.0));
  s.pieces.push_back(full_piece("BACK", "38", 1.5));
  // A sparse piece: defaults everywhere, open outline, no turn points at all.
  pattern::Piece bare;
  bare.block = "BARE";
  bare.name = "POCKET";
  bare.size = "38";
  bare.closed = false;
  bare.self_intersecting = true;
  bare.quantity = 0;
  bare.boundary = {{Vec2(3.0, 0.0)}, {Vec2(3.1, 0.0)}, {Vec2(3.1, 0.1)}};
  s.pieces.push_back(bare);
  return s;
}

// Boundary C2DSEQ ids of a pattern, in order.
inline std::vector<std::string> stretch_ids(const Document& doc, std::string_view pattern_id) {
  std::vector<std::string> ids;
  for (const auto& s : boundary_stretches(*doc.find(pattern_id))) ids.push_back(s.id);
  return ids;
}

// The full style plus a seam, a material, a texture, an accessory and parameters,
// added through commands as the GUI would.
inline Document full_document() {
  Document doc = from_style(full_style());
  const auto a = stretch_ids(doc, "pattern1"), b = stretch_ids(doc, "pattern2");
  Node seam{"SEAM", {{"name", "side seam"}, {"type", "plain"}}, {}};
  seam.children.push_back(Node{"HEM", {{"from", a[1]}, {"to", a[2]}, {"direction", "forward"}, {"type", "plain"}}, {}});
  seam.children.push_back(Node{"HEM", {{"from", b[3]}, {"to", b[3]}, {"direction", "reverse"}}, {}});
  AddNode add_seam("seams", seam);
  execute(doc, add_seam);
  Node material{"MATERIAL", {{"name", "denim"}}, {}};
  material.children.push_back(Node{"PARAMETER", {{"name", "density"}, {"value", "0.35"}, {"unit", "kg/m2"}}, {}});
  material.children.push_back(Node{"COLORRGBA", {{"r", "0.1"}, {"g", "0.2"}, {"b", "0.6"}, {"a", "1"}}, {}});
  AddNode add_material("materials", material);
  const std::string mat = execute(doc, add_material);
  Node texture{"TEXTURE", {{"name", "twill"}, {"file", "textures/twill.png"}}, {}};
  texture.children.push_back(Node{"SCALE2D", {{"x", "0.1"}, {"y", "0.1"}}, {}});
  texture.children.push_back(Node{"ROTATION2D", {{"angle", "45"}}, {}});
  AddNode add_texture("textures", texture);
  execute(doc, add_texture);
  Node accessory{"ACCESSORY", {{"name", "button"}, {"type", "button"}}, {}};
  accessory.children.push_back(Node{"COLORRGBA", {{"r", "0"}, {"g", "0"}, {"b", "0"}}, {}});
  accessory.children.push_back(
      Node{"POSITION", {{"type", "placement"}, {"x", "0.15"}, {"y", "0.3"}, {"pattern", "pattern1"}}, {}});
  AddNode add_accessory("accessories", accessory);
  execute(doc, add_accessory);
  AddNode assoc("pattern1", Node{"ASSOCIATION", {{"ref", mat}, {"role", "material"}}, {}});
  execute(doc, assoc);
  set_parameter(doc, "mesh.spacing", 0.01);
  set_parameter(doc, "mesh.turn_angle", 30);
  set_parameter(doc, "mesh.min_angle", 25);
  set_parameter(doc, "mesh.max_area", 2e-5);
  return doc;
}

inline std::filesystem::path schema() { return vgd::test::source_dir() / "schemas" / "xvc.xsd"; }
inline std::filesystem::path stylesheet() { return vgd::test::source_dir() / "schemas" / "xvc-to-svg.xsl"; }

// Runs a shell command; returns its exit code (stdout/stderr go to the given files).
inline int run(const std::string& command) {
  const int rc = std::system(command.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Error count of a document's messages (errors only).
inline std::size_t errors(const Diagnostics& d) { return d.count(Severity::error); }

// All messages in one string, for failure output.
inline std::string dump(const Diagnostics& d) {
  std::string s;
  for (const auto& i : d.items()) s += std::string(to_string(i.severity)) + ": " + i.format() + "\n";
  return s;
}

}  // namespace vgd::xvc::test
