// vgd remote: drapes on a vgd-server (docs/server.md).
//
//   vgd remote submit skirt.xvc --size 38 --server http://127.0.0.1:8765 [--watch]
//   vgd remote list | status ID | watch ID | get ID -o DIR | cancel ID
//
// The token comes from --token-file or $VGD_TOKEN.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "cli.hpp"
#include "vgd/batch/catalogue.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/net/client.hpp"

namespace cmd_remote {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct Options {
  std::string server = "http://127.0.0.1:8765", token_file, id, document, output = ".";
  std::string size, quality, fabric, body_size, body_table, model, avatar, unit = "auto", up = "auto", facing = "auto";
  double time_limit = 0, spacing = 0;
  std::vector<std::string> outputs, files;
  bool watch = false, json = false;
};

vgd::net::Client client(const Options& o) {
  std::string token;
  if (!o.token_file.empty()) token = std::string(vgd::trim(vgd::read_file(o.token_file)));
  else if (const char* t = std::getenv("VGD_TOKEN")) token = t;
  return vgd::net::Client(vgd::net::parse_server_url(o.server), token);
}

// The reply as JSON, or vgd::Error with the server's message.
json answer(const vgd::net::Reply& r, const std::string& what) {
  const json j = json::parse(r.body, nullptr, false);
  if (r.status >= 400) {
    const std::string msg = j.is_object() && j.contains("error") ? j["error"].get<std::string>() : r.body;
    throw vgd::Error(what, "", "the server answered " + std::to_string(r.status) + ": " + msg);
  }
  if (j.is_discarded()) throw vgd::Error(what, "", "the server's answer is not JSON");
  return j;
}

// Follows a job's stream with a progress line per stage; returns its end message.
json watch(const vgd::net::Client& c, const std::string& id, const vgd::cli::Common& common) {
  const bool tty = isatty(2) == 1;
  long long frames = 0;
  double frame_t = 0;  // s: the last frame's simulated time
  json end, progress;
  std::string stage;
  auto draw = [&](bool final) {
    if (common.quiet) return;
    std::string line = "job " + id + ": ";
    if (progress.is_object()) {
      // What the job reports: a drape all of it, a scene its stage only (its
      // frames carry the simulated time).
      line += progress.value("stage", "") + "  t " +
              vgd::format_fixed(progress.value("simulated_s", frame_t), 2) + " s";
      if (progress.contains("seam_pairs"))
        line += "  seams " + std::to_string(progress.value("seams_closed", 0)) + "/" +
                std::to_string(progress.value("seam_pairs", 0));
      if (progress.contains("kinetic_energy_j"))
        line += "  KE " + vgd::format_significant(progress.value("kinetic_energy_j", 0.0), 3) + " J/particle";
      if (progress.contains("wall_s")) line += "  wall " + vgd::format_fixed(progress.value("wall_s", 0.0), 1) + " s";
    } else if (frames > 0) {
      line += "t " + vgd::format_fixed(frame_t, 2) + " s";
    } else {
      line += "waiting for the first frame";
    }
    line += "  frames " + std::to_string(frames);
    const std::string now = progress.is_object() ? progress.value("stage", "") : "";
    if (tty) std::fprintf(stderr, "\r%s\033[K%s", line.c_str(), final ? "\n" : "");
    else if (final || now != stage) std::fprintf(stderr, "%s\n", line.c_str());
    stage = now;
    std::fflush(stderr);
  };
  c.watch(
      id,
      [&](const std::string& text) {
        const json j = json::parse(text, nullptr, false);
        if (!j.is_object()) return;
        if (j["type"] == "progress" && j["progress"].is_object()) progress = j["progress"];
        if (j["type"] == "end") end = j;
        if (j["type"] == "dropped" && !common.quiet)
          std::fprintf(stderr, "%svgd: %lld frames skipped (this viewer read slower than they came; the stored "
                               "trajectory has them)\n",
                       tty ? "\n" : "", j.value("total", 0LL));
        draw(false);
      },
      [&](const vgd::net::FrameMessage& f) {
        if (!f.checksum_ok) throw vgd::Error("job " + id, "frame " + std::to_string(f.seq), "checksum mismatch");
        ++frames;
        frame_t = f.t;
        draw(false);
      });
  draw(true);
  return end;
}

int finished_code(const std::string& state) {
  return state == "passed" ? vgd::cli::kOk : state == "failed" || state == "cancelled" ? vgd::cli::kCheckFailed
                                                                                      : vgd::cli::kFailed;
}

vgd::cli::Registrar reg{"remote", 95, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("remote", "Drapes on a vgd-server: submit, watch, list, status, get, cancel "
                                           "(docs/server.md)");
  sub->require_subcommand(1);
  auto o = std::make_shared<Options>();
  sub->add_option("--server", o->server, "The server (http://HOST:PORT)")->capture_default_str();
  sub->add_option("--token-file", o->token_file, "File holding the server's token (default: $VGD_TOKEN)")
      ->check(CLI::ExistingFile);
  auto* submit = sub->add_subcommand("submit", "Submit an XVC document (a drape) or a scene file (run as vgd "
                                               "simulate runs it); prints the job's id");
  submit->add_option("DOCUMENT", o->document,
                     "XVC document (vgd dress writes one: DIR/garment.xvc), or a self-contained scene .json "
                     "(materials inline, cloth as grids; docs/server.md)")
      ->required()
      ->check(CLI::ExistingFile);
  submit->add_option("--size", o->size, "The garment's size (default: the sample size)");
  submit->add_option("--quality", o->quality, "preview, standard or precise");
  submit->add_option("--time-limit", o->time_limit, "Simulated seconds at most (the server allows 60)");
  submit->add_option("--spacing", o->spacing, "Mesh spacing, m");
  submit->add_option("--model", o->model, "mass-spring or strain-rosette");
  submit->add_option("--fabric", o->fabric, "garment or a shipped material (denim, ...)");
  submit->add_option("--body-size", o->body_size, "The mannequin's size when it is not the garment's");
  submit->add_option("--body-table", o->body_table, "Its size table");
  submit->add_option("--outputs", o->outputs, "certificate, trj, wvt, vrml, vrml-animated, glb, previews");
  submit->add_option("--avatar", o->avatar, "A body file to drape on (OBJ, PLY, STL, glTF/GLB, FBX, Collada), sent "
                                            "with the job")
      ->check(CLI::ExistingFile);
  submit->add_option("--unit", o->unit, "--avatar's unit: auto, m, dm, cm, mm, in")->capture_default_str();
  submit->add_option("--up", o->up, "--avatar's up axis: auto, x, y, z, -x, -y, -z")->capture_default_str();
  submit->add_option("--facing", o->facing, "Where --avatar faces once up is +Y: auto, +z, -z, +x, -x")
      ->capture_default_str();
  submit->add_flag("--watch", o->watch, "Then follow it to its end (as vgd remote watch)");
  auto* list = sub->add_subcommand("list", "The server's jobs, newest first");
  auto* status = sub->add_subcommand("status", "One job: state, progress, certificate, files");
  auto* watch_cmd = sub->add_subcommand("watch", "Follow a job's frames and progress to its end");
  auto* get = sub->add_subcommand("get", "Download a finished job's files");
  auto* cancel = sub->add_subcommand("cancel", "Cancel a queued or running job");
  for (auto* c : {status, watch_cmd, get, cancel}) c->add_option("ID", o->id, "The job's id")->required();
  get->add_option("-o,--output", o->output, "Folder to write into")->capture_default_str();
  get->add_option("--files", o->files, "Only these (paths as the job lists them)");
  for (auto* c : {list, status}) c->add_flag("--json", o->json, "Print the server's JSON");
  sub->footer("Exit codes: 0 done (a watched job passed), 1 the server refused or cannot be reached, 3 a watched "
              "job failed or was cancelled.");
  return vgd::cli::Command{sub, [=, &common]() -> int {
    const auto c = client(*o);
    if (submit->parsed()) {
      vgd::net::JobRequest job;
      job.name = fs::path(o->document).filename().string();
      // A scene file (.json) is a scene job, run by the server's vgd simulate.
      if (vgd::iequals(fs::path(o->document).extension().string(), ".json")) job.scene = vgd::read_file(o->document);
      else job.document = vgd::read_file(o->document);
      job.size = o->size, job.quality = o->quality, job.model = o->model, job.fabric = o->fabric;
      job.body_size = o->body_size, job.body_table = o->body_table;
      job.time_limit = o->time_limit, job.spacing = o->spacing, job.outputs = o->outputs;
      if (!o->avatar.empty()) {
        job.avatar_name = fs::path(o->avatar).filename().string();
        job.avatar_bytes = vgd::read_file(o->avatar);
        job.unit = o->unit, job.up = o->up, job.facing = o->facing;
      }
      const std::string id = c.submit(job);
      std::printf("%s\n", id.c_str());
      std::fflush(stdout);
      if (!o->watch) return vgd::cli::kOk;
      const json end = watch(c, id, common);
      vgd::cli::say(common, "vgd: job " + id + ": " + end.value("state", "?"));
      return finished_code(end.value("state", ""));
    }
    if (list->parsed()) {
      const json j = answer(c.request("GET", "/v1/jobs"), o->server);
      if (o->json) {
        vgd::cli::print_json(j);
        return vgd::cli::kOk;
      }
      for (const auto& job : j) {
        std::string failure;
        if (job["failure"].is_object()) failure = "  " + job["failure"]["class"].get<std::string>();
        std::printf("%s  %-9s  %s  %s%s\n", job["id"].get<std::string>().c_str(), job["state"].get<std::string>().c_str(),
                    job["created"].get<std::string>().c_str(), job["name"].get<std::string>().c_str(), failure.c_str());
      }
      return vgd::cli::kOk;
    }
    if (status->parsed()) {
      const json j = answer(c.request("GET", "/v1/jobs/" + o->id), o->server);
      if (o->json) {
        vgd::cli::print_json(j);
        return vgd::cli::kOk;
      }
      std::printf("%s  %s  %s\n", o->id.c_str(), j["state"].get<std::string>().c_str(), j["name"].get<std::string>().c_str());
      if (j.contains("progress") && j["progress"].is_object())
        std::printf("  %s\n", j["progress"].dump().c_str());
      if (j["failure"].is_object())
        std::printf("  failed: %s: %s\n", j["failure"]["class"].get<std::string>().c_str(),
                    j["failure"]["message"].get<std::string>().c_str());
      if (j.contains("certificate") && j["certificate"].is_object())
        std::printf("  certificate: %s\n", j["certificate"].dump().c_str());
      if (j.contains("files"))
        for (const auto& f : j["files"])
          std::printf("  %s (%s bytes)\n", f["path"].get<std::string>().c_str(), std::to_string(f["bytes"].get<long long>()).c_str());
      return vgd::cli::kOk;
    }
    if (watch_cmd->parsed()) {
      const json end = watch(c, o->id, common);
      vgd::cli::say(common, "vgd: job " + o->id + ": " + end.value("state", "?"));
      return finished_code(end.value("state", ""));
    }
    if (get->parsed()) {
      const json j = answer(c.request("GET", "/v1/jobs/" + o->id), o->server);
      if (!j.contains("files"))
        throw vgd::Error(o->server, "job " + o->id, "no results yet (" + j["state"].get<std::string>() + ")");
      int n = 0;
      for (const auto& f : j["files"]) {
        const std::string path = f["path"];
        const fs::path rel(path);
        if (path.empty() || rel.is_absolute() || path.find("..") != std::string::npos)
          throw vgd::Error(o->server, path, "a file path outside the output folder: not written");
        if (!o->files.empty() && std::find(o->files.begin(), o->files.end(), path) == o->files.end()) continue;
        const auto r = c.request("GET", "/v1/jobs/" + o->id + "/files/" + path);
        if (r.status != 200) throw vgd::Error(o->server, path, "the server answered " + std::to_string(r.status));
        if (r.body.size() != f["bytes"].get<std::size_t>())
          throw vgd::Error(o->server, path, "received " + std::to_string(r.body.size()) + " bytes of " +
                                                std::to_string(f["bytes"].get<std::size_t>()));
        if (vgd::batch::sha256_hex(r.body) != f["sha256"].get<std::string>())
          throw vgd::Error(o->server, path, "the file received is not the one the job lists (SHA-256)");
        vgd::write_file_atomic(fs::path(o->output) / path, r.body);
        ++n;
      }
      vgd::cli::say(common, "vgd: " + std::to_string(n) + " files of job " + o->id + " in " + o->output);
      return vgd::cli::kOk;
    }
    if (cancel->parsed()) {
      const json j = answer(c.request("POST", "/v1/jobs/" + o->id + "/cancel"), o->server);
      std::printf("%s %s\n", o->id.c_str(), j.value("state", "?").c_str());
      return vgd::cli::kOk;
    }
    return vgd::cli::kUsage;
  }};
}};

}  // namespace
}  // namespace cmd_remote
