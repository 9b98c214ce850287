// The scene's body (AvatarDef -> Avatar): the mannequin, an imported mesh, or
// a benchmark solid.
#include <filesystem>

#include "vgd/body/avatar_io.hpp"
#include "vgd/body/mannequin.hpp"
#include "vgd/body/sizes.hpp"
#include "vgd/mesh/primitives.hpp"
#include "vgd/scene/build.hpp"

namespace vgd::scene {

using body::Avatar;

Avatar build_avatar(const SceneDef& def) {
  const AvatarDef& a = *def.avatar;
  const std::string file = def.source.string();
  try {
    switch (a.kind) {
      case AvatarDef::Kind::mannequin: {
        body::BodyMeasurements m = a.size.empty() ? a.measurements : body::find_size(a.size, a.table);
        body::MannequinOptions mo;
        if (a.triangles > 0) mo.target_triangles = a.triangles;
        return body::make_mannequin(m, mo);
      }
      case AvatarDef::Kind::file: {
        std::filesystem::path p = a.file;
        if (p.is_relative() && !def.source.empty()) p = def.source.parent_path() / p;
        body::AvatarImportOptions io;
        io.unit = a.unit;
        io.up = a.up;
        io.facing = a.facing;
        io.human = a.human;
        return body::import_avatar(p, io);
      }
      case AvatarDef::Kind::sphere: {
        Avatar out;
        out.source = "sphere r " + std::to_string(a.radius) + " m";
        out.surface = mesh::uv_sphere(a.centre, a.radius, a.segments, a.rings);
        out.triangle_segment.assign(out.surface.triangles.size(), -1);
        return out;
      }
      case AvatarDef::Kind::cylinder: {
        Avatar out;
        out.source = "cylinder r " + std::to_string(a.radius) + " m";
        out.surface = mesh::cylinder(a.centre, a.radius, a.height, a.segments, a.rings);
        out.triangle_segment.assign(out.surface.triangles.size(), -1);
        return out;
      }
    }
  } catch (const Error& e) {
    // Name the scene field; keep the inner message and what it names (the
    // body's file, the size asked for).
    const auto& d = e.diagnostic();
    throw Error(file, "avatar",
                (d.file.empty() || d.file == file ? "" : d.file + ": ") + (d.entity.empty() ? "" : d.entity + ": ") +
                    d.message);
  }
  throw Error(file, "avatar", "unknown kind of body");
}

}  // namespace vgd::scene
