// One item: its commands, the failure class of each way it can end, its
// manifest and what counts as finished; child processes with deadlines; the
// summaries. The steps run a stand-in for vgd (fake_vgd.sh) so every ending
// is made on purpose and quickly; tests/apps/test_cmd_batch.cpp runs real drapes.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <thread>

#include "support/test_paths.hpp"
#include "vgd/batch/catalogue.hpp"
#include "vgd/batch/item.hpp"
#include "vgd/batch/process.hpp"
#include "vgd/batch/report.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"

namespace vgd::test {
namespace {

namespace fs = std::filesystem;
namespace batch = vgd::batch;
using nlohmann::json;

const fs::path kFake = source_dir() / "tests/batch/fake_vgd.sh";

batch::Catalogue catalogue(const fs::path& dir, const json& extra = json::object()) {
  write_file_atomic(dir / "skirt.xvc", read_file(source_dir() / "data/garments/a-line-skirt.xvc"));
  json j = {{"name", "t"},
            {"styles", {{{"id", "skirt"}, {"file", "skirt.xvc"}}}},
            {"sizes", {"36", "38"}},
            {"outputs", {"certificate", "wvt", "glb", "previews"}},
            {"views", {"front"}},
            {"settings", {{"wall_limit", 20}}}};
  j.update(extra);
  write_file_atomic(dir / "catalogue.json", j.dump());
  return batch::load_catalogue(dir / "catalogue.json");
}

batch::ItemOutcome run(const batch::Catalogue& c, const fs::path& out, const char* mode, int index = 0,
                       bool retry = false) {
  setenv("FAKE_VGD", mode, 1);
  batch::RunItemOptions o;
  o.exe = kFake;
  o.retry_failed = retry;
  auto r = batch::run_item(c, c.items[static_cast<std::size_t>(index)], out, o);
  unsetenv("FAKE_VGD");
  return r;
}

TEST(BatchItem, TheStepsAreTheCommandsADesignerWouldType) {
  const auto dir = scratch_dir("batch-steps");
  const auto c = catalogue(dir, {{"outputs", {"certificate", "wvt", "vrml", "vrml-animated", "glb", "previews"}},
                                 {"fabrics", {"denim"}},
                                 {"avatars", {{{"id", "w40"}, {"mannequin", "40"}, {"table", "en13402-women"}}}},
                                 {"settings", {{"quality", "preview"}, {"spacing", 0.02}, {"threads", 2}}}});
  const auto steps = batch::item_steps(c, c.items[1], "/o");
  ASSERT_EQ(steps.size(), 4u);
  EXPECT_EQ(steps[0].name, "dress");
  const auto has = [](const batch::Step& s, std::vector<std::string> seq) {
    return std::search(s.args.begin(), s.args.end(), seq.begin(), seq.end()) != s.args.end();
  };
  EXPECT_TRUE(has(steps[0], {"--threads", "2", "dress"}));
  EXPECT_TRUE(has(steps[0], {"--size", "38"}));
  EXPECT_TRUE(has(steps[0], {"--quality", "preview"}));
  EXPECT_TRUE(has(steps[0], {"--spacing", "0.02"}));
  EXPECT_TRUE(has(steps[0], {"--body-size", "40", "--body-table", "en13402-women"}));
  EXPECT_TRUE(has(steps[0], {"--trj", "/o/drape.trj"}));
  EXPECT_TRUE(has(steps[0], {"--views", "front"}));
  EXPECT_FALSE(has(steps[0], {"--seams"})) << "no seam file: vgd's suggestions";
  EXPECT_EQ(steps[0].args[std::find(steps[0].args.begin(), steps[0].args.end(), "--material") - steps[0].args.begin() + 1]
                .substr(0, 1),
            "/")
      << "the shipped denim by its absolute path";
  EXPECT_EQ(steps[1].name, "compress");
  EXPECT_TRUE(has(steps[2], {"--vrml", "static", "-o", "/o/garment.wrl", "--gltf", "/o/garment.glb"}));
  EXPECT_TRUE(has(steps[3], {"--vrml", "animated"}));
  // A measurement set: the body made by vgd mannequin first, then draped on as a file.
  json anna = {{"id", "anna"}};
  anna["measurements"] = {{"sex", "female"}, {"height", 1.62}, {"hip", 0.98}, {"under_bust", 0.76}};
  const auto measured = catalogue(dir, {{"avatars", json::array({anna})}});
  const auto ms = batch::item_steps(measured, measured.items[0], "/o");
  ASSERT_GE(ms.size(), 2u);
  EXPECT_EQ(ms[0].name, "mannequin");
  EXPECT_TRUE(has(ms[0], {"mannequin", "-o", "/o/body.obj"}));
  EXPECT_TRUE(has(ms[0], {"--sex", "female"}));
  EXPECT_TRUE(has(ms[0], {"--height", "1.62"}));
  EXPECT_TRUE(has(ms[0], {"--under-bust", "0.76"}));
  EXPECT_TRUE(has(ms[1], {"--avatar", "/o/body.obj", "--unit", "m", "--up", "y", "--facing", "+z"}));
  // Nothing but the certificate: one step, no trajectory.
  const auto bare = catalogue(dir, {{"outputs", {"certificate"}}});
  const auto one = batch::item_steps(bare, bare.items[0], "/o");
  ASSERT_EQ(one.size(), 1u);
  EXPECT_FALSE(has(one[0], {"--trj"}));
  EXPECT_TRUE(has(one[0], {"--no-previews"}));
}

TEST(BatchItem, APassedItemHasAManifestThatVerifies) {
  const auto dir = scratch_dir("batch-pass");
  const auto c = catalogue(dir);
  const fs::path out = dir / "out";
  EXPECT_EQ(batch::item_status(out, c.items[0]).state, batch::ItemState::pending);
  const auto r = run(c, out, "pass");
  EXPECT_FALSE(r.skipped);
  EXPECT_EQ(r.manifest.state, "passed");
  const fs::path item = batch::item_dir(out, c.items[0].id);
  EXPECT_FALSE(fs::exists(item.string() + ".partial"));
  std::vector<std::string> paths;
  for (const auto& f : r.manifest.files) paths.push_back(f.path);
  EXPECT_EQ(paths, (std::vector<std::string>{"certificate.json", "drape.wvt", "garment.glb", "garment.obj", "log.txt",
                                             "previews/front.png"}))
      << "the trajectory was only the outputs' source: not kept";
  const json m = json::parse(read_file(item / "manifest.json"));
  EXPECT_EQ(m["certificate"]["seams_closed"], 40);
  ASSERT_EQ(m["steps"].size(), 3u) << "dress, compress, export: where the time went";
  EXPECT_EQ(m["steps"][0]["name"], "dress");
  EXPECT_EQ(m["steps"][2]["result"], "exit 0");
  EXPECT_DOUBLE_EQ(m["certificate"]["strain_p95_max"].get<double>(), 0.08);
  EXPECT_NEAR(m["certificate"]["max_penetration_mm"].get<double>(), 0.2, 1e-12);
  EXPECT_EQ(batch::item_status(out, c.items[0]).state, batch::ItemState::passed);
  // Finished: a second run does nothing.
  const auto again = run(c, out, "crash");
  EXPECT_TRUE(again.skipped);
  EXPECT_EQ(again.manifest.finished, r.manifest.finished);

  // A file changed after the manifest: no longer finished, and said why.
  write_file_atomic(item / "garment.obj", "garmenT\n");
  auto s = batch::item_status(out, c.items[0]);
  EXPECT_EQ(s.state, batch::ItemState::partial);
  EXPECT_NE(s.problem.find("SHA-256"), std::string::npos) << s.problem;
  EXPECT_EQ(batch::item_status(out, c.items[0], /*checksums=*/false).state, batch::ItemState::passed)
      << "the same size: only the checksum sees it";
  fs::remove(item / "previews/front.png");
  s = batch::item_status(out, c.items[0], false);
  EXPECT_EQ(s.state, batch::ItemState::partial);
  EXPECT_NE(s.problem.find("missing"), std::string::npos) << s.problem;
  // ... and is redone.
  EXPECT_FALSE(run(c, out, "pass").skipped);
  EXPECT_EQ(batch::item_status(out, c.items[0]).state, batch::ItemState::passed);
}

TEST(BatchItem, EachWayAnItemEndsHasItsFailureClass) {
  const auto dir = scratch_dir("batch-classes");
  const auto c = catalogue(dir, {{"settings", {{"wall_limit", 1}}}});
  const fs::path out = dir / "out";
  struct Case {
    const char* mode;
    std::string cls, words;
  };
  for (const Case& k : {Case{"check-failed", "seams open", "left armhole 10/40"},
                        Case{"bad-input", "bad input", "no such size"},
                        Case{"crash", "crash", "signal 11"},
                        Case{"hang", "time-out", "wall limit"}}) {
    const auto r = run(c, out, k.mode, 0, /*retry=*/true);
    EXPECT_EQ(r.manifest.state, "failed") << k.mode;
    EXPECT_EQ(r.manifest.failure_class, k.cls) << k.mode;
    EXPECT_NE(r.manifest.failure_message.find(k.words), std::string::npos) << k.mode << ": " << r.manifest.failure_message;
    const auto s = batch::item_status(out, c.items[0]);
    EXPECT_EQ(s.state, batch::ItemState::failed) << k.mode;
    if (std::string(k.mode) == "hang") {
      EXPECT_LT(r.manifest.wall_s, 8.0) << "stopped at its 1 s limit";
    }
  }
  // The check that failed first names the class; its outputs are kept.
  const auto r = run(c, out, "check-failed", 1);
  EXPECT_EQ(r.manifest.failure_class, "seams open");
  EXPECT_EQ(batch::item_status(out, c.items[1]).manifest->files.size(), 6u);
  // A failed item is finished: skipped unless retried.
  EXPECT_TRUE(run(c, out, "pass", 1).skipped);
  EXPECT_EQ(run(c, out, "pass", 1, /*retry=*/true).manifest.state, "passed");
  EXPECT_EQ(batch::failure_class_of_check("penetration"), "body penetration");
  EXPECT_EQ(batch::failure_class_of_check("error"), "diverged");
}

TEST(BatchItem, AnUnfinishedFolderIsPartialAndRedone) {
  const auto dir = scratch_dir("batch-partial");
  const auto c = catalogue(dir);
  const fs::path out = dir / "out";
  const fs::path item = batch::item_dir(out, c.items[0].id);
  fs::create_directories(item.string() + ".partial");
  write_file_atomic(item.string() + ".partial/certificate.json", "{");
  EXPECT_EQ(batch::item_status(out, c.items[0]).state, batch::ItemState::partial);
  EXPECT_EQ(run(c, out, "pass").manifest.state, "passed");
  EXPECT_FALSE(fs::exists(item.string() + ".partial"));
  // A worker that died: recorded as a crash, with no outputs.
  batch::record_failure(out, c, c.items[1], "crash", "the worker was killed by signal 9");
  const auto s = batch::item_status(out, c.items[1]);
  EXPECT_EQ(s.state, batch::ItemState::failed);
  EXPECT_EQ(s.manifest->failure_class, "crash");
  EXPECT_TRUE(s.manifest->files.empty());
}

TEST(BatchReport, TheSummariesListEveryItemWithItsState) {
  const auto dir = scratch_dir("batch-report");
  const auto c = catalogue(dir, {{"sizes", {"36", "38", "40"}}});
  const fs::path out = dir / "out";
  run(c, out, "pass", 0);
  run(c, out, "check-failed", 1);
  const auto s = batch::status(c, out);
  EXPECT_EQ(s.passed, 1);
  EXPECT_EQ(s.failed, 1);
  EXPECT_EQ(s.pending, 1);
  EXPECT_EQ(s.failed_by_class.at("seams open"), std::vector<int>{1});
  EXPECT_EQ(s.unfinished(), std::vector<int>{2});
  batch::write_summary(c, out, s);
  const std::string csv = read_file(out / "summary.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4) << csv;
  EXPECT_NE(csv.find(",skirt,36,garment,mannequin,passed,,,40,40,0.20,0,0.0800,1.50,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",failed,seams open,left armhole 10/40 pairs closed,10,40,"), std::string::npos) << csv;
  const json j = json::parse(read_file(out / "summary.json"));
  EXPECT_EQ(j["counts"]["items"], 3);
  EXPECT_EQ(j["items"][2]["state"], "pending");
  const std::string html = read_file(out / "index.html");
  const auto count = [&](const std::string& what) {
    int n = 0;
    for (auto at = html.find(what); at != std::string::npos; at = html.find(what, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("<div class=\"card\""), 3);
  EXPECT_EQ(count("data-state=\"passed\""), 1);
  EXPECT_EQ(count("data-state=\"failed\""), 1);
  EXPECT_EQ(count("data-state=\"pending\""), 1);
  EXPECT_EQ(count("<img "), 2) << "the failed item's preview is shown too";
  EXPECT_NE(html.find("<b>seams open</b>"), std::string::npos);
}

TEST(BatchProcess, ADeadlineStopsTheCommandAndEverythingItStarted) {
  const auto dir = scratch_dir("batch-process");
  batch::ProcessOptions o;
  o.log = dir / "log.txt";
  o.deadline_s = 0.5;
  const auto t0 = std::chrono::steady_clock::now();
  // The shell starts a sleep of its own and writes its pid: both must go.
  const auto r = batch::run_process("/bin/sh", {"-c", "sleep 30 & echo $! > " + (dir / "pid").string() + "; wait"}, o);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_TRUE(r.timed_out);
  EXPECT_LT(wall, 6.0);
  EXPECT_NE(r.describe().find("wall limit"), std::string::npos) << r.describe();
  const int child = std::stoi(read_file(dir / "pid"));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  // Gone, or a zombie waiting for whoever adopted it.
  const auto alive = [](int pid) {
    if (::kill(pid, 0) != 0) return false;
    const std::string stat = read_file("/proc/" + std::to_string(pid) + "/stat");
    return stat.substr(stat.rfind(')') + 2, 1) != "Z";
  };
  EXPECT_FALSE(alive(child)) << "the sleep it started is gone too";

  o.deadline_s = 0;
  const auto e = batch::run_process("/bin/sh", {"-c", "echo said; exit 7"}, o);
  EXPECT_EQ(e.exit_code, 7);
  EXPECT_FALSE(e.ok());
  EXPECT_EQ(e.describe(), "exit 7");
  EXPECT_NE(read_file(dir / "log.txt").find("said\n"), std::string::npos);
  const auto k = batch::run_process("/bin/sh", {"-c", "kill -KILL $$"}, o);
  EXPECT_EQ(k.signal, SIGKILL);
  EXPECT_NE(k.describe().find("signal 9"), std::string::npos);
  o.env = {{"VGD_BATCH_TEST", "here"}};
  batch::run_process("/bin/sh", {"-c", "echo \"v=$VGD_BATCH_TEST\""}, o);
  EXPECT_NE(read_file(dir / "log.txt").find("v=here"), std::string::npos);
}

}  // namespace
}  // namespace vgd::test
