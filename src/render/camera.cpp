// View presets and framing a box.
#include "vgd/render/camera.hpp"

#include <algorithm>
#include <cmath>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"

namespace vgd::render {

namespace {

using D3 = std::array<double, 3>;

constexpr double kPi = 3.14159265358979323846;
double radians(double deg) { return deg * kPi / 180.0; }
double dot(const D3& a, const D3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
D3 cross(const D3& a, const D3& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
D3 normalized(const D3& a) {
  const double l = std::sqrt(dot(a, a));
  return {a[0] / l, a[1] / l, a[2] / l};
}

}  // namespace

const std::vector<ViewPreset>& view_presets() {
  // Slightly above the centre, as a person of average height looks at a mannequin.
  static const std::vector<ViewPreset> presets = {
      {"front", 0, 5, 30},
      {"back", 180, 5, 30},
      {"left", 90, 5, 30},
      {"right", -90, 5, 30},
      {"three-quarter", 35, 12, 30},
  };
  return presets;
}

std::optional<ViewPreset> find_view(std::string_view name) {
  std::string n = to_lower(trim(name));
  if (n == "three_quarter" || n == "3/4" || n == "threequarter" || n == "three-quarters") n = "three-quarter";
  for (const auto& v : view_presets())
    if (v.name == n) return v;
  return std::nullopt;
}

Camera frame_camera(const ViewPreset& view, const Box& box, double aspect, double margin) {
  VGD_ASSERT(!box.empty(), "cannot frame an empty box");
  VGD_ASSERT(aspect > 0 && margin >= 0 && margin < 0.5, "aspect must be positive and margin in [0, 0.5)");
  const double a = radians(view.azimuth_deg), e = radians(view.elevation_deg);
  // From the target towards the eye; the camera's right and up.
  const D3 d{std::sin(a) * std::cos(e), std::sin(e), std::cos(a) * std::cos(e)};
  const D3 right = normalized(cross(D3{-d[0], -d[1], -d[2]}, D3{0, 1, 0}));
  const D3 up = cross(right, D3{-d[0], -d[1], -d[2]});
  const D3 centre{0.5 * (box.min[0] + box.max[0]), 0.5 * (box.min[1] + box.max[1]), 0.5 * (box.min[2] + box.max[2])};

  // The nearest distance at which every corner projects inside the margins:
  // |x| <= tan(half fov) (1 - 2 margin) (D - z) on both axes.
  const double ty = std::tan(radians(view.fov_y_deg) / 2) * (1 - 2 * margin);
  const double tx = std::tan(radians(view.fov_y_deg) / 2) * aspect * (1 - 2 * margin);
  double dist = 0, radius = 0;
  for (int c = 0; c < 8; ++c) {
    const D3 p{c & 1 ? box.max[0] : box.min[0], c & 2 ? box.max[1] : box.min[1], c & 4 ? box.max[2] : box.min[2]};
    const D3 rel{p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]};
    const double x = dot(rel, right), y = dot(rel, up), z = dot(rel, d);
    dist = std::max({dist, std::abs(x) / tx + z, std::abs(y) / ty + z});
    radius = std::max(radius, std::sqrt(dot(rel, rel)));
  }
  radius = std::max(radius, 1e-3);
  dist = std::max(dist, 1.5 * radius);

  Camera cam;
  cam.target = centre;
  cam.eye = {centre[0] + dist * d[0], centre[1] + dist * d[1], centre[2] + dist * d[2]};
  cam.up = up;
  cam.fov_y_deg = view.fov_y_deg;
  cam.near_m = std::max(0.01, 0.25 * (dist - radius));
  cam.far_m = dist + 12 * radius;  // far enough for the floor to fade out
  return cam;
}

namespace {
// The camera's frame: forward, right and up unit vectors, as the renderer's look-at builds it.
struct ViewFrame {
  D3 f, r, u;
  double ty, tx;  // tan of the half field of view, vertically and across
};
ViewFrame view_frame(const Camera& c, int width, int height) {
  ViewFrame v;
  v.f = normalized({c.target[0] - c.eye[0], c.target[1] - c.eye[1], c.target[2] - c.eye[2]});
  v.r = normalized(cross(v.f, c.up));
  v.u = cross(v.r, v.f);
  v.ty = std::tan(radians(c.fov_y_deg) / 2);
  v.tx = v.ty * static_cast<double>(width) / height;
  return v;
}
}  // namespace

std::optional<ScreenPoint> project(const Camera& c, int width, int height, const std::array<double, 3>& p) {
  const ViewFrame v = view_frame(c, width, height);
  const D3 d{p[0] - c.eye[0], p[1] - c.eye[1], p[2] - c.eye[2]};
  const double z = dot(d, v.f);
  if (!(z > 0)) return std::nullopt;
  const double nx = dot(d, v.r) / (z * v.tx), ny = dot(d, v.u) / (z * v.ty);
  return ScreenPoint{(nx + 1) / 2 * width, (1 - ny) / 2 * height, z};
}

std::array<double, 3> unproject(const Camera& c, int width, int height, double x, double y, double depth) {
  const ViewFrame v = view_frame(c, width, height);
  const double nx = 2 * x / width - 1, ny = 1 - 2 * y / height;
  D3 p;
  for (int k = 0; k < 3; ++k) p[k] = c.eye[k] + depth * (v.f[k] + nx * v.tx * v.r[k] + ny * v.ty * v.u[k]);
  return p;
}

}  // namespace vgd::render
