#pragma once
// The project's skirt document with data/textures/gingham.png (4 cm a
// repeat) associated to every pattern, written to `file` with the image
// beside it (tests of the looks: vgd render, the studio's preview).
#include <filesystem>
#include <string>

#include "support/test_paths.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"

namespace vgd::test {

inline void write_textured_skirt(const std::filesystem::path& file) {
  namespace fs = std::filesystem;
  std::string x = read_file(source_dir() / "data/garments/a-line-skirt.xvc");
  const std::string empty = "<TEXTURES id=\"textures\"/>";
  if (x.find(empty) == std::string::npos) throw Error(file.string(), "", "the skirt has no empty TEXTURES to fill");
  x.replace(x.find(empty), empty.size(),
            "<TEXTURES id=\"textures\">\n<TEXTURE id=\"texture1\" name=\"gingham\" file=\"gingham.png\">\n"
            "<SCALE2D id=\"texscale1\" x=\"0.04\" y=\"0.04\"/>\n</TEXTURE>\n</TEXTURES>");
  int n = 0;
  for (std::size_t at = x.find("</PATTERN>"); at != std::string::npos; at = x.find("</PATTERN>", at + 20)) {
    const std::string a = "<ASSOCIATION id=\"texassoc" + std::to_string(++n) + "\" ref=\"texture1\" role=\"texture\"/>\n";
    x.insert(at, a);
    at += a.size();
  }
  write_file_atomic(file, x);
  fs::copy_file(source_dir() / "data/textures/gingham.png", file.parent_path() / "gingham.png",
                fs::copy_options::overwrite_existing);
}

}  // namespace vgd::test
