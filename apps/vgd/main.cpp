// vgd — the command-line front end. Parses the command line, runs one
// subcommand, turns errors into messages and exit codes (docs/cli.md).
#include <cstdio>
#include <exception>

#include "cli.hpp"
#include "vgd/core/version.hpp"

int main(int argc, char** argv) {
  using namespace vgd::cli;
  CLI::App app{"vgd — Virtual Garment Designer: import garment patterns, mesh, simulate, publish"};
  app.set_version_flag("--version", std::string("vgd ") + vgd::kVersion);
  app.require_subcommand(1);
  app.footer("Run 'vgd COMMAND --help' for a command's options. Exit codes: 0 ok, 1 failed, "
             "2 usage, 3 check failed, 4 internal error.");
  Common common;
  app.add_flag("-q,--quiet", common.quiet, "No progress or summaries on stderr");

  Runner selected;
  register_import(app, selected, common);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? kOk : kUsage;
  }
  try {
    return selected ? selected() : kUsage;
  } catch (const vgd::Error& e) {
    std::fprintf(stderr, "vgd: error: %s\n", e.what());
    return kFailed;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vgd: internal error: %s\n", e.what());
    return kInternal;
  }
}
