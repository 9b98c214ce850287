// vgd import: AAMA/ASTM DXF -> XVC document, or a report of what the file holds.
#include <memory>

#include "cli.hpp"
#include "vgd/io/dxf/import.hpp"
#include "vgd/io/dxf/report.hpp"

#include "vgd/xvc/io.hpp"
#include "vgd/xvc/style.hpp"

namespace cmd_import {
namespace {

struct Options {
  std::string input, output, units;
  bool report = false, json = false, unfold = false, join = false, sew = false, strict = false, no_repair = false;
};

vgd::cli::Registrar reg{"import", 10, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("import", "Import an AAMA/ASTM DXF pattern file into an XVC document");
  auto o = std::make_shared<Options>();
  sub->add_option("FILE", o->input, "DXF file (AAMA or ASTM D6673, from Gerber, Lectra, CLO, Valentina, ...)")
      ->required();
  sub->add_option("-o,--output", o->output, "XVC document to write (written atomically)");
  sub->add_flag("--report", o->report, "Print what the file holds: pieces, sizes, blocks, warnings");
  sub->add_flag("--json", o->json, "With --report: machine-readable JSON on stdout");
  sub->add_flag("--unfold-mirrored", o->unfold, "Unfold half pieces about their mirror (fold) line");
  sub->add_flag("--join-per-side", o->join,
                "Join pieces written once per side whose names say nothing: mirror-image halves with a straight "
                "centre edge into one piece, two blocks of one outline into one piece cut twice (CLO; vgd dress "
                "does this)");
  sub->add_flag("--sew-lines", o->sew,
                "Sew each piece on its sew line (layer 14) where it has one closed inside its outline: the seam "
                "allowance is cut off (vgd dress does this)");
  sub->add_option("--units", o->units, "Units to read the file in, overriding what it states (mm, cm, in)");
  sub->add_flag("--strict", o->strict,
                "Write nothing when a block had to be dropped (default: the other blocks are written, each dropped "
                "block named on stderr, exit 3)");
  sub->add_flag("--no-repair", o->no_repair, "Do not cut small self-intersection loops out of outlines");
  return vgd::cli::Command{sub, [o, &common]() -> int {
    vgd::dxf::ImportOptions opts;
    opts.unfold_mirrored = o->unfold;
    opts.join_per_side = o->join;
    opts.sew_on_sew_lines = o->sew;
    opts.repair_self_intersections = !o->no_repair;
    if (!o->units.empty()) {
      opts.units = vgd::parse_length_unit(o->units);
      if (!opts.units) throw vgd::Error("", "--units", "unknown unit '" + o->units + "' (use mm, cm, m or in)");
    }
    if (!o->report && o->output.empty())
      throw vgd::Error("", "", "nothing to do: give -o OUTPUT.xvc and/or --report");
    const auto result = vgd::dxf::import_file(o->input, opts);
    const auto& s = result.summary;
    if (o->report && o->json) {
      vgd::cli::print_json(vgd::dxf::report_json(result));
    } else {
      vgd::cli::print_diagnostics(result.diagnostics, common);
      for (const auto& note : vgd::dxf::import_notes(result)) vgd::cli::say(common, "vgd: " + note);
      if (!o->join) {
        vgd::pattern::Style copy = result.style;
        if (const auto would = vgd::pattern::join_pieces_written_per_side(copy); !would.empty())
          vgd::cli::say(common, "vgd: note: " + std::to_string(would.size()) +
                                    " pair(s) of blocks look written once per side (" + would.front().kept + " and " +
                                    would.front().dropped + ", ...): --join-per-side joins them (vgd dress does)");
      }
      if (o->report) {
        std::printf("%s: %s %s, style '%s', %d pieces, %d blocks, sizes:", o->input.c_str(), s.producer.c_str(),
                    s.flavour.c_str(), s.style.c_str(), s.pieces, s.blocks);
        for (const auto& z : s.sizes) std::printf(" %s", z.c_str());
        std::printf(" (sample %s), units %s\n", s.sample_size.c_str(), s.units.c_str());
        std::printf("%-28s %-6s %6s %10s %9s %6s %s\n", "block", "size", "verts", "area m2", "perim m", "notch",
                    "flags");
        for (const auto& b : result.blocks)
          std::printf("%-28s %-6s %6d %10.5f %9.4f %6d %s%s%s%s\n", b.block.c_str(), b.size.c_str(),
                      b.boundary_vertices, b.area_m2, b.perimeter_m, b.notches, b.closed ? "" : "OPEN ",
                      b.self_intersecting ? "SELF-INTERSECTING " : "", b.mirror_line ? "half " : "",
                      b.imported ? "" : "DROPPED");
      }
    }
    if (o->output.empty()) return vgd::cli::kOk;
    const auto dropped = result.diagnostics.count(vgd::Severity::error);
    if (dropped > 0 && o->strict)
      throw vgd::Error(o->input, "", std::to_string(dropped) +
                                         " block(s) could not be imported; nothing written (--strict)");
    vgd::xvc::save_file(vgd::xvc::from_style(result.style), o->output);
    vgd::cli::say(common, "wrote " + o->output + ": " + std::to_string(result.style.piece_names().size()) +
                              " pieces, " + std::to_string(result.style.pieces.size()) + " blocks" +
                              (dropped > 0 ? " (" + std::to_string(dropped) + " dropped: see above)" : ""));
    return dropped > 0 ? vgd::cli::kCheckFailed : vgd::cli::kOk;
  }};
}};

}  // namespace
}  // namespace cmd_import
