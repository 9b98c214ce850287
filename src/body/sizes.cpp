// Body size tables (sizes.hpp, data/bodies/README.md).
#include "vgd/body/sizes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/core/units.hpp"
#include "vgd/core/data.hpp"

namespace vgd::body {

namespace {

bool male(const BodyMeasurements& m) { return iequals(m.sex, "male"); }

// "height_cm" -> ("height", cm). nullopt unit for unit-less columns (size, sex).
struct Column {
  std::string name;
  double metres_per_unit = 0.0;  // 0: not a length
};

Column parse_column(std::string_view text) {
  const std::string t = to_lower(trim(text));
  const auto us = t.rfind('_');
  if (us != std::string::npos) {
    const std::string unit = t.substr(us + 1);
    if (const auto u = parse_length_unit(unit)) return {t.substr(0, us), metres_per(*u)};
  }
  return {t, 0.0};
}

}  // namespace

void complete_measurements(BodyMeasurements& m) {
  // Proportions of data/bodies/README.md: typical adult fractions of the height.
  const double H = m.height;
  if (m.under_bust <= 0) m.under_bust = male(m) ? m.bust : m.bust - 0.13;
  if (m.shoulder_width <= 0) m.shoulder_width = male(m) ? 0.14 * H + 0.20 * m.bust : 0.13 * H + 0.19 * m.bust;
  if (m.neck <= 0) m.neck = (male(m) ? 0.40 : 0.39) * m.bust;
  if (m.arm_length <= 0) m.arm_length = (male(m) ? 0.355 : 0.35) * H;
  if (m.inseam <= 0) m.inseam = (male(m) ? 0.465 : 0.464) * H;
}

std::vector<BodyMeasurements> load_size_table(const std::filesystem::path& path) {
  const std::string file = path.string();
  const std::string text = read_file(path);
  if (trim(text).empty()) throw Error(file, "", "the size table is empty");
  std::istringstream in(text);
  std::vector<Column> columns;
  std::vector<BodyMeasurements> rows;
  const std::map<std::string, double BodyMeasurements::*> fields = {
      {"height", &BodyMeasurements::height},         {"bust", &BodyMeasurements::bust},
      {"chest", &BodyMeasurements::bust},            {"under_bust", &BodyMeasurements::under_bust},
      {"waist", &BodyMeasurements::waist},           {"hip", &BodyMeasurements::hip},
      {"shoulder_width", &BodyMeasurements::shoulder_width}, {"neck", &BodyMeasurements::neck},
      {"arm_length", &BodyMeasurements::arm_length}, {"inseam", &BodyMeasurements::inseam}};
  int line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (trim(line).empty() || trim(line).front() == '#') continue;
    const auto cells = split(line, ',');
    if (columns.empty()) {
      for (std::size_t c = 0; c < cells.size(); ++c) {
        Column col = parse_column(cells[c]);
        const bool length = fields.count(col.name) > 0;
        if (length && col.metres_per_unit == 0)
          throw Error(file, "column " + std::to_string(c + 1) + " '" + std::string(trim(cells[c])) + "'",
                      "a length column needs its unit in the name (e.g. " + col.name + "_cm)", line_no);
        if (!length && col.name != "size" && col.name != "sex")
          throw Error(file, "column " + std::to_string(c + 1) + " '" + std::string(trim(cells[c])) + "'",
                      "unknown column (known: size, sex, height, bust, chest, under_bust, waist, hip, shoulder_width, "
                      "neck, arm_length, inseam)",
                      line_no);
        columns.push_back(col);
      }
      for (const char* need : {"size", "height", "bust", "waist", "hip"}) {
        bool found = false;
        for (const auto& c : columns) found |= c.name == need || (std::string(need) == "bust" && c.name == "chest");
        if (!found) throw Error(file, "header", std::string("no '") + need + "' column", line_no);
      }
      continue;
    }
    if (cells.size() != columns.size())
      throw Error(file, "", "expected " + std::to_string(columns.size()) + " cells, found " + std::to_string(cells.size()),
                  line_no);
    BodyMeasurements m;
    m.under_bust = m.shoulder_width = m.neck = m.arm_length = m.inseam = 0;  // derived unless given
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const std::string_view cell = trim(cells[c]);
      const Column& col = columns[c];
      const std::string where = "column " + std::to_string(c + 1) + " '" + col.name + "'";
      if (col.name == "size") {
        if (cell.empty()) throw Error(file, where, "empty size label", line_no);
        m.label = std::string(cell);
      } else if (col.name == "sex") {
        if (!iequals(cell, "female") && !iequals(cell, "male"))
          throw Error(file, where, "sex must be female or male (got '" + std::string(cell) + "')", line_no);
        m.sex = to_lower(cell);
      } else if (!cell.empty()) {
        const auto v = parse_double(cell);
        if (!v || *v <= 0) throw Error(file, where, "'" + std::string(cell) + "' is not a positive number", line_no);
        m.*fields.at(col.name) = *v * col.metres_per_unit;
      } else if (col.name == "height" || col.name == "bust" || col.name == "chest" || col.name == "waist" || col.name == "hip") {
        throw Error(file, where, "empty cell (this measurement is required)", line_no);
      }
    }
    if (m.sex == "male" && m.under_bust <= 0) m.under_bust = m.bust;
    complete_measurements(m);
    rows.push_back(m);
  }
  if (rows.empty()) throw Error(file, "", "the size table has no rows");
  return rows;
}

NearestSize nearest_size(const BodyMeasurements& body) {
  NearestSize best;
  best.rms = std::numeric_limits<double>::infinity();
  for (const auto& name : size_table_names())
    for (const auto& row : load_size_table(size_table_file(name))) {
      double sum = 0;
      int n = 0;
      for (const auto& [a, b] : {std::pair{body.height, row.height}, {body.bust, row.bust}, {body.waist, row.waist},
                                {body.hip, row.hip}})
        if (a > 0) sum += (a - b) * (a - b), ++n;
      const double rms = n ? std::sqrt(sum / n) : std::numeric_limits<double>::infinity();
      if (rms < best.rms) best = {name, row, rms};
    }
  return best;
}

std::vector<std::string> size_table_names() { return {"en13402-women", "en13402-men", "astm-d5585-misses"}; }

std::filesystem::path size_table_file(std::string_view name) {
  const auto names = size_table_names();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw Error("", std::string(name), "no such size table (known: " + list + ")");
  }
  return data_file("bodies/" + std::string(name) + ".csv");
}

BodyMeasurements find_size(std::string_view size, std::string_view table) {
  std::vector<std::filesystem::path> files;
  if (table.empty()) {
    for (const auto& n : size_table_names()) files.push_back(size_table_file(n));
  } else if (table.find('/') != std::string_view::npos || table.ends_with(".csv")) {
    files.emplace_back(std::string(table));
  } else {
    files.push_back(size_table_file(table));
  }
  std::string available;
  for (const auto& f : files) {
    const auto rows = load_size_table(f);
    for (const auto& r : rows)
      if (iequals(r.label, size)) return r;
    available += (available.empty() ? "" : "; ") + f.stem().string() + ":";
    for (const auto& r : rows) available += " " + r.label;
  }
  throw Error(table.empty() ? "" : std::string(table), "size '" + std::string(size) + "'",
              "no such size (available: " + available + ")");
}

}  // namespace vgd::body
