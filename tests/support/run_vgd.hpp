#pragma once
// Runs the built `vgd` program as a user would, capturing its exit code, stdout
// and stderr separately. For the tests of apps/vgd (tests/apps).
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

extern char** environ;

namespace vgd::test {

struct CliResult {
  int code = -1;  // exit status, or -1 if the program did not exit normally
  std::string out, err;
};

// `vgd ARGS...` run in `cwd` (the current directory when empty).
inline CliResult run_vgd(const std::vector<std::string>& args, const std::filesystem::path& cwd = {}) {
  namespace fs = std::filesystem;
  static int serial = 0;
  const fs::path tmp = fs::temp_directory_path() /
                       ("vgd-cli-" + std::to_string(::getpid()) + "-" + std::to_string(serial++));
  fs::create_directories(tmp);
  const std::string out_path = (tmp / "out").string(), err_path = (tmp / "err").string();

  std::vector<std::string> argv_s{VGD_EXE};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&fa, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (!cwd.empty()) posix_spawn_file_actions_addchdir_np(&fa, cwd.c_str());
  CliResult r;
  pid_t pid = 0;
  if (posix_spawn(&pid, VGD_EXE, &fa, nullptr, argv.data(), environ) == 0) {
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  posix_spawn_file_actions_destroy(&fa);
  auto slurp = [](const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  };
  r.out = slurp(out_path);
  r.err = slurp(err_path);
  fs::remove_all(tmp);
  return r;
}

// The same with the arguments in one string, split at spaces (no quoting).
inline CliResult run_vgd(const std::string& args, const std::filesystem::path& cwd = {}) {
  std::vector<std::string> v;
  std::istringstream in(args);
  for (std::string a; in >> a;) v.push_back(a);
  return run_vgd(v, cwd);
}

}  // namespace vgd::test
