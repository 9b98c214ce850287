// Structural check of DXF text before dxflib sees it. dxflib accepts almost any
// input silently (even a Markdown file), so every problem a user can make is
// found here first, with the line it is on.
#include <cstring>

#include <dxflib/dl_codes.h>

#include "raw.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"

namespace vgd::dxf::raw {

namespace {

enum class ValueKind { string, real, integer };

constexpr std::size_t kMaxLine = DL_DXF_MAXLINE - 2;  // dxflib's buffer, less the line end

// DXF reference, "group code value types".
ValueKind kind_of(long code) {
  if ((code >= 10 && code <= 59) || (code >= 110 && code <= 149) || (code >= 210 && code <= 239) ||
      (code >= 460 && code <= 469) || (code >= 1010 && code <= 1059))
    return ValueKind::real;
  if ((code >= 60 && code <= 99) || (code >= 160 && code <= 179) || (code >= 270 && code <= 299) ||
      (code >= 370 && code <= 389) || (code >= 400 && code <= 409) || (code >= 420 && code <= 429) ||
      (code >= 440 && code <= 459) || (code >= 1060 && code <= 1071))
    return ValueKind::integer;
  return ValueKind::string;
}

std::string shorten(std::string_view s) {
  std::string out(s.substr(0, 40));
  for (auto& c : out)
    if (static_cast<unsigned char>(c) < 32) c = '?';
  if (s.size() > 40) out += "...";
  return out;
}

}  // namespace

ScanInfo scan(std::string_view text, const std::string& name) {
  ScanInfo info;
  if (trim(text).empty()) throw Error(name, "", "empty file: no DXF content");
  if (text.substr(0, 18) == "AutoCAD Binary DXF")
    throw Error(name, "", "binary DXF is not supported: export the pattern as ASCII (text) DXF");
  if (const auto nul = text.find('\0'); nul != std::string_view::npos)
    throw Error(name, "", "not a DXF text file: binary data at byte " + std::to_string(nul));

  // Walk the lines two at a time: group code, then value.
  std::size_t pos = 0;
  int line = 0;
  auto next_line = [&](std::string_view& out) {
    if (pos >= text.size()) return false;
    auto e = text.find('\n', pos);
    if (e == std::string_view::npos) e = text.size();
    out = text.substr(pos, e - pos);
    if (!out.empty() && out.back() == '\r') out.remove_suffix(1);
    pos = e + 1;
    ++line;
    // dxflib reads a line into DL_DXF_MAXLINE bytes and takes the rest of a
    // longer one as the next lines: the file's pairs would fall out of step.
    if (out.size() > kMaxLine)
      throw Error(name, "", "a line of " + std::to_string(out.size()) + " characters; a DXF line holds at most " +
                                std::to_string(kMaxLine),
                  line);
    return true;
  };

  std::string section;            // current SECTION name
  std::string block;              // current BLOCK name (empty when outside)
  int block_line = 0, section_line = 0;
  bool expect_section_name = false, expect_block_name = false, in_block_entity = false;
  bool first = true, eof = false;
  std::string_view code_text, value;
  while (next_line(code_text)) {
    const int code_line = line;
    if (eof) {
      if (!trim(code_text).empty())
        throw Error(name, "", "unexpected content after the EOF marker", code_line);
      continue;
    }
    const auto code = parse_int(code_text);
    if (!code || *code < 0 || *code > 1071)
      throw Error(name, "", "expected a group code (an integer 0..1071), found '" + shorten(code_text) + "'",
                  code_line);
    if (!next_line(value))
      throw Error(name, block.empty() ? "" : "block " + block,
                  "file is truncated: group code " + std::to_string(*code) + " has no value", code_line);
    ++info.pairs;
    const auto kind = kind_of(*code);
    if (kind != ValueKind::string && !parse_double(value))
      throw Error(name, block.empty() ? "" : "block " + block,
                  "group " + std::to_string(*code) + " expects a number, found '" + shorten(value) + "'", line);
    if (*code == 999) continue;  // comment
    const auto v = trim(value);
    if (first) {
      if (*code != 0 || v != "SECTION")
        throw Error(name, "", "not a DXF file: expected '0 / SECTION' at the start, found '" +
                                  std::to_string(*code) + " / " + shorten(v) + "'", code_line);
      first = false;
    }
    if (expect_section_name) {
      if (*code != 2) throw Error(name, "", "SECTION without a name (group 2)", code_line);
      section = std::string(v);
      expect_section_name = false;
      continue;
    }
    if (expect_block_name && *code == 2) {
      block = std::string(v);
      expect_block_name = false;
      continue;
    }
    if (*code != 0) continue;
    expect_block_name = false;
    info.entity_lines[std::string(v)].push_back(line);  // the line that names the entity
    if (v == "SECTION") {
      if (!section.empty())
        throw Error(name, "", "SECTION " + section + " (line " + std::to_string(section_line) +
                                  ") is not closed by ENDSEC before a new SECTION", code_line);
      expect_section_name = true;
      section_line = code_line;
    } else if (v == "ENDSEC") {
      if (!block.empty() || in_block_entity)
        throw Error(name, "block " + block, "block (line " + std::to_string(block_line) + ") has no ENDBLK",
                    code_line);
      section.clear();
    } else if (v == "BLOCK") {
      if (in_block_entity)
        throw Error(name, "block " + block, "block (line " + std::to_string(block_line) +
                                                ") has no ENDBLK before the next BLOCK", code_line);
      in_block_entity = true;
      expect_block_name = true;
      block.clear();
      block_line = code_line;
      ++info.blocks;
    } else if (v == "ENDBLK") {
      if (!in_block_entity) throw Error(name, "", "ENDBLK without BLOCK", code_line);
      in_block_entity = false;
      block.clear();
    } else if (v == "EOF") {
      eof = true;
    }
  }
  info.lines = line;
  if (!eof) {
    std::string where = section.empty() ? "" : " inside section " + section;
    if (in_block_entity) where += " in block '" + block + "' (line " + std::to_string(block_line) + ")";
    throw Error(name, "", "file is truncated: it ends at line " + std::to_string(line) + where +
                              " without the closing 'EOF' marker");
  }
  return info;
}

}  // namespace vgd::dxf::raw
