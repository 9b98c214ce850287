// docs/api/openapi.yaml is a valid OpenAPI 3 description (checked by
// swagger-parser under node, tests/web/check_openapi.mjs) and the server
// answers every documented operation with a status the description lists:
// each route called on a service with a finished job, and with a job that
// does not exist. The WebSocket route is exercised by ServerFrames.* (the
// service answers it only through the HTTP layer). Skipped with a message
// when node or tests/web/node_modules is absent (.ci/install-deps installs them).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <thread>

#include "support/command.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/file.hpp"
#include "vgd/net/service.hpp"

namespace vgd::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kWeb = VGD_WEB_TESTS_DIR;

json check(const fs::path& spec) {
  return json::parse(command_output("cd '" + kWeb.string() + "' && node check_openapi.mjs '" + spec.string() + "'"), nullptr,
                     false);
}

TEST(OpenApi, TheDescriptionIsValidAndEveryOperationAnswersAsDocumented) {
  if (std::system("node --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "SKIPPED: node not found";
  if (!fs::is_regular_file(kWeb / "node_modules/@apidevtools/swagger-parser/package.json"))
    GTEST_SKIP() << "SKIPPED: @apidevtools/swagger-parser not in " << kWeb / "node_modules"
                 << " (run .ci/install-deps)";
  const fs::path spec = source_dir() / "docs/api/openapi.yaml";
  const json api = check(spec);
  ASSERT_TRUE(api.is_object());
  ASSERT_TRUE(api["valid"].get<bool>()) << api.dump();
  // The validator refuses a broken description (a $ref to nothing).
  const auto dir = scratch_dir("net-openapi");
  std::string broken = read_file(spec);
  broken.replace(broken.find("#/components/schemas/Health"), 27, "#/components/schemas/Nothing");
  write_file_atomic(dir / "broken.yaml", broken);
  EXPECT_FALSE(check(dir / "broken.yaml")["valid"].get<bool>());

  net::ServiceOptions o;
  o.data = dir / "data";
  o.exe = VGD_EXE;
  net::Service s(o);
  const json job = {{"name", "skirt.xvc"},
                    {"document", read_file(source_dir() / "data/garments/a-line-skirt.xvc")},
                    {"settings", {{"quality", "preview"}, {"spacing", 0.03}, {"time_limit", 2}, {"outputs", {"certificate"}}}}};
  const std::string id = json::parse(s.handle({"POST", "/v1/jobs", job.dump()}).body)["id"];
  for (int i = 0; i < 1200; ++i) {
    const std::string st = json::parse(s.handle({"GET", "/v1/jobs/" + id, ""}).body)["state"];
    if (st == "passed" || st == "failed") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  int exercised = 0;
  for (const auto& op : api["operations"]) {
    if (op["websocket"].get<bool>()) continue;
    const std::string method = op["method"];
    std::vector<std::string> documented = op["responses"];
    const auto expect_documented = [&](const std::string& target, const std::string& body) {
      const int status = s.handle({method, target, body}).status;
      EXPECT_NE(std::find(documented.begin(), documented.end(), std::to_string(status)), documented.end())
          << method << " " << target << " answered " << status;
    };
    const auto fill = [&](std::string path, const std::string& job_id) {
      for (const auto& [name, value] : std::vector<std::pair<std::string, std::string>>{
               {"{id}", job_id}, {"{path}", "certificate.json"}})
        if (const auto at = path.find(name); at != std::string::npos) path.replace(at, name.size(), value);
      return path;
    };
    const std::string path = op["path"];
    const std::string body = method == "POST" && path == "/v1/jobs" ? job.dump() : "";
    expect_documented(fill(path, id), body);
    if (path.find("{id}") != std::string::npos) expect_documented(fill(path, "0123456789abcdef"), body);
    if (method == "POST" && path == "/v1/jobs") expect_documented(path, "{\"document\": 1}");
    ++exercised;
  }
  EXPECT_EQ(exercised, 7) << "health, metrics, list, submit, job, cancel, files";
}

}  // namespace
}  // namespace vgd::test
