// vgd bench server: vgd-server under load (net::run_load): N clients at once
// each submit a small job and read every frame of it over the WebSocket;
// then the same jobs with nobody reading. The job: a scene (default
// data/scenes/cloth-on-sphere.json, 20 x 20 cloth on a sphere for 0.5 s;
// then also run by vgd simulate without a server) or a drape (the shipped
// skirt, preview quality, 5 cm mesh, 0.5 s). Prints jobs per minute,
// submission → first frame p50/p95, frames received, skipped, corrupted and
// lost, the streaming and server overheads and the server's peak memory
// (docs/performance.md, "Server under load"). Exit 3 when a frame was lost
// or corrupted or a request failed.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cli.hpp"
#include "vgd/core/data.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/net/load.hpp"

namespace vgd::cli {

int bench_server(int clients, int workers, const std::string& job, bool json) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  fs::path server;
  for (const fs::path& p : {self.parent_path() / "vgd-server", self.parent_path().parent_path() / "vgd-server" / "vgd-server"})
    if (fs::is_regular_file(p, ec)) server = p;
  if (server.empty()) throw vgd::Error(self.string(), "", "vgd-server is not beside vgd: build it (cmake --build build)");
  net::LoadOptions o;
  o.server_exe = server;
  o.vgd_exe = self;
  o.data = fs::temp_directory_path() / ("vgd-bench-server-" + std::to_string(::getpid()));
  o.clients = clients;
  o.workers = workers;
  if (job == "drape") {
    o.document = vgd::read_file(vgd::data_file("garments/a-line-skirt.xvc"));
    o.settings_json = R"({"size": "38", "quality": "preview", "spacing": 0.05, "time_limit": 0.5, "outputs": ["certificate", "trj"]})";
  } else {
    o.scene_file = job == "scene" ? vgd::data_file("scenes/cloth-on-sphere.json") : fs::path(job);
    o.scene = vgd::read_file(o.scene_file);
  }
  const auto r = net::run_load(o, [&](const std::string& s) {
    if (!json) std::fprintf(stderr, "vgd: %s\n", s.c_str());
  });
  std::filesystem::remove_all(o.data, ec);
  auto row = [&](const char* name, const net::LoadRun& run) {
    nlohmann::json j = {{"jobs", run.jobs},
                        {"completed", run.completed},
                        {"errors", run.errors},
                        {"wall_s", run.wall_s},
                        {"jobs_per_minute", run.jobs_per_minute},
                        {"job_wall_p50_s", net::percentile(run.job_wall_s, 0.5)},
                        {"frames", run.frames},
                        {"dropped", run.dropped},
                        {"corrupted", run.corrupted},
                        {"lost", run.lost}};
    if (!run.first_frame_s.empty()) {
      j["first_frame_p50_s"] = net::percentile(run.first_frame_s, 0.5);
      j["first_frame_p95_s"] = net::percentile(run.first_frame_s, 0.95);
      j["start_to_first_frame_p50_s"] = net::percentile(run.start_to_frame_s, 0.5);
      j["start_to_first_frame_p95_s"] = net::percentile(run.start_to_frame_s, 0.95);
    }
    if (!json) {
      std::printf("%-10s %4d jobs %4d done %3d errors  %6.1f s  %6.1f jobs/min  job wall p50 %.2f s", name, run.jobs,
                  run.completed, run.errors, run.wall_s, run.jobs_per_minute, net::percentile(run.job_wall_s, 0.5));
      if (!run.first_frame_s.empty())
        std::printf("  submission -> first frame p50 %.2f s p95 %.2f s; job start -> first frame p50 %.2f s p95 %.2f s"
                    "  frames %lld skipped %lld corrupted %lld lost %lld",
                    net::percentile(run.first_frame_s, 0.5), net::percentile(run.first_frame_s, 0.95),
                    net::percentile(run.start_to_frame_s, 0.5), net::percentile(run.start_to_frame_s, 0.95), run.frames,
                    run.dropped, run.corrupted, run.lost);
      std::printf("\n");
    }
    return j;
  };
  if (!json) std::printf("vgd-server, %d clients, %d workers, loopback, job: %s\n", clients, workers, job.c_str());
  nlohmann::json out = {{"clients", clients}, {"workers", workers}, {"job", job}};
  out["watched"] = row("watched", r.watched);
  out["unwatched"] = row("unwatched", r.unwatched);
  out["streaming_overhead"] = r.overhead();
  out["server_peak_rss_kb"] = r.server_peak_rss_kb;
  if (r.direct_wall_s > 0) {
    out["direct_wall_s"] = r.direct_wall_s;
    out["server_overhead"] = r.server_overhead();
  }
  if (json) {
    vgd::cli::print_json(out);
  } else {
    std::printf("streaming overhead %+.1f %% of the unwatched wall time; server peak RSS %.1f MB\n", 100 * r.overhead(),
                r.server_peak_rss_kb / 1024.0);
    if (r.direct_wall_s > 0)
      std::printf("direct     the same %d scenes by vgd simulate, %d at once: %.1f s; the server's unwatched round "
                  "%+.1f %% of it\n",
                  clients, workers, r.direct_wall_s, 100 * r.server_overhead());
  }
  const bool bad = r.watched.lost + r.watched.corrupted + r.watched.errors + r.unwatched.errors > 0;
  return bad ? vgd::cli::kCheckFailed : vgd::cli::kOk;
}

}  // namespace vgd::cli
