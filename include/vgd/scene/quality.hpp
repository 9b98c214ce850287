#pragma once
// Quality presets: the seeds' fidelity-versus-performance trade-off as three
// named integrator settings (docs/accuracy-vs-time.md, "Quality presets",
// where each preset's measured error and cost are):
//
//   without contact (no collision, seams or self-collision: a flag, a hanging
//   cloth) — explicit methods at a fraction of their stability limit:
//     preview   symplectic Euler at 0.9 of its limit
//     standard  RK4 at 1/4 of its limit
//     precise   RK4 at 1/8 of its limit
//   with contact — implicit Euler (the explicit methods' step limits fall to
//   microseconds under contact springs), CG to a 1 % residual, steps per
//   25 fps frame:
//     preview   4 (10 ms); `vgd drape --quality preview` stops at 10x the rest threshold
//     standard  4 (10 ms), vgd drape's default
//     precise   8 (5 ms)
//   (20 ms steps settled slower than 10 ms and let a skirt ride up the body;
//   a 0.1 % residual stalled the T-shirt's settling: both measured, not used.)
//
// A scene's `integrator.preset` (or `--quality`) sets these; any other
// integrator field given with it overrides the preset's value.
#include <string>

#include "vgd/scene/scene.hpp"

namespace vgd::scene {

// "preview", "standard", "precise"; throws std::invalid_argument naming the choices.
Quality parse_quality(const std::string& name);
const char* to_string(Quality q);

// Whether the effects bring contact: body collision, seams or self-collision.
bool has_contact(const EffectsDef& effects);

// The preset's integrator (method, step or steps per frame, tolerances).
IntegratorDef quality_integrator(Quality q, bool contact);

}  // namespace vgd::scene
