// vgd draft: the project's own garments, drafted from measurements and written as AAMA DXF,
// or (when -o ends in .xvc) as an XVC document with the drafter's seams and arrangements.
#include <memory>

#include "cli.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/io/dxf/export.hpp"
#include "vgd/pattern/draft.hpp"
#include "vgd/xvc/arrangement.hpp"
#include "vgd/xvc/commands.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/seams.hpp"
#include "vgd/xvc/style.hpp"

namespace cmd_draft {
namespace {

// The style as XVC, with the drafter's seams (every size) and one arrangement per
// pattern, all added through the undoable commands so the document is checked.
void write_xvc(const vgd::pattern::Style& style, const std::vector<vgd::pattern::SeamPlan>& seams,
               const std::string& path) {
  auto doc = vgd::xvc::from_style(style);
  vgd::xvc::AddSeams add(vgd::xvc::plan_seam_nodes(doc, seams));
  vgd::xvc::execute(doc, add);
  for (const auto& [id, list] : vgd::xvc::suggest_arrangements(doc)) {
    vgd::xvc::SetArrangements set(id, list);
    vgd::xvc::execute(doc, set);
  }
  vgd::xvc::save_file(doc, path);
}

bool ends_with_xvc(const std::string& p) {
  return p.size() >= 4 && vgd::to_lower(p.substr(p.size() - 4)) == ".xvc";
}

struct Options {
  std::string garment = "skirt", output, sizes, size;
  double waist = 0, hip = 0, length = 0, hip_depth = 0, flare = -1;
  bool inch = false;
};

vgd::cli::Registrar reg{"draft", 5, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("draft", "Draft a garment from body measurements and write it as AAMA DXF or XVC");
  auto o = std::make_shared<Options>();
  sub->add_option("GARMENT", o->garment, "What to draft")->check(CLI::IsMember({"skirt", "tshirt"}))->capture_default_str();
  sub->add_option("-o,--output", o->output, "AAMA DXF file to write (atomically); a name ending in .xvc writes XVC with seams and arrangements")->required();
  sub->add_option("--sizes", o->sizes, "Comma-separated sizes from the built-in table (34,36,38,40,42); default all");
  sub->add_option("--size", o->size, "Label for a custom size given by measurements");
  sub->add_option("--waist", o->waist, "Waist girth, m (custom size)");
  sub->add_option("--hip", o->hip, "Hip girth, m (custom size)");
  sub->add_option("--length", o->length, "Skirt length, waist to hem, m (custom size)");
  sub->add_option("--hip-depth", o->hip_depth, "Waist to hip line, m (custom size)");
  sub->add_option("--flare", o->flare, "Extra half-width of each panel at the hem, m");
  sub->add_flag("--inch", o->inch, "Write inches (Units: ENGLISH) instead of millimetres");
  return vgd::cli::Command{sub, [o, &common]() -> int {
    vgd::dxf::ExportOptions eo;
    eo.units = o->inch ? vgd::LengthUnit::inch : vgd::LengthUnit::millimetre;
    if (o->garment == "tshirt") {
      if (o->waist > 0 || o->hip > 0 || o->length > 0 || o->flare >= 0)
        throw vgd::Error("", "draft tshirt", "custom measurements are for the skirt; the T-shirt takes --sizes");
      auto table = vgd::pattern::tshirt_size_table();
      std::vector<vgd::pattern::TShirtMeasurements> chosen;
      if (o->sizes.empty()) chosen = table;
      for (const auto& want : o->sizes.empty() ? std::vector<std::string>{} : vgd::split(o->sizes, ',')) {
        const auto it = std::find_if(table.begin(), table.end(), [&](const auto& m) { return m.size == vgd::trim(want); });
        if (it == table.end()) throw vgd::Error("", "--sizes", "no size '" + want + "' in the table (34..42)");
        chosen.push_back(*it);
      }
      const auto style = vgd::pattern::draft_tshirt_style(chosen);
      if (ends_with_xvc(o->output)) write_xvc(style, vgd::pattern::tshirt_seams(), o->output);
      else vgd::dxf::export_file(style, o->output, eo);
      vgd::cli::say(common, "wrote " + o->output + ": " + std::to_string(style.pieces.size()) + " pieces (" +
                                std::to_string(style.sizes.size()) + " sizes × FRONT, BACK, LEFT SLEEVE, RIGHT SLEEVE)");
      return vgd::cli::kOk;
    }
    auto table = vgd::pattern::skirt_size_table();
    std::vector<vgd::pattern::SkirtMeasurements> chosen;
    if (o->waist > 0 || o->hip > 0 || o->length > 0) {
      vgd::pattern::SkirtMeasurements m;  // defaults: size 38
      if (!o->size.empty()) m.size = o->size;
      else m.size = "custom";
      if (o->waist > 0) m.waist = o->waist;
      if (o->hip > 0) m.hip = o->hip;
      if (o->length > 0) m.length = o->length;
      if (o->hip_depth > 0) m.hip_depth = o->hip_depth;
      chosen.push_back(m);
    } else if (!o->sizes.empty()) {
      for (const auto& want : vgd::split(o->sizes, ',')) {
        const auto it = std::find_if(table.begin(), table.end(), [&](const auto& m) { return m.size == vgd::trim(want); });
        if (it == table.end()) throw vgd::Error("", "--sizes", "no size '" + want + "' in the table (34..42)");
        chosen.push_back(*it);
      }
    } else {
      chosen = table;
    }
    if (o->flare >= 0)
      for (auto& m : chosen) m.flare = o->flare;
    const auto style = vgd::pattern::draft_skirt_style(chosen);
    if (ends_with_xvc(o->output)) write_xvc(style, vgd::pattern::skirt_seams(), o->output);
    else vgd::dxf::export_file(style, o->output, eo);
    vgd::cli::say(common, "wrote " + o->output + ": " + std::to_string(style.pieces.size()) + " pieces (" +
                              std::to_string(style.sizes.size()) + " sizes × FRONT, BACK, WAISTBAND)");
    return vgd::cli::kOk;
  }};
}};

}  // namespace
}  // namespace cmd_draft
