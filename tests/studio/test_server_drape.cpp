// "Simulate on server": the studio sends its document to a vgd-server started
// by the test, shows the job's frames in its 3-D view while the server
// drapes, shows the job's certificate at the end, and cancels the job when
// the user presses Stop.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "support/server_process.hpp"
#include "vgd/net/client.hpp"
#include "vgd/studio/harness.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using vgd::studio::Harness;

namespace {

const fs::path kSkirt = fs::path(VGD_SOURCE_DIR) / "data/garments/a-line-skirt.xvc";

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("vgd-test-studio-server-" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// Pixels of the preview in the skirt's blue (render::kFabric family).
int blue_pixels(const vgd::render::Image& img, const vgd::studio::Rect& r) {
  int blue = 0;
  for (int y = static_cast<int>(r.y0); y < static_cast<int>(r.y1); ++y)
    for (int x = static_cast<int>(r.x0); x < static_cast<int>(r.x1); ++x) {
      const auto* p = img.pixel(x, y);
      blue += p[2] > p[0] + 40 && p[2] > p[1] + 20;
    }
  return blue;
}

json job_on(const vgd::test::ServerProcess& server, const std::string& id) {
  const vgd::net::Client c(vgd::net::parse_server_url(server.url()));
  return json::parse(c.get("/v1/jobs/" + id));
}

// The skirt at a coarse mesh (rests in about 2 s), preview quality, the
// server's address typed into the simulate panel.
void set_up(Harness& h, const std::string& url, double time_limit) {
  ASSERT_TRUE(h.studio().open(kSkirt));
  h.frame();
  h.studio().drape_options().time_limit = time_limit;
  h.studio().drape_options().spacing = 0.02;
  h.click("quality");
  h.click("quality:preview");
  h.click("server");
  h.type(url);
  h.frames(2);
  ASSERT_EQ(h.studio().server(), url);
}

}  // namespace

TEST(StudioServer, SimulateOnServerShowsTheJobsFramesLiveAndItsCertificate) {
  const auto dir = temp_dir("live");
  vgd::test::ServerProcess server(dir, {"--workers", "1"});
  ASSERT_NE(server.port, 0) << vgd::read_file(server.log);
  Harness h(1024, 700);
  set_up(h, server.url(), 4.0);
  h.click("Simulate on server");
  ASSERT_TRUE(h.studio().drape_status().running) << h.studio().status();
  EXPECT_NE(h.studio().status().find("on " + server.url()), std::string::npos) << h.studio().status();
  // While the server drapes, its frames reach the 3-D view: the skirt is
  // drawn before the job ends.
  int live_blue = 0;
  double live_t = 0;
  std::map<std::string, int> stages;
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (h.studio().drape_status().running && std::chrono::steady_clock::now() < until) {
    h.frames(2);
    const auto s = h.studio().drape_status();
    if (!s.running) break;
    ++stages[s.stage];
    if (const auto r = h.studio().widget("preview")) {
      const int b = blue_pixels(h.screenshot(), *r);
      if (b > live_blue) live_blue = b, live_t = s.t;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
  }
  h.studio().wait_for_drape();
  h.frames(4);
  EXPECT_GT(live_blue, 500) << "the skirt was drawn from a live frame (at " << live_t << " s simulated)";
  EXPECT_GT(stages["sewing"] + stages["settling"], 0) << "the server's stages reached the progress bar";
  const auto s = h.studio().drape_status();
  EXPECT_EQ(s.stage, "done") << s.message;
  const std::string id = h.studio().server_job();
  ASSERT_EQ(id.size(), 16u) << h.studio().status();
  EXPECT_NE(h.studio().status().find("on the server (job " + id + ")"), std::string::npos) << h.studio().status();
  // The certificate is the job's, read from the server.
  ASSERT_TRUE(h.studio().certificate());
  const auto& c = *h.studio().certificate();
  const auto totals = c.seam_totals();
  EXPECT_GT(totals.pairs, 0);
  EXPECT_EQ(totals.closed, totals.pairs);
  EXPECT_LT(c.max_penetration, 0.001);
  const json j = job_on(server, id);
  EXPECT_EQ(j["state"], "passed") << j.dump();
  EXPECT_EQ(j["certificate"]["simulated_s"].get<double>(), c.simulated_s) << j["certificate"].dump();
  // The final picture: the skirt on the body.
  const auto r = h.studio().widget("preview");
  ASSERT_TRUE(r);
  EXPECT_GT(blue_pixels(h.screenshot(), *r), 500);
}

TEST(StudioServer, StopCancelsTheJobOnTheServer) {
  const auto dir = temp_dir("stop");
  vgd::test::ServerProcess server(dir, {"--workers", "1"});
  ASSERT_NE(server.port, 0) << vgd::read_file(server.log);
  Harness h(1024, 700);
  set_up(h, server.url(), 60.0);
  h.click("Simulate on server");
  // Stop once the server is draping (the first frame has come).
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (h.studio().drape_status().running && h.studio().drape_status().t <= 0 &&
         std::chrono::steady_clock::now() < until) {
    h.frame();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_TRUE(h.studio().drape_status().running) << h.studio().drape_status().message;
  const std::string id = h.studio().server_job();
  ASSERT_FALSE(id.empty());
  h.click("Stop");
  h.studio().wait_for_drape();
  h.frames(2);
  EXPECT_EQ(h.studio().drape_status().stage, "stopped") << h.studio().drape_status().message;
  EXPECT_NE(h.studio().status().find("job " + id + " was cancelled on the server"), std::string::npos)
      << h.studio().status();
  EXPECT_EQ(job_on(server, id)["state"], "cancelled");
}

TEST(StudioServer, AServerThatCannotBeReachedOrRefusesSaysSo) {
  Harness h(1024, 700);
  // Nothing listens on port 9 of loopback.
  set_up(h, "http://127.0.0.1:9", 4.0);
  h.click("Simulate on server");
  h.studio().wait_for_drape();
  h.frames(2);
  EXPECT_EQ(h.studio().drape_status().stage, "failed");
  EXPECT_NE(h.studio().status().find("cannot reach the server"), std::string::npos) << h.studio().status();
  EXPECT_TRUE(h.studio().status_is_error());
  h.key("escape");  // the error's dialog
  h.frames(2);
  // A server that refuses the settings: its message, naming the field.
  const auto dir = temp_dir("refused");
  vgd::test::ServerProcess server(dir, {"--workers", "1"});
  ASSERT_NE(server.port, 0);
  h.click("server");
  h.key("ctrl+a");
  h.type(server.url());
  h.frames(2);
  ASSERT_EQ(h.studio().server(), server.url());
  h.studio().drape_options().time_limit = 100;  // more than the server's 60 s
  h.click("Simulate on server");
  h.studio().wait_for_drape();
  h.frames(2);
  EXPECT_EQ(h.studio().drape_status().stage, "failed");
  EXPECT_NE(h.studio().status().find("settings.time_limit"), std::string::npos) << h.studio().status();
  EXPECT_NE(h.studio().status().find("HTTP 400"), std::string::npos) << h.studio().status();
}
