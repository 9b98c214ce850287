#pragma once
// The entry points of the vgd_assimp module (assimp_module.cpp), as
// model_file.cpp finds them with dlsym. The module and vgd are built together
// by the same compiler, so the C++ types cross the boundary as they are;
// errors come back as text, not exceptions.
#include <filesystem>
#include <string>
#include <vector>

#include "vgd/body/model_file.hpp"

namespace vgd::body::assimp_module {

inline constexpr int kApiVersion = 3;

struct Api {
  int version = kApiVersion;
  // Returns "" on success, else why the file could not be read.
  std::string (*read)(const std::filesystem::path& path, const ModelReadOptions& options, ModelFile& out) = nullptr;
  // Returns "" on success, else why the file could not be written.
  std::string (*write)(const mesh::SurfaceMesh& surface, const std::vector<Eigen::Vector3d>& normals,
                       const std::filesystem::path& path, const std::string& format_id) = nullptr;
};

}  // namespace vgd::body::assimp_module

// The one symbol the module exports.
extern "C" const vgd::body::assimp_module::Api* vgd_assimp_module_api();
