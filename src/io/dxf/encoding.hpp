#pragma once
// Text encodings of DXF files: internal to io/dxf.
//
// DXF R2007 and later are UTF-8; older files are in the code page their
// header names ($DWGCODEPAGE, e.g. ANSI_1251 for Cyrillic), ANSI_1252 when
// it names none, and write characters outside it as \U+XXXX escapes. The
// importer reads every text as UTF-8: a file that is valid UTF-8 is kept as
// it is, another is converted from its code page (iconv), and \U+XXXX
// escapes become their characters. Line breaks are kept, so line numbers in
// messages stay those of the file.
#include <string>
#include <string_view>

namespace vgd::dxf {

struct Decoded {
  std::string text;       // UTF-8
  std::string code_page;  // the code page read from, "" when the file was UTF-8
  std::string note;       // what was done, for the import report ("" when nothing)
  int replaced = 0;       // bytes the code page has no character for (U+FFFD)
};

Decoded to_utf8(std::string_view text);

// \U+XXXX (and \u+XXXX) escapes as UTF-8; others kept.
std::string decode_unicode_escapes(std::string_view text);

}  // namespace vgd::dxf
