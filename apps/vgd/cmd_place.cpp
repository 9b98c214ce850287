// vgd place: arrange pattern pieces around the body (xvc/arrangement.hpp): suggest
// arrangements from piece names (--auto) or set them (--set PIECE=SEGMENT:SIDE:HEIGHT...).
// Changes go through the undoable commands; the output is written atomically.
#include <iostream>
#include <memory>

#include "cli.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/xvc/arrangement.hpp"
#include "vgd/xvc/commands.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/style.hpp"

namespace cmd_place {
namespace {

struct Options {
  std::string input, output;
  bool automatic = false, list = false;
  std::vector<std::string> sets;
  vgd::xvc::ArrangementOptions heights;
};

vgd::cli::Registrar reg{"place", 36, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("place", "Arrange pattern pieces around the body (POSITION type=arrangement)");
  auto o = std::make_shared<Options>();
  sub->add_option("FILE", o->input, "XVC document")->required()->check(CLI::ExistingFile);
  sub->add_option("-o,--output", o->output, "XVC file to write (atomically)");
  sub->add_flag("--auto", o->automatic, "Suggest an arrangement for every pattern from its name");
  sub->add_option("--set", o->sets,
                  "PIECE_OR_PATTERN=SEGMENT:SIDE[±DEG]:HEIGHT[:CLEARANCE[:ANGLE[:flip]]], e.g. FRONT=torso:front:1.25:0.03 "
                  "or POCKET=torso:front+30:1.1 (30° further round, towards the left) (a piece name sets it in every size)");
  sub->add_option("--neck-height", o->heights.neck_point_height, "World height of the neck point, m (for --auto)")->capture_default_str();
  sub->add_option("--waist-height", o->heights.waist_height, "World height of the waist, m (for --auto)")->capture_default_str();
  sub->add_flag("--list", o->list, "Print each pattern's pins and arrangements");
  return vgd::cli::Command{sub, [o, &common]() -> int {
    auto doc = vgd::xvc::load_file(o->input);
    std::vector<std::unique_ptr<vgd::xvc::Command>> cmds;
    if (o->automatic)
      for (const auto& [id, list] : vgd::xvc::suggest_arrangements(doc, o->heights)) {
        if (list.empty()) {
          vgd::cli::say(common, "vgd: warning: " + id + " (" + std::string(doc.find(id)->attribute("piece")) +
                                    "): no arrangement rule fits this piece name; use --set");
          continue;
        }
        cmds.push_back(std::make_unique<vgd::xvc::SetArrangements>(id, list));
      }
    for (const auto& s : o->sets) {
      const auto eq = s.find('=');
      if (eq == std::string::npos) throw vgd::Error("", "--set " + s, "expected PIECE=SEGMENT:SIDE:HEIGHT...");
      const std::string who = s.substr(0, eq);
      int n = 0;
      for (const auto* p : doc.patterns())
        if (p->id() == who || p->attribute("piece") == who) {
          const auto a = vgd::xvc::parse_arrangement(s.substr(eq + 1), vgd::xvc::to_piece(doc, p->id()));
          cmds.push_back(std::make_unique<vgd::xvc::SetArrangements>(std::string(p->id()), std::vector{a}));
          ++n;
        }
      if (n == 0) throw vgd::Error(doc.name(), who, "no PATTERN with this id or piece name");
    }
    if (!cmds.empty()) {
      vgd::xvc::Batch batch("Arrange pieces", std::move(cmds));
      vgd::xvc::execute(doc, batch);
    }
    if (o->list)
      for (const auto* p : doc.patterns()) {
        for (const auto& pin : vgd::xvc::pins_of(*p))
          std::cout << p->id() << "  " << p->attribute("piece") << " " << p->attribute("size") << "  pin " << pin.id << " at ("
                    << vgd::format_double(pin.x) << ", " << vgd::format_double(pin.y) << ") m\n";
        for (const auto& a : vgd::xvc::arrangements_of(*p))
          std::cout << p->id() << "  " << p->attribute("piece") << " " << p->attribute("size") << "  " << a.segment << ":"
                    << a.side << (a.around_deg > 0 ? "+" : "") << (a.around_deg != 0 ? vgd::format_double(a.around_deg) : "")
                    << ":" << vgd::format_double(a.height) << ":" << vgd::format_double(a.clearance)
                    << (a.angle_deg != 0 ? ":" + vgd::format_double(a.angle_deg) : "") << (a.flip ? " flip" : "") << "\n";
      }
    if (!o->output.empty()) {
      vgd::xvc::save_file(doc, o->output);
      vgd::cli::say(common, "wrote " + o->output);
    } else if (!o->list) {
      throw vgd::Error("", "place", "-o OUT.xvc is required to save the arrangements (or --list to print them)");
    }
    return vgd::cli::kOk;
  }};
}};

}  // namespace
}  // namespace cmd_place
