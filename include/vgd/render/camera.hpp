#pragma once
// Cameras and the fixed view presets, framed on a bounding box (docs/render.md).
//
// Azimuth is measured round +Y from the body's front (+Z) towards the body's
// left (+X): front 0°, left 90°, back 180°, right −90°. "left" is the view of
// the body's left side, as a tailor standing at that side sees it.
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vgd/render/scene.hpp"

namespace vgd::render {

struct ViewPreset {
  std::string name;
  double azimuth_deg = 0;    // round +Y, from +Z towards +X
  double elevation_deg = 0;  // above the horizontal through the box centre
  double fov_y_deg = 30;     // vertical field of view
};

// front, back, left, right, three-quarter (front-left, 35°, slightly above).
const std::vector<ViewPreset>& view_presets();

// The preset of that name ("three-quarter"; "three_quarter" and "3/4" also
// accepted), or empty.
std::optional<ViewPreset> find_view(std::string_view name);

// A perspective camera looking at `target`.
struct Camera {
  std::array<double, 3> eye{0, 0, 3}, target{0, 0, 0}, up{0, 1, 0};  // m
  double fov_y_deg = 30;
  double near_m = 0.05, far_m = 50;
};

// The preset's camera that shows the whole box in a viewport of the given
// aspect ratio (width / height), leaving `margin` (a fraction of the viewport)
// free on each side, looking at the box centre.
Camera frame_camera(const ViewPreset& view, const Box& box, double aspect, double margin = 0.05);

// Where a world point (m) appears in a width × height picture the camera
// draws: pixels from the top-left corner, x right and y down, and its depth
// along the view direction (m); nothing when it is not in front of the camera.
struct ScreenPoint {
  double x = 0, y = 0, depth = 0;
};
std::optional<ScreenPoint> project(const Camera& camera, int width, int height, const std::array<double, 3>& p);
// The world point (m) seen at pixel (x, y) at that depth: project's inverse.
std::array<double, 3> unproject(const Camera& camera, int width, int height, double x, double y, double depth);

}  // namespace vgd::render
