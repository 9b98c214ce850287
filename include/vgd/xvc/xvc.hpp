#pragma once
// Everything of the xvc stage: the document, files, style mapping, checks, edits, SVG.
#include "vgd/xvc/commands.hpp"
#include "vgd/xvc/document.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/style.hpp"
#include "vgd/xvc/svg.hpp"
#include "vgd/xvc/validate.hpp"
