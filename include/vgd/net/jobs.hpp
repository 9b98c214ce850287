#pragma once
// The simulation server's jobs (docs/server.md): each a garment document and
// its settings, kept in a SQLite database (WAL mode) in the server's data
// folder, so nothing a client submitted is lost when the server stops or is
// killed: a job that was running when the server went is queued again at the
// next start.
//
// A job runs as one catalogue item (batch/item.hpp): its document and a
// one-item catalogue.json are written in DATA/jobs/<id>/, and a worker process
// runs `vgd batch item` on them, so a job's outputs, manifest and failure
// class are those of a catalogue run.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace vgd::net {

enum class JobState { queued, running, passed, failed, cancelled };
const char* to_string(JobState s);

struct Job {
  std::string id;          // 16 hex digits
  long long seq = 0;       // submission order
  JobState state = JobState::queued;
  std::string name;        // the document's file name as submitted
  std::string created, started, finished;  // UTC, ISO 8601 with milliseconds ("" when not yet)
  std::string failure_class, message;
  int attempts = 0;        // times a worker started it (a restart requeues a running job)
  std::string client;      // the submitting client's address
};

class JobStore {
 public:
  // Opens (creating) DATA/jobs.sqlite. Throws vgd::Error naming the file.
  explicit JobStore(const std::filesystem::path& data_dir);
  ~JobStore();
  JobStore(const JobStore&) = delete;
  JobStore& operator=(const JobStore&) = delete;

  void insert(const Job& job);
  std::optional<Job> get(const std::string& id) const;
  std::vector<Job> list(int limit = 1000) const;  // newest first
  std::optional<Job> next_queued() const;         // oldest queued
  void set_state(const std::string& id, JobState state, const std::string& failure_class = "",
                 const std::string& message = "");
  // Jobs left running by a server that stopped: queued again. Returns how many.
  int requeue_running();
  long long count(JobState state) const;
  // Jobs of `client` queued or running.
  long long active_of(const std::string& client) const;

  struct Db;  // the SQLite connection (jobs.cpp)

 private:
  std::unique_ptr<Db> db_;
};

std::string utc_now();

}  // namespace vgd::net
