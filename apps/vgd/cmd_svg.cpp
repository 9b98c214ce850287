// vgd svg: draws an XVC document's patterns as SVG through schemas/xvc-to-svg.xsl.
#include <memory>

#include "cli.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/svg.hpp"

namespace cmd_svg {
namespace {
struct Options {
  std::string input;
  std::string output;
  std::string stylesheet;
  std::string layout = "rows";
  double scale = 1000;
};

vgd::cli::Registrar reg{"svg", 40, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("svg", "Draw an XVC document's patterns as SVG");
  auto o = std::make_shared<Options>();
  sub->add_option("FILE", o->input, "XVC document")->required();
  sub->add_option("-o,--output", o->output, "SVG file to write (atomically)")->required();
  sub->add_option("--stylesheet", o->stylesheet, "XSLT to use (default: xvc-to-svg.xsl beside xvc.xsd)");
  sub->add_option("--layout", o->layout, "rows: a row per piece, sizes side by side; row: all side by side; own: own coordinates")
      ->check(CLI::IsMember({"rows", "row", "own"}))
      ->capture_default_str();
  sub->add_option("--scale", o->scale, "SVG units per metre (1000: millimetres)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  return vgd::cli::Command{sub, [o, &common]() -> int {
    const auto doc = vgd::xvc::load_file(o->input);
    const std::filesystem::path xsl =
        o->stylesheet.empty() ? vgd::xvc::default_stylesheet_path() : std::filesystem::path(o->stylesheet);
    const std::string svg = vgd::xvc::render_svg(doc, xsl, {{"layout", o->layout}, {"scale", vgd::format_double(o->scale)}});
    vgd::write_file_atomic(o->output, svg);
    vgd::cli::say(common, "vgd: wrote " + o->output + " (" + std::to_string(doc.patterns().size()) + " patterns, " +
                              (vgd::xvc::svg_uses_libxslt() ? "libxslt" : "xsltproc") + ")");
    return vgd::cli::kOk;
  }};
}};
}  // namespace
}  // namespace cmd_svg
