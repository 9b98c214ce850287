#include "vgd/render/fit_map.hpp"

// stb_easy_font (libstb-dev): static functions, some unused here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wuseless-cast"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/mesh/strain.hpp"

namespace vgd::render {

std::optional<FitMap> parse_fit_map(std::string_view name) {
  for (FitMap m : {FitMap::warp, FitMap::weft, FitMap::shear, FitMap::stretch, FitMap::stress, FitMap::pressure})
    if (iequals(name, to_string(m))) return m;
  return std::nullopt;
}

const char* to_string(FitMap map) {
  switch (map) {
    case FitMap::warp: return "warp";
    case FitMap::weft: return "weft";
    case FitMap::shear: return "shear";
    case FitMap::stretch: return "stretch";
    case FitMap::stress: return "stress";
    case FitMap::pressure: return "pressure";
  }
  return "?";
}

const char* unit_of(FitMap map) {
  switch (map) {
    case FitMap::shear: return "deg";
    case FitMap::stress: return "N/m";
    case FitMap::pressure: return "kPa";
    default: return "%";
  }
}

std::string title_of(FitMap map) {
  switch (map) {
    case FitMap::warp: return "warp strain, %";
    case FitMap::weft: return "weft strain, %";
    case FitMap::shear: return "shear, deg";
    case FitMap::stretch: return "largest stretch, %";
    case FitMap::stress: return "tension, N/m";
    case FitMap::pressure: return "contact pressure, kPa";
  }
  return "?";
}

FitScale default_scale(FitMap map) {
  if (map == FitMap::shear) return {0.0, 20.0};
  if (map == FitMap::stress) return {0.0, 100.0};
  if (map == FitMap::pressure) return {0.0, 5.0};
  return {0.0, 40.0};
}

namespace {
// The larger principal membrane tension (N/m, ≥ 0) of a strained triangle.
double tension(const mesh::TriangleStrain& s, const Membrane& f) {
  const double nu_fw = f.nu_warp_weft * f.e_weft / f.e_warp;
  const double d = 1.0 - f.nu_warp_weft * nu_fw;
  const double sw = f.e_warp * (s.warp + nu_fw * s.weft) / d, sf = f.e_weft * (s.weft + f.nu_warp_weft * s.warp) / d;
  const double tau = f.g * s.shear_deg * 3.14159265358979323846 / 180.0;
  return std::max(0.0, 0.5 * (sw + sf) + std::hypot(0.5 * (sw - sf), tau));
}
}  // namespace

std::vector<double> fit_values(const Mesh& mesh, FitMap map, const Membrane* fabric) {
  const std::size_t n = mesh.positions.size();
  if (map == FitMap::pressure)
    throw Error(mesh.name, "", "a contact-pressure map comes from the drape's forces (contact-pressure.json beside "
                               "garment.obj), not from the garment's shape");
  if (mesh.uv.size() != n)
    throw Error(mesh.name, "", "no material coordinates (uv) to measure strain against: a fit map needs the "
                               "garment's rest shape (garment.obj's vt, a trajectory's topology)");
  if (map == FitMap::stress &&
      (!fabric || !(fabric->e_warp > 0) || !(fabric->e_weft > 0) || !(fabric->g >= 0) ||
       !(fabric->nu_warp_weft >= 0) || !(fabric->nu_warp_weft * fabric->nu_warp_weft * fabric->e_weft / fabric->e_warp < 1)))
    throw Error(mesh.name, "", "a stress map needs the fabric's sheet moduli (E_warp, E_weft > 0, G >= 0, "
                               "0 <= nu_warp_weft with nu_xy nu_yx < 1)");
  std::vector<double> sum(n, 0.0), weight(n, 0.0);
  auto v2 = [&](int i) { return Eigen::Vector2d(mesh.uv[i][0], mesh.uv[i][1]); };
  auto v3 = [&](int i) { return Eigen::Vector3d(mesh.positions[i][0], mesh.positions[i][1], mesh.positions[i][2]); };
  for (const auto& t : mesh.triangles) {
    const auto s = mesh::triangle_strain(v2(t[0]), v2(t[1]), v2(t[2]), v3(t[0]), v3(t[1]), v3(t[2]));
    if (!s.valid) continue;
    const double area = 0.5 * std::abs((v2(t[1]) - v2(t[0])).x() * (v2(t[2]) - v2(t[0])).y() -
                                       (v2(t[1]) - v2(t[0])).y() * (v2(t[2]) - v2(t[0])).x());
    double value = 0.0;
    switch (map) {
      case FitMap::warp: value = 100.0 * s.warp; break;
      case FitMap::weft: value = 100.0 * s.weft; break;
      case FitMap::shear: value = std::abs(s.shear_deg); break;
      case FitMap::stretch: value = 100.0 * s.stretch; break;
      case FitMap::stress: value = tension(s, *fabric); break;
      case FitMap::pressure: break;
    }
    for (int k = 0; k < 3; ++k) sum[t[k]] += area * value, weight[t[k]] += area;
  }
  for (std::size_t i = 0; i < n; ++i) sum[i] = weight[i] > 0.0 ? sum[i] / weight[i] : 0.0;
  return sum;
}

Colour ramp(double t) {
  // Five stops, equally spaced: blue, cyan, green, yellow, red.
  static constexpr Colour kStops[] = {
      {0.17f, 0.27f, 0.80f}, {0.10f, 0.72f, 0.85f}, {0.20f, 0.75f, 0.25f}, {0.96f, 0.85f, 0.15f}, {0.86f, 0.15f, 0.12f}};
  if (!(t > 0.0)) return kStops[0];
  if (t >= 1.0) return kStops[4];
  const double f = 4.0 * t;
  const int i = std::min(3, static_cast<int>(f));
  const float w = static_cast<float>(f - i);
  const Colour& a = kStops[i];
  const Colour& b = kStops[i + 1];
  return {a.r + w * (b.r - a.r), a.g + w * (b.g - a.g), a.b + w * (b.b - a.b)};
}

void colour_by(Mesh& mesh, const std::vector<double>& values, const FitScale& scale) {
  const double span = scale.hi - scale.lo;
  mesh.vertex_colours.clear();
  mesh.vertex_colours.reserve(values.size());
  for (double v : values) mesh.vertex_colours.push_back(ramp(span > 0.0 ? (v - scale.lo) / span : 0.0));
  mesh.colour = {1, 1, 1};
  mesh.texture.reset();
}

namespace {

// Fills the rectangle [x0, x1) × [y0, y1) with an sRGB colour, clipped.
void fill(Image& img, int x0, int y0, int x1, int y1, const Colour& c) {
  x0 = std::max(0, x0), y0 = std::max(0, y0), x1 = std::min(img.width, x1), y1 = std::min(img.height, y1);
  const auto byte = [](float v) { return static_cast<std::uint8_t>(std::lround(255.0f * std::clamp(v, 0.0f, 1.0f))); };
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      std::uint8_t* p = img.pixel(x, y);
      p[0] = byte(c.r), p[1] = byte(c.g), p[2] = byte(c.b), p[3] = 255;
    }
}

// Text with stb_easy_font's glyphs (each a set of axis-aligned quads), `scale`
// pixels per glyph unit, its top left at (x, y).
void text(Image& img, int x, int y, const std::string& s, int scale, const Colour& c) {
  std::string line = s.substr(0, 200);
  std::vector<float> buffer(line.size() * 80 + 64);  // about 270 bytes a character
  const int quads = stb_easy_font_print(0, 0, line.data(), nullptr, buffer.data(),
                                        static_cast<int>(buffer.size() * sizeof(float)));
  for (int q = 0; q < quads; ++q) {
    // Four vertices of 16 bytes each (x, y, z, colour): corners 0 and 2 are opposite.
    const float* a = buffer.data() + 16 * q;
    const float ax = a[0], ay = a[1], cx = a[8], cy = a[9];
    fill(img, x + static_cast<int>(std::lround(scale * ax)), y + static_cast<int>(std::lround(scale * ay)),
         x + static_cast<int>(std::lround(scale * cx)), y + static_cast<int>(std::lround(scale * cy)), c);
  }
}

int text_width(const std::string& s, int scale) {
  std::string line = s;
  return scale * stb_easy_font_width(line.data());
}

std::string label(double v, const char* unit) {
  const double r = std::round(v * 10.0) / 10.0;
  std::string t = std::abs(r - std::round(r)) < 1e-9 ? format_fixed(r, 0) : format_fixed(r, 1);
  return t + " " + unit;
}

}  // namespace

void draw_legend(Image& img, FitMap map, const FitScale& scale) {
  if (img.empty()) return;
  const int s = std::max(1, img.height / 320);  // glyph scale: 7-unit capitals, about 2 % of the height
  const int bar_h = img.height / 2, bar_w = std::max(8, img.width / 40);
  const int margin = std::max(6, img.width / 50);
  const std::string labels[3] = {label(scale.hi, unit_of(map)), label(0.5 * (scale.lo + scale.hi), unit_of(map)),
                                 label(scale.lo, unit_of(map))};
  int label_w = 0;
  for (const auto& l : labels) label_w = std::max(label_w, text_width(l, s));
  const std::string title = title_of(map);
  const int x1 = img.width - margin - label_w - 4 * s;  // the bar's right edge
  const int x0 = x1 - bar_w;
  const int y0 = (img.height - bar_h) / 2, y1 = y0 + bar_h;
  const Colour ink{0.15f, 0.15f, 0.15f};
  // The title, right-aligned over the bar and its labels.
  text(img, std::max(0, img.width - margin - text_width(title, s)), y0 - 14 * s, title, s, ink);
  for (int y = y0; y < y1; ++y) fill(img, x0, y, x1, y + 1, ramp(1.0 - static_cast<double>(y - y0) / (bar_h - 1)));
  // A thin frame and three ticks with their labels.
  fill(img, x0 - 1, y0 - 1, x1 + 1, y0, ink);
  fill(img, x0 - 1, y1, x1 + 1, y1 + 1, ink);
  fill(img, x0 - 1, y0, x0, y1, ink);
  fill(img, x1, y0, x1 + 1, y1, ink);
  for (int k = 0; k < 3; ++k) {
    const int y = y0 + k * (bar_h - 1) / 2;
    fill(img, x1, y, x1 + 3 * s, y + 1, ink);
    text(img, x1 + 4 * s, y - 3 * s, labels[k], s, ink);
  }
}

}  // namespace vgd::render
