#pragma once
// A load test of vgd-server (docs/performance.md, "Server under load";
// `vgd bench server`): a server started on loopback, N clients at once each
// submitting a small drape and watching all of its frames, then the same
// jobs with nobody watching, in one run.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace vgd::net {

struct LoadOptions {
  std::filesystem::path server_exe, vgd_exe;
  std::filesystem::path data;  // the server's data folder (emptied first)
  int clients = 50;
  int workers = 2;
  std::string document;        // XVC text of the job's garment
  std::string settings_json;   // its settings (JSON object)
};

struct LoadRun {
  int jobs = 0, completed = 0, errors = 0;
  double wall_s = 0.0;                    // first submission to last job finished
  double jobs_per_minute = 0.0;
  std::vector<double> first_frame_s;      // per watched job: submission → first frame received
  std::vector<double> start_to_frame_s;   // per watched job: its worker's start → first frame received
  std::vector<double> job_wall_s;         // per job: its worker's wall time (manifest)
  long long frames = 0, dropped = 0, corrupted = 0, lost = 0;
};

struct LoadResult {
  LoadRun watched, unwatched;
  long server_peak_rss_kb = 0;            // VmHWM of the server process
  double overhead() const;                // (watched wall − unwatched wall) / unwatched wall
};

double percentile(std::vector<double> v, double p);  // p in [0, 1]; NaN for an empty list

// Runs both rounds. Throws vgd::Error when the server cannot start.
LoadResult run_load(const LoadOptions& options, const std::function<void(const std::string&)>& say = {});

}  // namespace vgd::net
