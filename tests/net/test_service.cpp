// The server's service without sockets: every route answered, bad requests
// refused with the field named, a real drape run as a job by a worker
// process, results served only from the job's manifest, cancel, tokens.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <thread>

#include "support/test_paths.hpp"
#include "vgd/core/file.hpp"
#include "vgd/io/trj/trj.hpp"
#include "vgd/net/service.hpp"

namespace vgd::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using net::Request;
using net::Response;

json body(const Response& r) { return json::parse(r.body, nullptr, false); }

json skirt_job(double time_limit = 3) {
  return {{"name", "skirt.xvc"},
          {"document", read_file(source_dir() / "data/garments/a-line-skirt.xvc")},
          {"settings",
           {{"size", "38"}, {"quality", "preview"}, {"spacing", 0.03}, {"time_limit", time_limit},
            {"outputs", {"certificate", "glb"}}}}};
}

net::ServiceOptions options(const fs::path& dir) {
  net::ServiceOptions o;
  o.data = dir;
  o.exe = VGD_EXE;
  o.workers = 1;
  return o;
}

// Polls GET /v1/jobs/ID until its state is one of the finished ones.
json wait_finished(net::Service& s, const std::string& id, double seconds = 120) {
  const auto t0 = std::chrono::steady_clock::now();
  for (;;) {
    const json j = body(s.handle({"GET", "/v1/jobs/" + id, ""}));
    const std::string st = j.value("state", "");
    if (st == "passed" || st == "failed" || st == "cancelled") return j;
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > seconds) return j;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
}

TEST(ServerService, BadRequestsAreRefusedNamingTheField) {
  net::Service s(options(scratch_dir("net-bad")));
  EXPECT_EQ(s.handle({"GET", "/v1/health", ""}).status, 200);
  EXPECT_EQ(body(s.handle({"GET", "/v1/health", ""}))["status"], "ok");
  EXPECT_EQ(s.handle({"GET", "/v2/health", ""}).status, 404);
  EXPECT_EQ(s.handle({"DELETE", "/v1/jobs", ""}).status, 405);
  EXPECT_EQ(s.handle({"GET", "/v1/jobs/0123456789abcdef", ""}).status, 404);
  EXPECT_EQ(s.handle({"GET", "/v1/jobs/../../etc/passwd", ""}).status, 404);
  struct Case {
    json request;
    int status;
    std::string words;
  };
  json no_doc = skirt_job();
  no_doc.erase("document");
  json bad_name = skirt_job();
  bad_name["name"] = "../../skirt.xvc";
  json not_xvc = skirt_job();
  not_xvc["document"] = "<html>hello</html>";
  json quality = skirt_job();
  quality["settings"]["quality"] = "best";
  json key = skirt_job();
  key["settings"]["colour"] = "red";
  json longer = skirt_job(100);
  json fabric = skirt_job();
  fabric["settings"]["fabric"] = "velvet";
  json extra = skirt_job();
  extra["priority"] = 1;
  for (const Case& k : {Case{no_doc, 400, "document: missing"}, Case{bad_name, 400, "name: '../../skirt.xvc'"},
                        Case{not_xvc, 400, "skirt.xvc"}, Case{quality, 400, "settings.quality: 'best' is not one of"},
                        Case{key, 400, "settings.colour: unknown"}, Case{longer, 400, "settings.time_limit"},
                        Case{fabric, 400, "settings.fabric: 'velvet'"}, Case{extra, 400, "unknown key 'priority'"}}) {
    const Response r = s.handle({"POST", "/v1/jobs", k.request.dump()});
    EXPECT_EQ(r.status, k.status) << r.body;
    EXPECT_NE(body(r)["error"].get<std::string>().find(k.words), std::string::npos) << r.body;
  }
  EXPECT_EQ(s.handle({"POST", "/v1/jobs", "{not json"}).status, 400);
  EXPECT_TRUE(body(s.handle({"GET", "/v1/jobs", ""})).empty()) << "nothing accepted";
  const std::string m = s.handle({"GET", "/v1/metrics", ""}).body;
  EXPECT_NE(m.find("vgd_http_responses_total{code=\"400\"} 9"), std::string::npos) << m;
}

TEST(ServerService, AJobDrapesInAWorkerAndServesOnlyItsResults) {
  const auto dir = scratch_dir("net-job");
  net::Service s(options(dir));
  const Response sub = s.handle({"POST", "/v1/jobs", skirt_job().dump()});
  ASSERT_EQ(sub.status, 202) << sub.body;
  const std::string id = body(sub)["id"];
  const json j = wait_finished(s, id);
  ASSERT_EQ(j["state"], "passed") << j.dump(2);
  EXPECT_EQ(j["certificate"]["seams_closed"], j["certificate"]["seam_pairs"]);
  EXPECT_EQ(j["attempts"], 1);
  std::vector<std::string> files;
  for (const auto& f : j["files"]) files.push_back(f["path"]);
  EXPECT_NE(std::find(files.begin(), files.end(), "garment.glb"), files.end());
  const Response cert = s.handle({"GET", "/v1/jobs/" + id + "/files/certificate.json", ""});
  ASSERT_EQ(cert.status, 200);
  EXPECT_EQ(cert.content_type, "application/json");
  EXPECT_TRUE(json::parse(read_file(cert.file))["passed"].get<bool>());
  EXPECT_EQ(s.handle({"GET", "/v1/jobs/" + id + "/files/../../../jobs.sqlite", ""}).status, 404);
  EXPECT_EQ(s.handle({"GET", "/v1/jobs/" + id + "/files/manifest.json", ""}).status, 404) << "not a listed result";
  EXPECT_EQ(s.handle({"POST", "/v1/jobs/" + id + "/cancel", ""}).status, 409);
  const std::string m = s.handle({"GET", "/v1/metrics", ""}).body;
  EXPECT_NE(m.find("vgd_jobs{state=\"passed\"} 1"), std::string::npos) << m;
  EXPECT_NE(m.find("vgd_jobs_submitted_total 1"), std::string::npos) << m;
}

TEST(ServerService, QueuedAndRunningJobsCanBeCancelled) {
  net::Service s(options(scratch_dir("net-cancel")));
  const std::string a = body(s.handle({"POST", "/v1/jobs", skirt_job(20).dump()}))["id"];
  const std::string b = body(s.handle({"POST", "/v1/jobs", skirt_job().dump()}))["id"];
  const Response qb = s.handle({"POST", "/v1/jobs/" + b + "/cancel", ""});
  EXPECT_EQ(qb.status, 200) << qb.body;
  EXPECT_EQ(body(s.handle({"GET", "/v1/jobs/" + b, ""}))["state"], "cancelled");
  for (int i = 0; i < 200 && body(s.handle({"GET", "/v1/jobs/" + a, ""}))["state"] != "running"; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const Response ra = s.handle({"POST", "/v1/jobs/" + a + "/cancel", ""});
  EXPECT_EQ(ra.status, 202) << ra.body;
  const json ja = wait_finished(s, a, 30);
  EXPECT_EQ(ja["state"], "cancelled") << ja.dump();
}

// A job on an uploaded body: the mannequin written as OBJ by vgd mannequin,
// sent base64 with the document, draped on as a body file.
TEST(ServerService, AJobDrapesOnAnUploadedBody) {
  const auto dir = scratch_dir("net-avatar");
  ASSERT_EQ(std::system((std::string(VGD_EXE) + " -q mannequin --size 38 -o '" + (dir / "body.obj").string() + "'").c_str()), 0);
  const std::string obj = read_file(dir / "body.obj");
  // base64 by coreutils, as a client would make it.
  ASSERT_EQ(std::system(("base64 -w 0 '" + (dir / "body.obj").string() + "' > '" + (dir / "body.b64").string() + "'").c_str()), 0);
  net::Service s(options(dir / "data"));
  json j = skirt_job();
  j["avatar"] = {{"name", "body.obj"}, {"data", read_file(dir / "body.b64")}, {"unit", "m"}, {"up", "y"}, {"facing", "+z"}};
  const Response sub = s.handle({"POST", "/v1/jobs", j.dump()});
  ASSERT_EQ(sub.status, 202) << sub.body;
  const std::string id = body(sub)["id"];
  EXPECT_EQ(read_file(dir / "data/jobs" / id / "input/body.obj"), obj) << "the bytes sent";
  const json done = wait_finished(s, id);
  EXPECT_EQ(done["state"], "passed") << done.dump(2);
  // Draped on that body, not a mannequin.
  bool on_it = false;
  for (const auto& e : fs::recursive_directory_iterator(dir / "data/jobs" / id / "out/items"))
    if (e.path().filename() == "log.txt") on_it = read_file(e.path()).find("body.obj (as asked), not a mannequin") != std::string::npos;
  EXPECT_TRUE(on_it);
  json bad = skirt_job();
  bad["avatar"] = {{"name", "body.obj"}, {"data", "not base64!"}};
  EXPECT_EQ(body(s.handle({"POST", "/v1/jobs", bad.dump()}))["error"], "avatar.data: not base64");
  bad["avatar"] = {{"name", "../body.obj"}, {"data", "AAAA"}};
  EXPECT_EQ(s.handle({"POST", "/v1/jobs", bad.dump()}).status, 400);
  bad["avatar"] = {{"name", "body.exe"}, {"data", "AAAA"}};
  EXPECT_EQ(s.handle({"POST", "/v1/jobs", bad.dump()}).status, 400);
}

TEST(ServerService, OneClientCannotFillTheQueue) {
  auto o = options(scratch_dir("net-per-client"));
  o.max_per_client = 2;
  net::Service s(o);
  const json j = skirt_job(20);
  EXPECT_EQ(s.handle({"POST", "/v1/jobs", j.dump(), "", "10.0.0.1"}).status, 202);
  EXPECT_EQ(s.handle({"POST", "/v1/jobs", j.dump(), "", "10.0.0.1"}).status, 202);
  const Response third = s.handle({"POST", "/v1/jobs", j.dump(), "", "10.0.0.1"});
  EXPECT_EQ(third.status, 429);
  EXPECT_NE(body(third)["error"].get<std::string>().find("2 jobs queued or running"), std::string::npos) << third.body;
  EXPECT_EQ(s.handle({"POST", "/v1/jobs", j.dump(), "", "10.0.0.2"}).status, 202) << "another client is not held up";
  for (const auto& job : body(s.handle({"GET", "/v1/jobs", ""})))
    s.handle({"POST", "/v1/jobs/" + job["id"].get<std::string>() + "/cancel", ""});
}

TEST(ServerService, ATokenGuardsEveryRouteButHealth) {
  auto o = options(scratch_dir("net-token"));
  o.token = "0123456789abcdef-secret";
  net::Service s(o);
  EXPECT_EQ(s.handle({"GET", "/v1/health", ""}).status, 200);
  const Response none = s.handle({"GET", "/v1/jobs", ""});
  EXPECT_EQ(none.status, 401);
  EXPECT_EQ(none.body.find("secret"), std::string::npos) << "never echoed";
  EXPECT_EQ(s.handle({"GET", "/v1/jobs", "", "Bearer 0123456789abcdef-secreT"}).status, 403);
  EXPECT_EQ(s.handle({"GET", "/v1/jobs", "", "Bearer 0123456789abcdef"}).status, 403);
  EXPECT_EQ(s.handle({"GET", "/v1/jobs", "", "Bearer 0123456789abcdef-secret"}).status, 200);
}

// Scene jobs: a self-contained scene run by the worker's `vgd simulate`;
// the trajectory is its one result, checked against the same scene run here.
json sphere_scene() { return json::parse(read_file(source_dir() / "data/scenes/cloth-on-sphere.json")); }

TEST(ServerService, ASceneJobRunsAsVgdSimulateRunsIt) {
  const auto dir = scratch_dir("net-scene");
  net::Service s(options(dir));
  const Response sub = s.handle({"POST", "/v1/jobs", json{{"name", "sphere.json"}, {"scene", sphere_scene()}}.dump()});
  ASSERT_EQ(sub.status, 202) << sub.body;
  const std::string id = body(sub)["id"];
  const json j = wait_finished(s, id, 60);
  ASSERT_EQ(j["state"], "passed") << j.dump(2) << read_file(dir / "jobs" / id / "worker.log");
  EXPECT_EQ(j["kind"], "scene");
  EXPECT_EQ(j["name"], "sphere.json");
  ASSERT_EQ(j["files"].size(), 1u) << j.dump(2);
  EXPECT_EQ(j["files"][0]["path"], "scene.trj");
  const Response trj = s.handle({"GET", "/v1/jobs/" + id + "/files/scene.trj", ""});
  ASSERT_EQ(trj.status, 200);
  const std::string served = read_file(trj.file);
  EXPECT_EQ(served.size(), j["files"][0]["bytes"].get<std::size_t>());
  EXPECT_EQ(s.handle({"GET", "/v1/jobs/" + id + "/files/scene.json", ""}).status, 404) << "only its trajectory";
  EXPECT_EQ(s.handle({"GET", "/v1/jobs/" + id + "/files/../input/scene.json", ""}).status, 404);
  // The same scene by vgd simulate here: the same frames.
  const fs::path here = dir / "here.trj";
  const std::string cmd = std::string(VGD_EXE) + " simulate " + (source_dir() / "data/scenes/cloth-on-sphere.json").string() +
                          " --trj " + here.string() + " > /dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const auto a = io::trj::TrjReader::from_bytes(served, "served");
  const auto b = io::trj::TrjReader::from_bytes(read_file(here), "here");
  ASSERT_EQ(a.frame_count(), b.frame_count());
  EXPECT_EQ(a.frame_count(), 13) << "0.5 s at 25 fps";
  EXPECT_EQ(a.positions(a.frame_count() - 1), b.positions(b.frame_count() - 1));
}

TEST(ServerService, SceneJobsThatNameFilesOrExceedTheLimitsAreRefused) {
  auto o = options(scratch_dir("net-scene-bad"));
  o.max_particles = 1000;
  o.max_simulated_s = 10;
  net::Service s(o);
  struct Case {
    json scene;
    std::string words;
  };
  json xvc = sphere_scene();
  xvc["materials"]["shirting"] = {{"xvc", "../../../etc/passwd"}, {"id", "x"}};
  json body_file = sphere_scene();
  body_file["avatar"] = {{"file", "/etc/hostname"}};
  json out = sphere_scene();
  out["output"] = json::array({{{"type", "obj"}, {"folder", "/tmp/x"}}});
  json big = sphere_scene();
  big["cloth"][0]["grid"]["particles"] = {40, 40};
  json slow = sphere_scene();
  slow["frames"]["duration"] = "30 s";
  json broken = sphere_scene();
  broken["integrator"]["method"] = "leapfrog";
  for (const Case& k : {Case{xvc, "scene.materials.shirting.xvc: a scene job cannot name files"},
                        Case{body_file, "scene.avatar.file: a scene job cannot name files"},
                        Case{out, "scene.output: a scene job cannot name files"},
                        Case{big, "1600 particles, more than the server's 1000"},
                        Case{slow, "30.00 s, more than the server's 10 simulated seconds"},
                        Case{broken, "leapfrog"}}) {
    const Response r = s.handle({"POST", "/v1/jobs", json{{"scene", k.scene}}.dump()});
    EXPECT_EQ(r.status, 400) << k.words;
    EXPECT_NE(r.body.find(k.words), std::string::npos) << r.body;
  }
  EXPECT_EQ(s.handle({"POST", "/v1/jobs", json{{"scene", "not an object"}}.dump()}).status, 400);
  EXPECT_EQ(s.handle({"POST", "/v1/jobs", json{{"scene", sphere_scene()}, {"name", "../x.json"}}.dump()}).status, 400);
  EXPECT_EQ(s.handle({"POST", "/v1/jobs", json{{"scene", sphere_scene()}, {"settings", json::object()}}.dump()}).status, 400);
  EXPECT_EQ(body(s.handle({"GET", "/v1/health", ""}))["jobs"]["queued"], 0) << "nothing refused was queued";
}

}  // namespace
}  // namespace vgd::test
