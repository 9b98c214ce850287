#pragma once
// Standard body size tables as data (data/bodies/*.csv, README there): EN 13402-3
// women's and men's sizes, ASTM D5585 misses. Rows become BodyMeasurements
// (metres); measurements a table does not give are derived (complete_measurements).
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "vgd/body/avatar.hpp"

namespace vgd::body {

// Reads one table. Columns are named with their unit (height_cm, bust_in, ...;
// see data/bodies/README.md). Throws vgd::Error naming the file, the line and
// the column (file:line: column 'waist_cm': ...) for a bad cell, an unknown or
// unit-less column, a missing size/height/bust/waist/hip column, or no rows.
std::vector<BodyMeasurements> load_size_table(const std::filesystem::path& path);

// The shipped tables in lookup order: "en13402-women", "en13402-men", "astm-d5585-misses".
std::vector<std::string> size_table_names();

// data/bodies/<name>.csv (data_file()); throws naming the known tables.
std::filesystem::path size_table_file(std::string_view name);

// The size labelled `size` in `table` (a name above, or a path to a CSV), or,
// with table empty, in the first shipped table that has it (so "38" is the
// EN 13402-3 women's 38). Throws vgd::Error listing the sizes available.
BodyMeasurements find_size(std::string_view size, std::string_view table = "");

// The size of the shipped tables nearest to a body: smallest root mean square
// of the differences in height, bust, waist and hip (those given, > 0).
struct NearestSize {
  std::string table;          // e.g. "en13402-women"
  BodyMeasurements size;      // the table's row (label, sex, measurements)
  double rms = 0.0;           // m
};
NearestSize nearest_size(const BodyMeasurements& body);

// Fills measurements given as 0 from the others (proportions in data/bodies/README.md):
// under_bust, shoulder_width, neck, arm_length, inseam.
void complete_measurements(BodyMeasurements& m);

}  // namespace vgd::body
