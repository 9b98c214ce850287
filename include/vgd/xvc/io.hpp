#pragma once
// Reading and writing XVC files.
//
// Loading parses with tinyxml2 and then checks the tree (validate.hpp: structure,
// values, ids and references) without needing the XSD; any error is thrown as
// vgd::Error naming the file, the line, the element (its id, or its tag) and the
// problem. Saving writes one canonical layout (two-space indent, attributes in the
// order they are held, one element per line), so load -> save -> load -> save gives
// the same bytes. Comments and the XML declaration of a loaded file are not kept.
#include <filesystem>
#include <string>
#include <string_view>

#include "vgd/xvc/document.hpp"

namespace vgd::xvc {

// Loads and checks a file. Throws vgd::Error (file, line, element, problem).
Document load_file(const std::filesystem::path& path);

// Loads and checks XML text; `name_for_messages` stands in for the file name in errors.
Document load_string(std::string_view xml, std::string_view name_for_messages);

// XML text -> element tree without vgd's checks, for tools that report every problem
// (validate.hpp's check()). Throws vgd::Error (file, line) when the text is not
// well-formed or holds what a Node cannot (text content, a repeated attribute).
Node parse_tree(std::string_view xml, std::string_view name_for_messages);

// The document as XML text (UTF-8, ending in a newline).
std::string save_string(const Document& doc);

// Writes the document atomically (vgd::write_file_atomic): the old file stays intact
// until the new one is complete. Throws vgd::Error on failure.
void save_file(const Document& doc, const std::filesystem::path& path);

}  // namespace vgd::xvc
