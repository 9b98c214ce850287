// Child processes with a log, a process group and a deadline (process.hpp).
#include "vgd/batch/process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <thread>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"

namespace vgd::batch {

std::string ProcessResult::describe() const {
  if (timed_out) return "stopped at its wall limit after " + format_fixed(wall_s, 0) + " s";
  if (signal != 0) return "killed by signal " + std::to_string(signal) + " (" + strsignal(signal) + ")";
  return "exit " + std::to_string(exit_code);
}

Process::Process(const std::filesystem::path& exe, const std::vector<std::string>& args, const ProcessOptions& o)
    : start_(std::chrono::steady_clock::now()), deadline_s_(o.deadline_s) {
  // Everything the child needs is made before fork: it only calls
  // async-signal-safe functions afterwards.
  std::vector<std::string> argv_s;
  argv_s.push_back(exe.string());
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string log = o.log.empty() ? std::string("/dev/null") : o.log.string();
  const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) throw Error(log, "", std::string("cannot open the log: ") + std::strerror(errno));
  const int devnull = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  std::vector<std::string> env_s;
  for (char** e = environ; *e; ++e) {
    const std::string kv = *e;
    bool replaced = false;
    for (const auto& [k, v] : o.env) replaced = replaced || kv.rfind(k + "=", 0) == 0;
    if (!replaced) env_s.push_back(kv);
  }
  for (const auto& [k, v] : o.env) env_s.push_back(k + "=" + v);
  std::vector<char*> envp;
  for (auto& e : env_s) envp.push_back(e.data());
  envp.push_back(nullptr);
  const pid_t parent = ::getpid();
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer reserves terabytes of address space for its shadow
  // memory: an address-space limit would stop every sanitized child at start.
  const long memory_mb = 0;
#else
  const long memory_mb = o.memory_mb;
#endif

  pid_ = ::fork();
  if (pid_ < 0) {
    ::close(fd);
    if (devnull >= 0) ::close(devnull);
    throw Error(exe.string(), "", std::string("cannot start: ") + std::strerror(errno));
  }
  if (pid_ == 0) {
    ::setpgid(0, 0);                      // its own group: a time-out stops all it started
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);   // and it goes when its parent goes
    if (::getppid() != parent) ::_exit(127);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    if (devnull >= 0) ::dup2(devnull, 0);
    if (memory_mb > 0) {
      const rlimit lim{static_cast<rlim_t>(memory_mb) << 20, static_cast<rlim_t>(memory_mb) << 20};
      ::setrlimit(RLIMIT_AS, &lim);
    }
    ::execve(argv[0], argv.data(), envp.data());
    const char msg[] = "vgd batch: cannot run the command\n";
    [[maybe_unused]] auto n = ::write(2, msg, sizeof msg - 1);
    ::_exit(127);
  }
  ::setpgid(pid_, pid_);  // also from here, so kill(-pid) works at once
  ::close(fd);
  if (devnull >= 0) ::close(devnull);
}

Process::Process(Process&& o) noexcept
    : pid_(o.pid_), done_(o.done_), start_(o.start_), deadline_s_(o.deadline_s_), termed_(o.termed_),
      term_at_(o.term_at_), result_(o.result_) {
  o.pid_ = -1;
  o.done_ = true;
}

Process::~Process() {
  if (pid_ > 0 && !done_) {
    kill();
    int status = 0;
    ::waitpid(pid_, &status, 0);
  }
}

void Process::kill() {
  if (pid_ > 0 && !done_) ::kill(-pid_, SIGKILL);
}

bool Process::poll() {
  if (done_ || pid_ <= 0) return true;
  int status = 0;
  const pid_t r = ::waitpid(pid_, &status, WNOHANG);
  const auto now = std::chrono::steady_clock::now();
  const double wall = std::chrono::duration<double>(now - start_).count();
  if (r == pid_) {
    done_ = true;
    result_.wall_s = wall;
    if (WIFEXITED(status)) result_.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) result_.signal = WTERMSIG(status);
    // Anything of its group still running (a step it started) goes with it.
    ::kill(-pid_, SIGKILL);
    return true;
  }
  if (deadline_s_ > 0 && wall > deadline_s_) {
    if (!termed_) {
      termed_ = true;
      term_at_ = now;
      result_.timed_out = true;
      ::kill(-pid_, SIGTERM);
    } else if (std::chrono::duration<double>(now - term_at_).count() > 5.0) {
      ::kill(-pid_, SIGKILL);
    }
  }
  return false;
}

const ProcessResult& Process::wait() {
  while (!poll()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  return result_;
}

ProcessResult run_process(const std::filesystem::path& exe, const std::vector<std::string>& args,
                          const ProcessOptions& options) {
  Process p(exe, args, options);
  return p.wait();
}

}  // namespace vgd::batch
