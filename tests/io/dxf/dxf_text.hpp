#pragma once
// Builds small DXF texts for importer tests, so each test states the exact
// entities it feeds in (and can break them on purpose).
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace vgd::test {

class DxfText {
 public:
  DxfText& pair(int code, const std::string& value) {
    s_ << code << "\n" << value << "\n";
    return *this;
  }
  DxfText& pair(int code, double value) {
    std::ostringstream v;
    v.precision(17);
    v << value;
    return pair(code, v.str());
  }
  DxfText& begin_blocks() { return pair(0, "SECTION").pair(2, "BLOCKS"); }
  DxfText& begin_entities() { return pair(0, "SECTION").pair(2, "ENTITIES"); }
  DxfText& end_section() { return pair(0, "ENDSEC"); }
  DxfText& eof() { return pair(0, "EOF"); }
  DxfText& block(const std::string& name) {
    return pair(0, "BLOCK").pair(8, "0").pair(2, name).pair(70, "0").pair(10, 0.0).pair(20, 0.0);
  }
  DxfText& endblk() { return pair(0, "ENDBLK").pair(8, "0"); }
  DxfText& text(const std::string& layer, const std::string& value, double x = 0, double y = 0) {
    return pair(0, "TEXT").pair(8, layer).pair(10, x).pair(20, y).pair(40, 0.25).pair(1, value);
  }
  DxfText& polyline(const std::string& layer, const std::vector<std::pair<double, double>>& pts, bool closed = false,
                    const std::vector<double>& bulges = {}) {
    pair(0, "POLYLINE").pair(8, layer).pair(66, "1").pair(70, closed ? "1" : "0");
    for (std::size_t i = 0; i < pts.size(); ++i) {
      pair(0, "VERTEX").pair(8, layer).pair(10, pts[i].first).pair(20, pts[i].second);
      if (i < bulges.size() && bulges[i] != 0) pair(42, bulges[i]);
    }
    return pair(0, "SEQEND").pair(8, layer);
  }
  DxfText& lwpolyline(const std::string& layer, const std::vector<std::pair<double, double>>& pts, bool closed) {
    pair(0, "LWPOLYLINE").pair(8, layer).pair(90, std::to_string(pts.size())).pair(70, closed ? "1" : "0");
    for (const auto& [x, y] : pts) pair(10, x).pair(20, y);
    return *this;
  }
  DxfText& line(const std::string& layer, double x1, double y1, double x2, double y2) {
    return pair(0, "LINE").pair(8, layer).pair(10, x1).pair(20, y1).pair(11, x2).pair(21, y2);
  }
  DxfText& point(const std::string& layer, double x, double y) {
    return pair(0, "POINT").pair(8, layer).pair(10, x).pair(20, y);
  }
  DxfText& insert(const std::string& name, double x = 0, double y = 0, double sx = 1, double sy = 1,
                  double angle = 0) {
    pair(0, "INSERT").pair(8, "1").pair(2, name).pair(10, x).pair(20, y);
    if (sx != 1) pair(41, sx);
    if (sy != 1) pair(42, sy);
    if (angle != 0) pair(50, angle);
    return *this;
  }
  // A square piece block (mm), with the usual texts and a grain line.
  DxfText& square_piece(const std::string& block, const std::string& name, const std::string& size, double side = 100,
                        double x0 = 0, double y0 = 0) {
    return this->block(block)
        .text("1", "Piece Name: " + name)
        .text("1", "Size: " + size)
        .polyline("1", {{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}, {x0, y0}})
        .line("7", x0 + side / 2, y0 + 10, x0 + side / 2, y0 + side - 10)
        .endblk();
  }
  std::string str() const { return s_.str(); }

 private:
  std::ostringstream s_;
};

// A complete one-piece file in mm.
inline std::string one_square_file(double side = 100) {
  DxfText d;
  d.begin_blocks().square_piece("SQ_M", "SQUARE", "M", side).end_section();
  d.begin_entities().text("1", "Units: METRIC").text("1", "Sample Size: M").insert("SQ_M").end_section().eof();
  return d.str();
}

}  // namespace vgd::test
