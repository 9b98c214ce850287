#pragma once
// Diagnostics: what vgd tells a user about their input.
//
// Three tiers of errors (docs/architecture.md):
//   - programmer misuse      -> assert with a message (VGD_ASSERT)
//   - a bad input file       -> Diagnostic naming the file, the entity and the problem;
//                               fatal ones are thrown as vgd::Error, the rest collected
//   - numerical blow-up      -> reported by the engine, the caller decides
// Core code never prints and never exits: it returns or throws these.
#include <stdexcept>
#include <string>
#include <vector>

namespace vgd {

enum class Severity { info, warning, error };

const char* to_string(Severity s);

// One message about one place in one input.
struct Diagnostic {
  Severity severity = Severity::warning;
  std::string file;     // path as the user gave it; empty when not from a file
  std::string entity;   // block, piece, element id, ... ; empty when the whole file
  std::string message;  // a sentence a designer understands
  int line = 0;         // 1-based line in the file when known, else 0

  // "file:line: entity: message" with the empty parts left out.
  std::string format() const;
};

// The one exception type for bad input. Carries a Diagnostic, its texts made
// printable (valid UTF-8, control bytes escaped: core/strings.hpp).
class Error : public std::runtime_error {
 public:
  explicit Error(Diagnostic d);
  Error(std::string file, std::string entity, std::string message, int line = 0);
  const Diagnostic& diagnostic() const { return diag_; }

 private:
  Error(Diagnostic d, int);  // d already printable
  Diagnostic diag_;
};

// Collected, non-fatal findings of one operation (an import, a validation, ...).
class Diagnostics {
 public:
  void add(Diagnostic d);  // file, entity and message made printable (core/strings.hpp)
  void info(std::string file, std::string entity, std::string message, int line = 0);
  void warn(std::string file, std::string entity, std::string message, int line = 0);
  void error(std::string file, std::string entity, std::string message, int line = 0);

  const std::vector<Diagnostic>& items() const { return items_; }
  bool empty() const { return items_.empty(); }
  std::size_t count(Severity s) const;
  bool has_errors() const { return count(Severity::error) > 0; }
  void append(const Diagnostics& other);
  // Names `file` in the items from index `from` on that name no file (what a
  // stage that does not know the file said, e.g. the mesher).
  void name_file(const std::string& file, std::size_t from = 0);

 private:
  std::vector<Diagnostic> items_;
};

}  // namespace vgd

// Programmer-misuse check, active in every build type: a violated precondition
// is a bug in the caller, never a property of user input.
#define VGD_ASSERT(cond, msg)                                             \
  do {                                                                    \
    if (!(cond)) ::vgd::detail::assert_fail(#cond, msg, __FILE__, __LINE__); \
  } while (0)

namespace vgd::detail {
[[noreturn]] void assert_fail(const char* cond, const char* msg, const char* file, int line);
}
