#include "file_dialog.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

extern char** environ;

namespace vgd::studio {

std::vector<std::string> zenity_arguments(const FileDialogRequest& r) {
  std::vector<std::string> a{"--file-selection", "--title=" + r.title};
  if (r.save) a.insert(a.end(), {"--save", "--confirm-overwrite"});
  if (!r.start.empty()) a.push_back("--filename=" + r.start.string());
  for (const auto& f : r.filters) a.push_back("--file-filter=" + f);
  return a;
}

FileDialogAnswer run_file_dialog(const std::filesystem::path& program, const FileDialogRequest& request) {
  FileDialogAnswer out;
  int pipe_fd[2];
  if (::pipe(pipe_fd) != 0) {
    out.why = std::string("no pipe: ") + std::strerror(errno);
    return out;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, pipe_fd[1], STDOUT_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addclose(&actions, pipe_fd[0]);
  posix_spawn_file_actions_addclose(&actions, pipe_fd[1]);
  std::vector<std::string> args = zenity_arguments(request);
  args.insert(args.begin(), program.string());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int rc = ::posix_spawnp(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fd[1]);
  if (rc != 0) {
    ::close(pipe_fd[0]);
    out.why = program.string() + ": " + std::strerror(rc);
    return out;
  }
  std::string text;
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(pipe_fd[0], buf, sizeof buf);
    if (n > 0) text.append(buf, static_cast<std::size_t>(n));
    else if (n == 0 || errno != EINTR) break;
  }
  ::close(pipe_fd[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    const auto end = text.find_first_of("\r\n");
    if (end != std::string::npos) text.resize(end);
    if (text.empty()) {
      out.kind = FileDialogAnswer::Kind::cancelled;
    } else {
      out.kind = FileDialogAnswer::Kind::chosen;
      out.path = text;
    }
  } else if (WIFEXITED(status) && WEXITSTATUS(status) == 1) {
    out.kind = FileDialogAnswer::Kind::cancelled;
  } else {
    out.why = program.string() + (WIFEXITED(status) ? ": exit " + std::to_string(WEXITSTATUS(status))
                                                    : ": killed by signal " + std::to_string(WTERMSIG(status)));
  }
  return out;
}

}  // namespace vgd::studio
