// vgd edit: applies edits to an XVC document, in command-line order, and writes the
// result to -o (atomically; the input is only replaced when -o names it).
#include <map>
#include <memory>
#include <optional>

#include "cli.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/core/units.hpp"
#include "vgd/xvc/commands.hpp"
#include "vgd/xvc/io.hpp"

namespace cmd_edit {
namespace {
namespace xvc = vgd::xvc;

struct Options {
  std::string input;
  std::string output;
  std::vector<std::string> delete_pattern, copy_pattern, mirror_pattern, set_parameter, delete_node, copy_node, pin;
};

// "mesh.spacing=0.01", "mesh.spacing=10mm", "mesh.max_area=2e-5m2", "mesh.turn_angle=30deg".
// Length units are converted to the metres (or square metres) vgd stores.
xvc::SetParameter parse_parameter(const std::string& arg) {
  const auto eq = arg.find('=');
  if (eq == std::string::npos || eq == 0)
    throw vgd::Error("", arg, "--set-parameter wants NAME=VALUE[UNIT], e.g. mesh.spacing=0.01m");
  const std::string name = arg.substr(0, eq);
  const std::string_view rest = vgd::trim(std::string_view(arg).substr(eq + 1));
  // The longest leading text that is a number is the value; the remainder is the unit.
  std::optional<double> value;
  std::size_t cut = rest.size();
  for (; cut > 0; --cut)
    if ((value = vgd::parse_double(rest.substr(0, cut)))) break;
  if (!value) throw vgd::Error("", name, "no number in " + std::string(rest));
  std::string unit(vgd::trim(rest.substr(cut)));
  const auto* spec = xvc::find_parameter_spec(name);
  if (spec && !unit.empty() && unit != spec->unit) {
    const bool square = spec->unit == "m2" && unit.size() > 1 && unit.back() == '2';
    const auto length = vgd::parse_length_unit(square ? unit.substr(0, unit.size() - 1) : unit);
    if (length && spec->unit == "m") {
      *value *= vgd::metres_per(*length);
      unit = "m";
    } else if (length && square) {
      *value *= vgd::metres_per(*length) * vgd::metres_per(*length);
      unit = "m2";
    } else if (spec->unit == "deg" && unit == "rad") {
      *value *= 180.0 / 3.14159265358979323846;
      unit = "deg";
    }
  }
  return xvc::SetParameter(name, *value, unit);
}

// "pattern9=0,0.6", "pattern9=0,60cm": a pattern id and a point of it (metres,
// or in the unit after the second number, which applies to both).
xvc::AddPin parse_pin(const std::string& arg) {
  const auto eq = arg.find('=');
  const auto comma = arg.find(',', eq == std::string::npos ? 0 : eq);
  if (eq == std::string::npos || eq == 0 || comma == std::string::npos)
    throw vgd::Error("", arg, "--pin wants PATTERN=X,Y[UNIT], e.g. pattern9=0,0.6 or pattern9=0,60cm");
  const std::string id = arg.substr(0, eq);
  const auto x = vgd::parse_double(vgd::trim(std::string_view(arg).substr(eq + 1, comma - eq - 1)));
  const std::string_view rest = vgd::trim(std::string_view(arg).substr(comma + 1));
  std::optional<double> y;
  std::size_t cut = rest.size();
  for (; cut > 0; --cut)
    if ((y = vgd::parse_double(rest.substr(0, cut)))) break;
  if (!x || !y) throw vgd::Error("", id, "--pin's point is not two numbers: " + arg.substr(eq + 1));
  double scale = 1.0;
  if (const std::string unit(vgd::trim(rest.substr(cut))); !unit.empty()) {
    const auto length = vgd::parse_length_unit(unit);
    if (!length) throw vgd::Error("", id, "--pin's unit '" + unit + "' is not a length (m, cm, mm, in)");
    scale = vgd::metres_per(*length);
  }
  return xvc::AddPin(id, {*x * scale, *y * scale});
}

xvc::MirrorAxis parse_axis(std::string& id) {
  const auto colon = id.find(':');
  if (colon == std::string::npos) return xvc::MirrorAxis::automatic;
  const std::string axis = id.substr(colon + 1);
  id.resize(colon);
  if (axis == "grain") return xvc::MirrorAxis::grain_line;
  if (axis == "vertical") return xvc::MirrorAxis::vertical;
  throw vgd::Error("", id, "--mirror-pattern axis must be grain or vertical, not " + axis);
}

vgd::cli::Registrar reg{"edit", 30, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("edit", "Edit an XVC document: delete, copy, mirror patterns; pins; set parameters");
  auto o = std::make_shared<Options>();
  sub->add_option("FILE", o->input, "XVC document to read")->required();
  sub->add_option("-o,--output", o->output, "XVC document to write (may be FILE itself)")->required();
  auto repeatable = [&](const char* name, std::vector<std::string>& into, const char* help) {
    return sub->add_option(name, into, help)->expected(1)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  };
  auto* del = repeatable("--delete-pattern", o->delete_pattern, "Delete a PATTERN (and its hems, sizes, ...)");
  auto* cpy = repeatable("--copy-pattern", o->copy_pattern, "Copy a PATTERN as a new piece next to it");
  auto* mir = repeatable("--mirror-pattern", o->mirror_pattern,
                         "Mirror a PATTERN: ID (grain line, else vertical), ID:grain or ID:vertical");
  auto* par = repeatable("--set-parameter", o->set_parameter,
                         "Set a parameter: NAME=VALUE[UNIT], e.g. mesh.spacing=10mm, mesh.turn_angle=30deg");
  auto* dno = repeatable("--delete-node", o->delete_node, "Delete any element by id (and what would dangle)");
  auto* cno = repeatable("--copy-node", o->copy_node, "Copy any element by id, with fresh ids, right after it");
  auto* pin = repeatable("--pin", o->pin,
                         "Pin a PATTERN's cloth at a point of it, held where the arrangement puts it while the garment "
                         "drapes: PATTERN=X,Y[UNIT] in the pattern's frame, e.g. pattern9=0,0.6 or pattern9=0,60cm "
                         "(--delete-node removes a pin by its id)");
  sub->footer("Edits run in the order given and may be repeated. Each is checked; the first one\n"
              "refused stops the run and nothing is written.");
  return vgd::cli::Command{sub, [o, sub, del, cpy, mir, par, dno, cno, pin, &common]() -> int {
    xvc::Document doc = xvc::load_file(o->input);
    // Walk the options in command-line order; each occurrence takes its next value.
    std::map<const CLI::Option*, std::size_t> used;
    for (const CLI::Option* opt : sub->parse_order()) {
      if (opt != del && opt != cpy && opt != mir && opt != par && opt != dno && opt != cno && opt != pin) continue;
      std::string value = opt->results().at(used[opt]++);
      if (opt == del) {
        xvc::DeletePattern cmd(value);
        xvc::execute(doc, cmd);
        vgd::cli::say(common, "vgd: deleted pattern " + value);
      } else if (opt == cpy) {
        xvc::CopyPattern cmd(value);
        vgd::cli::say(common, "vgd: copied pattern " + value + " to " + xvc::execute(doc, cmd));
      } else if (opt == mir) {
        const auto axis = parse_axis(value);
        xvc::MirrorPattern cmd(value, axis);
        xvc::execute(doc, cmd);
        vgd::cli::say(common, "vgd: mirrored pattern " + value);
      } else if (opt == par) {
        auto cmd = parse_parameter(value);
        xvc::execute(doc, cmd);
        vgd::cli::say(common, "vgd: set " + value);
      } else if (opt == dno) {
        xvc::DeleteNode cmd(value);
        xvc::execute(doc, cmd);
        vgd::cli::say(common, "vgd: deleted " + value);
      } else if (opt == pin) {
        auto cmd = parse_pin(value);
        vgd::cli::say(common, "vgd: pinned " + value + " (" + xvc::execute(doc, cmd) + ")");
      } else if (opt == cno) {
        const auto path = doc.path_of(value);
        if (!path || path->empty()) throw vgd::Error(o->input, value, "no element with id " + value + " that can be copied");
        xvc::NodePath parent = *path;
        parent.pop_back();
        xvc::PasteNode cmd(std::string(doc.at(parent).id()), xvc::copy_node(doc, value), path->back() + 1);
        vgd::cli::say(common, "vgd: copied " + value + " to " + xvc::execute(doc, cmd));
      }
    }
    xvc::save_file(doc, o->output);
    vgd::cli::say(common, "vgd: wrote " + o->output);
    return vgd::cli::kOk;
  }};
}};
}  // namespace
}  // namespace cmd_edit
