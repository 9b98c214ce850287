#pragma once
// Drawing a document as SVG with schemas/xvc-to-svg.xsl (XSLT 1.0).
//
// The stylesheet lays the patterns out side by side (millimetres, y up in the pattern
// becomes y down in SVG) and draws each outline, cut-outs, internal lines, notches,
// grain lines and drill holes, labelled with piece name and size.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "vgd/xvc/document.hpp"

namespace vgd::xvc {

// find_schema_file("xvc-to-svg.xsl").
std::filesystem::path default_stylesheet_path();

// True when this build runs XSLT in-process with libxslt; false when render_svg runs
// the xsltproc program instead.
bool svg_uses_libxslt();

// Stylesheet parameters as name -> text (xsltproc --stringparam), e.g. {"layout", "own"}
// or {"scale", "1000"} (SVG user units per metre).
using StylesheetParams = std::vector<std::pair<std::string, std::string>>;

// The document as SVG text. Throws vgd::Error when the transformation fails.
std::string render_svg(const Document& doc, const std::filesystem::path& xsl, const StylesheetParams& params = {});

// The same through the xsltproc program (found on PATH), whatever this build links.
std::string render_svg_with_xsltproc(const Document& doc, const std::filesystem::path& xsl,
                                     const StylesheetParams& params = {});

}  // namespace vgd::xvc
