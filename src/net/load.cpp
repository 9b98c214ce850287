// The server's load test (load.hpp).
#include "vgd/net/load.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <nlohmann/json.hpp>
#include <memory>
#include <thread>

#include "vgd/batch/process.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/net/client.hpp"

namespace vgd::net {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double unix_now() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// "2026-11-27T17:08:01.123Z" as seconds since the epoch; NaN when not that.
double parse_utc(const std::string& s) {
  std::tm tm{};
  const char* rest = strptime(s.c_str(), "%Y-%m-%dT%H:%M:%S", &tm);
  if (!rest) return std::nan("");
  double frac = 0;
  if (*rest == '.') frac = std::atof(rest);
  return static_cast<double>(timegm(&tm)) + frac;
}

long peak_rss_kb(int pid) {
  try {
    for (const auto& line : split(read_file("/proc/" + std::to_string(pid) + "/status"), '\n'))
      if (line.rfind("VmHWM:", 0) == 0) return static_cast<long>(parse_int(trim(line.substr(6, line.size() - 9))).value_or(0));
  } catch (const Error&) {
  }
  return 0;
}

LoadRun round(const Client& client, const LoadOptions& o, bool watch) {
  LoadRun run;
  run.jobs = o.clients;
  std::mutex m;
  const json request = o.scene.empty()
                           ? json{{"name", "load.xvc"}, {"document", o.document}, {"settings", json::parse(o.settings_json)}}
                           : json{{"name", "load.json"}, {"scene", json::parse(o.scene)}};
  const std::string body = request.dump();
  const auto t0 = Clock::now();
  std::vector<std::string> ids(static_cast<std::size_t>(o.clients));
  std::vector<std::thread> threads;
  for (int c = 0; c < o.clients; ++c) {
    threads.emplace_back([&, c] {
      try {
        const auto submitted = Clock::now();
        const auto r = client.request("POST", "/v1/jobs", body);
        if (r.status != 202) throw Error("load", "", "submit answered " + std::to_string(r.status) + ": " + r.body);
        const std::string id = json::parse(r.body)["id"];
        ids[static_cast<std::size_t>(c)] = id;
        if (!watch) return;
        double first = -1, first_unix = 0;
        long long frames = 0, dropped = 0, corrupted = 0, lost = 0;
        long long expect = -1;  // the next frame index expected
        json end;
        client.watch(
            id,
            [&](const std::string& text) {
              const json j = json::parse(text, nullptr, false);
              if (!j.is_object()) return;
              if (j["type"] == "dropped") {
                dropped += j["count"].get<long long>();
                if (expect >= 0) expect += j["count"].get<long long>();
              }
              if (j["type"] == "end") end = j;
            },
            [&](const FrameMessage& f) {
              if (first < 0) first = since(submitted), first_unix = unix_now();
              ++frames;
              corrupted += !f.checksum_ok;
              if (expect >= 0 && static_cast<long long>(f.seq) != expect)
                lost += std::llabs(static_cast<long long>(f.seq) - expect);
              expect = static_cast<long long>(f.seq) + 1;
            });
        if (end.is_object() && expect >= 0) lost += std::max(0LL, end.value("frames", 0LL) - expect);
        const json job = json::parse(client.request("GET", "/v1/jobs/" + id).body, nullptr, false);
        const double started = job.is_object() ? parse_utc(job.value("started", "")) : std::nan("");
        std::lock_guard lock(m);
        if (first >= 0) run.first_frame_s.push_back(first);
        if (first >= 0 && std::isfinite(started)) run.start_to_frame_s.push_back(first_unix - started);
        run.frames += frames, run.dropped += dropped, run.corrupted += corrupted, run.lost += lost;
      } catch (const std::exception&) {
        std::lock_guard lock(m);
        ++run.errors;
      }
    });
  }
  for (auto& t : threads) t.join();
  // Every job to its end.
  for (;;) {
    int done = 0;
    for (const auto& id : ids) {
      if (id.empty()) {
        ++done;
        continue;
      }
      const json j = json::parse(client.request("GET", "/v1/jobs/" + id).body, nullptr, false);
      const std::string st = j.is_object() ? j.value("state", "") : "";
      done += st == "passed" || st == "failed" || st == "cancelled";
    }
    if (done == o.clients) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  run.wall_s = since(t0);
  for (const auto& id : ids) {
    if (id.empty()) continue;
    const json j = json::parse(client.request("GET", "/v1/jobs/" + id).body, nullptr, false);
    if (!j.is_object()) continue;
    if (j.value("state", "") != "cancelled") ++run.completed;
    const double started = parse_utc(j.value("started", "")), finished = parse_utc(j.value("finished", ""));
    if (std::isfinite(started) && std::isfinite(finished)) run.job_wall_s.push_back(finished - started);
  }
  run.jobs_per_minute = 60.0 * run.completed / run.wall_s;
  return run;
}

}  // namespace

double LoadResult::overhead() const {
  return unwatched.wall_s > 0 ? (watched.wall_s - unwatched.wall_s) / unwatched.wall_s : 0.0;
}

double LoadResult::server_overhead() const {
  return direct_wall_s > 0 ? (unwatched.wall_s - direct_wall_s) / direct_wall_s : std::nan("");
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const double at = p * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(at));
  const auto hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (v[hi] - v[lo]) * (at - static_cast<double>(lo));
}

LoadResult run_load(const LoadOptions& o, const std::function<void(const std::string&)>& say) {
  std::error_code ec;
  fs::remove_all(o.data, ec);
  fs::create_directories(o.data, ec);
  batch::ProcessOptions po;
  po.log = o.data / "server.log";
  batch::Process server(o.server_exe,
                        {"--listen", "127.0.0.1:0", "--data", (o.data / "server").string(), "--workers",
                         std::to_string(o.workers), "--vgd", o.vgd_exe.string()},
                        po);
  std::string port;
  for (int i = 0; i < 200 && port.empty(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    try {
      const std::string t = read_file(po.log);
      const auto at = t.rfind("127.0.0.1:");
      if (at != std::string::npos) port = std::to_string(parse_int(t.substr(at + 10, t.find(' ', at) - at - 10)).value_or(0));
    } catch (const Error&) {
    }
  }
  if (port.empty() || port == "0") throw Error(po.log.string(), "", "vgd-server did not start");
  Client client(ServerUrl{"127.0.0.1", port});
  LoadResult r;
  if (say) say("watched: " + std::to_string(o.clients) + " clients, each submitting a job and reading all its frames");
  r.watched = round(client, o, true);
  if (say) say("unwatched: the same jobs, nobody reading their frames");
  r.unwatched = round(client, o, false);
  r.server_peak_rss_kb = peak_rss_kb(server.pid());
  server.kill();
  server.wait();
  if (!o.scene_file.empty()) {
    if (say) say("direct: the same scenes run by vgd simulate, " + std::to_string(o.workers) + " at once, no server");
    const auto t0 = Clock::now();
    std::vector<std::unique_ptr<batch::Process>> running;
    int started = 0, failed = 0;
    while (started < o.clients || !running.empty()) {
      for (auto it = running.begin(); it != running.end();) {
        if ((*it)->poll()) {
          failed += !(*it)->result().ok();
          it = running.erase(it);
        } else {
          ++it;
        }
      }
      while (started < o.clients && static_cast<int>(running.size()) < std::max(1, o.workers)) {
        const fs::path trj = o.data / ("direct-" + std::to_string(started) + ".trj");
        batch::ProcessOptions dpo;
        dpo.log = o.data / "direct.log";
        running.push_back(std::make_unique<batch::Process>(
            o.vgd_exe, std::vector<std::string>{"simulate", o.scene_file.string(), "--trj", trj.string()}, dpo));
        ++started;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    r.direct_wall_s = since(t0);
    if (failed > 0) throw Error(o.scene_file.string(), "", std::to_string(failed) + " of its direct vgd simulate runs failed");
  }
  return r;
}

}  // namespace vgd::net
