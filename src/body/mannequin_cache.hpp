#pragma once
// The mannequin's surface kept between runs (mannequin_cache.cpp). Private to
// src/body.
#include <optional>
#include <string>

#include "vgd/body/mannequin.hpp"
#include "vgd/mesh/surface.hpp"

namespace vgd::body::detail {

// Everything the mannequin's mesh depends on, as text: the measurements, the
// options and the running executable (its path, size and modification time:
// a rebuilt vgd meshes anew).
std::string mannequin_cache_key(const BodyMeasurements& m, const MannequinOptions& o);

// The surface kept under `key`, when the cache holds it whole; nullopt
// otherwise (no cache, no file, another key, cut short or corrupt).
std::optional<mesh::SurfaceMesh> read_cached_surface(const std::string& key);

// Keeps `surface` under `key` (temporary file, then rename); a cache that
// cannot be written is left alone: the mannequin is made either way.
void write_cached_surface(const std::string& key, const mesh::SurfaceMesh& surface);

// Counts one surface meshed (mannequin_meshings()).
void count_meshing();

}  // namespace vgd::body::detail
