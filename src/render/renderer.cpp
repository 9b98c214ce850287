// The drawing code (OpenGL 3.3 core), independent of the context that runs it.
//
// Index
//   [shaders]   GLSL sources: meshes (flat and textured), floor, shadow depth
//   [math]      look-at, perspective and orthographic matrices
//   [gl]        loading functions, compiling programs
//   [scene]     uploading meshes, their textures and the floor
//   [draw]      shadow pass, then floor and meshes
#include "vgd/render/renderer.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "gl_functions.hpp"
#include "vgd/core/diagnostics.hpp"

namespace vgd::render {

namespace {

using Mat4 = Eigen::Matrix4f;
using Vec3f = Eigen::Vector3f;

// ---- [shaders] ----------------------------------------------------------------

// Meshes: per-vertex normals, lit on the side facing the camera (cloth has two
// sides), a sky/ground ambient term, a key and a fill light that follow the
// camera, a faint specular and rim. Lighting is done in linear RGB.
// Meshes: per-vertex normals, lit on the side facing the camera (cloth has two
// sides), a sky/ground ambient term, a key and a fill light that follow the
// camera, a faint specular and rim. Lighting is done in linear RGB. Compiled
// twice: TEXTURED 0 (flat colour) and 1 (the colour times an sRGB texture,
// sampled as linear RGB with trilinear mipmapping so fine checks do not alias).
// The untextured variant preprocesses to the same code as before textures.
constexpr const char* kMeshVertex = R"(
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 3) in vec3 a_colour;  // linear RGB per vertex (white when the mesh has none)
out vec3 v_colour;
#if TEXTURED
layout(location = 2) in vec2 a_texcoord;
out vec2 v_texcoord;
#endif
uniform mat4 u_view_projection;
out vec3 v_position;
out vec3 v_normal;
void main() {
  v_position = a_position;
  v_normal = a_normal;
  v_colour = a_colour;
#if TEXTURED
  v_texcoord = a_texcoord;
#endif
  gl_Position = u_view_projection * vec4(a_position, 1.0);
}
)";

constexpr const char* kMeshFragment = R"(
in vec3 v_position;
in vec3 v_normal;
in vec3 v_colour;
#if TEXTURED
in vec2 v_texcoord;
uniform sampler2D u_texture;  // sRGB texels, read as linear RGB
#endif
uniform vec3 u_eye;
uniform vec3 u_colour;     // linear RGB
uniform vec3 u_key;        // unit vector towards the key light
uniform vec3 u_fill;       // unit vector towards the fill light
uniform float u_specular;
uniform float u_shininess;
out vec4 frag_colour;
void main() {
  vec3 n = normalize(v_normal);
  vec3 v = normalize(u_eye - v_position);
  // Two-sided: the side the camera sees is the lit side.
  if (dot(n, v) < 0.0) n = -n;
  vec3 ambient = mix(vec3(0.16), vec3(0.40), 0.5 + 0.5 * n.y);
  float key = max(dot(n, u_key), 0.0);
  float fill = max(dot(n, u_fill), 0.0);
  float spec = key > 0.0 ? u_specular * pow(max(dot(n, normalize(u_key + v)), 0.0), u_shininess) : 0.0;
  float rim = 0.10 * pow(1.0 - max(dot(n, v), 0.0), 3.0);
  vec3 albedo = u_colour * v_colour;
#if TEXTURED
  albedo *= texture(u_texture, v_texcoord).rgb;
#endif
  vec3 c = albedo * (ambient + 0.80 * key + 0.25 * fill) + vec3(spec + rim);
  frag_colour = vec4(pow(clamp(c, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
)";

// The mesh shaders' source with the variant chosen.
std::string mesh_source(const char* body, bool textured) {
  return std::string("#version 330 core\n#define TEXTURED ") + (textured ? "1" : "0") + body;
}

// The floor: its colour darkened by the percentage-closer-filtered shadow map
// (16 taps on a Poisson disc, each a bilinear 2 x 2 comparison), fading into
// the background away from the scene so there is no horizon line.
constexpr const char* kFloorVertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
uniform mat4 u_view_projection;
out vec3 v_position;
void main() {
  v_position = a_position;
  gl_Position = u_view_projection * vec4(a_position, 1.0);
}
)";

constexpr const char* kFloorFragment = R"(#version 330 core
in vec3 v_position;
uniform sampler2DShadow u_shadow_map;
uniform mat4 u_light_view_projection;
uniform int u_use_shadow;
uniform float u_pcf_radius;   // penumbra half-width in shadow-map texture coordinates
uniform float u_strength;
uniform vec3 u_centre;
uniform float u_fade_start;
uniform float u_fade_end;
uniform vec3 u_floor;         // linear RGB
uniform vec3 u_background;    // linear RGB
out vec4 frag_colour;
const vec2 disc[16] = vec2[](
  vec2(-0.94201624, -0.39906216), vec2(0.94558609, -0.76890725), vec2(-0.09418410, -0.92938870),
  vec2(0.34495938, 0.29387760), vec2(-0.91588581, 0.45771432), vec2(-0.81544232, -0.87912464),
  vec2(-0.38277543, 0.27676845), vec2(0.97484398, 0.75648379), vec2(0.44323325, -0.97511554),
  vec2(0.53742981, -0.47373420), vec2(-0.26496911, -0.41893023), vec2(0.79197514, 0.19090188),
  vec2(-0.24188840, 0.99706507), vec2(-0.81409955, 0.91437590), vec2(0.19984126, 0.78641367),
  vec2(0.14383161, -0.14100790));
void main() {
  float lit = 1.0;
  if (u_use_shadow != 0) {
    vec4 lp = u_light_view_projection * vec4(v_position, 1.0);
    vec3 p = lp.xyz / lp.w * 0.5 + 0.5;
    float sum = 0.0;
    for (int i = 0; i < 16; ++i)
      sum += texture(u_shadow_map, vec3(p.xy + u_pcf_radius * disc[i], p.z - 0.001));
    lit = sum / 16.0;
  }
  vec3 c = u_floor * (1.0 - u_strength * (1.0 - lit));
  float d = length(v_position.xz - u_centre.xz);
  c = mix(c, u_background, smoothstep(u_fade_start, u_fade_end, d));
  frag_colour = vec4(pow(clamp(c, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
)";

// Depth only, from the light.
constexpr const char* kDepthVertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
uniform mat4 u_view_projection;
void main() { gl_Position = u_view_projection * vec4(a_position, 1.0); }
)";

constexpr const char* kDepthFragment = R"(#version 330 core
void main() {}
)";

// ---- [math] -------------------------------------------------------------------

Vec3f to_vec(const std::array<double, 3>& a) {
  return {static_cast<float>(a[0]), static_cast<float>(a[1]), static_cast<float>(a[2])};
}

Mat4 look_at(const Vec3f& eye, const Vec3f& target, const Vec3f& up_hint) {
  const Vec3f f = (target - eye).normalized();
  const Vec3f s = f.cross(up_hint).normalized();
  const Vec3f u = s.cross(f);
  Mat4 m = Mat4::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m;
}

Mat4 perspective(float fov_y_rad, float aspect, float near, float far) {
  const float t = 1.0f / std::tan(fov_y_rad / 2);
  Mat4 m = Mat4::Zero();
  m(0, 0) = t / aspect;
  m(1, 1) = t;
  m(2, 2) = (far + near) / (near - far);
  m(2, 3) = 2 * far * near / (near - far);
  m(3, 2) = -1;
  return m;
}

Mat4 orthographic(float half_w, float half_h, float near, float far) {
  Mat4 m = Mat4::Identity();
  m(0, 0) = 1 / half_w;
  m(1, 1) = 1 / half_h;
  m(2, 2) = -2 / (far - near);
  m(2, 3) = -(far + near) / (far - near);
  return m;
}

float linear(float srgb) { return std::pow(std::clamp(srgb, 0.0f, 1.0f), 2.2f); }

struct GpuMesh {
  GLuint vao = 0, vbo = 0, ebo = 0;
  GLsizei indices = 0;
  GLuint texture = 0;  // 0 = flat colour; owned by Renderer::Impl::textures
  Colour colour;
  MeshKind kind = MeshKind::garment;
};

// The light that casts the floor shadow: from above, a little from the front
// and the body's left, fixed in the world so every view shows the same shadow.
const Vec3f kShadowLight = Vec3f(0.08f, 1.0f, 0.15f).normalized();

}  // namespace

// ---- [gl] ---------------------------------------------------------------------

std::string gl::Functions::load(Renderer::ProcLoader loader) {
#define VGD_GL_LOAD(type, name)                                              \
  name = reinterpret_cast<type>(loader("gl" #name));                         \
  if (!name) return "gl" #name;
  VGD_GL_FUNCTIONS(VGD_GL_LOAD)
#undef VGD_GL_LOAD
  return {};
}

struct Renderer::Impl {
  gl::Functions gl;
  GLuint mesh_program = 0, textured_program = 0, floor_program = 0, depth_program = 0;
  std::vector<GpuMesh> meshes;
  std::vector<GLuint> textures;
  GLuint floor_vao = 0, floor_vbo = 0;
  GLuint shadow_fbo = 0, shadow_texture = 0;
  int shadow_size = 0;
  GLuint view_fbo = 0, view_texture = 0, view_depth = 0;  // draw_to_texture's target
  int view_w = 0, view_h = 0;
  Box scene_box, body_box;

  GLuint compile(GLenum kind, const char* source) {
    const GLuint s = gl.CreateShader(kind);
    gl.ShaderSource(s, 1, &source, nullptr);
    gl.CompileShader(s);
    GLint ok = 0;
    gl.GetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      char log[2048] = {0};
      gl.GetShaderInfoLog(s, sizeof log, nullptr, log);
      detail::assert_fail("shader compiles", log, __FILE__, __LINE__);
    }
    return s;
  }

  GLuint program(const char* vertex, const char* fragment) {
    const GLuint vs = compile(GL_VERTEX_SHADER, vertex), fs = compile(GL_FRAGMENT_SHADER, fragment);
    const GLuint p = gl.CreateProgram();
    gl.AttachShader(p, vs);
    gl.AttachShader(p, fs);
    gl.LinkProgram(p);
    gl.DeleteShader(vs);
    gl.DeleteShader(fs);
    GLint ok = 0;
    gl.GetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
      char log[2048] = {0};
      gl.GetProgramInfoLog(p, sizeof log, nullptr, log);
      detail::assert_fail("program links", log, __FILE__, __LINE__);
    }
    return p;
  }

  GLint uniform(GLuint p, const char* name) { return gl.GetUniformLocation(p, name); }
  void set(GLuint p, const char* name, const Mat4& m) { gl.UniformMatrix4fv(uniform(p, name), 1, GL_FALSE, m.data()); }
  void set(GLuint p, const char* name, const Vec3f& v) { gl.Uniform3f(uniform(p, name), v.x(), v.y(), v.z()); }
  void set(GLuint p, const char* name, float v) { gl.Uniform1f(uniform(p, name), v); }
  void set_linear(GLuint p, const char* name, const Colour& c) {
    gl.Uniform3f(uniform(p, name), linear(c.r), linear(c.g), linear(c.b));
  }

  void release_meshes() {
    for (auto& m : meshes) {
      gl.DeleteVertexArrays(1, &m.vao);
      gl.DeleteBuffers(1, &m.vbo);
      gl.DeleteBuffers(1, &m.ebo);
    }
    meshes.clear();
    for (GLuint t : textures) gl.DeleteTextures(1, &t);
    textures.clear();
  }

  // A texture with its mipmaps: sRGB storage (so filtering and mipmaps average
  // light, not gamma-encoded values), repeated in both directions. RGBA8 rows
  // are 4-byte aligned, so the default unpack alignment fits.
  GLuint upload_texture(const Image& image) {
    GLuint t = 0;
    gl.GenTextures(1, &t);
    gl.BindTexture(GL_TEXTURE_2D, t);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_SRGB8_ALPHA8, image.width, image.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                  image.rgba.data());
    gl.GenerateMipmap(GL_TEXTURE_2D);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    textures.push_back(t);
    return t;
  }

  // The shadow map's depth texture and framebuffer, (re)made at this size.
  void ensure_shadow_map(int size) {
    if (shadow_size == size) return;
    if (shadow_fbo) gl.DeleteFramebuffers(1, &shadow_fbo);
    if (shadow_texture) gl.DeleteTextures(1, &shadow_texture);
    gl.GenTextures(1, &shadow_texture);
    gl.BindTexture(GL_TEXTURE_2D, shadow_texture);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, size, size, 0, GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
    const float border[4] = {1, 1, 1, 1};  // outside the map: lit
    gl.TexParameterfv(GL_TEXTURE_2D, GL_TEXTURE_BORDER_COLOR, border);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    gl.GenFramebuffers(1, &shadow_fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, shadow_fbo);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, shadow_texture, 0);
    gl.DrawBuffer(GL_NONE);
    gl.ReadBuffer(GL_NONE);
    VGD_ASSERT(gl.CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE,
               "the shadow-map framebuffer is incomplete");
    shadow_size = size;
  }

  // The light's view-projection: an orthographic box round the scene's bounding sphere.
  Mat4 light_view_projection(const Box& box, float margin) const {
    const Vec3f centre = 0.5f * (to_vec(box.min) + to_vec(box.max));
    const float r = 0.5f * (to_vec(box.max) - to_vec(box.min)).norm() + margin;
    const Vec3f eye = centre + 2 * r * kShadowLight;
    const Mat4 view = look_at(eye, centre, Vec3f(0, 0, -1));  // kShadowLight is far from -Z
    return orthographic(r, r, 0.01f * r, 4 * r) * view;
  }

  // The depth pass draws every mesh with `depth_program`; the lit pass picks
  // the flat or the textured mesh program for each mesh.
  void draw_meshes(bool lit) {
    GLuint current = lit ? 0 : depth_program;
    for (const auto& m : meshes) {
      if (lit) {
        const GLuint p = m.texture ? textured_program : mesh_program;
        if (p != current) gl.UseProgram(current = p);
        set_linear(p, "u_colour", m.colour);
        const bool body = m.kind == MeshKind::body;
        set(p, "u_specular", body ? 0.12f : 0.04f);
        set(p, "u_shininess", body ? 24.0f : 12.0f);
        if (m.texture) {
          gl.ActiveTexture(GL_TEXTURE1);
          gl.BindTexture(GL_TEXTURE_2D, m.texture);
          gl.Uniform1i(uniform(p, "u_texture"), 1);
        }
      }
      gl.BindVertexArray(m.vao);
      gl.DrawElements(GL_TRIANGLES, m.indices, GL_UNSIGNED_INT, nullptr);
    }
  }
};

Renderer::Renderer(ProcLoader loader) : impl_(std::make_unique<Impl>()) {
  VGD_ASSERT(loader != nullptr, "the Renderer needs a GL function loader");
  const std::string missing = impl_->gl.load(loader);
  if (!missing.empty()) throw Error("", "OpenGL", "the context lacks " + missing + " (OpenGL 3.3 core is needed)");
  auto& I = *impl_;
  I.mesh_program = I.program(mesh_source(kMeshVertex, false).c_str(), mesh_source(kMeshFragment, false).c_str());
  I.textured_program = I.program(mesh_source(kMeshVertex, true).c_str(), mesh_source(kMeshFragment, true).c_str());
  I.floor_program = I.program(kFloorVertex, kFloorFragment);
  I.depth_program = I.program(kDepthVertex, kDepthFragment);
  I.gl.GenVertexArrays(1, &I.floor_vao);
  I.gl.GenBuffers(1, &I.floor_vbo);
}

Renderer::~Renderer() {
  auto& I = *impl_;
  I.release_meshes();
  I.gl.DeleteVertexArrays(1, &I.floor_vao);
  I.gl.DeleteBuffers(1, &I.floor_vbo);
  if (I.shadow_fbo) I.gl.DeleteFramebuffers(1, &I.shadow_fbo);
  if (I.shadow_texture) I.gl.DeleteTextures(1, &I.shadow_texture);
  if (I.view_fbo) I.gl.DeleteFramebuffers(1, &I.view_fbo);
  if (I.view_texture) I.gl.DeleteTextures(1, &I.view_texture);
  if (I.view_depth) I.gl.DeleteRenderbuffers(1, &I.view_depth);
  I.gl.DeleteProgram(I.mesh_program);
  I.gl.DeleteProgram(I.textured_program);
  I.gl.DeleteProgram(I.floor_program);
  I.gl.DeleteProgram(I.depth_program);
}

// ---- [scene] ------------------------------------------------------------------

void Renderer::set_scene(const Scene& input) {
  check_scene(input);
  Scene scene = input;
  compute_normals(scene);
  auto& I = *impl_;
  auto& gl = I.gl;
  I.release_meshes();
  I.scene_box = bounds(scene);
  I.body_box = bounds(scene, MeshKind::body);

  // One VAO per mesh: interleaved position, normal, colour (linear RGB, white
  // unless the mesh has its own per vertex) and (textured meshes) texture
  // coordinate in repeats, 32-bit indices. Each texture is uploaded once.
  std::vector<std::pair<const Texture*, GLuint>> uploaded;
  for (const auto& m : scene.meshes) {
    if (m.triangles.empty()) continue;
    GpuMesh g;
    g.colour = m.colour;
    g.kind = m.kind;
    const Texture* tex = m.texture.get();
    if (tex) {
      auto it = std::find_if(uploaded.begin(), uploaded.end(), [&](const auto& u) { return u.first == tex; });
      g.texture = it != uploaded.end() ? it->second : uploaded.emplace_back(tex, I.upload_texture(tex->image)).second;
    }
    // Pattern metres to repeats, turned as the document says; t grows up the
    // image (row 0 on top at t = 0), hence -v.
    const double cr = std::cos(tex ? tex->rotation_rad : 0.0), sr = std::sin(tex ? tex->rotation_rad : 0.0);
    const int stride = tex ? 11 : 9;
    const bool coloured = m.vertex_colours.size() == m.positions.size();
    std::vector<float> vertices;
    vertices.reserve(m.positions.size() * static_cast<std::size_t>(stride));
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
      vertices.insert(vertices.end(), m.positions[v].begin(), m.positions[v].end());
      vertices.insert(vertices.end(), m.normals[v].begin(), m.normals[v].end());
      if (coloured) {
        const Colour& c = m.vertex_colours[v];
        vertices.insert(vertices.end(), {linear(c.r), linear(c.g), linear(c.b)});
      } else {
        vertices.insert(vertices.end(), {1.0f, 1.0f, 1.0f});
      }
      if (tex) {
        const double u = m.uv[v][0], w = m.uv[v][1];
        vertices.push_back(static_cast<float>((cr * u - sr * w) / tex->repeat_m[0]));
        vertices.push_back(static_cast<float>(-(sr * u + cr * w) / tex->repeat_m[1]));
      }
    }
    std::vector<GLuint> indices;
    indices.reserve(m.triangles.size() * 3);
    for (const auto& t : m.triangles)
      for (int k = 0; k < 3; ++k) indices.push_back(static_cast<GLuint>(t[k]));
    gl.GenVertexArrays(1, &g.vao);
    gl.BindVertexArray(g.vao);
    gl.GenBuffers(1, &g.vbo);
    gl.BindBuffer(GL_ARRAY_BUFFER, g.vbo);
    gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)), vertices.data(),
                  GL_STATIC_DRAW);
    gl.GenBuffers(1, &g.ebo);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.ebo);
    gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * sizeof(GLuint)), indices.data(),
                  GL_STATIC_DRAW);
    const GLsizei bytes = stride * static_cast<GLsizei>(sizeof(float));
    gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, bytes, nullptr);
    gl.EnableVertexAttribArray(0);
    gl.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, bytes, reinterpret_cast<void*>(3 * sizeof(float)));
    gl.EnableVertexAttribArray(1);
    gl.VertexAttribPointer(3, 3, GL_FLOAT, GL_FALSE, bytes, reinterpret_cast<void*>(6 * sizeof(float)));
    gl.EnableVertexAttribArray(3);
    if (tex) {
      gl.VertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, bytes, reinterpret_cast<void*>(9 * sizeof(float)));
      gl.EnableVertexAttribArray(2);
    }
    g.indices = static_cast<GLsizei>(indices.size());
    I.meshes.push_back(g);
  }

  // The floor: a square under the lowest point, wide enough to fade out before its edges.
  if (!I.scene_box.empty()) {
    const Vec3f lo = to_vec(I.scene_box.min), hi = to_vec(I.scene_box.max);
    const Vec3f c = 0.5f * (lo + hi);
    const float r = 20 * std::max(0.5f * (hi - lo).norm(), 0.01f);
    const float y = lo.y() - 1e-3f * std::max(hi.y() - lo.y(), 0.01f);
    const float quad[] = {c.x() - r, y, c.z() - r, c.x() + r, y, c.z() - r, c.x() + r, y, c.z() + r,
                          c.x() - r, y, c.z() - r, c.x() + r, y, c.z() + r, c.x() - r, y, c.z() + r};
    gl.BindVertexArray(I.floor_vao);
    gl.BindBuffer(GL_ARRAY_BUFFER, I.floor_vbo);
    gl.BufferData(GL_ARRAY_BUFFER, sizeof quad, quad, GL_STATIC_DRAW);
    gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
    gl.EnableVertexAttribArray(0);
  }
  gl.BindVertexArray(0);
}

const Box& Renderer::scene_bounds() const { return impl_->scene_box; }
const Box& Renderer::body_bounds() const { return impl_->body_box; }

// ---- [draw] -------------------------------------------------------------------

void Renderer::draw(const Camera& camera, const Target& target, const RenderOptions& options) {
  VGD_ASSERT(target.width > 0 && target.height > 0, "the target must have a positive size");
  auto& I = *impl_;
  auto& gl = I.gl;
  const bool have_scene = !I.scene_box.empty();
  const bool shadow = options.floor && options.shadow && have_scene && !I.meshes.empty();
  gl.Enable(GL_DEPTH_TEST);
  gl.DepthFunc(GL_LESS);
  gl.DepthMask(GL_TRUE);
  gl.Disable(GL_CULL_FACE);
  gl.Disable(GL_BLEND);

  // 1. Shadow pass: depth of every mesh as the overhead light sees it.
  Mat4 light_vp = Mat4::Identity();
  if (shadow) {
    I.ensure_shadow_map(std::max(64, options.shadow_map_size));
    light_vp = I.light_view_projection(I.scene_box, options.shadow_softness_m);
    gl.BindFramebuffer(GL_FRAMEBUFFER, I.shadow_fbo);
    gl.Viewport(0, 0, I.shadow_size, I.shadow_size);
    gl.ClearDepth(1.0);
    gl.Clear(GL_DEPTH_BUFFER_BIT);
    gl.UseProgram(I.depth_program);
    I.set(I.depth_program, "u_view_projection", light_vp);
    I.draw_meshes(false);
  }

  // 2. The target: background, then the floor, then the meshes.
  gl.BindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
  gl.Viewport(0, 0, target.width, target.height);
  gl.ClearColor(options.background.r, options.background.g, options.background.b, 1.0f);
  gl.ClearDepth(1.0);
  gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (!have_scene) return;

  const Vec3f eye = to_vec(camera.eye), look = to_vec(camera.target), up = to_vec(camera.up);
  const float aspect = static_cast<float>(target.width) / static_cast<float>(target.height);
  const float fov = static_cast<float>(camera.fov_y_deg * 3.14159265358979323846 / 180.0);
  const Mat4 vp = perspective(fov, aspect, static_cast<float>(camera.near_m), static_cast<float>(camera.far_m)) *
                  look_at(eye, look, up);

  if (options.floor) {
    const Vec3f lo = to_vec(I.scene_box.min), hi = to_vec(I.scene_box.max);
    const float radius = std::max(0.5f * (hi - lo).norm(), 0.01f);
    const float map_radius = radius + options.shadow_softness_m;
    const GLuint p = I.floor_program;
    gl.UseProgram(p);
    I.set(p, "u_view_projection", vp);
    I.set(p, "u_light_view_projection", light_vp);
    gl.Uniform1i(I.uniform(p, "u_use_shadow"), shadow ? 1 : 0);
    gl.Uniform1i(I.uniform(p, "u_shadow_map"), 0);
    I.set(p, "u_pcf_radius", 0.5f * options.shadow_softness_m / (2 * map_radius));
    I.set(p, "u_strength", std::clamp(options.shadow_strength, 0.0f, 1.0f));
    I.set(p, "u_centre", Vec3f(0.5f * (lo + hi)));
    I.set(p, "u_fade_start", 0.9f * radius);
    I.set(p, "u_fade_end", 3.0f * radius);
    I.set_linear(p, "u_floor", options.floor_colour);
    I.set_linear(p, "u_background", options.background);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, shadow ? I.shadow_texture : 0);
    gl.BindVertexArray(I.floor_vao);
    gl.DrawArrays(GL_TRIANGLES, 0, 6);
  }

  // Lights follow the camera: the key from above and to the left, a fill from the right.
  const Vec3f toward = (eye - look).normalized();
  const Vec3f right = (-toward).cross(up).normalized();
  const Vec3f cam_up = right.cross(-toward);
  for (const GLuint p : {I.textured_program, I.mesh_program}) {
    gl.UseProgram(p);
    I.set(p, "u_view_projection", vp);
    I.set(p, "u_eye", eye);
    I.set(p, "u_key", Vec3f(-0.45f * right + 0.60f * cam_up + 0.70f * toward).normalized());
    I.set(p, "u_fill", Vec3f(0.70f * right + 0.05f * cam_up + 0.70f * toward).normalized());
  }
  I.draw_meshes(true);
  gl.ActiveTexture(GL_TEXTURE0);
  gl.BindVertexArray(0);
}

std::string Renderer::gl_description() const {
  auto str = [&](GLenum e) {
    const GLubyte* s = impl_->gl.GetString(e);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return "OpenGL " + str(GL_VERSION) + ", " + str(GL_RENDERER);
}

unsigned Renderer::draw_to_texture(const Camera& camera, int width, int height, const RenderOptions& options) {
  VGD_ASSERT(width > 0 && height > 0, "the texture must have a positive size");
  auto& I = *impl_;
  auto& gl = I.gl;
  GLint bound = 0;
  gl.GetIntegerv(GL_FRAMEBUFFER_BINDING, &bound);
  if (!I.view_fbo || I.view_w != width || I.view_h != height) {
    if (!I.view_texture) gl.GenTextures(1, &I.view_texture);
    gl.BindTexture(GL_TEXTURE_2D, I.view_texture);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    if (!I.view_depth) gl.GenRenderbuffers(1, &I.view_depth);
    gl.BindRenderbuffer(GL_RENDERBUFFER, I.view_depth);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
    if (!I.view_fbo) gl.GenFramebuffers(1, &I.view_fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, I.view_fbo);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, I.view_texture, 0);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, I.view_depth);
    const GLenum status = gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
    gl.BindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(bound));
    if (status != GL_FRAMEBUFFER_COMPLETE)
      throw Error("", "OpenGL", "cannot make a " + std::to_string(width) + " x " + std::to_string(height) +
                                    " framebuffer to draw the view in");
    I.view_w = width, I.view_h = height;
  }
  draw(camera, {I.view_fbo, width, height}, options);
  gl.BindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(bound));
  return I.view_texture;
}

}  // namespace vgd::render
