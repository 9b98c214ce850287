// vgd batch: a catalogue of real drapes (the shipped skirt, coarse mesh,
// preview quality) run here with two workers, resumed, partly redone after an
// edit, and a worker killed mid-item.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "support/json_file.hpp"
#include "support/run_vgd.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/file.hpp"

namespace vgd::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Two styles (the shipped skirt and a copy with a comment: another file),
// sizes 38 and 42 for the first, 38 for the second: three items of ~3 s.
fs::path write_catalogue(const fs::path& dir) {
  const std::string skirt = read_file(source_dir() / "data/garments/a-line-skirt.xvc");
  write_file_atomic(dir / "skirt.xvc", skirt);
  write_file_atomic(dir / "skirt-b.xvc", skirt + "<!-- b -->\n");
  const json j = {{"name", "test"},
                  {"styles", {{{"id", "skirt"}, {"file", "skirt.xvc"}, {"sizes", {"38", "42"}}},
                              {{"id", "b"}, {"file", "skirt-b.xvc"}, {"sizes", {"38"}}}}},
                  {"settings", {{"quality", "preview"}, {"spacing", 0.03}, {"time_limit", 3}, {"wall_limit", 300}}},
                  {"outputs", {"certificate", "wvt", "vrml", "glb", "previews"}},
                  {"views", {"front"}},
                  {"preview_size", 192}};
  write_file_atomic(dir / "catalogue.json", j.dump(2));
  return dir / "catalogue.json";
}

std::map<std::string, std::string> finished_times(const fs::path& out) {
  std::map<std::string, std::string> t;
  for (const auto& e : fs::directory_iterator(out / "items"))
    if (fs::exists(e.path() / "manifest.json"))
      t[e.path().filename().string()] = read_json(e.path() / "manifest.json")["finished"];
  return t;
}

TEST(CliBatch, ACatalogueRunsHereResumesAndRedoesOnlyAnEditedStyle) {
  const auto dir = scratch_dir("cli-batch-run");
  const auto cat = write_catalogue(dir).string();
  const auto out = (dir / "out").string();
  const auto count = run_vgd({"batch", "count", cat});
  EXPECT_EQ(count.out, "3\n");

  const auto r = run_vgd({"batch", "run", cat, "-o", out, "--jobs", "2"});
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("3 passed, 0 failed this run; 0 already finished"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("3 passed, 0 failed, 0 running, 0 left"), std::string::npos) << r.err;
  const json summary = read_json(dir / "out/summary.json");
  ASSERT_EQ(summary["items"].size(), 3u);
  for (const auto& item : summary["items"]) {
    EXPECT_EQ(item["state"], "passed") << item.dump();
    EXPECT_EQ(item["certificate"]["seams_closed"], item["certificate"]["seam_pairs"]) << item.dump();
    EXPECT_GT(item["certificate"]["seam_pairs"].get<int>(), 50);
    const fs::path d = dir / "out" / item["dir"].get<std::string>();
    for (const char* f : {"certificate.json", "drape.wvt", "garment.wrl", "garment.glb", "garment.xvc",
                          "previews/front.png", "log.txt"})
      EXPECT_TRUE(fs::is_regular_file(d / f)) << d / f;
    EXPECT_FALSE(fs::exists(d / "drape.trj")) << "not asked for";
  }
  EXPECT_TRUE(fs::is_regular_file(dir / "out/index.html"));
  // A 3-D viewer page per item (X_ITE, docs/vrml.md), linked from its card.
  if (fs::is_regular_file(source_dir() / "tests/web/node_modules/x_ite/dist/x_ite.min.js")) {
    const std::string sheet = read_file(dir / "out/index.html");
    for (const auto& item : summary["items"]) {
      const std::string page = "web/" + item["id"].get<std::string>() + ".html";
      EXPECT_TRUE(fs::is_regular_file(dir / "out" / page)) << page;
      EXPECT_NE(sheet.find("href=\"" + page + "\""), std::string::npos) << page;
      EXPECT_NE(read_file(dir / "out" / page).find("../items/" + item["id"].get<std::string>() + "/garment.wrl"),
                std::string::npos);
    }
    EXPECT_TRUE(fs::is_regular_file(dir / "out/web/x_ite/x_ite.min.js"));
  }
  const auto st = run_vgd({"batch", "status", cat, "-o", out});
  EXPECT_EQ(st.code, 0) << st.out << st.err;
  EXPECT_NE(st.out.find("3 items: 3 passed, 0 failed, 0 partial, 0 pending"), std::string::npos) << st.out;

  // Run again: nothing to do.
  const auto before = finished_times(dir / "out");
  const auto again = run_vgd({"batch", "run", cat, "-o", out, "--jobs", "2"});
  EXPECT_EQ(again.code, 0);
  EXPECT_NE(again.out.find("0 passed, 0 failed this run; 3 already finished"), std::string::npos) << again.out;
  EXPECT_EQ(finished_times(dir / "out"), before);

  // Style b edited: its one item is new, the others are not redone.
  write_file_atomic(dir / "skirt-b.xvc", read_file(dir / "skirt-b.xvc") + "<!-- edited -->\n");
  const auto edited = run_vgd({"batch", "run", cat, "-o", out});
  EXPECT_EQ(edited.code, 0) << edited.err;
  EXPECT_NE(edited.out.find("1 passed, 0 failed this run; 2 already finished"), std::string::npos) << edited.out;
  const auto after = finished_times(dir / "out");
  EXPECT_EQ(after.size(), 4u) << "the old item of b stays, no longer in the catalogue";
  for (const auto& [id, t] : before) EXPECT_EQ(after.at(id), t) << id;
}

// The pid of the worker running item `index` of catalogue `cat`, or 0.
int worker_pid(const std::string& cat, int index) {
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(e.path() / "cmdline", std::ios::binary);
    std::string cmd((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (auto& c : cmd)
      if (c == '\0') c = ' ';
    if (cmd.find("batch item " + cat + " ") != std::string::npos &&
        cmd.find("--index " + std::to_string(index) + " ") != std::string::npos)
      return std::stoi(name);
  }
  return 0;
}

TEST(CliBatch, AWorkerKilledMidItemIsRecordedAsACrashAndRedoneNothingElseIs) {
  const auto dir = scratch_dir("cli-batch-kill");
  const auto cat = write_catalogue(dir).string();
  const auto out = (dir / "out").string();
  CliResult r;
  std::thread runner([&] { r = run_vgd({"batch", "run", cat, "-o", out, "--jobs", "2"}); });
  int killed = 0;
  for (int i = 0; i < 600 && !killed; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (const int pid = worker_pid(cat, 0)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(800));  // well into its drape
      if (::kill(pid, SIGKILL) == 0) killed = pid;
    }
  }
  runner.join();
  ASSERT_NE(killed, 0) << "no worker for item 0 seen";
  EXPECT_EQ(r.code, 3) << r.out << r.err;
  EXPECT_NE(r.out.find("2 passed, 1 failed this run"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("crash"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("vgd batch run " + cat + " -o " + out + " --retry-failed"), std::string::npos) << r.out;
  const json s = read_json(dir / "out/summary.json");
  EXPECT_EQ(s["items"][0]["state"], "failed");
  EXPECT_EQ(s["items"][0]["failure"]["class"], "crash");
  EXPECT_NE(s["items"][0]["failure"]["message"].get<std::string>().find("signal 9"), std::string::npos);
  for (const auto& e : fs::directory_iterator(dir / "out/items"))
    EXPECT_EQ(e.path().extension(), "") << "no partial folder left: " << e.path();

  const auto before = finished_times(dir / "out");
  const auto retry = run_vgd({"batch", "run", cat, "-o", out, "--retry-failed"});
  EXPECT_EQ(retry.code, 0) << retry.out << retry.err;
  EXPECT_NE(retry.out.find("1 passed, 0 failed this run; 2 already finished"), std::string::npos) << retry.out;
  const auto after = finished_times(dir / "out");
  int redone = 0;
  for (const auto& [id, t] : before) redone += after.at(id) != t;
  EXPECT_EQ(redone, 1);
}

TEST(CliBatch, OneItemTakesItsIndexFromTheSchedulerAndSaysWhyItFailed) {
  const auto dir = scratch_dir("cli-batch-item");
  write_catalogue(dir);
  json j = read_json(dir / "catalogue.json");
  j["styles"][1]["sizes"] = {"99"};
  j["outputs"] = {"certificate"};
  write_file_atomic(dir / "catalogue.json", j.dump());
  const auto cat = (dir / "catalogue.json").string(), out = (dir / "out").string();
  setenv("SLURM_ARRAY_TASK_ID", "2", 1);
  const auto r = run_vgd({"batch", "item", cat, "-o", out});
  unsetenv("SLURM_ARRAY_TASK_ID");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("item 2 ("), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("failed: bad input: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("99"), std::string::npos) << r.err;
  const auto none = run_vgd({"batch", "item", cat, "-o", out});
  EXPECT_EQ(none.code, 1);
  EXPECT_NE(none.err.find("which item?"), std::string::npos) << none.err;
  const auto far = run_vgd({"batch", "item", cat, "-o", out, "--index", "3"});
  EXPECT_EQ(far.code, 1);
  EXPECT_NE(far.err.find("no item 3: the catalogue has 3 items"), std::string::npos) << far.err;

  // A drape stopped long before rest: the certificate's first failed check
  // is the class, its detail the message.
  json short_run = j;
  short_run["settings"]["time_limit"] = 0.05;
  write_file_atomic(dir / "short.json", short_run.dump());
  const auto sh = run_vgd({"batch", "item", (dir / "short.json").string(), "-o", (dir / "short").string(),
                           "--index", "0"});
  EXPECT_EQ(sh.code, 3) << sh.err;
  EXPECT_NE(sh.err.find("failed: no rest: stopped at the time limit"), std::string::npos) << sh.err;

  // An item past its memory: the allocation fails, the class says so (not
  // in an AddressSanitizer build, where no address-space limit is set).
#if !defined(__SANITIZE_ADDRESS__)
  json small = j;
  small["settings"]["memory_mb"] = 100;
  write_file_atomic(dir / "small.json", small.dump());
  const auto sm = run_vgd({"batch", "item", (dir / "small.json").string(), "-o", (dir / "small").string(),
                           "--index", "0"});
  EXPECT_EQ(sm.code, 3) << sm.err;
  EXPECT_NE(sm.err.find("failed: out of memory: past settings.memory_mb (100 MB"), std::string::npos) << sm.err;
#endif

  // The Slurm script for what is left: items 0 and 1.
  const auto sl = run_vgd({"batch", "slurm", cat, "-o", out, "--max-running", "2"});
  EXPECT_EQ(sl.code, 0) << sl.err;
  EXPECT_NE(sl.out.find("2 items as --array=0-1%2"), std::string::npos) << sl.out;
  const std::string script = read_file(dir / "out/slurm/test.sbatch");
  EXPECT_NE(script.find("#SBATCH --array=0-1%2"), std::string::npos) << script;
  const auto with_failed = run_vgd({"batch", "slurm", cat, "-o", out, "--retry-failed"});
  EXPECT_NE(with_failed.out.find("3 items as --array=0-2"), std::string::npos) << with_failed.out;
}

// A customer's measurements instead of a size's mannequin: the body made by
// vgd mannequin inside the item, the skirt draped on it.
TEST(CliBatch, AMeasurementSetIsABodyMadeForTheItem) {
  const auto dir = scratch_dir("cli-batch-measured");
  write_file_atomic(dir / "skirt.xvc", read_file(source_dir() / "data/garments/a-line-skirt.xvc"));
  json anna = {{"id", "anna"}};
  anna["measurements"] = {{"sex", "female"}, {"height", 1.62}, {"bust", 0.92}, {"waist", 0.76}, {"hip", 1.01}};
  json j = {{"sizes", {"40"}}, {"outputs", {"certificate"}}};
  j["styles"] = json::array({{{"id", "skirt"}, {"file", "skirt.xvc"}}});
  j["avatars"] = json::array({anna});
  j["settings"] = {{"quality", "preview"}, {"spacing", 0.03}, {"time_limit", 3}};
  write_file_atomic(dir / "catalogue.json", j.dump());
  const auto r = run_vgd({"batch", "item", (dir / "catalogue.json").string(), "-o", (dir / "out").string(),
                          "--index", "0"});
  EXPECT_EQ(r.code, 0) << r.err;
  const auto items = fs::directory_iterator(dir / "out/items");
  const fs::path item = items->path();
  const json m = read_json(item / "manifest.json");
  EXPECT_EQ(m["state"], "passed") << m.dump();
  EXPECT_EQ(m["avatar"], "anna");
  EXPECT_EQ(m["steps"][0]["name"], "mannequin");
  EXPECT_TRUE(fs::is_regular_file(item / "body.obj"));
  const std::string log = read_file(item / "log.txt");
  EXPECT_NE(log.find("--height 1.62"), std::string::npos) << log;
}

}  // namespace
}  // namespace vgd::test
