#pragma once
// A JSON file read whole (certificate.json, reports), for the tests.
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace vgd::test {

inline nlohmann::json read_json(const std::filesystem::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

}  // namespace vgd::test
