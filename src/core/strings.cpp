#include "vgd/core/strings.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace vgd {

std::string_view trim(std::string_view s) {
  const char* ws = " \t\r\n\f\v";
  const auto b = s.find_first_not_of(ws);
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(ws);
  return s.substr(b, e - b + 1);
}

std::string to_lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

std::string to_upper(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return out;
}

bool iequals(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](unsigned char x, unsigned char y) {
           return std::tolower(x) == std::tolower(y);
         });
}

bool istarts_with(std::string_view s, std::string_view prefix) {
  return s.size() >= prefix.size() && iequals(s.substr(0, prefix.size()), prefix);
}

std::vector<std::string> split(std::string_view s, char sep) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const auto pos = s.find(sep, start);
    out.emplace_back(s.substr(start, pos == std::string_view::npos ? std::string_view::npos : pos - start));
    if (pos == std::string_view::npos) break;
    start = pos + 1;
  }
  return out;
}

std::optional<double> parse_double(std::string_view s) {
  s = trim(s);
  if (s.empty()) return std::nullopt;
  if (s.front() == '+') s.remove_prefix(1);
  double v = 0;
  // from_chars rejects a leading '.', which DXF writers use (".25"): handle the sign and prefix a 0.
  std::string buf;
  std::string_view t = s;
  bool neg = false;
  if (!t.empty() && t.front() == '-') {
    neg = true;
    t.remove_prefix(1);
  }
  if (!t.empty() && t.front() == '.') {
    buf = "0";
    buf += t;
    t = buf;
  }
  const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (ec != std::errc() || p != t.data() + t.size() || !std::isfinite(v)) return std::nullopt;
  return neg ? -v : v;
}

std::optional<long long> parse_int(std::string_view s) {
  s = trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  long long v = 0;
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || p != s.data() + s.size()) return std::nullopt;
  return v;
}

std::string format_double(double v) {
  char buf[64];
  const auto [p, ec] = std::to_chars(buf, buf + sizeof buf, v);  // shortest round-trip form
  return std::string(buf, ec == std::errc() ? p : buf);
}

std::string format_fixed(double v, int decimals) {
  char buf[64];
  const auto [p, ec] = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, decimals);
  return std::string(buf, ec == std::errc() ? p : buf);
}

std::string format_significant(double v, int digits) {
  char buf[64];
  const auto [p, ec] = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, digits);
  return std::string(buf, ec == std::errc() ? p : buf);
}

std::uint32_t next_utf8(std::string_view s, std::size_t& i) {
  const auto b = static_cast<unsigned char>(s[i]);
  if (b < 0x80) {
    ++i;
    return b;
  }
  const int n = (b >> 5) == 0x6 ? 1 : (b >> 4) == 0xE ? 2 : (b >> 3) == 0x1E ? 3 : -1;
  if (n < 0 || i + n >= s.size()) {
    ++i;
    return kInvalidUtf8;
  }
  std::uint32_t c = n == 1 ? (b & 0x1F) : n == 2 ? (b & 0x0F) : (b & 0x07);
  for (int k = 1; k <= n; ++k) {
    const auto cb = static_cast<unsigned char>(s[i + k]);
    if ((cb & 0xC0) != 0x80) {
      ++i;
      return kInvalidUtf8;
    }
    c = (c << 6) | (cb & 0x3F);
  }
  i += n + 1;
  return c;
}

bool is_utf8(std::string_view s) {
  for (std::size_t i = 0; i < s.size();)
    if (next_utf8(s, i) == kInvalidUtf8) return false;
  return true;
}

void append_utf8(std::string& out, std::uint32_t c) {
  if (c < 0x80) {
    out += static_cast<char>(c);
  } else if (c < 0x800) {
    out += static_cast<char>(0xC0 | (c >> 6));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else if (c < 0x10000) {
    out += static_cast<char>(0xE0 | (c >> 12));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (c >> 18));
    out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  }
}

std::string printable(std::string_view s) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    const std::size_t start = i;
    const std::uint32_t c = next_utf8(s, i);
    const bool control = c < 0x20 ? (c != '\n' && c != '\t') : (c == 0x7F || (c >= 0x80 && c < 0xA0));
    if (c == kInvalidUtf8 || control) {
      for (std::size_t k = start; k < i; ++k) {
        const auto b = static_cast<unsigned char>(s[k]);
        out += "\\x";
        out += hex[b >> 4];
        out += hex[b & 0xF];
      }
    } else {
      out.append(s.substr(start, i - start));
    }
  }
  return out;
}

std::string json_error_message(std::string_view what, std::string_view lead) {
  std::string s(what);
  if (s.rfind("[json.exception.", 0) == 0)
    if (const auto p = s.find("] "); p != std::string::npos) s.erase(0, p + 2);
  std::string where;
  if (s.rfind("parse error at ", 0) == 0)
    if (const auto p = s.find(": "); p != std::string::npos) {
      where = s.substr(15, p - 15);
      s.erase(0, p + 2);
    }
  if (s.rfind("parse error: ", 0) == 0) s.erase(0, 13);
  if (s.rfind("syntax error while parsing ", 0) == 0)
    if (const auto p = s.find(" - "); p != std::string::npos) s.erase(0, p + 3);
  if (const auto p = s.find("; last read: '"); p != std::string::npos) {
    const auto q = s.find('\'', p + 14);
    const std::string read = s.substr(p + 14, q == std::string::npos ? std::string::npos : q - p - 14);
    const std::string rest = q == std::string::npos ? "" : s.substr(q + 1);
    s = s.substr(0, p) + " (read up to: " + read + ")" + rest;
  }
  if (s.rfind("number overflow parsing '", 0) == 0) s = "a number too large for a double: " + s.substr(25);
  if (!s.empty() && s.back() == '\'') s.pop_back();
  return printable(std::string(lead) + (where.empty() ? ": " : " at " + where + ": ") + s);
}

std::string html_escape(std::string_view s) {
  std::string o;
  o.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      case '\'': o += "&#39;"; break;
      default: o += c;
    }
  }
  return o;
}

}  // namespace vgd
