// Avatar import and export (avatar_io.hpp): files read and written through
// the assimp module (model_file.hpp), normalised here.
#include "vgd/body/avatar_io.hpp"

#include <algorithm>
#include <cmath>
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

// The loop of a slice around (x, z) = p, or the nearest loop's index when none encloses it.
int loop_around(const std::vector<std::vector<mesh::Vec2d>>& loops, const mesh::Vec2d& p) {
  for (std::size_t i = 0; i < loops.size(); ++i)
    if (loops[i].size() > 2 && mesh::point_in_polygon(loops[i], p)) return static_cast<int>(i);
  return -1;
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

double loop_area(const std::vector<mesh::Vec2d>& l) {
  double a = 0;
  for (std::size_t i = 0, j = l.size() - 1; i < l.size(); j = i++) a += l[j].x() * l[i].y() - l[i].x() * l[j].y();
  return std::abs(0.5 * a);
}

}  // namespace

std::vector<BodySegment> segments_from_slices(const mesh::SurfaceMesh& surface) {
  std::vector<BodySegment> out;
  const mesh::Box3 box = mesh::bounding_box(surface);
  const double H = box.size().y(), y0 = box.min.y();
  if (H <= 0) return out;
  const mesh::Vec2d centre(box.centre().x(), box.centre().z());
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
      s.rings.push_back(ring_of(loops[k], y, y - ya));
    }
    s.start = Vec3(s.rings.front().centre.x(), ya, s.rings.front().centre.z());
    s.length = yb - ya;
    out.push_back(std::move(s));
  };
  // Proportions of an adult body (fractions of the height above the floor).
  const double waist = y0 + 0.62 * H, shoulder = y0 + 0.80 * H;
  trunk("hips", crotch + 0.01 * H, waist, 8);
  trunk("torso", waist, shoulder, 8);
  trunk("neck", y0 + 0.835 * H, y0 + 0.865 * H, 3);
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
        if (const double a = loop_area(loops[k]); a > best_area) best_area = a, best = static_cast<int>(k);
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
  static const std::vector<std::string> facings{"+z", "-z", "+x", "-x", "z", "x"};
  if (std::find(facings.begin(), facings.end(), facing_opt) == facings.end())
    throw Error(file, "facing", "unknown facing '" + o.facing + "' (+z, -z, +x, -x)");

  AvatarReport r;
  r.file = file;
  r.format = to_lower(path.extension().string());
  if (!r.format.empty() && r.format.front() == '.') r.format.erase(0, 1);

  ModelFile model = read_model_file(path);
  mesh::SurfaceMesh& s = model.surface;
  const int meshes = model.meshes, dropped = model.dropped;
  r.meshes = meshes;
  r.dropped_primitives = dropped;
  if (s.triangles.empty())
    throw Error(file, "", "the file holds no triangles" + std::string(dropped ? " (only points or lines)" : ""));
  mesh::remove_unused_vertices(s);

  // ---- up axis ----
  const bool gltf = r.format == "gltf" || r.format == "glb";
  std::string up = up_opt.front() == '+' ? up_opt.substr(1) : up_opt;
  if (up == "auto") {
    r.up_guessed = false;
    if (gltf) {
      up = "y", r.up_reason = "glTF is +Y up by specification";
    } else if (r.format == "dae") {
      up = "y", r.up_reason = "Collada up_axis applied by the importer";
    } else if (const auto ax = metadata_number(model, "UpAxis")) {
      const auto sign = metadata_number(model, "UpAxisSign").value_or(1.0);
      up = std::string(sign < 0 ? "-" : "") + "xyz"[std::clamp(static_cast<int>(*ax), 0, 2)];
      r.up_reason = "the file's UpAxis metadata";
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
        const double area = 0.5 * (b - a).cross(c - a).norm();
        (((a[k] + b[k] + c[k]) / 3.0 > mid) ? above : below) += area;
      }
      up = std::string(above >= below ? "" : "-") + "xyz"[k];
      r.up_guessed = true;
      r.up_reason = "no metadata: the longest extent, towards the side with more surface area";
    }
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
  double metres = 1.0;
  if (unit_opt != "auto") {
    metres = metres_per(*parse_length_unit(unit_opt));
    r.unit = to_string(*parse_length_unit(unit_opt));
    r.unit_reason = "given";
  } else {
    std::optional<double> meta;
    std::string meta_reason;
    if (gltf) meta = 1.0, meta_reason = "glTF is in metres by specification";
    else if (r.format == "dae") meta = 1.0, meta_reason = "Collada <unit> applied by the importer";
    else if (const auto f = metadata_number(model, "UnitScaleFactor"))
      meta = *f * 0.01, meta_reason = "the file's UnitScaleFactor metadata (" + format_double(*f) + " cm per unit)";
    const auto human = [](double h) { return h >= 1.0 && h <= 2.3; };
    if (meta && human(raw_height * *meta)) {
      metres = *meta;
      r.unit_reason = meta_reason;
    } else {
      r.unit_guessed = true;
      const LengthUnit candidates[] = {LengthUnit::metre, LengthUnit::centimetre, LengthUnit::millimetre, LengthUnit::inch};
      LengthUnit best = LengthUnit::metre;
      double best_err = 1e300;
      for (const auto u : candidates) {
        const double h = raw_height * metres_per(u);
        const double err = human(h) ? 0.0 : std::abs(std::log(h / 1.7));
        if (err < best_err) best_err = err, best = u;
      }
      metres = metres_per(best);
      r.unit_reason = std::string(best_err == 0 ? "a human is 1.0–2.3 m tall" : "closest to a human height (1.7 m)") +
                      (meta ? "; the metadata's unit gives " + format_fixed(raw_height * *meta, 3) + " m" : "");
    }
    r.unit = "m";
    for (const auto u : {LengthUnit::metre, LengthUnit::centimetre, LengthUnit::millimetre, LengthUnit::inch})
      if (metres_per(u) == metres) r.unit = to_string(u);
    if (r.unit == "m" && metres != 1.0) r.unit = format_double(metres) + " m";
  }

  // ---- normalise ----
  mesh::transform(s, metres * facing_rotation(facing_opt) * up_rotation(up));
  r.welded_vertices = mesh::weld_vertices(s, o.weld_tolerance);
  if (o.recentre) {
    const mesh::Box3 b = mesh::bounding_box(s);
    mesh::translate(s, Vec3(-b.centre().x(), -b.min.y(), -b.centre().z()));
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
  av.surface = std::move(s);
  if (o.segments) av.segments = segments_from_slices(av.surface);
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
                   {"segments", r.segments},
                   {"notes", r.notes}};
  return j.dump(2);
}

std::vector<std::string> avatar_export_extensions() { return {".obj", ".ply", ".stl", ".glb", ".gltf", ".dae"}; }

void export_avatar(const Avatar& avatar, const fs::path& path) {
  const std::string file = path.string();
  const std::string ext = to_lower(path.extension().string());
  const std::pair<const char*, const char*> formats[] = {{".obj", "objnomtl"}, {".ply", "plyb"}, {".stl", "stlb"},
                                                         {".glb", "glb2"},     {".gltf", "gltf2"}, {".dae", "collada"}};
  const char* id = nullptr;
  for (const auto& [e, f] : formats)
    if (ext == e) id = f;
  if (!id) throw Error(file, "", "cannot write '" + ext + "' files (obj, ply, stl, glb, gltf, dae)");
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
