#pragma once
// Shared plumbing of the `vgd` subcommands: exit codes, output, registration.
//
// Each subcommand lives in its own cmd_<name>.cpp, parses its options and calls
// the library. A file registers its command with a static Registrar:
//
//   static vgd::cli::Registrar reg{"import", 10, [](CLI::App& app, vgd::cli::Common& common) {
//     auto* sub = app.add_subcommand("import", "Import an AAMA/ASTM DXF pattern file");
//     auto opts = std::make_shared<Options>();
//     sub->add_option(...);
//     return vgd::cli::Command{sub, [opts, &common] { ... return vgd::cli::kOk; }};
//   }};
//
// main() builds the commands in `order`, parses, runs the selected one and maps
// exceptions to exit codes (vgd::Error -> kFailed with its message).
#include <CLI/CLI.hpp>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "vgd/core/diagnostics.hpp"

namespace vgd::cli {

// Exit codes (docs/cli.md).
enum Exit : int {
  kOk = 0,           // success
  kFailed = 1,       // the input was bad or the operation failed; the message says why
  kUsage = 2,        // wrong command line (CLI11 prints the reason; see --help)
  kCheckFailed = 3,  // a check ran and found problems (validate, compare)
  kInternal = 4,     // an unexpected internal error (a bug: please report it)
};

// Options every subcommand shares (set on the top-level app).
struct Common {
  bool quiet = false;    // no progress or summaries on stderr
  bool verbose = false;  // also print informational diagnostics
  int threads = 0;       // OpenMP threads for the engine's force kernels (0 = all cores)
};

struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

using Factory = std::function<Command(CLI::App& app, Common& common)>;

// Registers a subcommand at static-initialisation time; `order` sorts --help.
struct Registrar {
  Registrar(std::string name, int order, Factory factory);
};

struct Entry {
  std::string name;
  int order;
  Factory factory;
};
std::vector<Entry>& registry();

// Prints warnings and errors to stderr, one line each
// ("vgd: warning: file:line: entity: message"); info lines only when verbose.
void print_diagnostics(const Diagnostics& d, const Common& common);

// JSON array of diagnostics: [{severity, message, file?, line?, entity?}].
nlohmann::json to_json(const Diagnostics& d);

// Writes JSON to stdout, pretty-printed.
void print_json(const nlohmann::json& j);

// Prints a summary line to stderr unless quiet.
void say(const Common& common, const std::string& line);

// `vgd bench robustness` (cmd_bench_robustness.cpp): the sweep, or the parts
// of it the options name.
struct RobustnessArgs {
  bool quick = false, json = false, between_particles = true, sleeves_first = false;
  double time_limit = 8.0;
  std::vector<std::string> garments, sizes, fabrics, models;
  std::vector<double> spacings;
  int jitters = -1;  // -1: the sweep's
};

}  // namespace vgd::cli
