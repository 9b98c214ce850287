// vgd export-dxf: an XVC document back to AAMA DXF for the CAD systems.
#include <memory>

#include "cli.hpp"
#include "vgd/core/units.hpp"
#include "vgd/io/dxf/export.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/style.hpp"

namespace cmd_export_dxf {
namespace {

struct Options {
  std::string input, output, units = "mm", size;
};

vgd::cli::Registrar reg{"export-dxf", 20, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("export-dxf", "Write an XVC document's patterns as AAMA DXF");
  auto o = std::make_shared<Options>();
  sub->add_option("FILE", o->input, "XVC document")->required();
  sub->add_option("-o,--output", o->output, "AAMA DXF file to write (atomically)")->required();
  sub->add_option("--units", o->units, "mm (Units: METRIC) or in (Units: ENGLISH)")
      ->check(CLI::IsMember({"mm", "in", "inch"}))
      ->capture_default_str();
  sub->add_option("--size", o->size, "Only this size (default: every size)");
  return vgd::cli::Command{sub, [o, &common]() -> int {
    const auto style = vgd::xvc::to_style(vgd::xvc::load_file(o->input));
    vgd::dxf::ExportOptions eo;
    eo.units = *vgd::parse_length_unit(o->units);
    if (!o->size.empty()) eo.size = o->size;
    vgd::dxf::export_file(style, o->output, eo);
    std::size_t blocks = 0;
    for (const auto& p : style.pieces) blocks += o->size.empty() || p.size == o->size;
    vgd::cli::say(common, "wrote " + o->output + ": " + std::to_string(style.piece_names().size()) + " pieces, " +
                              std::to_string(blocks) + " blocks, " + o->units);
    return vgd::cli::kOk;
  }};
}};

}  // namespace
}  // namespace cmd_export_dxf
