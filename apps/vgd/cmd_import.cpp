#include <memory>

#include "cli.hpp"

namespace {
struct Options {
  std::string input;
};

vgd::cli::Registrar reg{"import", 10, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("import", "Import an AAMA/ASTM DXF pattern file into an XVC document");
  auto o = std::make_shared<Options>();
  sub->add_option("FILE", o->input, "DXF file (AAMA or ASTM D6673)")->required();
  return vgd::cli::Command{sub, [o]() -> int {
    throw vgd::Error(o->input, "", "the DXF importer is not built yet");
  }};
}};
}  // namespace
