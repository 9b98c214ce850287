// 3-D model files through the vgd_assimp module, opened on first use
// (model_file.hpp).
#include "vgd/body/model_file.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <mutex>
#include <string>

#include "assimp/module_api.hpp"
#include "vgd/core/diagnostics.hpp"

namespace vgd::body {

namespace {

namespace fs = std::filesystem;

constexpr const char* kModule = "libvgd_assimp.so";

// Opens the module once per process and keeps it open. Throws vgd::Error
// naming `file` and the places tried when it cannot be opened.
const assimp_module::Api& api(const std::string& file) {
  static std::once_flag once;
  static const assimp_module::Api* found = nullptr;
  static std::string problem;
  std::call_once(once, [] {
    std::string tried;
    std::vector<fs::path> dirs;
    if (const char* env = std::getenv("VGD_MODULE_DIR"); env && *env) dirs.emplace_back(env);
    dirs.emplace_back(VGD_BUILD_MODULE_DIR);
    dirs.emplace_back(VGD_INSTALL_MODULE_DIR);
    for (const auto& d : dirs) {
      const fs::path p = d / kModule;
      std::error_code ec;
      if (!fs::is_regular_file(p, ec)) {
        tried += (tried.empty() ? "" : ", ") + p.string();
        continue;
      }
      void* lib = ::dlopen(p.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!lib) {
        const char* e = ::dlerror();
        problem = "cannot open " + p.string() + ": " + (e ? e : "unknown reason");
        return;
      }
      using Entry = const assimp_module::Api* (*)();
      const auto entry = reinterpret_cast<Entry>(::dlsym(lib, "vgd_assimp_module_api"));
      const assimp_module::Api* a = entry ? entry() : nullptr;
      if (!a || a->version != assimp_module::kApiVersion || !a->read || !a->write) {
        problem = p.string() + " is not this vgd's assimp module (rebuild vgd)";
        return;
      }
      found = a;
      return;
    }
    problem = "cannot find vgd's assimp module " + std::string(kModule) + " (tried " + tried +
              "); set VGD_MODULE_DIR to the folder that holds it";
  });
  if (!found) throw Error(file, "", problem);
  return *found;
}

}  // namespace

ModelFile read_model_file(const fs::path& path, const ModelReadOptions& options) {
  const std::string file = path.string();
  ModelFile out;
  const std::string why = api(file).read(path, options, out);
  if (!why.empty())
    throw Error(file, "", "not a 3-D model vgd can read (OBJ, PLY, STL, glTF/GLB, FBX, Collada): " + why);
  return out;
}

void write_model_file(const mesh::SurfaceMesh& surface, const std::vector<Eigen::Vector3d>& normals,
                      const fs::path& path, const std::string& format_id) {
  const std::string file = path.string();
  VGD_ASSERT(normals.size() == surface.vertices.size(), "one normal per vertex");
  const std::string why = api(file).write(surface, normals, path, format_id);
  if (!why.empty()) throw Error(file, "", "writing failed: " + why);
}

}  // namespace vgd::body
