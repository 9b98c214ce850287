#pragma once
// The studio's few OpenGL calls outside ImGui's renderer: the preview's
// texture. Private to src/studio (defined in imgui_gl.cpp, where the GL
// functions are loaded).
#include "vgd/render/image.hpp"
#include "vgd/studio/studio.hpp"

namespace vgd::studio::gl {

// Uploads the image into texture `reuse` (0 = a new one) and returns its name.
unsigned upload_texture(const render::Image& image, unsigned reuse);
void delete_texture(unsigned texture);
// Whether init_gl() has run (the studio draws no preview before).
bool ready();
// The function loader init_gl() was given (for render::Renderer in the same context).
GlLoader loader();

}  // namespace vgd::studio::gl
