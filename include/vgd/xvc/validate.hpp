#pragma once
// Checking XVC documents.
//
// Two independent checks, both run by validate_*:
//   - the XSD (schemas/xvc.xsd) through libxml2: structure and value types, as any
//     other XML tool would see them;
//   - vgd's own rules (check): the same structure and values plus what an XSD cannot
//     say well: ids unique, references that name an existing element of the right kind
//     (a HEM's from/to a boundary C2DSEQ of one pattern, a SIZE's pattern a PATTERN of
//     that piece and size), the unit and range of known PARAMETERs, finite numbers.
// Each problem is a Diagnostic with the file, the line, the element's id (or tag) and
// a sentence. When both checks flag one line, the clearer rule message is kept.
#include <filesystem>
#include <string>
#include <string_view>

#include "vgd/core/diagnostics.hpp"
#include "vgd/xvc/document.hpp"

namespace vgd::xvc {

// vgd's rules on a tree; `file` goes into each diagnostic. Errors make the tree
// unusable as a Document; warnings (e.g. two PATTERNs with one block name) do not.
Diagnostics check(const Node& root, std::string_view file);
Diagnostics check(const Document& doc);

// XSD validation plus check(), on a file or on text. Malformed XML is reported as a
// diagnostic, not thrown. Throws vgd::Error only when the file or the schema cannot be
// read or the schema itself is broken.
Diagnostics validate_file(const std::filesystem::path& xvc, const std::filesystem::path& xsd);
Diagnostics validate_string(std::string_view xml, std::string_view name_for_messages,
                            const std::filesystem::path& xsd);

// Where schemas/xvc.xsd is: $VGD_SCHEMA_DIR, else the source tree this build came from,
// else the installed share directory. Throws vgd::Error naming the places tried.
std::filesystem::path default_schema_path();

// The same search for any file shipped in schemas/ (e.g. "xvc-to-svg.xsl").
std::filesystem::path find_schema_file(std::string_view filename);

}  // namespace vgd::xvc
