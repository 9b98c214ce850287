#include "cli.hpp"

#include <cstdio>
#include <iostream>

namespace vgd::cli {

std::vector<Entry>& registry() {
  static std::vector<Entry> r;
  return r;
}

Registrar::Registrar(std::string name, int order, Factory factory) {
  registry().push_back({std::move(name), order, std::move(factory)});
}

void print_diagnostics(const Diagnostics& d, const Common& common) {
  for (const auto& item : d.items()) {
    if (item.severity == Severity::info && !common.verbose) continue;
    if (item.severity == Severity::warning && common.quiet) continue;
    std::fprintf(stderr, "vgd: %s: %s\n", to_string(item.severity), item.format().c_str());
  }
}

nlohmann::json to_json(const Diagnostics& d) {
  auto arr = nlohmann::json::array();
  for (const auto& item : d.items()) {
    nlohmann::json j{{"severity", to_string(item.severity)}, {"message", item.message}};
    if (!item.file.empty()) j["file"] = item.file;
    if (item.line > 0) j["line"] = item.line;
    if (!item.entity.empty()) j["entity"] = item.entity;
    arr.push_back(std::move(j));
  }
  return arr;
}

// Invalid UTF-8 (a name read from a file) is printed as U+FFFD, never refused.
void print_json(const nlohmann::json& j) {
  std::cout << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
}

void say(const Common& common, const std::string& line) {
  std::fflush(stdout);  // keep reports and summaries in the order they were made
  if (!common.quiet) std::fprintf(stderr, "%s\n", line.c_str());
}

}  // namespace vgd::cli
