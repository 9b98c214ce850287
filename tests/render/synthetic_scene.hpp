#pragma once
// A tiny dressed body for the renderer's tests: a standing cylinder (the body,
// 1.7 m, feet on y = 0) and a wider open tube round its middle (the garment,
// y 0.6–1.0 m), in vgd's frame.
#include <cmath>
#include <string>

#include "vgd/render/scene.hpp"

namespace vgd::test {

// An open cylinder round the Y axis, `segments` round, `rings` high.
inline render::Mesh tube(float radius, float y0, float y1, int segments = 48, int rings = 8) {
  render::Mesh m;
  for (int j = 0; j <= rings; ++j)
    for (int i = 0; i < segments; ++i) {
      const float a = 2.0f * static_cast<float>(M_PI) * static_cast<float>(i) / static_cast<float>(segments);
      m.positions.push_back({radius * std::sin(a), y0 + (y1 - y0) * static_cast<float>(j) / static_cast<float>(rings),
                             radius * std::cos(a)});
    }
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < segments; ++i) {
      const int a = j * segments + i, b = j * segments + (i + 1) % segments;
      m.triangles.push_back({a, b, a + segments});
      m.triangles.push_back({b, b + segments, a + segments});
    }
  return m;
}

inline render::Scene dressed_cylinder(render::Colour garment = {0.80f, 0.12f, 0.12f}) {
  render::Scene s;
  render::Mesh body = tube(0.15f, 0.0f, 1.7f, 48, 24);
  body.name = "body";
  body.kind = render::MeshKind::body;
  body.colour = render::kBody;
  s.meshes.push_back(body);
  render::Mesh skirt = tube(0.2f, 0.6f, 1.0f);
  skirt.name = "SKIRT";
  skirt.colour = garment;
  s.meshes.push_back(skirt);
  return s;
}

}  // namespace vgd::test
