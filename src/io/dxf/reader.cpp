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

  // Every pair passes here first: track the line where the current entity began.
  // dxflib reports an entity when the next "0" group arrives, so the entity's
  // own start is the previous "0" group.
  void processCodeValuePair(unsigned int code, const std::string&) override {
    ++pairs_;
    if (code == 0) {
      entity_line_ = zero_line_;
      zero_line_ = 2 * pairs_ - 1;
    }
  }

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
    b.line = entity_line_;
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
    p.line = entity_line_;
    target().points.push_back(p);
  }
  void addLine(const DL_LineData& d) override {
    finish_polyline();
    target().lines.push_back({layer(), d.x1, d.y1, d.x2, d.y2, entity_line_});
  }
  void addPolyline(const DL_PolylineData& d) override {
    finish_polyline();
    poly_ = Polyline{layer(), {}, (d.flags & 1) != 0, entity_line_};
    poly_open_ = true;
  }
  void addVertex(const DL_VertexData& d) override {
    if (!poly_open_) return;  // a stray VERTEX outside a POLYLINE: nothing to attach it to
    poly_.vertices.push_back({d.x, d.y, d.bulge});
  }
  void endSequence() override { finish_polyline(); }
  void addText(const DL_TextData& d) override {
    finish_polyline();
    target().texts.push_back({layer(), d.ipx, d.ipy, d.text, entity_line_});
  }
  void addMText(const DL_MTextData& d) override {
    finish_polyline();
    target().texts.push_back({layer(), d.ipx, d.ipy, d.text, entity_line_});
  }
  void addAttribute(const DL_AttributeData& d) override {
    // ATTRIB/ATTDEF: treat as a text so "Key: value" attributes are not lost.
    finish_polyline();
    target().texts.push_back({layer(), d.ipx, d.ipy, d.text, entity_line_});
  }
  void addInsert(const DL_InsertData& d) override {
    finish_polyline();
    target().inserts.push_back({std::string(trim(d.name)), d.ipx, d.ipy, d.sx, d.sy, d.angle, entity_line_});
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
  long pairs_ = 0;
  int zero_line_ = 0, entity_line_ = 0;
};

}  // namespace

Drawing read(std::string_view text, const std::string& name) {
  DL_Dxf dxf;
  Collector c(dxf);
  std::istringstream in{std::string(text)};
  // Blocks live in a vector that grows while current_ points into it: reserve
  // for the block count so the pointer stays valid.
  c.drawing.blocks.reserve(scan(text, name).blocks + 1);
  if (!dxf.in(in, &c)) throw Error(name, "", "dxflib could not read the file");
  c.finish_polyline();
  return std::move(c.drawing);
}

}  // namespace vgd::dxf::raw
