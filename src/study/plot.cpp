// Work-precision diagrams (study/plot.hpp).
#include "vgd/study/plot.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <map>

#include "vgd/render/image.hpp"

namespace vgd::study {

namespace {

// ---- a small PNG plotter (log–log work-precision diagrams) -----------------------

// A 3 × 5 pixel font: rows top to bottom, '1' = ink.
const std::map<char, const char*>& font() {
  static const std::map<char, const char*> f{
      {'0', "111101101101111"}, {'1', "010110010010111"}, {'2', "111001111100111"}, {'3', "111001111001111"},
      {'4', "101101111001001"}, {'5', "111100111001111"}, {'6', "111100111101111"}, {'7', "111001001001001"},
      {'8', "111101111101111"}, {'9', "111101111001111"}, {'A', "010101111101101"}, {'B', "110101110101110"},
      {'C', "011100100100011"}, {'D', "110101101101110"}, {'E', "111100110100111"}, {'F', "111100110100100"},
      {'G', "011100101101011"}, {'H', "101101111101101"}, {'I', "111010010010111"}, {'J', "001001001101010"},
      {'K', "101101110101101"}, {'L', "100100100100111"}, {'M', "101111111101101"}, {'N', "110101101101101"},
      {'O', "010101101101010"}, {'P', "110101110100100"}, {'Q', "010101101110011"}, {'R', "110101110101101"},
      {'S', "011100010001110"}, {'T', "111010010010010"}, {'U', "101101101101111"}, {'V', "101101101101010"},
      {'W', "101101111111101"}, {'X', "101101010101101"}, {'Y', "101101010010010"}, {'Z', "111001010100111"},
      {'-', "000000111000000"}, {'.', "000000000000010"}, {'+', "000010111010000"}, {'(', "001010010010001"},
      {')', "100010010010100"}, {'/', "001001010100100"}, {'=', "000111000111000"}, {':', "000010000010000"},
      {'x', "000101010101000"}};
  return f;
}

using Rgb = std::array<std::uint8_t, 3>;

struct Canvas {
  render::Image img;
  explicit Canvas(int w, int h) : img(w, h, {255, 255, 255, 255}) {}
  void dot(int x, int y, Rgb c) {
    if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
    auto* p = img.pixel(x, y);
    p[0] = c[0], p[1] = c[1], p[2] = c[2];
  }
  void box(int x, int y, int r, Rgb c) {
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx) dot(x + dx, y + dy, c);
  }
  void line(int x0, int y0, int x1, int y1, Rgb c, int width = 1) {
    const int n = std::max({std::abs(x1 - x0), std::abs(y1 - y0), 1});
    for (int k = 0; k <= n; ++k) {
      const int x = x0 + (x1 - x0) * k / n, y = y0 + (y1 - y0) * k / n;
      box(x, y, width / 2, c);
    }
  }
  void ring(int x, int y, int r, Rgb c) {
    for (int a = 0; a < 360; a += 3) {
      const double t = a * 3.14159265358979 / 180;
      box(x + static_cast<int>(std::lround(r * std::cos(t))), y + static_cast<int>(std::lround(r * std::sin(t))), 0, c);
    }
  }
  // Text in the 3 × 5 font at `scale` pixels per font pixel; lower case drawn as upper.
  void text(int x, int y, const std::string& s, Rgb c, int scale = 2) {
    for (char ch : s) {
      const char u = ch == 'x' ? 'x' : static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
      const auto it = font().find(u);
      if (it != font().end())
        for (int r = 0; r < 5; ++r)
          for (int q = 0; q < 3; ++q)
            if (it->second[3 * r + q] == '1')
              for (int dy = 0; dy < scale; ++dy)
                for (int dx = 0; dx < scale; ++dx) dot(x + q * scale + dx, y + r * scale + dy, c);
      x += 4 * scale;
    }
  }
};

Rgb colour(const std::string& method) {
  if (method == "symplectic-euler") return {213, 94, 0};
  if (method == "midpoint") return {0, 158, 115};
  if (method == "rk4") return {0, 114, 178};
  if (method == "implicit-euler") return {204, 121, 167};
  return {230, 159, 0};  // bdf
}

// True for the rows no other row beats in both error and CPU time.
std::vector<bool> pareto(const std::vector<const PlotPoint*>& rows) {
  std::vector<bool> front(rows.size(), true);
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < rows.size(); ++j)
      if (i != j && rows[j]->cpu_s <= rows[i]->cpu_s && rows[j]->error_mm <= rows[i]->error_mm &&
          (rows[j]->cpu_s < rows[i]->cpu_s || rows[j]->error_mm < rows[i]->error_mm))
        front[i] = false;
  return front;
}

}  // namespace

void plot_work_precision(const std::string& title, const std::vector<PlotPoint>& points,
                         const std::filesystem::path& file, double floor) {
  std::vector<const PlotPoint*> rows;
  for (const auto& p : points) rows.push_back(&p);
  const int W = 900, H = 620, left = 90, right = 220, top = 50, bottom = 70;
  Canvas cv(W, H);
  const int pw = W - left - right, ph = H - top - bottom;
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  for (const PlotPoint* r : rows) {
    xmin = std::min(xmin, std::log10(std::max(r->cpu_s, 1e-4))), xmax = std::max(xmax, std::log10(std::max(r->cpu_s, 1e-4)));
    ymin = std::min(ymin, std::log10(r->error_mm)), ymax = std::max(ymax, std::log10(r->error_mm));
  }
  if (floor > 0) ymin = std::min(ymin, std::log10(floor)), ymax = std::max(ymax, std::log10(floor));
  xmin = std::floor(xmin), xmax = std::max(std::ceil(xmax), xmin + 1);
  ymin = std::floor(ymin), ymax = std::max(std::ceil(ymax), ymin + 1);
  auto px = [&](double cpu) {
    return left + static_cast<int>(std::lround((std::log10(std::max(cpu, 1e-4)) - xmin) / (xmax - xmin) * pw));
  };
  auto py = [&](double err) { return top + ph - static_cast<int>(std::lround((std::log10(err) - ymin) / (ymax - ymin) * ph)); };
  const Rgb ink{0, 0, 0}, grid{220, 220, 220};
  // Decade grid and labels.
  for (int e = static_cast<int>(xmin); e <= static_cast<int>(xmax); ++e) {
    const int x = left + static_cast<int>(std::lround((e - xmin) / (xmax - xmin) * pw));
    cv.line(x, top, x, top + ph, grid);
    cv.text(x - 14, top + ph + 8, "1E" + std::to_string(e), ink);
  }
  for (int e = static_cast<int>(ymin); e <= static_cast<int>(ymax); ++e) {
    const int y = top + ph - static_cast<int>(std::lround((e - ymin) / (ymax - ymin) * ph));
    cv.line(left, y, left + pw, y, grid);
    cv.text(left - 50, y - 5, "1E" + std::to_string(e), ink);
  }
  cv.line(left, top, left, top + ph, ink);
  cv.line(left, top + ph, left + pw, top + ph, ink);
  cv.text(left, 15, title, ink, 3);
  cv.text(left + pw / 2 - 60, H - 30, "CPU TIME (S)", ink);
  cv.text(8, top - 25, "ERROR (MM)", ink);
  if (floor > 0) {
    const Rgb grey{120, 120, 120};
    for (int x = left; x < left + pw; x += 12) cv.line(x, py(floor), std::min(x + 6, left + pw), py(floor), grey);
    cv.text(left + pw - 160, py(floor) - 16, "2X REFERENCE ERROR", grey);
  }
  // One curve per method, in the order of its step or tolerance.
  std::map<std::string, std::vector<const PlotPoint*>> by_method;
  for (const PlotPoint* r : rows) by_method[r->method].push_back(r);
  int legend = top + 10;
  for (auto& [method, list] : by_method) {
    std::sort(list.begin(), list.end(), [](const PlotPoint* a, const PlotPoint* b) { return a->step_or_tol > b->step_or_tol; });
    const Rgb c = colour(method);
    for (std::size_t k = 0; k + 1 < list.size(); ++k)
      cv.line(px(list[k]->cpu_s), py(list[k]->error_mm), px(list[k + 1]->cpu_s), py(list[k + 1]->error_mm), c, 2);
    for (const PlotPoint* r : list) {
      cv.box(px(r->cpu_s), py(r->error_mm), 3, c);
      if (r->hollow) cv.box(px(r->cpu_s), py(r->error_mm), 1, {255, 255, 255});  // hollow: unresolved
    }
    cv.line(left + pw + 20, legend + 4, left + pw + 45, legend + 4, c, 3);
    cv.text(left + pw + 52, legend, method, ink);
    legend += 22;
  }
  const auto front = pareto(rows);
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (front[i]) cv.ring(px(rows[i]->cpu_s), py(rows[i]->error_mm), 8, ink);
  cv.ring(left + pw + 32, legend + 6, 8, ink);
  cv.text(left + pw + 52, legend + 1, "PARETO FRONT", ink);
  render::write_png(cv.img, file);
}

}  // namespace vgd::study
