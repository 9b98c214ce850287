// vgd-server's browser page in headless Chromium (tests/web/server_page.mjs):
// opened on a job as it is submitted, it lists the job, draws the drape
// with three.js from the job's WebSocket until the stream ends, and the
// garment covers a visible share of the view. three.js comes from the server,
// not from a CDN. Skipped with a message when node, playwright-core, three or
// chromium are absent (.ci/install-deps installs them).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <thread>

#include "support/command.hpp"
#include "support/server_process.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"

namespace vgd::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kWeb = VGD_WEB_TESTS_DIR;

TEST(ServerPage, ABrowserDrawsAJobsDrapeLiveWithThreeJs) {
  if (std::system("node --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "SKIPPED: node not found";
  for (const char* m : {"playwright-core", "three"})
    if (!fs::is_regular_file(kWeb / "node_modules" / m / "package.json"))
      GTEST_SKIP() << "SKIPPED: " << m << " not in " << kWeb / "node_modules" << " (run .ci/install-deps)";
  if (!fs::is_regular_file("/usr/bin/chromium")) GTEST_SKIP() << "SKIPPED: /usr/bin/chromium not installed";
  const auto dir = scratch_dir("net-page");
  ServerProcess server(dir);
  const int port = server.port;
  ASSERT_GT(port, 0);
  const std::string base = "http://127.0.0.1:" + std::to_string(port);
  // A job of several seconds (the skirt at 2 cm, standard: about 1.7 s
  // simulated): the browser starts after the job does, and at 3 cm and the
  // preview preset the drape (2.5 s wall) had ended on an idle machine before
  // the page joined, which then drew its last frame only.
  const json job = {{"name", "skirt.xvc"},
                    {"document", read_file(source_dir() / "data/garments/a-line-skirt.xvc")},
                    {"settings", {{"size", "38"}, {"quality", "standard"}, {"spacing", 0.02}, {"time_limit", 3},
                                  {"outputs", {"certificate", "trj"}}}}};
  write_file_atomic(dir / "job.json", job.dump());
  const json sub = json::parse(command_output("curl -s -X POST --data-binary @'" + (dir / "job.json").string() + "' " + base +
                                   "/v1/jobs"),
                               nullptr, false);
  ASSERT_TRUE(sub.is_object() && sub.contains("id")) << sub.dump();
  const std::string id = sub["id"];
  const std::string text = command_output("cd '" + kWeb.string() + "' && node server_page.mjs " + base + " " + id + " '" +
                               (dir / "page.png").string() + "'");
  server.stop();
  const json r = json::parse(text, nullptr, false);
  ASSERT_TRUE(r.is_object()) << text;
  EXPECT_TRUE(r["page_errors"].empty()) << r["page_errors"].dump();
  ASSERT_TRUE(r.contains("viewer")) << text;
  EXPECT_EQ(r["viewer"]["state"], "end");
  EXPECT_EQ(r["viewer"]["endState"], "passed");
  EXPECT_GT(r["viewer"]["frames"].get<int>(), 5);
  EXPECT_GT(r["viewer"]["particles"].get<int>(), 500);
  EXPECT_GE(r["listed"].get<int>(), 1);
  EXPECT_GT(r["pixels"]["garment_fraction"].get<double>(), 0.02) << "the garment is drawn: " << r["pixels"].dump();
  EXPECT_TRUE(fs::is_regular_file(dir / "page.png"));
}

}  // namespace
}  // namespace vgd::test
