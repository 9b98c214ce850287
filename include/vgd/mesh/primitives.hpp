#pragma once
// Closed triangle surfaces of simple solids: colliders for benchmarks and
// tests (Blender's UV sphere and cylinder, a box). Units: metres; triangles
// counter-clockwise seen from outside; every surface is watertight.
#include "vgd/mesh/surface.hpp"

namespace vgd::mesh {

// Blender's UV sphere: `segments` around (≥ 3), `rings` from pole to pole (≥ 2).
// It has 2·segments·(rings − 1) triangles: 64 × 40 gives 4 992, the drape
// benchmark's sphere.
SurfaceMesh uv_sphere(const Vec3& centre, double radius, int segments, int rings);

// A cylinder along +Y from `base` (centre of the bottom cap), capped by fans
// around a centre vertex: 4·segments + 2·segments·(stacks − 1) triangles.
SurfaceMesh cylinder(const Vec3& base, double radius, double height, int segments, int stacks = 1);

// An axis-aligned box, 12 triangles.
SurfaceMesh box(const Vec3& min, const Vec3& max);

}  // namespace vgd::mesh
