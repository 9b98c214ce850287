// vgd batch: catalogue runs (docs/batch.md).
//
//   vgd batch count catalogue.json
//   vgd batch run catalogue.json -o out/ --jobs 2          every item here, a progress bar
//   vgd batch item catalogue.json -o out/ [--index I]      one item (the index from Slurm, Kubernetes, PBS)
//   vgd batch slurm catalogue.json -o out/ --max-running 8 --submit
//   vgd batch status catalogue.json -o out/
//   vgd batch collect catalogue.json -o out/               summary.csv, summary.json, index.html
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <fstream>

#include "cli.hpp"
#include "vgd/batch/catalogue.hpp"
#include "vgd/batch/item.hpp"
#include "vgd/batch/process.hpp"
#include "vgd/batch/report.hpp"
#include "vgd/batch/run.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"

namespace cmd_batch {
namespace {

namespace fs = std::filesystem;
namespace batch = vgd::batch;

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

struct Options {
  std::string catalogue, output = "out", partition;
  int jobs = 1, index = -1, max_running = 0, max_array_size = 1001;
  bool retry_failed = false, force = false, submit = false, json = false, failed_only = false, sizes_only = false;
};

fs::path self_exe() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw vgd::Error("/proc/self/exe", "", "cannot find the vgd executable: " + ec.message());
  return p;
}

std::string duration(double s) {
  if (s < 0) return "?";
  if (s < 120) return vgd::format_fixed(s, 0) + " s";
  if (s < 7200) return vgd::format_fixed(s / 60, 0) + " min";
  return vgd::format_fixed(s / 3600, 1) + " h";
}

void add_catalogue(CLI::App* sub, const std::shared_ptr<Options>& o, bool output = true) {
  sub->add_option("CATALOGUE", o->catalogue, "catalogue.json (docs/batch.md)")->required()->check(CLI::ExistingFile);
  if (output) sub->add_option("-o,--output", o->output, "Output folder (default: out)")->capture_default_str();
}

// Failures by class, each with its items, and the command that redoes them.
void print_failures(const batch::Catalogue& c, const batch::Status& s, const Options& o, bool slurm) {
  for (const auto& [cls, indices] : s.failed_by_class) {
    std::printf("  %-18s %zu:", cls.c_str(), indices.size());
    for (std::size_t k = 0; k < indices.size() && k < 8; ++k)
      std::printf(" %d (%s)", indices[k], c.items[static_cast<std::size_t>(indices[k])].name.c_str());
    if (indices.size() > 8) std::printf(" ...");
    std::printf("\n");
  }
  std::vector<int> redo = s.failed_indices();
  for (int i : s.unfinished()) redo.push_back(i);
  if (redo.empty()) return;
  std::printf("to redo the %zu failed or unfinished items:\n", redo.size());
  if (slurm)
    std::printf("  vgd batch slurm %s -o %s --indices %s --retry-failed --submit\n", o.catalogue.c_str(),
                o.output.c_str(), batch::array_ranges(redo).c_str());
  std::printf("  vgd batch run %s -o %s --retry-failed\n", o.catalogue.c_str(), o.output.c_str());
}

vgd::cli::Registrar reg{"batch", 90, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("batch", "Catalogue runs: every style x size x fabric x body, resumable, here or "
                                          "as a Slurm job array (docs/batch.md)");
  sub->require_subcommand(1);
  auto o = std::make_shared<Options>();
  std::string indices_text;

  auto* count = sub->add_subcommand("count", "Print the number of items in the catalogue");
  add_catalogue(count, o, false);
  count->add_flag("--json", o->json, "Every item (index, id, name) as JSON");

  auto* run = sub->add_subcommand("run", "Run every unfinished item on this machine, --jobs at a time");
  add_catalogue(run, o);
  run->add_option("-j,--jobs", o->jobs, "Items at once (worker processes)")->check(CLI::Range(1, 256))->capture_default_str();
  run->add_flag("--retry-failed", o->retry_failed, "Also redo items that finished failed");

  auto* item = sub->add_subcommand("item", "Run one item (its index from --index, SLURM_ARRAY_TASK_ID, "
                                           "JOB_COMPLETION_INDEX or PBS_ARRAY_INDEX)");
  add_catalogue(item, o);
  item->add_option("--index", o->index, "The item's index (vgd batch count; 0-based)")->check(CLI::NonNegativeNumber);
  item->add_flag("--retry-failed", o->retry_failed, "Redo it if it finished failed");
  item->add_flag("--force", o->force, "Redo it whatever its state");
  item->footer("Exit codes: 0 passed (or already finished), 3 the item failed (its manifest says why), 1 bad "
               "catalogue or output folder.");

  auto* slurm = sub->add_subcommand("slurm", "Write an sbatch script running the catalogue as a job array "
                                             "(and submit it with --submit)");
  add_catalogue(slurm, o);
  slurm->add_option("--max-running", o->max_running, "At most K tasks at once (--array=...%K; 0 = no limit)")
      ->check(CLI::NonNegativeNumber);
  slurm->add_option("--indices", indices_text, "Only these items, as --array takes them (\"3,7,9-11\"); default: "
                                               "every unfinished item");
  slurm->add_option("--partition", o->partition, "Slurm partition (default: the cluster's)");
  slurm->add_option("--max-array-size", o->max_array_size,
                    "The cluster's MaxArraySize (scontrol show config): task ids stay below it, more items go in "
                    "several arrays")
      ->check(CLI::Range(1, 4000001))
      ->capture_default_str();
  slurm->add_flag("--retry-failed", o->retry_failed, "Also submit items that finished failed");
  slurm->add_flag("--submit", o->submit, "Submit it with sbatch and print the job id");

  auto* st = sub->add_subcommand("status", "Items passed, failed (by class), unfinished");
  add_catalogue(st, o);
  st->add_flag("--json", o->json, "As JSON (summary.json's content)");
  st->add_flag("--quick", o->sizes_only, "Check the outputs' sizes, not their SHA-256");

  auto* collect = sub->add_subcommand("collect", "Write summary.csv, summary.json and the contact sheet "
                                                 "index.html; list failures and how to redo them");
  add_catalogue(collect, o);

  return vgd::cli::Command{sub, [=, &common]() -> int {
    const batch::Catalogue c = batch::load_catalogue(o->catalogue);
    const fs::path out = o->output;
    if (count->parsed()) {
      if (o->json) {
        nlohmann::json j = nlohmann::json::array();
        for (const auto& it : c.items) j.push_back({{"index", it.index}, {"id", it.id}, {"name", it.name}});
        vgd::cli::print_json(j);
      } else {
        std::printf("%zu\n", c.items.size());
      }
      return vgd::cli::kOk;
    }
    if (item->parsed()) {
      int index = o->index;
      if (index < 0) index = batch::index_from_environment();
      if (index < 0)
        throw vgd::Error(o->catalogue, "", "which item? give --index or run it as an array task "
                                           "(SLURM_ARRAY_TASK_ID, JOB_COMPLETION_INDEX or PBS_ARRAY_INDEX)");
      const batch::Item& it = batch::item_at(c, index);
      batch::RunItemOptions ro;
      ro.exe = self_exe();
      ro.retry_failed = o->retry_failed;
      ro.force = o->force;
      vgd::cli::say(common, "vgd: item " + std::to_string(index) + " (" + it.id + "): " + it.name);
      const auto r = batch::run_item(c, it, out, ro);
      const auto& m = r.manifest;
      const std::string where = batch::item_dir(out, it.id).string();
      if (r.skipped) vgd::cli::say(common, "vgd: already finished (" + m.state + ") in " + where);
      else vgd::cli::say(common, "vgd: " + m.state + " in " + vgd::format_fixed(m.wall_s, 1) + " s; " +
                                     std::to_string(m.files.size()) + " files in " + where);
      if (m.state == "failed") std::fprintf(stderr, "vgd: failed: %s: %s\n", m.failure_class.c_str(), m.failure_message.c_str());
      return m.state == "passed" ? vgd::cli::kOk : vgd::cli::kCheckFailed;
    }
    if (run->parsed()) {
      std::signal(SIGINT, on_signal);
      std::signal(SIGTERM, on_signal);
      const bool tty = isatty(2) == 1;
      batch::LocalOptions lo;
      lo.exe = self_exe();
      lo.jobs = o->jobs;
      lo.retry_failed = o->retry_failed;
      lo.stop = &g_stop;
      std::string last_line;
      bool first = true;
      lo.progress = [&](const batch::RunProgress& p) {
        if (common.quiet) return;
        const int total = p.done + p.failed + p.left + p.running;
        const int finished = p.done + p.failed;
        const int width = 24, filled = total > 0 ? width * finished / total : width;
        std::string line = "[" + std::string(filled, '#') + std::string(width - filled, '.') + "] " +
                           std::to_string(p.done) + " passed, " + std::to_string(p.failed) + " failed, " +
                           std::to_string(p.running) + " running, " + std::to_string(p.left) + " left";
        if (p.skipped) line += " (" + std::to_string(p.skipped) + " already finished)";
        line += "  wall " + duration(p.wall_s) + "  ETA " + duration(p.eta_s);
        if (tty) {
          std::fprintf(stderr, "\r%s\033[K", line.c_str());
          if (!p.last.empty() && p.last != last_line) std::fprintf(stderr, "\n  %s\n", p.last.c_str());
        } else if (p.last != last_line || first) {
          std::fprintf(stderr, "%s%s\n", line.c_str(), p.last.empty() ? "" : ("  last: " + p.last).c_str());
        }
        last_line = p.last;
        first = false;
        std::fflush(stderr);
      };
      const auto r = batch::run_local(c, out, lo);
      if (tty && !common.quiet) std::fprintf(stderr, "\n");
      const batch::Status s = batch::status(c, out, /*checksums=*/false);
      batch::write_summary(c, out, s);
      std::printf("%s: %d passed, %d failed this run; %d already finished; %d interrupted\n", o->catalogue.c_str(),
                  r.passed, r.failed, r.skipped, r.interrupted);
      std::printf("contact sheet: %s\n", (out / "index.html").string().c_str());
      print_failures(c, s, *o, false);
      if (r.interrupted) return vgd::cli::kFailed;
      return s.failed == 0 && s.pending + s.partial == 0 ? vgd::cli::kOk : vgd::cli::kCheckFailed;
    }
    if (slurm->parsed()) {
      batch::SlurmOptions so;
      so.exe = self_exe();
      so.max_running = o->max_running;
      so.partition = o->partition;
      if (!indices_text.empty()) {
        for (const auto& part : vgd::split(indices_text, ',')) {
          const auto dash = part.find('-');
          const auto a = vgd::parse_int(part.substr(0, dash));
          const auto b = dash == std::string::npos ? a : vgd::parse_int(part.substr(dash + 1));
          if (!a || !b || *a > *b) throw vgd::Error("--indices", "", "'" + part + "' is not an index or a range a-b");
          for (long long i = *a; i <= *b; ++i) so.indices.push_back(static_cast<int>(i));
        }
      } else {
        const batch::Status s = batch::status(c, out, /*checksums=*/false);
        so.indices = s.unfinished();
        if (o->retry_failed)
          for (int i : s.failed_indices()) so.indices.push_back(i);
        if (so.indices.empty()) {
          std::printf("every item of %s is finished in %s; nothing to submit\n", o->catalogue.c_str(), out.string().c_str());
          return vgd::cli::kOk;
        }
      }
      std::error_code ec;
      fs::create_directories(out / "slurm", ec);
      // Task ids must stay below the cluster's MaxArraySize: more items go
      // in several arrays, each with its offset.
      const auto arrays = batch::slurm_arrays(so.indices, o->max_array_size);
      std::vector<fs::path> scripts;
      for (std::size_t k = 0; k < arrays.size(); ++k) {
        batch::SlurmOptions part = so;
        part.indices = arrays[k].indices;
        part.offset = arrays[k].offset;
        const fs::path script =
            out / "slurm" / (c.name + (arrays.size() > 1 ? "-" + std::to_string(k + 1) : std::string()) + ".sbatch");
        vgd::write_file_atomic(script, batch::slurm_script(c, out, part));
        fs::permissions(script, fs::perms::owner_exec, fs::perm_options::add, ec);
        std::printf("wrote %s: %zu items as --array=%s%s%s\n", script.string().c_str(), part.indices.size(),
                    batch::array_ranges(part.indices).c_str(),
                    o->max_running > 0 ? ("%" + std::to_string(o->max_running)).c_str() : "",
                    part.offset > 0 ? (" (task ids offset by " + std::to_string(part.offset) + ")").c_str() : "");
        scripts.push_back(script);
      }
      if (!o->submit) {
        for (const auto& script : scripts) std::printf("submit it with: sbatch %s\n", script.string().c_str());
        return vgd::cli::kOk;
      }
      for (std::size_t k = 0; k < scripts.size(); ++k) {
        const fs::path log = out / "slurm" / "sbatch.out";
        fs::remove(log, ec);
        batch::ProcessOptions po;
        po.log = log;
        po.deadline_s = 120;
        const auto r = batch::run_process("/usr/bin/env", {"sbatch", "--parsable", scripts[k].string()}, po);
        std::string said;
        try {
          said = std::string(vgd::trim(vgd::read_file(log)));
        } catch (const vgd::Error&) {
        }
        if (!r.ok()) throw vgd::Error(scripts[k].string(), "", "sbatch " + r.describe() + ": " + said);
        const std::string job = vgd::split(said, ';').front();
        std::ofstream(out / "slurm" / "jobs.txt", std::ios::app)
            << job << " " << batch::array_ranges(arrays[k].indices) << "\n";
        std::printf("submitted job %s\n", job.c_str());
      }
      return vgd::cli::kOk;
    }
    const bool checksums = !o->sizes_only;
    const batch::Status s = batch::status(c, out, checksums);
    if (st->parsed() && o->json) {
      std::fputs(batch::summary_json(c, s).c_str(), stdout);
      return vgd::cli::kOk;
    }
    const int pages = collect->parsed() ? batch::write_summary(c, out, s) : 0;
    std::printf("%s: %zu items: %d passed, %d failed, %d partial, %d pending\n", o->catalogue.c_str(),
                c.items.size(), s.passed, s.failed, s.partial, s.pending);
    for (std::size_t i = 0; i < s.items.size(); ++i)
      if (s.items[i].state == batch::ItemState::partial)
        std::printf("  partial %zu (%s): %s\n", i, c.items[i].name.c_str(), s.items[i].problem.c_str());
    if (collect->parsed())
      std::printf("wrote %s, %s and %s%s\n", (out / "summary.csv").string().c_str(),
                  (out / "summary.json").string().c_str(), (out / "index.html").string().c_str(),
                  pages > 0 ? (", and " + std::to_string(pages) + " 3-D viewer pages in " + (out / "web").string())
                                  .c_str()
                            : "");
    const bool used_slurm = fs::exists(out / "slurm" / "jobs.txt");
    print_failures(c, s, *o, used_slurm);
    return s.failed == 0 && s.pending + s.partial == 0 ? vgd::cli::kOk : vgd::cli::kCheckFailed;
  }};
}};

}  // namespace
}  // namespace cmd_batch
