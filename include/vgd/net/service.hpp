#pragma once
// The simulation server's service (docs/server.md), apart from sockets: jobs
// submitted, run by worker processes, inspected, cancelled and their results
// served, answered as HTTP responses. http.hpp puts it on the network.
//
// API (version 1, JSON unless said):
//   GET  /v1/health                 {"status": "ok", "version", "jobs": {state: count}}
//   GET  /v1/metrics                Prometheus text format
//   POST /v1/jobs                   {"name": "skirt.xvc", "document": "<XVC text>", "settings": {...}}
//                                   → 202 {"id", "state": "queued"}; 400 with the message naming the field
//   GET  /v1/jobs                   [{"id", "state", "name", "created", ...}], newest first
//   GET  /v1/jobs/{id}              the job: state, progress (stage, simulated s, seams, kinetic
//                                   energy, wall s), failure, the certificate's figures, its files
//   POST /v1/jobs/{id}/cancel       a queued or running job → cancelled
//   GET  /v1/jobs/{id}/files/{path} one of its result files (as listed by its manifest)
//   GET  /                          the browser page (page.hpp); /web/three/*.js its three.js
#include <atomic>
#include <condition_variable>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <nlohmann/json_fwd.hpp>

#include "vgd/net/jobs.hpp"

namespace vgd::net {

struct ServiceOptions {
  std::filesystem::path data = "vgd-data";  // jobs.sqlite and jobs/<id>/
  std::filesystem::path exe;                // the vgd executable the workers run
  int workers = 1;                          // jobs at once
  std::size_t max_document = 16u << 20;     // bytes of a submitted document
  int max_queued = 1000;                    // queued jobs at most (then 429)
  int max_per_client = 100;                 // queued and running jobs of one client address at most (then 429)
  // Scene jobs (`vgd simulate` on a submitted scene): cloth particles,
  // simulated seconds, wall seconds and address space at most.
  long max_particles = 250000;
  double max_simulated_s = 60.0;
  double scene_wall_limit = 600.0;
  long scene_memory_mb = 4096;
  // When set, every request but /v1/health needs "Authorization: Bearer
  // <token>" (compared in constant time, never logged or echoed): 401
  // without it, 403 with another.
  std::string token;
  // three.js's build folder (three.module.js, three.core.js) for the browser
  // page; "" = the copy this build found (tests/web/node_modules), if any.
  std::filesystem::path three_dir;
};

struct Request {
  std::string method, target, body;
  std::string authorization;  // the Authorization header, if any
  std::string client;         // the client's address ("" in tests without sockets)
};

struct Response {
  int status = 200;
  std::string content_type = "application/json";
  std::string body;
  std::filesystem::path file;  // when set: the body is this file's content
};

class Service {
 public:
  // Opens the job database (jobs left running are queued again) and starts
  // the runner thread. Throws vgd::Error naming the data folder.
  explicit Service(ServiceOptions options);
  ~Service();  // stops: running jobs are killed and queued again
  Service(const Service&) = delete;
  Service& operator=(const Service&) = delete;

  Response handle(const Request& request);

  // Where job `id`'s frames are now (for the live stream, http.cpp): the
  // trajectory its worker is writing, or the finished item's; `finished`
  // once the job will write no more. Nothing when there is no such job.
  struct Trajectory {
    std::filesystem::path file;  // may not exist yet
    bool finished = false;
    std::string state;
  };
  std::optional<Trajectory> trajectory(const std::string& id);
  // Authorization for a request other than handle() (the live stream): an
  // error response, or nothing when it may go on.
  std::optional<Response> check_token(const std::string& authorization) const;
  void count_stream(long long frames, long long dropped);
  // A running job's progress as JSON ({"stage", "simulated_s", "seams_closed",
  // "seam_pairs", "kinetic_energy_j", "wall_s"}), or "" when there is none.
  std::string progress(const std::string& id);
  // Stops the runner: running workers are killed, their jobs queued again for
  // the next start. Idempotent.
  void stop();
  int requeued_at_start() const { return requeued_; }

 private:
  void run();
  Response submit(const std::string& body, const std::string& client);
  Response submit_scene(const nlohmann::json& request, const std::string& client);
  std::optional<Response> refuse_when_full(const std::string& client);
  Response queue(const std::string& id, const std::string& name, const std::string& client);
  Response job(const std::string& id);
  Response cancel(const std::string& id);
  Response file(const std::string& id, const std::string& path);
  Response metrics();
  std::filesystem::path three_dir() const;

  ServiceOptions o_;
  JobStore store_;
  int requeued_ = 0;
  std::atomic<bool> stop_{false};
  std::mutex mutex_;                   // cancels_, woken_ and the counters below
  std::condition_variable wake_;       // the runner: a job submitted or cancelled, or stopping
  bool woken_ = false;
  std::map<std::string, bool> cancels_;  // running job ids asked to cancel
  std::map<int, long long> responses_;   // status → count
  long long submitted_ = 0;
  long long streamed_frames_ = 0, dropped_frames_ = 0, streams_ = 0;
  std::thread runner_;
};

}  // namespace vgd::net
