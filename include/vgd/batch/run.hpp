#pragma once
// Where a catalogue runs (docs/batch.md): on this machine with N worker
// processes (run_local), or as a Slurm job array whose task I runs item I
// (slurm_script). Both run `vgd batch item`, so an item is the same command
// wherever it runs; neither schedules anything a scheduler already does.
#include <csignal>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "vgd/batch/catalogue.hpp"
#include "vgd/batch/item.hpp"

namespace vgd::batch {

struct RunProgress {
  int done = 0, failed = 0, left = 0, running = 0, skipped = 0;
  double wall_s = 0.0, eta_s = -1.0;   // -1: not known yet
  std::string last;                     // the last item finished ("skirt 38 garment mannequin: passed")
};

struct LocalOptions {
  std::filesystem::path exe;          // vgd
  int jobs = 1;                       // worker processes at once
  bool retry_failed = false;
  const volatile std::sig_atomic_t* stop = nullptr;  // set by a signal handler: kill the workers, return
  std::function<void(const RunProgress&)> progress;
};

struct LocalResult {
  int passed = 0, failed = 0, skipped = 0, interrupted = 0;
};

// Runs every unfinished item of the catalogue, `jobs` at a time, each as
// `vgd batch item CATALOGUE -o OUT --index I` (its output in
// OUT/logs/<index>.log). A worker that dies without a manifest (killed, out
// of memory) is recorded as failed: "crash". Throws vgd::Error when OUT
// cannot be written.
LocalResult run_local(const Catalogue& catalogue, const std::filesystem::path& out, const LocalOptions& options);

// The array index of this task: SLURM_ARRAY_TASK_ID, JOB_COMPLETION_INDEX
// (Kubernetes Indexed Job) or PBS_ARRAY_INDEX; -1 when none is set. Throws
// vgd::Error naming the variable when it is not a number.
int index_from_environment();

struct SlurmOptions {
  std::filesystem::path exe;        // vgd, absolute (the nodes run it from shared storage)
  int max_running = 0;              // %K: at most K tasks at once; 0 = no limit
  std::vector<int> indices;         // only these (a resubmission); empty = every item
  std::string partition;            // "" = the cluster's default
  // Array task ids are indices - offset (Slurm refuses task ids of
  // MaxArraySize or more: 1001 by default); the task runs item
  // SLURM_ARRAY_TASK_ID + offset.
  int offset = 0;
};

// The indices split into arrays whose task ids (index - the array's first
// index) stay below `max_array_size`: one array when the largest index is
// below it (offset 0), else as few as that allows, each with its offset.
struct SlurmArray {
  std::vector<int> indices;
  int offset = 0;
};
std::vector<SlurmArray> slurm_arrays(std::vector<int> indices, int max_array_size = 1001);

// An sbatch script: `--array=<indices>%K`, a task's time (the item's wall
// limit plus a margin), memory and CPUs from the catalogue's settings, its
// log in OUT/slurm/, running `vgd batch item` for $SLURM_ARRAY_TASK_ID.
std::string slurm_script(const Catalogue& catalogue, const std::filesystem::path& out, const SlurmOptions& options);

// "0-5", "3,7,9-11": indices as Slurm's --array takes them.
std::string array_ranges(std::vector<int> indices);

}  // namespace vgd::batch
