#pragma once
// How each piece looks, from the XVC document (docs/xvc.md): a PATTERN's
// ASSOCIATIONs name a MATERIAL (its COLORRGBA is the piece's colour) and a
// TEXTURE (image file, SCALE2D = metres of fabric per repeat, ROTATION2D).
// A piece without a material association takes the document's only MATERIAL
// when there is exactly one; otherwise, and for a document without colours,
// the defaults of garment.hpp (kDefaultFabric).
#include <string>
#include <vector>

#include "vgd/core/diagnostics.hpp"
#include "vgd/io/vrml/garment.hpp"
#include "vgd/xvc/document.hpp"

namespace vgd::io::vrml {

// One look per piece name. A name matches a PATTERN by its piece name, block
// name or id (the first such pattern in document order). Names that match no
// pattern get the document-wide look and an info diagnostic.
std::vector<PieceLook> looks_from_xvc(const xvc::Document& doc, const std::vector<std::string>& pieces,
                                      Diagnostics* diagnostics = nullptr);

}  // namespace vgd::io::vrml
