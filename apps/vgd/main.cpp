// vgd — the command-line front end. Builds the registered subcommands, parses the
// command line, runs one, and turns errors into messages and exit codes (docs/cli.md).
#include <algorithm>
#include <cstdio>
#include <exception>

#include <omp.h>

#include "cli.hpp"
#include "vgd/core/version.hpp"

int main(int argc, char** argv) {
  using namespace vgd::cli;
  CLI::App app{"vgd — Virtual Garment Designer: import garment patterns, edit, mesh, simulate, publish"};
  app.set_version_flag("--version", std::string("vgd ") + vgd::kVersion);
  app.require_subcommand(1);
  app.fallthrough();  // global options (-q) may follow the subcommand
  app.footer("Run 'vgd COMMAND --help' for a command's options.\n"
             "Exit codes: 0 ok, 1 failed (bad input), 2 usage, 3 check failed, 4 internal error.");
  Common common;
  app.add_flag("-q,--quiet", common.quiet, "No progress, summaries or warnings on stderr (errors still shown)");
  app.add_flag("-v,--verbose", common.verbose, "Also show informational messages (units found, repairs made)");
  // Every core by default: a simulation run uses fewer threads while other
  // processes keep cores busy (sim/threads.hpp), so more threads are never
  // slower than one on a shared machine (docs/performance.md, "Threads").
  app.add_option("--threads", common.threads,
                 "Threads for the simulation's force kernels (0 = all cores, fewer while other processes keep "
                 "them busy)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();

  auto entries = registry();
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.order < b.order; });
  std::vector<Command> commands;
  for (auto& e : entries) commands.push_back(e.factory(app, common));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? kOk : kUsage;
  }
  omp_set_num_threads(common.threads > 0 ? common.threads : omp_get_num_procs());
  try {
    for (auto& c : commands)
      if (c.app->parsed()) return c.run();
    return kUsage;
  } catch (const vgd::Error& e) {
    std::fprintf(stderr, "vgd: error: %s\n", e.what());
    return kFailed;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vgd: internal error: %s\n", e.what());
    return kInternal;
  }
}
