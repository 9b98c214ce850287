// dxflib adapter: collects the entities vgd needs into raw::Drawing, with the
// line each entity starts on. dxflib stays inside this file.
#include <dxflib/dl_creationadapter.h>
#include <dxflib/dl_dxf.h>

#include <sstream>

#include "raw.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"

namespace vgd::dxf::raw {

namespace {

class Collector final : public DL_CreationAdapter {
 public:
  explicit Collector(DL_Dxf& dxf) : dxf_(dxf) {}
  Drawing drawing;

  // Lines of the entities, from the scan (dxflib gives none when reading memory).
  void set_lines(const ScanInfo& info) { lines_ = &info.entity_lines; }

  void addComment(const std::string& c) override { drawing.comments.push_back(c); }

  void setVariableString(const std::string& key, const std::string& value, int) override {
    drawing.header[key] = value;
  }
  void setVariableInt(const std::string& key, int value, int) override { drawing.header[key] = std::to_string(value); }
  void setVariableDouble(const std::string& key, double value, int) override {
    drawing.header[key] = std::to_string(value);
  }

  void addBlock(const DL_BlockData& d) override {
    finish_polyline();
    Block b;
    b.name = std::string(trim(d.name));
    b.base_x = d.bpx;
    b.base_y = d.bpy;
    b.line = line_of("BLOCK");
    drawing.blocks.push_back(std::move(b));
    current_ = &drawing.blocks.back();
  }
  void endBlock() override {
    finish_polyline();
    current_ = &drawing.model;
  }
  // dxflib calls endSection() for many groups, not only ENDSEC: it must not end a polyline.
  void endEntity() override {}

  void addPoint(const DL_PointData& d) override {
    finish_polyline();
    Point p;
    p.layer = layer();
    p.x = d.x;
    p.y = d.y;
    p.z = d.z;
    p.thickness = dxf_.getRealValue(39, 0.0);
    p.has_angle = dxf_.hasValue(50);
    p.angle = dxf_.getRealValue(50, 0.0);
    p.line = line_of("POINT");
    target().points.push_back(p);
  }
  void addLine(const DL_LineData& d) override {
    finish_polyline();
    target().lines.push_back({layer(), d.x1, d.y1, d.x2, d.y2, line_of("LINE")});
  }
  void addPolyline(const DL_PolylineData& d) override {
    finish_polyline();
    // dxflib reports POLYLINE and LWPOLYLINE alike; only LWPOLYLINE carries group 90.
    poly_ = Polyline{layer(), {}, (d.flags & 1) != 0, line_of(dxf_.hasValue(90) ? "LWPOLYLINE" : "POLYLINE")};
    poly_open_ = true;
  }
  void addVertex(const DL_VertexData& d) override {
    if (!poly_open_) return;  // a stray VERTEX outside a POLYLINE: nothing to attach it to
    poly_.vertices.push_back({d.x, d.y, d.bulge});
  }
  void endSequence() override { finish_polyline(); }
  void addText(const DL_TextData& d) override {
    finish_polyline();
    target().texts.push_back({layer(), d.ipx, d.ipy, d.text, line_of("TEXT")});
  }
  void addMText(const DL_MTextData& d) override {
    finish_polyline();
    target().texts.push_back({layer(), d.ipx, d.ipy, d.text, line_of("MTEXT")});
  }
  void addAttribute(const DL_AttributeData& d) override {
    // ATTRIB/ATTDEF: treat as a text so "Key: value" attributes are not lost.
    finish_polyline();
    target().texts.push_back({layer(), d.ipx, d.ipy, d.text, 0});
  }
  void addInsert(const DL_InsertData& d) override {
    finish_polyline();
    target().inserts.push_back({std::string(trim(d.name)), d.ipx, d.ipy, d.sx, d.sy, d.angle, line_of("INSERT")});
  }

  void finish_polyline() {
    if (!poly_open_) return;
    poly_open_ = false;
    target().polylines.push_back(std::move(poly_));
    poly_ = {};
  }

 private:
  std::string layer() const { return std::string(trim(attributes.getLayer())); }
  Block& target() { return *current_; }

  DL_Dxf& dxf_;
  Block* current_ = &drawing.model;
  Polyline poly_;
  bool poly_open_ = false;
  const std::map<std::string, std::vector<int>, std::less<>>* lines_ = nullptr;
  std::map<std::string, std::size_t, std::less<>> seen_;

  // Line of the next entity of this type (0 if the counts ever disagree).
  int line_of(std::string_view type) {
    if (!lines_) return 0;
    const auto it = lines_->find(type);
    auto& n = seen_[std::string(type)];
    const int line = it != lines_->end() && n < it->second.size() ? it->second[n] : 0;
    ++n;
    return line;
  }
};

}  // namespace

Drawing read(std::string_view text, const std::string& name) {
  DL_Dxf dxf;
  Collector c(dxf);
  std::istringstream in{std::string(text)};
  // Blocks live in a vector that grows while current_ points into it: reserve
  // for the block count so the pointer stays valid.
  const ScanInfo info = scan(text, name);
  c.drawing.blocks.reserve(info.blocks + 1);
  c.set_lines(info);
  if (!dxf.in(in, &c)) throw Error(name, "", "dxflib could not read the file");
  c.finish_polyline();
  return std::move(c.drawing);
}

}  // namespace vgd::dxf::raw
