#include "vgd/io/dxf/report.hpp"

namespace vgd::dxf {

nlohmann::json report_json(const ImportResult& r) {
  using nlohmann::json;
  const auto& s = r.summary;
  json out;
  out["summary"] = {{"producer", s.producer}, {"flavour", s.flavour},   {"style", s.style},
                    {"units", s.units},       {"sample_size", s.sample_size}, {"pieces", s.pieces},
                    {"blocks", s.blocks},     {"sizes", s.sizes}};
  json blocks = json::array();
  for (const auto& b : r.blocks) {
    blocks.push_back({{"block", b.block},
                      {"piece", b.piece},
                      {"size", b.size},
                      {"quantity", b.quantity},
                      {"category", b.category},
                      {"boundary_vertices", b.boundary_vertices},
                      {"closed", b.closed},
                      {"area_m2", b.area_m2},
                      {"perimeter_m", b.perimeter_m},
                      {"grain_angle_deg", b.grain_angle_deg},
                      {"notches", b.notches},
                      {"internal_lines", b.internal_lines},
                      {"drill_holes", b.drill_holes},
                      {"mirror_line", b.mirror_line},
                      {"self_intersecting", b.self_intersecting},
                      {"imported", b.imported}});
  }
  out["blocks"] = std::move(blocks);
  json warnings = json::array();
  for (const auto& d : r.diagnostics.items()) {
    if (d.severity == Severity::info) continue;
    json w{{"severity", to_string(d.severity)}, {"message", d.message}};
    w["block"] = d.entity.rfind("block ", 0) == 0 ? d.entity.substr(6) : d.entity;
    if (d.line > 0) w["line"] = d.line;
    warnings.push_back(std::move(w));
  }
  out["warnings"] = std::move(warnings);
  return out;
}

}  // namespace vgd::dxf
