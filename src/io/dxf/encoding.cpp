// Text encodings of DXF files (encoding.hpp).
#include "encoding.hpp"

#include <iconv.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <string>

#include "vgd/core/strings.hpp"

namespace vgd::dxf {

namespace {

// The value of the header variable $DWGCODEPAGE (group 3 after it), or "".
std::string code_page_of(std::string_view text) {
  const std::size_t at = text.find("$DWGCODEPAGE");
  if (at == std::string_view::npos) return "";
  std::size_t pos = text.find('\n', at);
  for (int line = 0; line < 2 && pos != std::string_view::npos; ++line) {  // the group code, then its value
    const std::size_t next = text.find('\n', pos + 1);
    if (line == 1) {
      std::string v(text.substr(pos + 1, next == std::string_view::npos ? std::string_view::npos : next - pos - 1));
      while (!v.empty() && (v.back() == '\r' || v.back() == ' ')) v.pop_back();
      while (!v.empty() && v.front() == ' ') v.erase(v.begin());
      return v;
    }
    pos = next;
  }
  return "";
}

// iconv's name for a DXF code page ("ANSI_1251" -> "CP1251"); "" when unknown.
std::string iconv_name(const std::string& dxf) {
  const std::string u = to_upper(dxf);
  if (u.rfind("ANSI_", 0) == 0) {
    const std::string n = u.substr(5);
    if (n == "936") return "GBK";
    if (n == "950") return "BIG5";
    if (n == "949" || n == "932" || (n.size() == 4 && n[0] == '1' && n[1] == '2')) return "CP" + n;
    return "";
  }
  if (u.rfind("DOS", 0) == 0) return "CP" + u.substr(3);
  if (u.rfind("ISO8859-", 0) == 0) return "ISO-8859-" + u.substr(8);
  return "";
}

}  // namespace

std::string decode_unicode_escapes(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\\' && i + 7 <= text.size() && (text[i + 1] == 'U' || text[i + 1] == 'u') && text[i + 2] == '+') {
      std::uint32_t c = 0;
      bool hex = true;
      for (std::size_t k = 3; k < 7; ++k) {
        const char h = text[i + k];
        const int d = h >= '0' && h <= '9' ? h - '0' : h >= 'a' && h <= 'f' ? h - 'a' + 10 : h >= 'A' && h <= 'F' ? h - 'A' + 10 : -1;
        if (d < 0) hex = false;
        c = c * 16 + static_cast<std::uint32_t>(std::max(d, 0));
      }
      if (hex && c != 0 && (c < 0xD800 || c > 0xDFFF)) {
        append_utf8(out, c);
        i += 6;
        continue;
      }
    }
    out += text[i];
  }
  return out;
}

Decoded to_utf8(std::string_view text) {
  Decoded d;
  if (is_utf8(text)) {
    d.text = decode_unicode_escapes(text);
    return d;
  }
  const std::string stated = code_page_of(text);
  std::string from = stated.empty() ? "CP1252" : iconv_name(stated);
  d.code_page = stated.empty() ? "ANSI_1252" : stated;
  if (from.empty()) {
    from = "CP1252";
    d.code_page = "ANSI_1252";
    d.note = "the file is not UTF-8 and its code page " + stated + " is not one vgd reads: read as ANSI_1252";
  } else if (stated.empty()) {
    d.note = "the file is not UTF-8 and names no code page ($DWGCODEPAGE): read as ANSI_1252";
  } else {
    d.note = "the file is not UTF-8: texts read in its code page " + stated + " ($DWGCODEPAGE)";
  }
  iconv_t cd = iconv_open("UTF-8", from.c_str());
  if (cd == reinterpret_cast<iconv_t>(-1)) {
    d.text = decode_unicode_escapes(text);
    d.note = "the file is not UTF-8 and its code page " + d.code_page + " cannot be read here: texts kept as bytes";
    return d;
  }
  std::string out;
  out.resize(text.size() * 4 + 16);
  char* in = const_cast<char*>(text.data());
  std::size_t in_left = text.size();
  char* o = out.data();
  std::size_t out_left = out.size();
  while (in_left > 0) {
    if (iconv(cd, &in, &in_left, &o, &out_left) == static_cast<std::size_t>(-1)) {
      if (errno == EILSEQ || errno == EINVAL) {  // a byte the code page lacks: U+FFFD, go on
        if (out_left < 3) break;
        *o++ = static_cast<char>(0xEF), *o++ = static_cast<char>(0xBF), *o++ = static_cast<char>(0xBD);
        out_left -= 3;
        ++in;
        --in_left;
        ++d.replaced;
      } else {
        break;  // E2BIG cannot happen: 4 bytes per input byte is room enough
      }
    }
  }
  iconv_close(cd);
  out.resize(out.size() - out_left);
  d.text = decode_unicode_escapes(out);
  return d;
}

}  // namespace vgd::dxf
