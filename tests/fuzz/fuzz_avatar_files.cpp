// libFuzzer target for body files read as avatars (body/avatar_io.hpp): any
// byte string, written as an OBJ, PLY, STL or glTF file (the first byte picks
// which), must import or fail with vgd::Error — never crash or hang in vgd's
// own code: the body alone, up axis, unit, facing, landmarks, segments and
// the skeleton's joints. assimp parses the file (in its own module, not
// instrumented); what it hands back is vgd's to check.
// Build: make fuzz; run: build-fuzz/tests/fuzz/vgd_fuzz_avatar_files tests/fuzz/corpus/avatar
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "vgd/body/avatar_io.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  static const char* const kExtensions[] = {".obj", ".ply", ".stl", ".gltf"};
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("vgd-fuzz-avatar-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  const std::filesystem::path file = dir / (std::string("body") + kExtensions[data[0] % 4]);
  vgd::write_file_atomic(file, std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  try {
    vgd::body::AvatarReport report;
    vgd::body::AvatarImportOptions options;
    options.read_time_limit_s = 0.5;  // inputs assimp loops on are known (corpus/avatar): keep the fuzzer fast
    const vgd::body::Avatar a = vgd::body::import_avatar(file, options, &report);
    for (const auto& t : a.surface.triangles)
      for (int c : t)
        if (c < 0 || c >= a.surface.num_vertices()) __builtin_trap();  // a body's triangles index its vertices
    for (const auto& v : a.surface.vertices)
      if (!v.allFinite()) __builtin_trap();  // non-finite coordinates are refused, never passed on
  } catch (const vgd::Error&) {
    // Refused with a message: fine.
  }
  return 0;
}
