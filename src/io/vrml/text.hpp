#pragma once
// Private helpers of the VRML writers: numbers, names, strings and the parts
// every flavour shares (world info, viewpoint, appearances, the body).
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "vgd/io/vrml/garment.hpp"

namespace vgd::io::vrml::detail {

// An axis-aligned box, m.
struct Box {
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  void add(double x, double y, double z);
  bool empty() const { return lo[0] > hi[0]; }
};

// The box of the cloth at frame `f` (what the viewpoint frames; the body is context).
Box garment_box(const Garment& g, int frame);

// A VRML string literal: quotes and backslashes escaped.
std::string quoted(std::string_view s);
// A DEF name from free text: VRML97 identifier characters only, not starting with a digit.
std::string def_name(std::string_view prefix, std::string_view s);

// "#VRML V2.0 utf8", comments, WorldInfo, NavigationInfo, Background and a
// Viewpoint framing `box` from the front (looking along -z) or from the side
// (+x, looking along -x). `comments` are written as # lines.
std::string preamble(const std::string& title, const std::vector<std::string>& comments, const Box& box,
                     bool side_view = false);

// An Appearance node for a piece (Material from the colour; ImageTexture and
// TextureTransform when it has a texture).
std::string appearance(const PieceLook& look, int indent);
// A Material-only appearance in a colour.
std::string appearance(const Rgba& colour, int indent);

// The body as `DEF Avatar Shape { ... }`.
std::string body_shape(const Body& body, int precision);

// `[ x y z, x y z, ... ]` of the given particles' positions in frame x.
void append_points(std::string& out, const std::vector<float>& x, const std::vector<int>& particles, int decimals,
                   int indent);
// The same without the brackets, each line ending in ",\n" (for keyValue lists).
void append_point_lines(std::string& out, const std::vector<float>& x, const std::vector<int>& particles,
                        int decimals, int indent);
// `[ a b c -1 ... ]` of faces.
void append_faces(std::string& out, const std::vector<std::array<int, 3>>& faces, int indent);
// `[ u v, ... ]` of material coordinates.
void append_uv(std::string& out, const std::vector<std::array<double, 2>>& uv, int decimals, int indent);

// Decimals are between 0 and 9 (a programmer's error otherwise).
int checked_decimals(int decimals);

}  // namespace vgd::io::vrml::detail
