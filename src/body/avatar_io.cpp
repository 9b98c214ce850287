// Avatar import and export (avatar_io.hpp): files read and written through
// the assimp module (model_file.hpp), normalised here.
#include "vgd/body/avatar_io.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>

#include "vgd/body/model_file.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/core/units.hpp"

namespace vgd::body {

namespace fs = std::filesystem;

namespace {

// Rotation taking the file's up direction to +Y (a proper rotation: det = +1).
Eigen::Matrix3d up_rotation(const std::string& up) {
  Eigen::Matrix3d r;
  if (up == "y") r.setIdentity();
  else if (up == "-y") r << 1, 0, 0, 0, -1, 0, 0, 0, -1;
  else if (up == "z") r << 1, 0, 0, 0, 0, 1, 0, -1, 0;   // (x, y, z) -> (x, z, -y)
  else if (up == "-z") r << 1, 0, 0, 0, 0, -1, 0, 1, 0;  // (x, y, z) -> (x, -z, y)
  else if (up == "x") r << 0, -1, 0, 1, 0, 0, 0, 0, 1;   // (x, y, z) -> (-y, x, z)
  else r << 0, 1, 0, -1, 0, 0, 0, 0, 1;                  // -x: (x, y, z) -> (y, -x, z)
  return r;
}

Eigen::Matrix3d facing_rotation(const std::string& facing) {
  Eigen::Matrix3d r;
  if (facing == "+z" || facing == "z") r.setIdentity();
  else if (facing == "-z") r << -1, 0, 0, 0, 1, 0, 0, 0, -1;
  else if (facing == "+x" || facing == "x") r << 0, 0, -1, 0, 1, 0, 1, 0, 0;  // +X -> +Z
  else r << 0, 0, 1, 0, 1, 0, -1, 0, 0;                                       // -X -> +Z
  return r;
}

int axis_index(const std::string& up) { return up.back() == 'x' ? 0 : up.back() == 'y' ? 1 : 2; }

std::optional<double> metadata_number(const ModelFile& f, const char* key) {
  const auto it = f.metadata.find(key);
  if (it == f.metadata.end()) return std::nullopt;
  return it->second;
}

// A mesh of helper geometry rather than body: MakeHuman's base mesh carries
// proxies for clothes, eyes and joints ("helper-tights", "joint-l-knee").
bool helper_mesh(const ModelMesh& m) {
  for (const std::string& n : {to_lower(m.name), to_lower(m.node)})
    if (n.find("helper") != std::string::npos || n.rfind("joint-", 0) == 0 || n.rfind("joint_", 0) == 0) return true;
  return false;
}

double triangle_area(const mesh::SurfaceMesh& s, const std::array<int, 3>& t) {
  return 0.5 * (s.vertices[t[1]] - s.vertices[t[0]]).cross(s.vertices[t[2]] - s.vertices[t[0]]).norm();
}

// Connected parts of a mesh (triangles sharing a vertex), their triangle
// lists, largest area first.
std::vector<std::vector<int>> connected_parts(const mesh::SurfaceMesh& s) {
  std::vector<int> parent(s.vertices.size());
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<int>(i);
  std::function<int(int)> find = [&](int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  for (const auto& t : s.triangles)
    for (int k = 1; k < 3; ++k) parent[find(t[k])] = find(t[0]);
  std::map<int, std::vector<int>> by_root;
  for (int i = 0; i < s.num_triangles(); ++i) by_root[find(s.triangles[i][0])].push_back(i);
  std::vector<std::pair<double, std::vector<int>>> parts;
  for (auto& [root, tris] : by_root) {
    double a = 0;
    for (int i : tris) a += triangle_area(s, s.triangles[i]);
    parts.emplace_back(a, std::move(tris));
  }
  std::sort(parts.begin(), parts.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  std::vector<std::vector<int>> out;
  for (auto& p : parts) out.push_back(std::move(p.second));
  return out;
}

// The up direction the body itself shows, if it shows one clearly. The axis:
// the one along which the surface is spread furthest (area-weighted standard
// deviation of the triangles' centres), which a T-pose's arm span does not
// beat (arms are a small share of the area, the legs and trunk spread along
// the height). The sign: the feet end's slice, 4 % in, cuts two loops (the
// legs), the head end's one.
struct UpFromBody {
  std::string up;      // "" when unclear
  std::string reason;
};
UpFromBody up_from_body(const mesh::SurfaceMesh& s) {
  Vec3 mean = Vec3::Zero();
  double total = 0;
  std::vector<std::pair<Vec3, double>> centres;
  centres.reserve(s.triangles.size());
  for (const auto& t : s.triangles) {
    const double a = triangle_area(s, t);
    const Vec3 c = (s.vertices[t[0]] + s.vertices[t[1]] + s.vertices[t[2]]) / 3.0;
    centres.emplace_back(c, a);
    mean += a * c, total += a;
  }
  if (!(total > 0)) return {};
  mean /= total;
  Vec3 var = Vec3::Zero();
  for (const auto& [c, a] : centres) var += a * (c - mean).cwiseAbs2();
  const Vec3 sd = (var / total).cwiseSqrt();
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (sd[i] > sd[k]) k = i;
  double second = 0;
  for (int i = 0; i < 3; ++i)
    if (i != k) second = std::max(second, sd[i]);
  if (sd[k] < 1.15 * second) return {};  // no axis stands out
  const std::string axis(1, "xyz"[k]);
  // Slices across the axis, near each end.
  mesh::SurfaceMesh m = s;
  mesh::transform(m, up_rotation(axis));
  const mesh::Box3 b = mesh::bounding_box(m);
  const double h = b.size().y();
  auto loops_at = [&](double y) {
    int n = 0;
    for (const auto& l : mesh::slice_horizontal(m, y))
      if (l.size() > 2) ++n;
    return n;
  };
  const int low = loops_at(b.min.y() + 0.04 * h), high = loops_at(b.max.y() - 0.04 * h);
  const std::string spread = "the body's surface spreads furthest along " + axis;
  if (low >= 2 && high == 1) return {axis, spread + ", the legs at its low end"};
  if (high >= 2 && low == 1) return {"-" + axis, spread + ", the legs at its high end"};
  return {};
}

// Where the body faces, from its feet: the soles' centre (lowest 3 % of the
// height) lies forward of the ankles' (5–9 %). Needs +Y up; "" when unclear.
std::string facing_from_feet(const mesh::SurfaceMesh& s) {
  const mesh::Box3 b = mesh::bounding_box(s);
  const double h = b.size().y();
  Vec3 sole = Vec3::Zero(), ankle = Vec3::Zero();
  double ws = 0, wa = 0;
  for (const auto& t : s.triangles) {
    const Vec3 c = (s.vertices[t[0]] + s.vertices[t[1]] + s.vertices[t[2]]) / 3.0;
    const double f = (c.y() - b.min.y()) / h, a = triangle_area(s, t);
    if (f < 0.03) sole += a * c, ws += a;
    else if (f > 0.05 && f < 0.09) ankle += a * c, wa += a;
  }
  if (!(ws > 0 && wa > 0)) return "";
  const Vec3 d = sole / ws - ankle / wa;
  const double dx = d.x(), dz = d.z();
  if (std::hypot(dx, dz) < 0.01 * h) return "";  // the feet point nowhere in particular
  if (std::abs(dz) >= std::abs(dx)) return dz > 0 ? "+z" : "-z";
  return dx > 0 ? "+x" : "-x";
}

// glTF's external buffers that are not there (a .gltf whose .bin was not copied).
std::vector<std::string> missing_gltf_buffers(const fs::path& path) {
  std::vector<std::string> missing;
  try {
    const auto j = nlohmann::json::parse(read_file(path));
    if (!j.contains("buffers") || !j["buffers"].is_array()) return missing;
    for (const auto& b : j["buffers"])
      if (b.contains("uri") && b["uri"].is_string()) {
        const std::string uri = b["uri"].get<std::string>();
        if (uri.rfind("data:", 0) == 0) continue;
        std::error_code ec;
        if (!fs::exists(path.parent_path() / uri, ec)) missing.push_back(uri);
      }
  } catch (const std::exception&) {
    // not JSON: assimp says what is wrong with it
  }
  return missing;
}

mesh::SurfaceCheck fill_check(AvatarReport& r, const mesh::SurfaceMesh& s) {
  const auto c = mesh::check_surface(s);
  r.vertices = c.vertices, r.triangles = c.triangles;
  r.box = mesh::bounding_box(s);
  r.height = r.box.size().y();
  r.watertight = c.watertight();
  r.boundary_edges = c.boundary_edges, r.non_manifold_edges = c.non_manifold_edges;
  r.inconsistent_edges = c.inconsistent_edges, r.degenerate_triangles = c.degenerate_triangles;
  r.area = c.area, r.volume = c.volume;
  return c;
}

// The outermost loop around p (a model's inner shells may enclose it too), or -1.
int loop_around(const std::vector<std::vector<mesh::Vec2d>>& loops, const mesh::Vec2d& p) {
  int best = -1;
  double best_area = 0;
  for (std::size_t i = 0; i < loops.size(); ++i)
    if (loops[i].size() > 2 && mesh::point_in_polygon(loops[i], p))
      if (const double a = mesh::loop_area(loops[i]); a > best_area) best_area = a, best = static_cast<int>(i);
  return best;
}

SegmentRing ring_of(const std::vector<mesh::Vec2d>& loop, double y, double s) {
  mesh::Vec2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const auto& q : loop) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  SegmentRing r;
  r.s = s;
  r.centre = Vec3(0.5 * (lo.x() + hi.x()), y, 0.5 * (lo.y() + hi.y()));
  r.half_width = 0.5 * (hi.x() - lo.x());
  r.half_depth = 0.5 * (hi.y() - lo.y());
  return r;
}

}  // namespace

std::vector<BodySegment> segments_from_slices(const mesh::SurfaceMesh& surface, const BodyLandmarks* landmarks) {
  std::vector<BodySegment> out;
  const mesh::Box3 box = mesh::bounding_box(surface);
  const double H = box.size().y(), y0 = box.min.y();
  if (H <= 0) return out;
  const mesh::Vec2d centre = trunk_centre(surface);
  // Crotch: the lowest height (from 30 % up) whose slice has a loop around the centre line.
  double crotch = -1;
  for (double f = 0.30; f < 0.60; f += 0.0025)
    if (loop_around(mesh::slice_horizontal(surface, y0 + f * H), centre) >= 0) {
      crotch = y0 + f * H;
      break;
    }
  if (crotch < 0) return out;
  auto trunk = [&](const std::string& name, double ya, double yb, int n) {
    BodySegment s;
    s.name = name;
    for (int i = 0; i <= n; ++i) {
      const double y = ya + (yb - ya) * i / n;
      const auto loops = mesh::slice_horizontal(surface, y);
      const int k = loop_around(loops, centre);
      if (k < 0) return;
      SegmentRing r = ring_of(loops[k], y, y - ya);
      // A slice that takes in an arm (at the shoulders, an arm hanging
      // against the flank) is no wider than the trunk below it.
      if (!s.rings.empty() && r.half_width > 1.25 * s.rings.back().half_width) {
        const SegmentRing& prev = s.rings.back();
        r.half_width = prev.half_width;
        r.centre.x() = prev.centre.x();
      }
      s.rings.push_back(r);
    }
    s.start = Vec3(s.rings.front().centre.x(), ya, s.rings.front().centre.z());
    s.length = yb - ya;
    out.push_back(std::move(s));
  };
  // The landmarks measured on the body, else proportions of an adult body
  // (fractions of the height above the floor).
  double waist = y0 + 0.62 * H, shoulder = y0 + 0.80 * H;
  if (landmarks && landmarks->waist > 0 && landmarks->shoulder > landmarks->waist)
    waist = y0 + landmarks->waist, shoulder = y0 + landmarks->shoulder;
  if (landmarks && landmarks->crotch > 0) crotch = y0 + landmarks->crotch;
  trunk("hips", crotch + 0.01 * H, waist, 8);
  trunk("torso", waist, shoulder, 8);
  // The neck from its base, 3 % of the height above the shoulders (as on the
  // mannequin), when the shoulders were measured.
  const double neck = landmarks && landmarks->shoulder > 0 ? shoulder + 0.03 * H : y0 + 0.835 * H;
  trunk("neck", neck, neck + 0.03 * H, 3);
  // Legs: the two largest loops below the crotch, left (+X) and right.
  for (int side = 0; side < 2; ++side) {
    BodySegment s;
    s.name = side == 0 ? "left-leg" : "right-leg";
    const double ya = crotch - 0.02 * H, yb = y0 + 0.06 * H;
    const int n = 10;
    for (int i = 0; i <= n; ++i) {
      const double y = ya + (yb - ya) * i / n;
      const auto loops = mesh::slice_horizontal(surface, y);
      int best = -1;
      double best_area = 0;
      for (std::size_t k = 0; k < loops.size(); ++k) {
        double cx = 0;
        for (const auto& q : loops[k]) cx += q.x();
        cx /= std::max<std::size_t>(loops[k].size(), 1);
        if ((side == 0) != (cx > centre.x())) continue;
        if (const double a = mesh::loop_area(loops[k]); a > best_area) best_area = a, best = static_cast<int>(k);
      }
      if (best < 0) break;
      s.rings.push_back(ring_of(loops[best], y, 0));
    }
    if (s.rings.size() != n + 1) continue;
    s.start = s.rings.front().centre;
    const Vec3 end = s.rings.back().centre;
    s.length = (end - s.start).norm();
    s.axis = (end - s.start).normalized();
    s.front = (Vec3::UnitZ() - Vec3::UnitZ().dot(s.axis) * s.axis).normalized();
    for (auto& r : s.rings) r.s = std::clamp((r.centre - s.start).dot(s.axis), 0.0, s.length);
    s.rings.front().s = 0, s.rings.back().s = s.length;
    out.push_back(std::move(s));
  }
  return out;
}

Avatar import_avatar(const fs::path& path, const AvatarImportOptions& o, AvatarReport* report_out) {
  const std::string file = path.string();
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error(file, "", "no such file");
  if (fs::is_directory(path, ec)) throw Error(file, "", "is a directory, not a 3-D model file");
  if (fs::file_size(path, ec) == 0) throw Error(file, "", "the file is empty");
  const std::string unit_opt = to_lower(o.unit), up_opt = to_lower(o.up), facing_opt = to_lower(o.facing);
  if (unit_opt != "auto" && !parse_length_unit(unit_opt))
    throw Error(file, "unit", "unknown unit '" + o.unit + "' (auto, m, cm, mm, in)");
  static const std::vector<std::string> ups{"auto", "x", "y", "z", "-x", "-y", "-z", "+x", "+y", "+z"};
  if (std::find(ups.begin(), ups.end(), up_opt) == ups.end())
    throw Error(file, "up", "unknown up axis '" + o.up + "' (auto, x, y, z, -x, -y, -z)");
  static const std::vector<std::string> facings{"auto", "+z", "-z", "+x", "-x", "z", "x"};
  if (std::find(facings.begin(), facings.end(), facing_opt) == facings.end())
    throw Error(file, "facing", "unknown facing '" + o.facing + "' (auto, +z, -z, +x, -x)");

  AvatarReport r;
  r.file = file;
  r.format = to_lower(path.extension().string());
  if (!r.format.empty() && r.format.front() == '.') r.format.erase(0, 1);
  const bool gltf = r.format == "gltf" || r.format == "glb";
  if (r.format == "gltf")
    if (const auto missing = missing_gltf_buffers(path); !missing.empty())
      throw Error(file, "buffers", "the glTF file keeps its data in " + missing.front() +
                                       ", which is not beside it (" + (path.parent_path() / missing.front()).string() +
                                       "): copy the .bin files with the .gltf, or export a single .glb");

  ModelReadOptions ro;
  ro.bind_pose = gltf;  // glTF: a skinned mesh ignores its node's transform
  ro.time_limit_s = o.read_time_limit_s;
  ModelFile model = read_model_file(path, ro);
  mesh::SurfaceMesh& s = model.surface;
  r.dropped_primitives = model.dropped;
  if (s.triangles.empty())
    throw Error(file, "", "the file holds no triangles" + std::string(model.dropped ? " (only points or lines)" : ""));
  for (int i = 0; i < s.num_vertices(); ++i)
    if (!s.vertices[i].allFinite())
      throw Error(file, "vertex " + std::to_string(i + 1),
                  "has a coordinate that is not a finite number (NaN or infinity): the file is corrupt");
  if (std::any_of(model.meshes.begin(), model.meshes.end(), [](const ModelMesh& m) { return m.skinned; }) && gltf)
    r.notes.push_back("skinned meshes taken in their bind pose (glTF: the node transform of a skinned mesh is ignored)");

  // ---- the body: helper meshes and loose small parts left out ----
  if (o.human) {
    std::vector<char> keep(s.triangles.size(), 1);
    std::vector<std::string> helpers;
    for (const auto& m : model.meshes)
      if (helper_mesh(m) && m.triangles < s.num_triangles()) {
        std::fill_n(keep.begin() + m.first_triangle, m.triangles, 0);
        helpers.push_back(m.name.empty() ? m.node : m.name);
      }
    int kept_meshes = 0;
    for (const auto& m : model.meshes) kept_meshes += !helper_mesh(m) || m.triangles == s.num_triangles();
    r.meshes = kept_meshes;
    if (!helpers.empty()) {
      std::string list;
      for (std::size_t i = 0; i < helpers.size() && i < 6; ++i) list += (i ? ", " : "") + helpers[i];
      r.notes.push_back("left out " + std::to_string(helpers.size()) + " helper mesh" + (helpers.size() > 1 ? "es" : "") +
                        " (" + list + (helpers.size() > 6 ? ", ..." : "") + ")");
    }
    mesh::SurfaceMesh body;
    body.vertices = s.vertices;
    for (int i = 0; i < s.num_triangles(); ++i)
      if (keep[i]) body.triangles.push_back(s.triangles[i]);
    // Parts not touching the body (eyes, teeth, hair, loose props): a part
    // under 5 % of the largest one's area is left out.
    const mesh::Box3 box = mesh::bounding_box(body);
    mesh::SurfaceMesh welded = body;
    mesh::weld_vertices(welded, 1e-7 * box.size().norm());
    const auto parts = connected_parts(welded);
    if (parts.size() > 1) {
      std::vector<double> area;
      for (const auto& p : parts) {
        double a = 0;
        for (int i : p) a += triangle_area(welded, welded.triangles[i]);
        area.push_back(a);
      }
      std::vector<char> keep_body(body.triangles.size(), 0);
      int left_out = 0;
      double left_area = 0;
      for (std::size_t k = 0; k < parts.size(); ++k) {
        if (area[k] < 0.05 * area[0]) {
          ++left_out, left_area += area[k];
          continue;
        }
        for (int i : parts[k]) keep_body[i] = 1;
      }
      if (left_out > 0) {
        mesh::SurfaceMesh kept;
        kept.vertices = body.vertices;
        for (int i = 0; i < body.num_triangles(); ++i)
          if (keep_body[i]) kept.triangles.push_back(body.triangles[i]);
        body = std::move(kept);
        r.notes.push_back("left out " + std::to_string(left_out) + " loose part" + (left_out > 1 ? "s" : "") +
                          " smaller than 5 % of the body (" + format_fixed(100.0 * left_area / area[0], 1) +
                          " % of its area together: eyes, teeth, hair or props)");
      }
    }
    s = std::move(body);
  }
  mesh::remove_unused_vertices(s);

  // ---- up axis ----
  std::string up = up_opt.front() == '+' ? up_opt.substr(1) : up_opt;
  if (up == "auto") {
    // The file's own word, where it has one.
    std::string meta_up, meta_reason;
    if (gltf) {
      meta_up = "y", meta_reason = "glTF is +Y up by specification";
    } else if (r.format == "dae") {
      meta_up = "y", meta_reason = "Collada up_axis applied by the importer";
    } else if (const auto ax = metadata_number(model, "UpAxis")) {
      const auto sign = metadata_number(model, "UpAxisSign").value_or(1.0);
      meta_up = std::string(sign < 0 ? "-" : "") + "xyz"[std::clamp(static_cast<int>(*ax), 0, 2)];
      meta_reason = "the file's UpAxis metadata";
    }
    // The body's word wins when it is clear: files lie (a body modelled
    // lying down, an armature's rotation, a converter's axis swap).
    const UpFromBody found = o.human ? up_from_body(s) : UpFromBody{};
    if (!found.up.empty()) {
      up = found.up;
      r.up_reason = found.reason;
      if (!meta_up.empty() && meta_up != found.up)
        r.notes.push_back("up axis " + found.up + " from the body itself, not " + meta_up + " (" + meta_reason + ")");
    } else if (!meta_up.empty()) {
      up = meta_up, r.up_reason = meta_reason;
    } else {
      // The longest extent, towards the side with more surface area.
      const Vec3 size = mesh::bounding_box(s).size();
      int k = 0;
      for (int i = 1; i < 3; ++i)
        if (size[i] > size[k]) k = i;
      const double mid = mesh::bounding_box(s).centre()[k];
      double above = 0, below = 0;
      for (const auto& t : s.triangles) {
        const Vec3 &a = s.vertices[t[0]], &b = s.vertices[t[1]], &c = s.vertices[t[2]];
        (((a[k] + b[k] + c[k]) / 3.0 > mid) ? above : below) += triangle_area(s, t);
      }
      up = std::string(above >= below ? "" : "-") + "xyz"[k];
      r.up_reason = "no metadata and no clear body axis: the longest extent, towards the side with more surface area";
    }
    r.up_guessed = meta_up.empty() || up != meta_up;
  } else {
    r.up_reason = "given";
  }
  r.up = up;

  // ---- unit ----
  const double raw_height = mesh::bounding_box(s).size()[axis_index(up)];
  if (!(raw_height > 0))
    throw Error(file, "", "the mesh is flat: zero height along the up axis (" + up + ")");
  {
    const Vec3 size = mesh::bounding_box(s).size();
    if ((size.array() <= 0).count() >= 2) throw Error(file, "", "the mesh is degenerate: it has no extent in two directions");
  }
  const auto human = [](double h) { return h >= 1.0 && h <= 2.3; };      // m: the unit guess
  const auto plausible = [](double h) { return h >= 0.5 && h <= 2.5; };  // m: anything else is no body
  const LengthUnit units[] = {LengthUnit::metre, LengthUnit::decimetre, LengthUnit::centimetre, LengthUnit::millimetre,
                              LengthUnit::inch};
  double metres = 1.0;
  if (unit_opt != "auto") {
    metres = metres_per(*parse_length_unit(unit_opt));
    r.unit = to_string(*parse_length_unit(unit_opt));
    r.unit_reason = "given";
    if (o.human && !plausible(raw_height * metres))
      throw Error(file, "unit", "the body is " + format_fixed(raw_height * metres, 3) + " m tall in " + r.unit +
                                    " (the unit given): not a human body (0.5–2.5 m)");
  } else {
    std::optional<double> meta;
    std::string meta_reason;
    if (gltf) meta = 1.0, meta_reason = "glTF is in metres by specification";
    else if (r.format == "dae") meta = 1.0, meta_reason = "Collada <unit> applied by the importer";
    else if (const auto f = metadata_number(model, "UnitScaleFactor"))
      meta = *f * 0.01, meta_reason = "the file's UnitScaleFactor metadata (" + format_double(*f) + " cm per unit)";
    if (meta && human(raw_height * *meta)) {
      metres = *meta;
      r.unit_reason = meta_reason;
    } else {
      // At most one of m, dm, cm, mm and in makes a height of 1.0–2.3 m (they
      // are at least 2.54 times apart).
      r.unit_guessed = true;
      LengthUnit best = LengthUnit::metre;
      double best_err = 1e300;
      for (const auto u : units) {
        const double h = raw_height * metres_per(u);
        const double err = human(h) ? 0.0 : std::abs(std::log(h / 1.7));
        if (err < best_err) best_err = err, best = u;
      }
      metres = metres_per(best);
      if (o.human && !plausible(raw_height * metres)) {
        std::string heights;
        for (const auto u : units)
          heights += std::string(heights.empty() ? "" : ", ") + format_fixed(raw_height * metres_per(u), 3) + " m in " +
                     to_string(u);
        throw Error(file, "", "not a human body: it is " + format_double(raw_height) + " units tall (" + heights +
                                  "); a body is 0.5–2.5 m tall (give --unit if the file's unit is unusual)");
      }
      r.unit_reason = std::string(best_err == 0 ? "a human is 1.0–2.3 m tall (m, dm, cm, mm and in considered)"
                                                : "closest to a human height (1.7 m)") +
                      (meta ? "; the metadata's unit gives " + format_fixed(raw_height * *meta, 3) + " m" : "");
      if (meta) r.notes.push_back("unit " + std::string(to_string(best)) + " from the body's height, not the file's (" +
                                  meta_reason + ": " + format_fixed(raw_height * *meta, 3) + " m tall)");
    }
    r.unit = "m";
    for (const auto u : units)
      if (metres_per(u) == metres) r.unit = to_string(u);
    if (r.unit == "m" && metres != 1.0) r.unit = format_double(metres) + " m";
  }

  // ---- facing ----
  std::string facing = facing_opt == "z" ? "+z" : facing_opt == "x" ? "+x" : facing_opt;
  if (facing == "auto" && !o.human) facing = "+z";
  if (facing == "auto") {
    mesh::SurfaceMesh upright = s;
    mesh::transform(upright, up_rotation(up));
    facing = facing_from_feet(upright);
    if (facing.empty()) {
      facing = "+z";
      r.facing_reason = "the feet show no direction: taken as facing +Z";
      r.facing_guessed = true;
    } else {
      r.facing_reason = "the feet point " + facing;
    }
  } else {
    r.facing_reason = "given";
  }
  r.facing = facing;

  // ---- normalise ----
  const Eigen::Matrix3d to_vgd = metres * facing_rotation(facing) * up_rotation(up);
  mesh::transform(s, to_vgd);
  std::vector<ModelJoint> joints = std::move(model.joints);  // moved with the body
  for (auto& j : joints) j.position = to_vgd * j.position;
  r.welded_vertices = mesh::weld_vertices(s, o.weld_tolerance);
  if (o.recentre) {
    const mesh::Box3 b = mesh::bounding_box(s);
    const Vec3 shift(-b.centre().x(), -b.min.y(), -b.centre().z());
    mesh::translate(s, shift);
    for (auto& j : joints) j.position += shift;
  }
  if (s.triangles.empty()) throw Error(file, "", "no triangle is left after merging coincident vertices (a degenerate mesh)");
  const auto check = fill_check(r, s);
  if (!check.watertight())
    r.notes.push_back("not watertight: " + std::to_string(check.boundary_edges) + " boundary edges, " +
                      std::to_string(check.non_manifold_edges) + " non-manifold edges, " +
                      std::to_string(check.inconsistent_edges) + " inconsistently oriented edges");
  if (r.height < 1.0 || r.height > 2.3) r.notes.push_back("height " + format_fixed(r.height, 3) + " m is outside 1.0–2.3 m");

  Avatar av;
  av.source = file;
  av.notes.push_back("unit " + r.unit + " (" + r.unit_reason + ")");
  av.notes.push_back("up " + r.up + " (" + r.up_reason + ")");
  av.notes.push_back("facing " + r.facing + " (" + r.facing_reason + ")");
  av.notes.insert(av.notes.end(), r.notes.begin(), r.notes.end());
  av.surface = std::move(s);
  if (o.segments) {
    if (o.human) {
      BodyMeasuring measured = measure_body(av.surface);
      if (landmarks_from_skeleton(measured.landmarks, joints, measured.notes) > 0)
        measured.arms = arm_segments(av.surface, measured.landmarks);  // along the skeleton's arms
      av.segments = segments_from_slices(av.surface, &measured.landmarks);
      for (const auto& arm : measured.arms) av.segments.push_back(arm);
      av.landmarks = measured.landmarks;
      av.measured = measured.measurements;
      for (const auto& n : measured.notes) r.notes.push_back(n), av.notes.push_back(n);
      if (measured.measurements.bust > 0 && measured.measurements.waist > 0 && measured.measurements.hip > 0)
        r.nearest = nearest_size(measured.measurements);
      r.measuring = std::move(measured);
    } else {
      av.segments = segments_from_slices(av.surface);
    }
  }
  for (const auto& seg : av.segments) r.segments.push_back(seg.name);
  av.triangle_segment.assign(av.surface.triangles.size(), -1);
  if (report_out) *report_out = r;
  return av;
}

AvatarReport report_avatar(const Avatar& avatar) {
  AvatarReport r;
  r.file = avatar.source;
  r.meshes = 1;
  r.unit = "m", r.unit_reason = "vgd's frame";
  r.up = "y", r.up_reason = "vgd's frame";
  r.facing = "+z", r.facing_reason = "vgd's frame";
  fill_check(r, avatar.surface);
  for (const auto& s : avatar.segments) r.segments.push_back(s.name);
  return r;
}

std::string to_json(const AvatarReport& r) {
  auto v3 = [](const Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); };
  nlohmann::json j{{"file", r.file},
                   {"format", r.format},
                   {"meshes", r.meshes},
                   {"vertices", r.vertices},
                   {"triangles", r.triangles},
                   {"welded_vertices", r.welded_vertices},
                   {"dropped_primitives", r.dropped_primitives},
                   {"bbox_min_m", v3(r.box.min)},
                   {"bbox_max_m", v3(r.box.max)},
                   {"height_m", r.height},
                   {"area_m2", r.area},
                   {"volume_m3", r.volume},
                   {"watertight", r.watertight},
                   {"boundary_edges", r.boundary_edges},
                   {"non_manifold_edges", r.non_manifold_edges},
                   {"inconsistent_edges", r.inconsistent_edges},
                   {"degenerate_triangles", r.degenerate_triangles},
                   {"unit", {{"value", r.unit}, {"guessed", r.unit_guessed}, {"reason", r.unit_reason}}},
                   {"up", {{"value", r.up}, {"guessed", r.up_guessed}, {"reason", r.up_reason}}},
                   {"facing", {{"value", r.facing}, {"guessed", r.facing_guessed}, {"reason", r.facing_reason}}},
                   {"segments", r.segments},
                   {"notes", r.notes}};
  if (r.measuring) {
    const auto& l = r.measuring->landmarks;
    const auto& m = r.measuring->measurements;
    nlohmann::json lj{{"height_m", l.height},       {"neck_m", l.neck},   {"shoulder_m", l.shoulder},
                      {"bust_m", l.bust},           {"under_bust_m", l.under_bust},
                      {"waist_m", l.waist},         {"hip_m", l.hip},     {"crotch_m", l.crotch},
                      {"knee_m", l.knee},           {"ankle_m", l.ankle}};
    for (const auto& [name, arm] : {std::pair{"left_arm", &l.left_arm}, {"right_arm", &l.right_arm}})
      if (*arm)
        lj[name] = {{"shoulder_m", v3((*arm)->shoulder)}, {"shoulder_from_skeleton", (*arm)->shoulder_from_skeleton},
                    {"elbow_m", v3((*arm)->elbow)},
                    {"elbow_from_skeleton", (*arm)->elbow_from_skeleton},
                    {"elbow_on_surface", (*arm)->elbow_on_surface},
                    {"wrist_m", v3((*arm)->wrist)}, {"wrist_from_skeleton", (*arm)->wrist_from_skeleton},
                    {"wrist_girth_m", (*arm)->wrist_girth}};
    j["landmarks"] = lj;
    j["measurements"] = {{"height_m", m.height},   {"bust_m", m.bust},         {"under_bust_m", m.under_bust},
                         {"waist_m", m.waist},     {"hip_m", m.hip},           {"shoulder_width_m", m.shoulder_width},
                         {"neck_m", m.neck},       {"arm_length_m", m.arm_length}, {"inseam_m", m.inseam}};
  }
  if (r.nearest)
    j["nearest_size"] = {{"table", r.nearest->table}, {"size", r.nearest->size.label}, {"sex", r.nearest->size.sex},
                         {"rms_m", r.nearest->rms}, {"bust_m", r.nearest->size.bust}, {"waist_m", r.nearest->size.waist},
                         {"hip_m", r.nearest->size.hip}, {"height_m", r.nearest->size.height}};
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::vector<std::string> avatar_export_extensions() { return {".obj", ".ply", ".stl", ".glb", ".gltf", ".dae", ".fbx"}; }

void export_avatar(const Avatar& avatar, const fs::path& path) {
  const std::string file = path.string();
  const std::string ext = to_lower(path.extension().string());
  const std::pair<const char*, const char*> formats[] = {{".obj", "objnomtl"}, {".ply", "plyb"},     {".stl", "stlb"},
                                                         {".glb", "glb2"},     {".gltf", "gltf2"},   {".dae", "collada"},
                                                         {".fbx", "fbxa"}};
  const char* id = nullptr;
  for (const auto& [e, f] : formats)
    if (ext == e) id = f;
  if (!id) throw Error(file, "", "cannot write '" + ext + "' files (obj, ply, stl, glb, gltf, dae, fbx)");
  const auto& s = avatar.surface;
  if (s.triangles.empty()) throw Error(file, avatar.source, "the avatar has no triangles to write");

  // assimp writes straight to its path (and glTF a .bin beside it): export into a
  // private folder next to the target, then move each file in atomically.
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code ec;
  fs::create_directories(dir, ec);
  std::mt19937_64 rng(std::random_device{}());
  const fs::path tmp = dir / (".vgd-export-" + std::to_string(rng() % 1000000000ULL));
  fs::create_directories(tmp, ec);
  if (ec) throw Error(file, "", "cannot create a temporary folder beside the target: " + ec.message());
  struct Cleanup {
    fs::path p;
    ~Cleanup() {
      std::error_code e;
      fs::remove_all(p, e);
    }
  } cleanup{tmp};
  try {
    write_model_file(s, mesh::vertex_normals(s), tmp / path.filename(), id);
  } catch (const Error& e) {
    throw Error(file, "", e.diagnostic().message);
  }
  for (const auto& entry : fs::directory_iterator(tmp))
    write_file_atomic(dir / entry.path().filename(), read_file(entry.path()));
}

}  // namespace vgd::body
