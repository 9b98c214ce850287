#pragma once
// A load test of vgd-server (docs/performance.md, "Server under load";
// `vgd bench server`): a server started on loopback, N clients at once each
// submitting a small job (a scene or a drape) and watching all of its frames,
// then the same jobs with nobody watching, then (scenes) the same scenes run
// by `vgd simulate` without a server, in one run.
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
  std::string scene;           // or a self-contained scene's JSON text: scene jobs, and the
                               // same scene run by `vgd simulate` directly for comparison
  std::filesystem::path scene_file;  // that scene's file, for the direct runs
};

struct LoadRun {
  int jobs = 0, completed = 0, errors = 0;
  double wall_s = 0.0;                    // first submission to last job finished
  double jobs_per_minute = 0.0;
  std::vector<double> first_frame_s;      // per watched job: submission → first frame received
  std::vector<double> start_to_frame_s;   // per watched job: its worker's start → first frame received
  std::vector<double> job_wall_s;         // per job: started → finished, as the server records them
  long long frames = 0, dropped = 0, corrupted = 0, lost = 0;
};

struct LoadResult {
  LoadRun watched, unwatched;
  // Scene jobs: the same scenes run by `vgd simulate` directly, `workers`
  // at once, no server (wall seconds, first start to last end); 0 otherwise.
  double direct_wall_s = 0.0;
  long server_peak_rss_kb = 0;            // VmHWM of the server process
  double overhead() const;                // (watched wall − unwatched wall) / unwatched wall
  double server_overhead() const;         // (unwatched wall − direct wall) / direct wall; NaN without direct runs
};

double percentile(std::vector<double> v, double p);  // p in [0, 1]; NaN for an empty list

// Runs both rounds. Throws vgd::Error when the server cannot start.
LoadResult run_load(const LoadOptions& options, const std::function<void(const std::string&)>& say = {});

}  // namespace vgd::net
