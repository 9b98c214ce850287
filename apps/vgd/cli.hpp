#pragma once
// Shared plumbing of the `vgd` subcommands: exit codes, output, error handling.
// Each subcommand lives in its own cmd_<name>.cpp and only parses options and
// calls the library.
#include <CLI/CLI.hpp>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "vgd/core/diagnostics.hpp"

namespace vgd::cli {

// Exit codes (docs/cli.md).
enum Exit : int {
  kOk = 0,          // success
  kFailed = 1,      // the input was bad or the operation failed; the message says why
  kUsage = 2,       // wrong command line (CLI11 prints the reason and --help)
  kCheckFailed = 3, // a check ran and found problems (validate, compare)
  kInternal = 4,    // an unexpected internal error (a bug: please report)
};

// Options every subcommand shares.
struct Common {
  bool quiet = false;  // no progress or summaries on stderr
};

// Registers one subcommand; `run` is stored and called after parsing.
using Runner = std::function<int()>;
void add_command(CLI::App& app, Runner& selected, CLI::App* sub, Runner run);

// Prints diagnostics (warnings, errors) to stderr, one line each.
void print_diagnostics(const Diagnostics& d, bool quiet);

// JSON array of diagnostics: [{severity, file, line, entity, message}].
nlohmann::json to_json(const Diagnostics& d);

// Writes JSON to stdout, pretty-printed.
void print_json(const nlohmann::json& j);

// Subcommand registration, one per file.
void register_import(CLI::App& app, Runner& selected, Common& common);

}  // namespace vgd::cli
