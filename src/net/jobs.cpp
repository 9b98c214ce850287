// Jobs in SQLite (jobs.hpp).
#include "vgd/net/jobs.hpp"

#include <sqlite3.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <mutex>

#include "vgd/core/diagnostics.hpp"

namespace vgd::net {

struct JobStore::Db {
  sqlite3* db = nullptr;
  std::string file;
  mutable std::mutex mutex;  // one connection, used from the HTTP and runner threads

  void exec(const char* sql) const {
    char* err = nullptr;
    if (sqlite3_exec(db, sql, nullptr, nullptr, &err) != SQLITE_OK) {
      const std::string msg = err ? err : "unknown";
      sqlite3_free(err);
      throw Error(file, "", std::string("SQLite: ") + msg);
    }
  }
  struct Stmt {
    sqlite3_stmt* s = nullptr;
    const Db& d;
    Stmt(const Db& db, const char* sql) : d(db) {
      if (sqlite3_prepare_v2(db.db, sql, -1, &s, nullptr) != SQLITE_OK)
        throw Error(db.file, "", std::string("SQLite: ") + sqlite3_errmsg(db.db));
    }
    ~Stmt() { sqlite3_finalize(s); }
    Stmt& text(int i, const std::string& v) {
      sqlite3_bind_text(s, i, v.c_str(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
      return *this;
    }
    Stmt& integer(int i, long long v) {
      sqlite3_bind_int64(s, i, v);
      return *this;
    }
    bool step() {
      const int rc = sqlite3_step(s);
      if (rc == SQLITE_ROW) return true;
      if (rc == SQLITE_DONE) return false;
      throw Error(d.file, "", std::string("SQLite: ") + sqlite3_errmsg(d.db));
    }
    std::string col(int i) const {
      const auto* t = sqlite3_column_text(s, i);
      return t ? reinterpret_cast<const char*>(t) : "";
    }
  };
};

namespace {

constexpr const char* kColumns = "id, seq, state, name, created, started, finished, failure_class, message, attempts";

JobState parse_state(const std::string& s) {
  if (s == "running") return JobState::running;
  if (s == "passed") return JobState::passed;
  if (s == "failed") return JobState::failed;
  if (s == "cancelled") return JobState::cancelled;
  return JobState::queued;
}

Job row(const JobStore::Db::Stmt& st) {
  Job j;
  j.id = st.col(0);
  j.seq = sqlite3_column_int64(st.s, 1);
  j.state = parse_state(st.col(2));
  j.name = st.col(3);
  j.created = st.col(4), j.started = st.col(5), j.finished = st.col(6);
  j.failure_class = st.col(7), j.message = st.col(8);
  j.attempts = sqlite3_column_int(st.s, 9);
  return j;
}

}  // namespace

const char* to_string(JobState s) {
  switch (s) {
    case JobState::queued: return "queued";
    case JobState::running: return "running";
    case JobState::passed: return "passed";
    case JobState::failed: return "failed";
    case JobState::cancelled: return "cancelled";
  }
  return "?";
}

std::string utc_now() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t t = std::chrono::system_clock::to_time_t(now);
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[40];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", &tm);
  char out[48];
  std::snprintf(out, sizeof out, "%s.%03dZ", buf, static_cast<int>(ms));
  return out;
}

JobStore::JobStore(const std::filesystem::path& data_dir) : db_(std::make_unique<Db>()) {
  std::error_code ec;
  std::filesystem::create_directories(data_dir, ec);
  db_->file = (data_dir / "jobs.sqlite").string();
  if (sqlite3_open_v2(db_->file.c_str(), &db_->db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_FULLMUTEX,
                      nullptr) != SQLITE_OK)
    throw Error(db_->file, "", std::string("cannot open the job database: ") +
                                   (db_->db ? sqlite3_errmsg(db_->db) : "out of memory"));
  sqlite3_busy_timeout(db_->db, 5000);
  db_->exec("PRAGMA journal_mode=WAL");
  db_->exec("PRAGMA synchronous=NORMAL");
  db_->exec(
      "CREATE TABLE IF NOT EXISTS jobs (id TEXT PRIMARY KEY, seq INTEGER NOT NULL, state TEXT NOT NULL, "
      "name TEXT NOT NULL, created TEXT NOT NULL, started TEXT NOT NULL DEFAULT '', finished TEXT NOT NULL DEFAULT '', "
      "failure_class TEXT NOT NULL DEFAULT '', message TEXT NOT NULL DEFAULT '', attempts INTEGER NOT NULL DEFAULT 0)");
  db_->exec("CREATE INDEX IF NOT EXISTS jobs_state ON jobs(state, seq)");
  // The client column (added to a database made before it had one).
  char* err = nullptr;
  sqlite3_exec(db_->db, "ALTER TABLE jobs ADD COLUMN client TEXT NOT NULL DEFAULT ''", nullptr, nullptr, &err);
  sqlite3_free(err);
}

JobStore::~JobStore() {
  if (db_ && db_->db) sqlite3_close(db_->db);
}

void JobStore::insert(const Job& j) {
  std::lock_guard lock(db_->mutex);
  Db::Stmt st(*db_, "INSERT INTO jobs (id, seq, state, name, created, client) VALUES (?, "
                    "(SELECT COALESCE(MAX(seq), 0) + 1 FROM jobs), ?, ?, ?, ?)");
  st.text(1, j.id).text(2, to_string(j.state)).text(3, j.name).text(4, j.created.empty() ? utc_now() : j.created);
  st.text(5, j.client);
  st.step();
}

std::optional<Job> JobStore::get(const std::string& id) const {
  std::lock_guard lock(db_->mutex);
  Db::Stmt st(*db_, (std::string("SELECT ") + kColumns + " FROM jobs WHERE id = ?").c_str());
  st.text(1, id);
  if (!st.step()) return std::nullopt;
  return row(st);
}

std::vector<Job> JobStore::list(int limit) const {
  std::lock_guard lock(db_->mutex);
  Db::Stmt st(*db_, (std::string("SELECT ") + kColumns + " FROM jobs ORDER BY seq DESC LIMIT ?").c_str());
  st.integer(1, limit);
  std::vector<Job> v;
  while (st.step()) v.push_back(row(st));
  return v;
}

std::optional<Job> JobStore::next_queued() const {
  std::lock_guard lock(db_->mutex);
  Db::Stmt st(*db_, (std::string("SELECT ") + kColumns + " FROM jobs WHERE state = 'queued' ORDER BY seq LIMIT 1").c_str());
  if (!st.step()) return std::nullopt;
  return row(st);
}

void JobStore::set_state(const std::string& id, JobState state, const std::string& failure_class,
                         const std::string& message) {
  std::lock_guard lock(db_->mutex);
  const bool start = state == JobState::running;
  const bool end = state == JobState::passed || state == JobState::failed || state == JobState::cancelled;
  Db::Stmt st(*db_, start ? "UPDATE jobs SET state = ?, started = ?, attempts = attempts + 1, failure_class = ?, "
                            "message = ? WHERE id = ?"
                    : end ? "UPDATE jobs SET state = ?, finished = ?, failure_class = ?, message = ? WHERE id = ?"
                          : "UPDATE jobs SET state = ?, started = ?, failure_class = ?, message = ? WHERE id = ?");
  st.text(1, to_string(state)).text(2, start || end ? utc_now() : "").text(3, failure_class).text(4, message).text(5, id);
  st.step();
}

int JobStore::requeue_running() {
  std::lock_guard lock(db_->mutex);
  db_->exec("UPDATE jobs SET state = 'queued', started = '' WHERE state = 'running'");
  return sqlite3_changes(db_->db);
}

long long JobStore::active_of(const std::string& client) const {
  std::lock_guard lock(db_->mutex);
  Db::Stmt st(*db_, "SELECT COUNT(*) FROM jobs WHERE client = ? AND state IN ('queued', 'running')");
  st.text(1, client);
  st.step();
  return sqlite3_column_int64(st.s, 0);
}

long long JobStore::count(JobState state) const {
  std::lock_guard lock(db_->mutex);
  Db::Stmt st(*db_, "SELECT COUNT(*) FROM jobs WHERE state = ?");
  st.text(1, to_string(state));
  st.step();
  return sqlite3_column_int64(st.s, 0);
}

}  // namespace vgd::net
