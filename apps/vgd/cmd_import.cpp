#include "cli.hpp"

namespace vgd::cli {

void register_import(CLI::App& app, Runner& selected, Common& common) {
  auto* sub = app.add_subcommand("import", "Import an AAMA/ASTM DXF pattern file");
  static std::string input;
  sub->add_option("FILE", input, "DXF file (AAMA or ASTM D6673)")->required();
  add_command(app, selected, sub, [&] {
    throw vgd::Error(input, "", "the DXF importer is not built yet");
    return kFailed;
  });
}

}  // namespace vgd::cli
