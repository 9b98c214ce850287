#pragma once
// The web catalogue (docs/vrml.md): a folder a designer copies to any web
// server — index.html linking every garment, one <garment>.html per garment
// showing its VRML in the browser with X_ITE (an <x3d-canvas>), and X_ITE
// itself (its whole dist/ folder) in x_ite/, so the pages work offline.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace vgd::io::vrml {

struct WebEntry {
  std::string name;   // page stem: <name>.html (letters, digits, '-', '_', '.')
  std::string title;  // shown on the pages
  std::string wrl;    // the VRML file shown, relative to the folder
  std::vector<std::pair<std::string, std::string>> downloads;  // (label, file) links: other flavours, .glb, .obj
  std::vector<std::pair<std::string, std::string>> facts;      // (label, value) rows: pieces, triangles, sizes
};

// A file-name-safe page stem from a garment name ("A-line skirt" -> "A-line_skirt").
std::string page_stem(const std::string& name);

// The HTML of one garment's page and of the index.
std::string garment_page(const WebEntry& entry);
std::string index_page(const std::vector<WebEntry>& entries, const std::string& title = "vgd garment catalogue");

// X_ITE's dist/ folder as this build found it (tests/web/node_modules, set by
// CMake), or "" when the build did not find it.
std::filesystem::path default_x_ite_dir();

// Writes index.html and one page per entry into `dir` (atomically) and copies
// `x_ite_dist` (a folder holding x_ite.min.js) to dir/x_ite. The .wrl and
// download files are the caller's. Throws vgd::Error naming the folder when
// X_ITE is not there or a file cannot be written.
void write_web_catalogue(const std::filesystem::path& dir, const std::vector<WebEntry>& entries,
                         const std::filesystem::path& x_ite_dist);

}  // namespace vgd::io::vrml
