#pragma once
// Fit maps (docs/render.md, "Fit maps"): a garment coloured by how its cloth
// is strained where it hangs — along the warp, along the weft, in shear, or
// its largest principal stretch — from the rest shape in material
// coordinates (Mesh::uv: warp along u, weft along v, m) and the positions
// now (mesh/strain.hpp), with a legend. The same maps in `vgd render --map`
// and the studio's preview.
//
//   auto values = render::fit_values(mesh, render::FitMap::weft);   // per vertex, %
//   render::colour_by(mesh, values, render::default_scale(FitMap::weft));
//   ... render ...
//   render::draw_legend(image, FitMap::weft, scale);
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vgd/render/image.hpp"
#include "vgd/render/scene.hpp"

namespace vgd::render {

enum class FitMap {
  warp,     // engineering strain along the warp, % (|F e_u| − 1)
  weft,     // along the weft, %
  shear,    // change of the warp–weft angle, degrees (its magnitude)
  stretch,  // largest principal stretch − 1, %
  stress,   // largest principal membrane tension, N/m (needs the fabric: Membrane)
  // Contact pressure of the cloth on the body, kPa: not from the shape but
  // from the drape's forces (dress::ContactState::particle_pressure, a drape
  // folder's contact-pressure.json); fit_values refuses it.
  pressure,
};
std::optional<FitMap> parse_fit_map(std::string_view name);  // "warp", "weft", "shear", "stretch", "stress", "pressure"
const char* to_string(FitMap map);
const char* unit_of(FitMap map);   // "%", "deg", "N/m" or "kPa"
std::string title_of(FitMap map);  // "weft strain, %"

// The values the colour ramp spans: [lo, hi] in the map's unit. Defaults:
// 0–40 % for the strains (a woven hangs at 0–5 %, a knit worn with negative
// ease at 20–40 %), 0–20° for shear, 0–100 N/m for stress (a woven under its
// own weight carries under 1 N/m; a waistband gripping the waist, tens),
// 0–5 kPa for pressure (a garment resting on the shoulders presses tenths of
// a kPa; medical compression stockings, 2–5 kPa).
// Values beyond take the end colours.
struct FitScale {
  double lo = 0.0, hi = 40.0;
};
FitScale default_scale(FitMap map);

// A fabric's sheet moduli for the stress map (the MATERIAL's E_warp, E_weft,
// G, N/m, and nu_warp_weft): plane stress from the small strains,
//   σ_w = E_w (ε_w + ν_fw ε_f) / (1 − ν_wf ν_fw),  ν_fw = ν_wf E_f / E_w,
//   σ_f = E_f (ε_f + ν_wf ε_w) / (1 − ν_wf ν_fw),  τ = G γ,
// and the map shows the larger principal tension, 0 where both are
// compressive (cloth buckles rather than carry compression).
struct Membrane {
  double e_warp = 0.0, e_weft = 0.0, g = 0.0;  // N/m
  double nu_warp_weft = 0.0;                   // –
};

// Per vertex of a garment mesh, in the map's unit: the mean of its triangles'
// values weighted by their rest areas (0 for a vertex of no valid triangle).
// Throws vgd::Error when the mesh has no uv (nothing to measure against), and
// for the stress map without a fabric.
std::vector<double> fit_values(const Mesh& mesh, FitMap map, const Membrane* fabric = nullptr);

// Ramp from blue (lo) through cyan, green and yellow to red (hi), sRGB; t in [0, 1].
Colour ramp(double t);

// Sets mesh.vertex_colours from `values` over `scale` and its colour to
// white; drops its texture.
void colour_by(Mesh& mesh, const std::vector<double>& values, const FitScale& scale);

// Draws the legend onto a rendered image: a vertical colour bar at the right
// edge with its ends and middle labelled in the map's unit and the map's
// title above it (stb_easy_font's glyphs, scaled with the image's height).
void draw_legend(Image& image, FitMap map, const FitScale& scale);

}  // namespace vgd::render
