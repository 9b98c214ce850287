#pragma once
// A small garment for the exporters' tests: a tube skirt of two pieces
// (FRONT, BACK), each a nu x nv grid of particles in material space (u along
// the grain, v across), wrapped round a vertical cylinder and sewn at both
// sides (the BACK's side columns merged into the FRONT's), swaying over its
// frames; a closed elliptic prism for a body inside it.
#include <cmath>
#include <numbers>

#include "vgd/io/vrml/garment.hpp"

namespace vgd::test {

struct TubeSkirtSpec {
  int nu = 9, nv = 7;           // particles per piece along u (height) and v (around)
  double width = 0.5;           // m of each piece around the body
  double length = 0.6;          // m from waist to hem
  double waist_y = 1.0;         // m
  int frames = 11;              // over 1 s
  bool body = true;
};

inline io::vrml::Garment tube_skirt(const TubeSkirtSpec& s = {}) {
  using io::vrml::Garment;
  Garment g;
  g.name = "tube skirt";
  g.cloth.pieces = {"FRONT", "BACK"};
  const double r = 2 * s.width / (2 * std::numbers::pi);  // two pieces make the circumference
  const int per = s.nu * s.nv;
  // Particles: piece p, column j (around), row i (down the grain). u = i du, v = j dv.
  for (int p = 0; p < 2; ++p)
    for (int j = 0; j < s.nv; ++j)
      for (int i = 0; i < s.nu; ++i)
        g.cloth.uv.push_back({s.length * i / (s.nu - 1), s.width * j / (s.nv - 1)});
  auto id = [&](int p, int i, int j) { return p * per + j * s.nu + i; };
  // Triangles counter-clockwise in (u, v).
  for (int p = 0; p < 2; ++p)
    for (int j = 0; j + 1 < s.nv; ++j)
      for (int i = 0; i + 1 < s.nu; ++i) {
        g.cloth.triangles.push_back({id(p, i, j), id(p, i + 1, j), id(p, i + 1, j + 1)});
        g.cloth.triangles.push_back({id(p, i, j), id(p, i + 1, j + 1), id(p, i, j + 1)});
        g.cloth.triangle_piece.push_back(p);
        g.cloth.triangle_piece.push_back(p);
      }
  // Side seams: BACK column 0 on FRONT's last column, BACK's last column on FRONT's column 0.
  g.cloth.representative.resize(2 * per);
  for (int k = 0; k < 2 * per; ++k) g.cloth.representative[k] = k;
  for (int i = 0; i < s.nu; ++i) {
    g.cloth.representative[id(1, i, 0)] = id(0, i, s.nv - 1);
    g.cloth.representative[id(1, i, s.nv - 1)] = id(0, i, 0);
  }
  // Frames: the tube, its hem swaying in x.
  for (int f = 0; f < s.frames; ++f) {
    const double t = f / 10.0;
    std::vector<float> x(3 * 2 * per);
    for (int p = 0; p < 2; ++p)
      for (int j = 0; j < s.nv; ++j)
        for (int i = 0; i < s.nu; ++i) {
          const double a = std::numbers::pi * (p + static_cast<double>(j) / (s.nv - 1));  // FRONT 0..π, BACK π..2π
          const double down = static_cast<double>(i) / (s.nu - 1);
          const double flare = r * (1 + 0.3 * down);
          const int k = id(p, i, j);
          x[3 * k] = static_cast<float>(flare * std::cos(a) + 0.05 * down * std::sin(3 * t));
          x[3 * k + 1] = static_cast<float>(s.waist_y - s.length * down);
          x[3 * k + 2] = static_cast<float>(flare * std::sin(a));
        }
    g.frames.times.push_back(t);
    g.frames.positions.push_back(std::move(x));
  }
  // Looks: the default fabric for the front, a red back.
  g.looks.resize(2);
  g.looks[1].colour = {0.8, 0.1, 0.1, 1.0};
  if (s.body) {
    // An elliptic prism from y = 0.3 to 1.2 m: rings of 8 vertices every 0.15 m, capped.
    io::vrml::Body b;
    const int rings = 7, around = 8;
    for (int k = 0; k < rings; ++k)
      for (int j = 0; j < around; ++j) {
        const double a = 2 * std::numbers::pi * j / around;
        b.vertices.push_back({0.12 * std::cos(a), 0.3 + 0.15 * k, 0.08 * std::sin(a)});
      }
    b.vertices.push_back({0, 0.3, 0});
    b.vertices.push_back({0, 1.2, 0});
    const int bottom = rings * around, top = bottom + 1;
    for (int k = 0; k + 1 < rings; ++k)
      for (int j = 0; j < around; ++j) {
        const int a0 = k * around + j, a1 = k * around + (j + 1) % around;
        b.triangles.push_back({a0, a1 + around, a1});
        b.triangles.push_back({a0, a0 + around, a1 + around});
      }
    for (int j = 0; j < around; ++j) {
      b.triangles.push_back({bottom, j, (j + 1) % around});
      b.triangles.push_back({top, (rings - 1) * around + (j + 1) % around, (rings - 1) * around + j});
    }
    g.body = b;
  }
  return g;
}

}  // namespace vgd::test
