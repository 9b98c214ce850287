// vgd validate: checks an XVC document against schemas/xvc.xsd and vgd's own rules.
#include <cstdio>
#include <memory>

#include "cli.hpp"
#include "vgd/xvc/validate.hpp"

namespace cmd_validate {
namespace {
struct Options {
  std::string input;
  std::string schema;
  bool json = false;
};

vgd::cli::Registrar reg{"validate", 20, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("validate", "Check an XVC document against the XSD and vgd's rules");
  auto o = std::make_shared<Options>();
  sub->add_option("FILE", o->input, "XVC document")->required();
  sub->add_option("--schema", o->schema, "XSD to use (default: xvc.xsd from $VGD_SCHEMA_DIR, the source tree or the install)");
  sub->add_flag("--json", o->json, "Print the result as JSON on stdout");
  sub->footer("Prints each problem as FILE:LINE: ELEMENT: MESSAGE on stdout.\n"
              "Exit codes: 0 valid (warnings allowed), 3 invalid, 1 the file or schema cannot be read.");
  return vgd::cli::Command{sub, [o, &common]() -> int {
    const std::filesystem::path xsd = o->schema.empty() ? vgd::xvc::default_schema_path() : std::filesystem::path(o->schema);
    const vgd::Diagnostics d = vgd::xvc::validate_file(o->input, xsd);
    const auto errors = d.count(vgd::Severity::error), warnings = d.count(vgd::Severity::warning);
    if (o->json) {
      vgd::cli::print_json({{"file", o->input},
                            {"schema", xsd.string()},
                            {"valid", errors == 0},
                            {"errors", errors},
                            {"warnings", warnings},
                            {"diagnostics", vgd::cli::to_json(d)}});
    } else {
      // One problem per line, in the form editors and CI annotators understand.
      for (auto item : d.items()) {
        if (item.severity != vgd::Severity::error) item.message = std::string(vgd::to_string(item.severity)) + ": " + item.message;
        std::printf("%s\n", item.format().c_str());
      }
      std::fflush(stdout);
    }
    vgd::cli::say(common, "vgd: " + o->input + ": " +
                              (errors == 0 ? std::string("valid") : std::to_string(errors) + " error(s)") +
                              (warnings ? ", " + std::to_string(warnings) + " warning(s)" : ""));
    return errors == 0 ? vgd::cli::kOk : vgd::cli::kCheckFailed;
  }};
}};
}  // namespace
}  // namespace cmd_validate
