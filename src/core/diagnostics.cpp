#include "vgd/core/diagnostics.hpp"

#include <cstdio>
#include <cstdlib>

namespace vgd {

const char* to_string(Severity s) {
  switch (s) {
    case Severity::info: return "info";
    case Severity::warning: return "warning";
    case Severity::error: return "error";
  }
  return "?";
}

std::string Diagnostic::format() const {
  std::string out;
  if (!file.empty()) {
    out += file;
    if (line > 0) {
      out += ':';
      out += std::to_string(line);
    }
    out += ": ";
  }
  if (!entity.empty()) {
    out += entity;
    out += ": ";
  }
  out += message;
  return out;
}

Error::Error(Diagnostic d) : std::runtime_error(d.format()), diag_(std::move(d)) {
  diag_.severity = Severity::error;
}

Error::Error(std::string file, std::string entity, std::string message, int line)
    : Error(Diagnostic{Severity::error, std::move(file), std::move(entity), std::move(message), line}) {}

void Diagnostics::info(std::string file, std::string entity, std::string message, int line) {
  add({Severity::info, std::move(file), std::move(entity), std::move(message), line});
}
void Diagnostics::warn(std::string file, std::string entity, std::string message, int line) {
  add({Severity::warning, std::move(file), std::move(entity), std::move(message), line});
}
void Diagnostics::error(std::string file, std::string entity, std::string message, int line) {
  add({Severity::error, std::move(file), std::move(entity), std::move(message), line});
}

std::size_t Diagnostics::count(Severity s) const {
  std::size_t n = 0;
  for (const auto& d : items_) n += d.severity == s;
  return n;
}

void Diagnostics::append(const Diagnostics& other) {
  items_.insert(items_.end(), other.items_.begin(), other.items_.end());
}

namespace detail {
void assert_fail(const char* cond, const char* msg, const char* file, int line) {
  // The only place core code writes to stderr: a programming error, about to abort.
  std::fprintf(stderr, "vgd: internal error at %s:%d: %s (%s)\n", file, line, msg, cond);
  std::abort();
}
}  // namespace detail

}  // namespace vgd
