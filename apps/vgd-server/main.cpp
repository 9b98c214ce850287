// vgd-server: the simulation server (docs/server.md). Jobs over HTTP, kept in
// a SQLite database in --data, each run by a worker process (`vgd batch
// item`); a SIGTERM or SIGINT stops it, its running jobs queued again for the
// next start.
//
//   vgd-server [--listen 127.0.0.1:8765] [--workers N] [--data DIR] [--token-file F] [--vgd PATH]
#include <pthread.h>
#include <signal.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/core/version.hpp"
#include "vgd/net/http.hpp"
#include "vgd/net/service.hpp"

namespace fs = std::filesystem;

namespace {

// The vgd executable beside this one (installed), or in the build tree's apps/vgd.
fs::path find_vgd() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  for (const fs::path& p : {self.parent_path() / "vgd", self.parent_path().parent_path() / "vgd" / "vgd"})
    if (fs::is_regular_file(p, ec)) return p;
  return {};
}

bool loopback(const std::string& host) { return host == "127.0.0.1" || host == "::1" || host.rfind("127.", 0) == 0; }

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"vgd-server — the simulation server: garment drapes as jobs over HTTP (docs/server.md)"};
  app.set_version_flag("--version", std::string("vgd-server ") + vgd::kVersion);
  std::string listen = "127.0.0.1:8765", data = "vgd-data", token_file, vgd_exe, three;
  int workers = 1;
  app.add_option("--listen", listen, "Address and port (port 0: any free port, printed)")->capture_default_str();
  app.add_option("--workers", workers, "Jobs run at once, each in its own process")->check(CLI::Range(1, 256))
      ->capture_default_str();
  app.add_option("--data", data, "Folder of the job database (jobs.sqlite) and the jobs' files")->capture_default_str();
  app.add_option("--token-file", token_file, "File holding the token clients must send (Authorization: Bearer); "
                                             "required for an address other than loopback")
      ->check(CLI::ExistingFile);
  app.add_option("--vgd", vgd_exe, "The vgd executable the workers run (default: the one beside vgd-server)");
  app.add_option("--three", three, "three.js's build folder (three.module.js, three.core.js) for the browser page "
                                   "at / (default: the copy this build found)");
  app.footer("Exit codes: 0 stopped by a signal, 1 cannot start (address in use, data folder, no vgd), 2 usage.");
  CLI11_PARSE(app, argc, argv);

  // Signals are taken by one thread (sigwait), before any other thread starts.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  ::signal(SIGPIPE, SIG_IGN);
  try {
    const auto colon = listen.rfind(':');
    const auto port = colon == std::string::npos ? std::nullopt : vgd::parse_int(listen.substr(colon + 1));
    if (!port || *port < 0 || *port > 65535) throw vgd::Error("--listen", "", "'" + listen + "' is not HOST:PORT");
    std::string host = listen.substr(0, colon);
    if (host.size() > 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
    vgd::net::ServiceOptions so;
    so.data = data;
    so.workers = workers;
    so.exe = vgd_exe.empty() ? find_vgd() : fs::path(vgd_exe);
    so.three_dir = three;
    if (so.exe.empty() || !fs::is_regular_file(so.exe))
      throw vgd::Error(so.exe.string(), "", "the vgd executable is not there: give --vgd PATH");
    if (!token_file.empty()) so.token = std::string(vgd::trim(vgd::read_file(token_file)));
    if (!token_file.empty() && so.token.size() < 16)
      throw vgd::Error(token_file, "", "the token is shorter than 16 characters");
    if (!loopback(host) && so.token.empty())
      throw vgd::Error("--listen", "", host + " is not a loopback address: give --token-file (clients must send it)");
    vgd::net::Service service(so);
    vgd::net::HttpServer server(service, host, static_cast<unsigned short>(*port));
    // One write, the requeued jobs first: whoever waits for "listening on" in
    // a line-buffered log finds both.
    std::string hello;
    if (service.requeued_at_start() > 0)
      hello += "vgd-server: " + std::to_string(service.requeued_at_start()) +
               " jobs that were running when the server stopped are queued again\n";
    hello += "vgd-server: listening on http://" + host + ":" + std::to_string(server.port()) + " (data " +
             data + ", " + std::to_string(workers) + " workers, vgd " + so.exe.string() + ")" +
             (so.token.empty() ? "" : ", token required") + "\n";
    std::fputs(hello.c_str(), stdout);
    std::fflush(stdout);
    std::thread waiter([&] {
      int sig = 0;
      sigwait(&signals, &sig);
      std::printf("vgd-server: %s: stopping; running jobs are queued again\n", sig == SIGINT ? "SIGINT" : "SIGTERM");
      std::fflush(stdout);
      server.stop();
    });
    server.run();
    service.stop();
    waiter.join();
    std::printf("vgd-server: stopped\n");
    return 0;
  } catch (const vgd::Error& e) {
    std::fprintf(stderr, "vgd-server: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vgd-server: internal error: %s\n", e.what());
    return 4;
  }
}
