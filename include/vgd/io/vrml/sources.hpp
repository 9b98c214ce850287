#pragma once
// Where an exported garment comes from: a trajectory (.trj, io/trj) with every
// frame, the material coordinates and the seam merges, or — without one — the
// OBJ a drape writes (garment.obj: one `g` group per piece, the final frame).
#include <filesystem>
#include <string>

#include "vgd/io/trj/trj.hpp"
#include "vgd/io/vrml/garment.hpp"

namespace vgd::io::vrml {

// The garment of a whole trajectory: topology, uv and every frame; the merges
// in force at the last frame become Cloth::representative. Throws vgd::Error
// (naming `name`, the file it came from, also the garment's name) when the
// trajectory has no material coordinates or no frame.
Garment garment_from_trajectory(const trj::Trajectory& trajectory, const std::string& name);

// The garment of a drape's OBJ (`v`, triangles `f`, one `g` per piece): one
// frame at t = 0. An OBJ holds no material coordinates: each piece's uv is
// its projection on its best-fitting plane (u along the axis closest to the
// vertical, the grain of a hanging piece) — close to the pattern for gently
// curved pieces, an approximation otherwise. Vertices at one position (to
// 1 µm: the copies of a closed seam) are merged. Throws vgd::Error naming the file.
Garment garment_from_obj(const std::filesystem::path& obj);

}  // namespace vgd::io::vrml
