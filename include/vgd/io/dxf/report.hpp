#pragma once
// The import report as JSON: {"summary": {...}, "blocks": [...], "warnings": [...]}
// (docs/cli.md lists every field). Used by `vgd import --report --json` and tests.
#include <nlohmann/json.hpp>

#include "vgd/io/dxf/import.hpp"

namespace vgd::dxf {

nlohmann::json report_json(const ImportResult& result);

}  // namespace vgd::dxf
