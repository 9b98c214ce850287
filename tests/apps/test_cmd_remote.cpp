// vgd remote against a vgd-server started by the test on a free loopback
// port: submit and watch a drape to its end, list, status, get its files
// (checked against the job's SHA-256), cancel; a server with a token refuses
// a client without it.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <thread>

#include "support/json_file.hpp"
#include "support/run_vgd.hpp"
#include "support/server_process.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"

namespace vgd::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A scene file is a scene job: run by the server's vgd simulate, followed to
// its end with the simulated time of its frames, its trajectory downloaded;
// one that names files on the server is refused with the field.
TEST(CliRemote, ASceneFileIsASceneJob) {
  const auto dir = scratch_dir("cli-remote-scene");
  ServerProcess server(dir);
  ASSERT_GT(server.port, 0);
  const auto sub = run_vgd({"remote", "--server", server.url(), "submit",
                            (source_dir() / "data/scenes/cloth-on-sphere.json").string(), "--watch"});
  EXPECT_EQ(sub.code, 0) << sub.err;
  const std::string id(trim(sub.out));
  ASSERT_EQ(id.size(), 16u) << sub.out;
  EXPECT_NE(sub.err.find("t 0.48 s"), std::string::npos) << "the last frame's time: " << sub.err;
  EXPECT_EQ(sub.err.find("seams"), std::string::npos) << "a scene has no seams: " << sub.err;
  EXPECT_NE(sub.err.find("job " + id + ": passed"), std::string::npos) << sub.err;
  const auto get = run_vgd({"remote", "--server", server.url(), "get", id, "-o", (dir / "got").string()});
  EXPECT_EQ(get.code, 0) << get.err;
  EXPECT_TRUE(fs::is_regular_file(dir / "got" / "scene.trj"));
  const auto refused = run_vgd({"remote", "--server", server.url(), "submit",
                                (source_dir() / "data/scenes/drape-sphere.json").string()});
  EXPECT_EQ(refused.code, 1);
  EXPECT_NE(refused.err.find("scene.materials.shirting.xvc: a scene job cannot name files"), std::string::npos)
      << refused.err;
}

TEST(CliRemote, ADrapeSubmittedWatchedListedAndDownloaded) {
  const auto dir = scratch_dir("cli-remote");
  ServerProcess server(dir);
  ASSERT_GT(server.port, 0);
  const std::string doc = (source_dir() / "data/garments/a-line-skirt.xvc").string();
  const auto sub = run_vgd({"remote", "--server", server.url(), "submit", doc, "--size", "38", "--quality", "preview",
                            "--spacing", "0.03", "--time-limit", "3", "--outputs", "certificate", "trj", "glb",
                            "--watch"});
  EXPECT_EQ(sub.code, 0) << sub.err;
  const std::string id(trim(sub.out));
  ASSERT_EQ(id.size(), 16u) << sub.out;
  EXPECT_NE(sub.err.find("job " + id + ": passed"), std::string::npos) << sub.err;
  EXPECT_NE(sub.err.find("seams"), std::string::npos) << "the progress line: " << sub.err;
  EXPECT_NE(sub.err.find("frames "), std::string::npos) << sub.err;

  const auto list = run_vgd({"remote", "--server", server.url(), "list"});
  EXPECT_EQ(list.code, 0);
  EXPECT_NE(list.out.find(id + "  passed"), std::string::npos) << list.out;
  const auto status = run_vgd({"remote", "--server", server.url(), "status", id, "--json"});
  const json st = json::parse(status.out);
  EXPECT_EQ(st["state"], "passed");
  const auto get = run_vgd({"remote", "--server", server.url(), "get", id, "-o", (dir / "got").string()});
  EXPECT_EQ(get.code, 0) << get.err;
  for (const auto& f : st["files"]) EXPECT_TRUE(fs::is_regular_file(dir / "got" / f["path"].get<std::string>())) << f;
  EXPECT_TRUE(read_json(dir / "got/certificate.json")["passed"].get<bool>());
  const auto again = run_vgd({"remote", "--server", server.url(), "watch", id});
  EXPECT_EQ(again.code, 0) << "a finished job's stream: its last frame and its end";
  const auto cancel = run_vgd({"remote", "--server", server.url(), "cancel", id});
  EXPECT_EQ(cancel.code, 1);
  EXPECT_NE(cancel.err.find("409"), std::string::npos) << cancel.err;
  const auto nobody = run_vgd({"remote", "--server", "http://127.0.0.1:1", "list"});
  EXPECT_EQ(nobody.code, 1);
  EXPECT_NE(nobody.err.find("cannot reach the server"), std::string::npos) << nobody.err;
}

TEST(CliRemote, AJobOnABodyFileOfTheClients) {
  const auto dir = scratch_dir("cli-remote-avatar");
  ServerProcess server(dir);
  ASSERT_GT(server.port, 0);
  ASSERT_EQ(run_vgd({"mannequin", "--size", "40", "-o", (dir / "body.glb").string(), "-q"}).code, 0);
  const auto sub = run_vgd({"remote", "--server", server.url(), "submit",
                            (source_dir() / "data/garments/a-line-skirt.xvc").string(), "--size", "40", "--quality",
                            "preview", "--spacing", "0.03", "--time-limit", "3", "--outputs", "certificate",
                            "--avatar", (dir / "body.glb").string(), "--watch"});
  EXPECT_EQ(sub.code, 0) << sub.err;
  const std::string id(trim(sub.out));
  const auto body = read_file(dir / "data/jobs" / id / "input/body.glb");
  EXPECT_EQ(body, read_file(dir / "body.glb")) << "the file arrives as it was";
}

TEST(CliRemote, AServerWithATokenRefusesAClientWithout) {
  const auto dir = scratch_dir("cli-remote-token");
  write_file_atomic(dir / "token", "a-token-of-more-than-16-characters\n");
  ServerProcess server(dir, {"--token-file", (dir / "token").string()});
  ASSERT_GT(server.port, 0);
  const auto without = run_vgd({"remote", "--server", server.url(), "list"});
  EXPECT_EQ(without.code, 1);
  EXPECT_NE(without.err.find("401"), std::string::npos) << without.err;
  const auto with = run_vgd({"remote", "--server", server.url(), "--token-file", (dir / "token").string(), "list"});
  EXPECT_EQ(with.code, 0) << with.err;
}

}  // namespace
}  // namespace vgd::test
