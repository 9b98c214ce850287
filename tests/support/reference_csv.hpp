#pragma once
// The analytic reference tables of ../shared/reference (mechanics.md): a CSV
// as columns by header name. Empty when the file is absent (callers skip
// with VGD_REQUIRE_SHARED()). Text cells (heavy_elastica.csv's `grid`) are
// read as NaN.
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "support/test_paths.hpp"

namespace vgd::test {

inline std::map<std::string, std::vector<double>> reference_csv(const std::string& name) {
  std::map<std::string, std::vector<double>> cols;
  std::ifstream in(shared_dir() / "reference" / name);
  if (!in) return cols;
  std::string line, cell;
  std::getline(in, line);
  std::vector<std::string> head;
  for (std::stringstream ss(line); std::getline(ss, cell, ',');) head.push_back(cell);
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    for (std::size_t k = 0; k < head.size() && std::getline(ss, cell, ','); ++k) {
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      cols[head[k]].push_back(end == cell.c_str() ? std::nan("") : v);
    }
  }
  return cols;
}

}  // namespace vgd::test
