#pragma once
// Headless previews of a drape folder, a garment OBJ or a trajectory: what
// `vgd render` does, also called by `vgd dress` (cmd_render.cpp).
#include <string>

#include "cli.hpp"

namespace vgd::cli {

struct RenderOptions {
  std::string input, avatar, output = "previews", views = "front,back,left,right,three-quarter", size = "1024x1024";
  std::string colour, body_colour, fit = "body", look;
  std::string unit = "auto", up = "auto", facing = "auto";  // --avatar's, as vgd drape takes them
  bool piece_colours = false, no_floor = false, no_shadow = false, no_texture = false;
  int supersample = 3, frame = -1;
  std::string map, map_range;  // a fit map (render/fit_map.hpp): warp, weft, shear, stretch; "LO,HI" in its unit
  bool list_files = true;  // print a line per PNG written (on stdout)
};

// Writes OUTPUT/<view>.png per view and prints what it wrote. Returns an exit
// code (kUsage for a bad view or size); throws vgd::Error for bad input.
int write_previews(const RenderOptions& options, const Common& common);

}  // namespace vgd::cli
