#pragma once
// Small string helpers used by the file readers.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vgd {

std::string_view trim(std::string_view s);
std::string to_lower(std::string_view s);
std::string to_upper(std::string_view s);
bool iequals(std::string_view a, std::string_view b);
bool istarts_with(std::string_view s, std::string_view prefix);
std::vector<std::string> split(std::string_view s, char sep);

// Strict number parsing: the whole (trimmed) text must be a finite number.
// Accepts forms like ".25", "-1.", "1e-3". Locale-independent.
std::optional<double> parse_double(std::string_view s);
std::optional<long long> parse_int(std::string_view s);

// Shortest text that reads back to the same double ("%.17g" trimmed), locale-independent.
std::string format_double(double v);

// Fixed-point text for messages ("3.14"), locale-independent.
std::string format_fixed(double v, int decimals);
// `digits` significant digits for messages ("9e-06", "2.34e-06", "0.125"), as
// printf's %g, locale-independent.
std::string format_significant(double v, int digits);

// UTF-8. The code point starting at s[i], i moved past it; kInvalidUtf8 (i
// moved one byte) for a byte that starts no valid sequence or a sequence cut
// short. Overlong forms are not rejected.
inline constexpr std::uint32_t kInvalidUtf8 = 0xFFFFFFFF;
std::uint32_t next_utf8(std::string_view s, std::size_t& i);
bool is_utf8(std::string_view s);
void append_utf8(std::string& out, std::uint32_t code_point);

// Text safe to print and to put in JSON: valid UTF-8 kept, line breaks and tabs
// kept, every other control byte and every byte that starts no valid UTF-8
// sequence written as \xNN (a binary file's bytes echoed in a message).
std::string printable(std::string_view s);

// Text for HTML: & < > " ' as character references.
std::string html_escape(std::string_view s);

// nlohmann::json's exception text in words, after `lead`: with lead "not valid
// JSON", "[json.exception.parse_error.101] parse error at line 1, column 19:
// syntax error while parsing object key - invalid string: missing closing
// quote; last read: '"di'" becomes "not valid JSON at line 1, column 19:
// invalid string: missing closing quote (read up to: "di)".
std::string json_error_message(std::string_view what, std::string_view lead);

}  // namespace vgd
