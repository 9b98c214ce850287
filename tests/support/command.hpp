#pragma once
// A shell command's standard output, whole (node scripts, curl).
#include <cstdio>
#include <string>

namespace vgd::test {

inline std::string command_output(const std::string& command) {
  std::string out;
  FILE* p = popen(command.c_str(), "r");
  if (!p) return out;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  pclose(p);
  return out;
}

}  // namespace vgd::test
