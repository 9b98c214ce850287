#pragma once
// A small VRML97 tokenizer for the tests: comments dropped, strings kept
// whole, brackets and braces as their own tokens. Enough to find a node by
// its DEF name and read a field's numbers.
#include <cctype>
#include <string>
#include <vector>

namespace vgd::test {

inline std::vector<std::string> vrml_tokens(const std::string& text) {
  std::vector<std::string> t;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '#') {
      while (i < text.size() && text[i] != '\n') ++i;
    } else if (std::isspace(static_cast<unsigned char>(c)) || c == ',') {
      ++i;
    } else if (c == '[' || c == ']' || c == '{' || c == '}') {
      t.emplace_back(1, c), ++i;
    } else if (c == '"') {
      std::size_t j = i + 1;
      while (j < text.size() && text[j] != '"') j += text[j] == '\\' ? 2 : 1;
      t.push_back(text.substr(i, j + 1 - i)), i = j + 1;
    } else {
      std::size_t j = i;
      while (j < text.size() && !std::isspace(static_cast<unsigned char>(text[j])) && text[j] != ',' &&
             text[j] != '[' && text[j] != ']' && text[j] != '{' && text[j] != '}' && text[j] != '#' && text[j] != '"')
        ++j;
      t.push_back(text.substr(i, j - i)), i = j;
    }
  }
  return t;
}

inline int count_token(const std::vector<std::string>& t, const std::string& word) {
  int n = 0;
  for (const auto& s : t) n += s == word;
  return n;
}

// The numbers of the first `[ ... ]` after token position `from` (or a single
// value when no bracket follows).
inline std::vector<double> numbers_after(const std::vector<std::string>& t, std::size_t from) {
  std::vector<double> v;
  std::size_t i = from;
  if (i < t.size() && t[i] == "[") {
    for (++i; i < t.size() && t[i] != "]"; ++i) v.push_back(std::stod(t[i]));
  } else if (i < t.size()) {
    v.push_back(std::stod(t[i]));
  }
  return v;
}

// Position just after the first occurrence of the sequence `words`, or npos.
inline std::size_t find_seq(const std::vector<std::string>& t, const std::vector<std::string>& words,
                            std::size_t from = 0) {
  for (std::size_t i = from; i + words.size() <= t.size(); ++i) {
    bool ok = true;
    for (std::size_t k = 0; k < words.size() && ok; ++k) ok = t[i + k] == words[k];
    if (ok) return i + words.size();
  }
  return std::string::npos;
}

// Every `field [ ... ]` value of that field name, in file order.
inline std::vector<std::vector<double>> all_fields(const std::vector<std::string>& t, const std::string& field) {
  std::vector<std::vector<double>> out;
  for (std::size_t i = 0; i + 1 < t.size(); ++i)
    if (t[i] == field && t[i + 1] == "[") out.push_back(numbers_after(t, i + 1));
  return out;
}

inline bool balanced(const std::vector<std::string>& t) {
  int sq = 0, br = 0;
  for (const auto& s : t) {
    sq += s == "[" ? 1 : s == "]" ? -1 : 0;
    br += s == "{" ? 1 : s == "}" ? -1 : 0;
    if (sq < 0 || br < 0) return false;
  }
  return sq == 0 && br == 0;
}

}  // namespace vgd::test
