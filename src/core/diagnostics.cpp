#include "vgd/core/diagnostics.hpp"

#include <cstdio>
#include <cstdlib>

#include "vgd/core/strings.hpp"

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

namespace {
// A message may quote what a file holds; a binary file's bytes are escaped.
Diagnostic printable(Diagnostic d) {
  d.file = vgd::printable(d.file);
  d.entity = vgd::printable(d.entity);
  d.message = vgd::printable(d.message);
  return d;
}
}  // namespace

Error::Error(Diagnostic d) : Error(printable(std::move(d)), 0) {}

Error::Error(Diagnostic d, int) : std::runtime_error(d.format()), diag_(std::move(d)) {
  diag_.severity = Severity::error;
}

void Diagnostics::add(Diagnostic d) { items_.push_back(printable(std::move(d))); }

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

void Diagnostics::name_file(const std::string& file, std::size_t from) {
  for (std::size_t i = from; i < items_.size(); ++i)
    if (items_[i].file.empty()) items_[i].file = vgd::printable(file);
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
