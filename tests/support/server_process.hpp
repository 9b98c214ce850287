#pragma once
// vgd-server started by a test on a free loopback port (--listen
// 127.0.0.1:0), its output in DIR/server.log, its data in DIR/data (or
// `data`); stopped with SIGTERM when the test ends. For tests/net and
// tests/apps (they define VGD_SERVER_EXE and VGD_EXE).
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"

namespace vgd::test {

struct ServerProcess {
  pid_t pid = -1;
  int port = 0;  // 0: it did not start (the test asserts)
  std::filesystem::path log;

  explicit ServerProcess(const std::filesystem::path& dir, std::vector<std::string> extra = {},
                         std::filesystem::path data = {})
      : log(dir / "server.log") {
    if (data.empty()) data = dir / "data";
    std::vector<std::string> args = {VGD_SERVER_EXE, "--listen", "127.0.0.1:0", "--data", data.string(), "--vgd",
                                     VGD_EXE};
    args.insert(args.end(), extra.begin(), extra.end());
    // The log may hold earlier runs' lines (a restart): only what this run appends counts.
    std::error_code size_ec;
    const auto before = std::filesystem::exists(log, size_ec) ? std::filesystem::file_size(log, size_ec) : 0;
    pid = ::fork();
    if (pid == 0) {
      const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
      ::dup2(fd, 1);
      ::dup2(fd, 2);
      std::vector<char*> argv;
      for (auto& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    // The port it printed ("listening on http://127.0.0.1:PORT") in what it appended to the log.
    for (int i = 0; i < 200 && port == 0; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      try {
        const std::string all = read_file(log);
        const std::string t = all.size() > before ? all.substr(before) : std::string();
        const auto at = t.rfind("listening on http://127.0.0.1:");
        if (at != std::string::npos) port = std::stoi(t.substr(at + 30));
      } catch (const Error&) {
      }
    }
  }
  std::string url() const { return "http://127.0.0.1:" + std::to_string(port); }
  // Sends `sig` and waits; returns the wait status.
  int stop(int sig = SIGTERM) {
    if (pid <= 0) return -1;
    ::kill(pid, sig);
    int status = 0;
    ::waitpid(pid, &status, 0);
    pid = -1;
    return status;
  }
  ~ServerProcess() { stop(SIGTERM); }
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;
};

}  // namespace vgd::test
