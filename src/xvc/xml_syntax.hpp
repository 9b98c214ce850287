#pragma once
// libxml2's account of why a text is not well-formed XML (validate.cpp). The loader
// asks it before building the tree with tinyxml2, which is more lenient; its messages
// name the line of the actual fault ("Opening and ending tag mismatch: PATTERNS line 2
// and SEAMS").
#include <optional>
#include <string>
#include <string_view>

#include "vgd/core/diagnostics.hpp"

namespace vgd::xvc::detail {

// The first well-formedness error (a DOCTYPE counts as one), or nullopt.
std::optional<Diagnostic> xml_syntax_error(std::string_view xml, const std::string& file);

}  // namespace vgd::xvc::detail
