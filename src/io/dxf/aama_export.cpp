// AAMA DXF writer on dxflib's DL_Writer, writing into memory so that the file
// can be replaced atomically.
#include <dxflib/dl_writer.h>

#include <cmath>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/core/version.hpp"
#include "vgd/io/dxf/export.hpp"

namespace vgd::dxf {

using pattern::Piece;
using pattern::PointKind;
using pattern::Vec2;

namespace {

// DL_Writer that appends to a string. Reals use the shortest round-trip form so
// that export -> import is exact to the last bit of the file-unit value.
class StringWriter final : public DL_Writer {
 public:
  StringWriter() : DL_Writer(DL_Codes::AC1009) {}
  // DL_Writer's output methods are const; the buffer is this writer's whole state.
  mutable std::string out;
  void dxfReal(int gc, double v) const override { pair(gc, format_double(v == 0.0 ? 0.0 : v)); }
  void dxfInt(int gc, int v) const override { pair(gc, std::to_string(v)); }
  void dxfHex(int gc, int v) const override {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%X", v);
    pair(gc, buf);
  }
  void dxfString(int gc, const char* v) const override { pair(gc, v); }
  void dxfString(int gc, const std::string& v) const override { pair(gc, v); }

 private:
  void pair(int gc, const std::string& v) const {
    char code[8];
    std::snprintf(code, sizeof code, "%3d\n", gc);
    out += code;
    out += v;
    out += '\n';
  }
};

class AamaWriter {
 public:
  AamaWriter(StringWriter& w, double units_per_metre) : w_(w), k_(units_per_metre) {}

  void text(const std::string& layer, const Vec2& at, const std::string& value) {
    w_.dxfString(0, "TEXT");
    w_.dxfString(8, layer);
    w_.dxfReal(10, at.x() * k_);
    w_.dxfReal(20, at.y() * k_);
    w_.dxfReal(40, 0.25 * 0.0254 * k_);  // 1/4 inch letters, as Gerber writes
    w_.dxfString(1, value);
  }
  void point(const std::string& layer, const Vec2& p) {
    w_.dxfString(0, "POINT");
    w_.dxfString(8, layer);
    w_.dxfReal(10, p.x() * k_);
    w_.dxfReal(20, p.y() * k_);
  }
  void line(const std::string& layer, const pattern::Segment& s) {
    w_.dxfString(0, "LINE");
    w_.dxfString(8, layer);
    w_.dxfReal(10, s.a.x() * k_);
    w_.dxfReal(20, s.a.y() * k_);
    w_.dxfReal(11, s.b.x() * k_);
    w_.dxfReal(21, s.b.y() * k_);
  }
  template <class Points, class Get>
  void polyline(const std::string& layer, const Points& pts, bool closed, Get get) {
    w_.dxfString(0, "POLYLINE");
    w_.dxfString(8, layer);
    w_.dxfInt(66, 1);
    w_.dxfInt(70, closed ? 1 : 0);
    for (const auto& item : pts) {
      const Vec2 p = get(item);
      w_.dxfString(0, "VERTEX");
      w_.dxfString(8, layer);
      w_.dxfReal(10, p.x() * k_);
      w_.dxfReal(20, p.y() * k_);
    }
    w_.dxfString(0, "SEQEND");
    w_.dxfString(8, layer);
  }

  void piece(const Piece& p, const std::string& flavour) {
    w_.dxfString(0, "BLOCK");
    w_.dxfString(8, "0");
    w_.dxfString(2, p.block);
    w_.dxfInt(70, 0);
    w_.dxfReal(10, 0.0);
    w_.dxfReal(20, 0.0);
    w_.dxfString(3, p.block);

    // Attribute texts sit near the piece's lower-left corner.
    Vec2 lo = p.boundary.empty() ? Vec2::Zero() : p.boundary.front().p;
    for (const auto& c : p.boundary) lo = lo.cwiseMin(c.p);
    Vec2 at = lo + Vec2(0.01, 0.01);
    auto label = [&](const std::string& v) {
      text("1", at, v);
      at.y() += 0.01;
    };
    label("Piece Name: " + p.name);
    label("Size: " + p.size);
    if (flavour == "ASTM")
      label("Quantity: " + std::to_string(p.quantity - p.quantity_flipped) + "," + std::to_string(p.quantity_flipped));
    else
      label("Quantity: " + std::to_string(p.quantity));
    if (!p.category.empty()) label("Category: " + p.category);
    if (!p.fabric.empty()) label("Fabric: " + p.fabric);
    if (!p.annotation.empty()) label("Annotation: " + p.annotation);
    for (const auto& [k, v] : p.annotations) label(k.empty() ? v : k + ": " + v);

    polyline("1", p.boundary, true, [](const pattern::ContourPoint& c) { return c.p; });
    for (const auto& c : p.boundary) {
      if (c.kind == PointKind::turn) point("2", c.p);
      if (c.kind == PointKind::curve) point("3", c.p);
    }
    for (const auto& n : p.notches) {
      w_.dxfString(0, "POINT");
      w_.dxfString(8, n.type >= 80 && n.type <= 83 ? std::to_string(n.type) : "4");
      w_.dxfReal(10, n.position.x() * k_);
      w_.dxfReal(20, n.position.y() * k_);
      w_.dxfReal(30, n.length_m * k_);
      w_.dxfReal(39, n.width_m * k_);
      w_.dxfReal(50, n.angle_deg);
    }
    if (p.grade_reference) line("5", *p.grade_reference);
    if (p.mirror_line) line("6", *p.mirror_line);
    if (p.grain_line) line("7", *p.grain_line);
    auto id = [](const Vec2& v) { return v; };
    for (const auto& l : p.internal_lines) polyline("8", l.points, l.closed, id);
    for (const auto& l : p.cutouts) polyline("11", l.points, true, id);
    for (const auto& h : p.drill_holes) point("13", h);
    for (const auto& l : p.sew_lines) polyline("14", l.points, l.closed, id);

    w_.dxfString(0, "ENDBLK");
    w_.dxfString(8, "0");
  }

 private:
  StringWriter& w_;
  double k_;  // file units per metre
};

}  // namespace

std::string export_string(const pattern::Style& style, const ExportOptions& opts) {
  if (opts.units != LengthUnit::millimetre && opts.units != LengthUnit::inch)
    throw Error("", "", "AAMA DXF states units as METRIC (mm) or ENGLISH (inch); choose mm or in");
  for (const auto& p : style.pieces)
    for (const auto& c : p.boundary)
      if (!std::isfinite(c.p.x()) || !std::isfinite(c.p.y()))
        throw Error("", "piece " + p.block, "non-finite coordinate: refusing to write a corrupt file");

  StringWriter w;
  AamaWriter aama(w, 1.0 / metres_per(opts.units));
  w.sectionHeader();
  w.dxfString(9, "$ACADVER");
  w.dxfString(1, "AC1009");
  w.sectionEnd();

  w.sectionBlocks();
  std::vector<const Piece*> written;
  for (const auto& p : style.pieces) {
    if (opts.size && p.size != *opts.size) continue;
    aama.piece(p, style.flavour);
    written.push_back(&p);
  }
  if (written.empty())
    throw Error("", "", opts.size ? "no piece has size '" + *opts.size + "'" : "the style has no pieces");
  w.sectionEnd();

  w.sectionEntities();
  Vec2 at(0, -0.05);
  auto label = [&](const std::string& v) {
    aama.text("1", at, v);
    at.y() -= 0.01;
  };
  label("Style Name: " + style.name);
  label("Author: vgd " + std::string(kVersion));
  label("PRODUCT: vgd");
  if (!style.sample_size.empty()) label("Sample Size: " + style.sample_size);
  label(std::string("Units: ") + (opts.units == LengthUnit::inch ? "ENGLISH" : "METRIC"));
  if (style.flavour == "ASTM") label("ASTM/D13Proposal 1 Version: D 6673-04");
  for (const auto* p : written) {
    w.dxfString(0, "INSERT");
    w.dxfString(8, "1");
    w.dxfString(2, p->block);
    w.dxfReal(10, 0.0);
    w.dxfReal(20, 0.0);
  }
  w.sectionEnd();
  w.dxfEOF();
  return std::move(w.out);
}

void export_file(const pattern::Style& style, const std::filesystem::path& path, const ExportOptions& opts) {
  std::string text;
  try {
    text = export_string(style, opts);
  } catch (const Error& e) {
    Diagnostic d = e.diagnostic();
    d.file = path.string();
    throw Error(d);
  }
  write_file_atomic(path, text);
}

}  // namespace vgd::dxf
