// Running a catalogue here or through Slurm (run.hpp).
#include "vgd/batch/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <deque>
#include <list>
#include <thread>

#include "vgd/batch/process.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"

namespace vgd::batch {
namespace {

namespace fs = std::filesystem;

// A quoted word for a shell script.
std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

LocalResult run_local(const Catalogue& c, const fs::path& out, const LocalOptions& o) {
  LocalResult result;
  std::error_code ec;
  fs::create_directories(out / "logs", ec);
  if (ec) throw Error(out.string(), "", "cannot make the output folder: " + ec.message());
  std::deque<int> queue;
  RunProgress p;
  for (const Item& item : c.items) {
    const ItemStatus s = item_status(out, item, /*checksums=*/false);
    if (s.state == ItemState::passed || (s.state == ItemState::failed && !o.retry_failed)) {
      ++result.skipped;
      continue;
    }
    queue.push_back(item.index);
  }
  p.skipped = result.skipped;
  p.left = static_cast<int>(queue.size());
  const auto t0 = std::chrono::steady_clock::now();
  struct Running {
    int index;
    Process process;
  };
  std::list<Running> running;
  double item_wall = 0.0;  // sum over finished items
  int finished = 0;
  const int jobs = std::max(1, o.jobs);
  auto report = [&] {
    p.running = static_cast<int>(running.size());
    p.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    p.eta_s = finished > 0 ? item_wall / finished * (p.left + p.running * 0.5) / jobs : -1.0;
    if (o.progress) o.progress(p);
  };
  report();
  bool started = false;
  while (!queue.empty() || !running.empty()) {
    if (o.stop && *o.stop) {
      for (auto& r : running) r.process.kill();
      for (auto& r : running) r.process.wait();
      result.interrupted = static_cast<int>(running.size() + queue.size());
      running.clear();
      break;
    }
    while (static_cast<int>(running.size()) < jobs && !queue.empty()) {
      const int index = queue.front();
      queue.pop_front();
      ProcessOptions po;
      po.log = out / "logs" / (std::to_string(index) + ".log");
      fs::create_directories(po.log.parent_path(), ec);
      fs::remove(po.log, ec);
      po.deadline_s = c.settings.wall_limit + 120.0;  // the item stops its own steps first
      running.push_back(Running{index, Process(o.exe, {"batch", "item", c.file.string(), "-o", out.string(), "--index",
                                                std::to_string(index), "--retry-failed"},
                                        po)});
      --p.left;
      started = true;
    }
    if (started) report();
    started = false;
    bool changed = false;
    for (auto it = running.begin(); it != running.end();) {
      if (!it->process.poll()) {
        ++it;
        continue;
      }
      const ProcessResult& r = it->process.result();
      const Item& item = c.items[static_cast<std::size_t>(it->index)];
      ItemStatus s = item_status(out, item, /*checksums=*/false);
      if (s.state != ItemState::passed && s.state != ItemState::failed) {
        // The worker went without its manifest: killed, out of memory, a bug.
        record_failure(out, c, item, r.timed_out ? "time-out" : "crash",
                       "the worker (vgd batch item) " + r.describe() + " before it finished; its output is in " +
                           (out / "logs" / (std::to_string(it->index) + ".log")).string());
        s = item_status(out, item, false);
      }
      const bool passed = s.state == ItemState::passed;
      passed ? ++result.passed : ++result.failed;
      passed ? ++p.done : ++p.failed;
      p.last = item.name + ": " + (passed ? std::string("passed")
                                          : "failed (" + (s.manifest ? s.manifest->failure_class : "?") + ")");
      item_wall += r.wall_s;
      ++finished;
      it = running.erase(it);
      changed = true;
    }
    // Finished items are reported with the next ones started (or at the end).
    if (changed && (queue.empty() || (o.stop && *o.stop))) report();
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return result;
}

int index_from_environment() {
  for (const char* var : {"SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX", "PBS_ARRAY_INDEX"}) {
    const char* v = std::getenv(var);
    if (!v || !*v) continue;
    const auto n = parse_int(v);
    if (!n || *n < 0 || *n > 100000000) throw Error(var, "", std::string("'") + printable(v) + "' is not an index");
    return static_cast<int>(*n);
  }
  return -1;
}

std::string array_ranges(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  std::string s;
  for (std::size_t i = 0; i < v.size();) {
    std::size_t j = i;
    while (j + 1 < v.size() && v[j + 1] == v[j] + 1) ++j;
    s += (s.empty() ? "" : ",") + std::to_string(v[i]) + (j > i ? "-" + std::to_string(v[j]) : "");
    i = j + 1;
  }
  return s;
}

std::string slurm_script(const Catalogue& c, const fs::path& out, const SlurmOptions& o) {
  std::vector<int> indices = o.indices;
  if (indices.empty())
    for (const auto& item : c.items) indices.push_back(item.index);
  if (indices.empty()) throw Error(c.file.string(), "", "no items to submit");
  for (int i : indices) item_at(c, i);  // each one exists
  const fs::path abs_out = fs::absolute(out).lexically_normal();
  // A task's time: the item's wall limit and a margin for previews and exports, in whole minutes.
  const int minutes = static_cast<int>(std::ceil((c.settings.wall_limit + 300.0) / 60.0));
  std::string s = "#!/bin/bash\n";
  s += "# Written by vgd batch slurm: one array task per catalogue item (docs/batch.md).\n";
  s += "# Catalogue: " + c.file.string() + " (" + std::to_string(c.items.size()) + " items)\n";
  s += "#SBATCH --job-name=" + shell_quote("vgd-" + c.name) + "\n";
  std::vector<int> tasks;
  for (int i : indices) {
    if (i < o.offset) throw Error(c.file.string(), "", "item " + std::to_string(i) + " is below the array's offset");
    tasks.push_back(i - o.offset);
  }
  s += "#SBATCH --array=" + array_ranges(tasks) + (o.max_running > 0 ? "%" + std::to_string(o.max_running) : "") + "\n";
  s += "#SBATCH --ntasks=1\n";
  s += "#SBATCH --cpus-per-task=" + std::to_string(c.settings.threads) + "\n";
  s += "#SBATCH --mem=" + std::to_string(c.settings.memory_mb) + "M\n";
  s += "#SBATCH --time=" + std::to_string(minutes) + "\n";
  s += "#SBATCH --output=" + (abs_out / "slurm" / "%A_%a.log").string() + "\n";
  if (!o.partition.empty()) s += "#SBATCH --partition=" + o.partition + "\n";
  s += "set -eu\n";
  s += "exec " + shell_quote(o.exe.string()) + " batch item " + shell_quote(c.file.string()) + " -o " +
       shell_quote(abs_out.string()) +
       (o.offset > 0 ? " --index \"$((SLURM_ARRAY_TASK_ID + " + std::to_string(o.offset) + "))\"\n"
                     : " --index \"$SLURM_ARRAY_TASK_ID\"\n");
  return s;
}

std::vector<SlurmArray> slurm_arrays(std::vector<int> indices, int max_array_size) {
  std::sort(indices.begin(), indices.end());
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
  std::vector<SlurmArray> arrays;
  if (indices.empty()) return arrays;
  if (indices.back() < max_array_size) return {SlurmArray{indices, 0}};
  for (int i : indices) {
    if (arrays.empty() || i - arrays.back().offset >= max_array_size) arrays.push_back({{}, i});
    arrays.back().indices.push_back(i);
  }
  return arrays;
}

}  // namespace vgd::batch
