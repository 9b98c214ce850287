// vgd-server over HTTP on loopback, as a client sees it: started on a free
// port, a job submitted and its results downloaded, the server killed with
// SIGKILL mid-job and started again (the job completes), garbage requests
// answered without the server going down, SIGTERM stopping it cleanly.
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <thread>

#include "support/server_process.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"

namespace vgd::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct Reply {
  int status = 0;
  std::string body;
};

// One request on a fresh connection (Connection: close), the whole reply read.
Reply http(int port, const std::string& method, const std::string& target, const std::string& body = "",
           const std::string& raw = "") {
  Reply r;
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return r;
  }
  const std::string req = !raw.empty() ? raw
                                       : method + " " + target + " HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n" +
                                             "Content-Type: application/json\r\nContent-Length: " +
                                             std::to_string(body.size()) + "\r\n\r\n" + body;
  for (std::size_t sent = 0; sent < req.size();) {
    const ssize_t n = ::send(fd, req.data() + sent, req.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) break;
    sent += static_cast<std::size_t>(n);
  }
  ::shutdown(fd, SHUT_WR);  // all sent: a cut request ends here instead of waiting for the server's time-out
  std::string in;
  char buf[65536];
  for (ssize_t n; (n = ::recv(fd, buf, sizeof buf, 0)) > 0;) in.append(buf, static_cast<std::size_t>(n));
  ::close(fd);
  if (in.rfind("HTTP/1.1 ", 0) == 0) r.status = std::stoi(in.substr(9, 3));
  const auto split = in.find("\r\n\r\n");
  if (split != std::string::npos) r.body = in.substr(split + 4);
  return r;
}

json skirt_job(double time_limit) {
  return {{"name", "skirt.xvc"},
          {"document", read_file(source_dir() / "data/garments/a-line-skirt.xvc")},
          {"settings",
           {{"size", "38"}, {"quality", "preview"}, {"spacing", 0.03}, {"time_limit", time_limit},
            {"outputs", {"certificate", "previews"}}, {"views", {"front"}}, {"preview_size", 128}}}};
}

std::string state_of(int port, const std::string& id) {
  const json j = json::parse(http(port, "GET", "/v1/jobs/" + id).body, nullptr, false);
  return j.is_object() ? j.value("state", "") : "";
}

TEST(Server, AJobSurvivesTheServerKilledMidRunAndCompletesAfterRestart) {
  const auto dir = scratch_dir("net-server");
  const fs::path log = dir / "server.log";
  std::string id;
  {
    ServerProcess s(dir);
    ASSERT_GT(s.port, 0) << read_file(log);
    const Reply h = http(s.port, "GET", "/v1/health");
    EXPECT_EQ(h.status, 200) << h.body;
    const Reply sub = http(s.port, "POST", "/v1/jobs", skirt_job(3).dump());
    ASSERT_EQ(sub.status, 202) << sub.body;
    id = json::parse(sub.body)["id"];
    for (int i = 0; i < 400 && state_of(s.port, id) != "running"; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    ASSERT_EQ(state_of(s.port, id), "running");
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    s.stop(SIGKILL);
  }
  // The worker went with the server (it is killed with its parent).
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_NE(std::system(("pgrep -f '[b]atch item " + (dir / "data/jobs" / id).string() + "' > /dev/null").c_str()), 0);
  ServerProcess again(dir);
  ASSERT_GT(again.port, 0) << read_file(log);
  EXPECT_NE(read_file(log).find("1 jobs that were running when the server stopped are queued again"),
            std::string::npos);
  std::string st;
  for (int i = 0; i < 1200; ++i) {
    st = state_of(again.port, id);
    if (st == "passed" || st == "failed") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ASSERT_EQ(st, "passed") << http(again.port, "GET", "/v1/jobs/" + id).body;
  const json j = json::parse(http(again.port, "GET", "/v1/jobs/" + id).body);
  EXPECT_EQ(j["attempts"], 2);
  const Reply png = http(again.port, "GET", "/v1/jobs/" + id + "/files/previews/front.png");
  EXPECT_EQ(png.status, 200);
  EXPECT_EQ(png.body.substr(1, 3), "PNG");
  // SIGTERM: a clean stop.
  const int status = again.stop(SIGTERM);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  EXPECT_NE(read_file(log).find("vgd-server: stopped"), std::string::npos);
}

TEST(Server, GarbageAndOversizedRequestsAreAnsweredAndTheServerStaysUp) {
  const auto dir = scratch_dir("net-garbage");
  ServerProcess s(dir);
  ASSERT_GT(s.port, 0);
  // Mutations of a valid request: bytes flipped, cut, repeated (bounded: 1 000).
  const std::string valid = "POST /v1/jobs HTTP/1.1\r\nHost: x\r\nConnection: close\r\nContent-Length: 27\r\n\r\n"
                            "{\"name\": \"a.xvc\", \"doc\": 1}";
  std::mt19937 rng(7);
  int answered = 0;
  for (int i = 0; i < 1000; ++i) {
    std::string m = valid;
    const int edits = 1 + static_cast<int>(rng() % 8);
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = rng() % m.size();
      switch (rng() % 3) {
        case 0: m[at] = static_cast<char>(rng() % 256); break;
        case 1: m.erase(at, 1 + rng() % 10); break;
        default: m.insert(at, std::string(1 + rng() % 50, static_cast<char>(rng() % 256)));
      }
      if (m.empty()) m = "x";
    }
    const Reply r = http(s.port, "", "", "", m);
    answered += r.status >= 400 && r.status < 500;
  }
  EXPECT_GT(answered, 850) << "mutations get a 4xx (a few: an empty or unparseable start, dropped)";
  // A document over the server's limit (16 MB): 413.
  const std::string big = json{{"name", "big.xvc"}, {"document", std::string(17u << 20, 'x')}}.dump();
  EXPECT_EQ(http(s.port, "POST", "/v1/jobs", big).status, 413);
  const Reply h = http(s.port, "GET", "/v1/health");
  EXPECT_EQ(h.status, 200) << "still up";
  EXPECT_EQ(json::parse(h.body)["jobs"]["queued"], 0);
}

// The processes whose command line holds `needle` (this machine's /proc).
std::vector<pid_t> processes_with(const std::string& needle, const std::string& also = "") {
  std::vector<pid_t> out;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(e.path() / "cmdline", std::ios::binary);
    const std::string cmd((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (cmd.find(needle) != std::string::npos && (also.empty() || cmd.find(also) != std::string::npos))
      out.push_back(static_cast<pid_t>(std::stol(name)));
  }
  return out;
}

json wait_finished(int port, const std::string& id, double seconds) {
  const auto t0 = std::chrono::steady_clock::now();
  for (;;) {
    const json j = json::parse(http(port, "GET", "/v1/jobs/" + id).body, nullptr, false);
    const std::string st = j.is_object() ? j.value("state", "") : "";
    if (st == "passed" || st == "failed" || st == "cancelled") return j;
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > seconds) return j;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

// A worker killed with SIGKILL (as the kernel's OOM killer or an operator
// would) fails its job as a crash, saying so; the server stays up and runs
// the next job.
TEST(Server, AWorkerKilledWithSigkillFailsItsJobAndTheServerGoesOn) {
  const auto dir = scratch_dir("server-worker-kill");
  ServerProcess s(dir, {"--workers", "1"});
  ASSERT_GT(s.port, 0) << read_file(s.log);
  const json scene = json::parse(read_file(source_dir() / "data/scenes/cloth-on-sphere.json"));
  json long_scene = scene;
  long_scene["frames"]["duration"] = "30 s";
  long_scene["cloth"][0]["grid"]["particles"] = {40, 40};
  // A scene job: its worker is vgd simulate itself.
  const std::string a = json::parse(http(s.port, "POST", "/v1/jobs", json{{"scene", long_scene}}.dump()).body)["id"];
  // A drape: its worker is `vgd batch item`, which runs vgd dress.
  const std::string b = json::parse(http(s.port, "POST", "/v1/jobs", skirt_job(30).dump()).body)["id"];
  for (const std::string& id : {a, b}) {
    std::vector<pid_t> worker;
    for (int i = 0; i < 400 && worker.empty(); ++i) {
      worker = id == a ? processes_with("jobs/" + id + "/input/scene.json") : processes_with("jobs/" + id + "/", "batch");
      if (worker.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    ASSERT_EQ(worker.size(), 1u) << "job " << id << "'s worker";
    std::this_thread::sleep_for(std::chrono::milliseconds(500));  // well into its run
    ASSERT_EQ(::kill(worker[0], SIGKILL), 0);
    const json j = wait_finished(s.port, id, 60);
    EXPECT_EQ(j["state"], "failed") << j.dump(2);
    ASSERT_TRUE(j["failure"].is_object()) << j.dump(2);
    EXPECT_EQ(j["failure"]["class"], "crash") << j.dump(2);
    EXPECT_NE(j["failure"]["message"].get<std::string>().find("signal 9"), std::string::npos) << j.dump(2);
  }
  // The drape's own process is sent SIGKILL as its worker dies (the kernel's
  // parent-death signal); a process with a large address space takes a
  // moment to be torn down, so it is given up to 5 s to be gone.
  bool drape_gone = false;
  for (int i = 0; i < 100 && !drape_gone; ++i) {
    drape_gone = processes_with("jobs/" + b + "/", "dress").empty();
    if (!drape_gone) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_TRUE(drape_gone) << "the drape's own process went with its worker";
  // The server is up, and the next job runs.
  EXPECT_EQ(http(s.port, "GET", "/v1/health").status, 200);
  const std::string c = json::parse(http(s.port, "POST", "/v1/jobs", json{{"scene", scene}}.dump()).body)["id"];
  EXPECT_EQ(wait_finished(s.port, c, 60)["state"], "passed");
}

}  // namespace
}  // namespace vgd::test
