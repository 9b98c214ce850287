// The simulation server's service: jobs as catalogue items run by worker
// processes, answered as HTTP responses (service.hpp).
#include "vgd/net/service.hpp"

#include <openssl/evp.h>

#include <algorithm>
#include <chrono>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <random>

#include "vgd/batch/catalogue.hpp"
#include "vgd/batch/item.hpp"
#include "vgd/batch/process.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/core/version.hpp"
#include "vgd/net/page.hpp"
#include "vgd/scene/json.hpp"
#include "vgd/xvc/io.hpp"

namespace vgd::net {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Bytes that are not UTF-8 (a garbled path echoed in a message) are replaced, never thrown on.
Response json_response(int status, const json& j) {
  return {status, "application/json", j.dump(2, ' ', false, json::error_handler_t::replace) + "\n", {}};
}
Response error(int status, const std::string& message) { return json_response(status, {{"error", message}}); }

std::string new_id() {
  static std::mutex m;
  static std::random_device rd;
  std::lock_guard lock(m);
  std::uniform_int_distribution<unsigned> d(0, 15);
  std::string s;
  for (int i = 0; i < 16; ++i) s += "0123456789abcdef"[d(rd)];
  return s;
}

// Standard base64 (RFC 4648, OpenSSL's decoder); nothing for anything else.
std::optional<std::string> base64_decode(const std::string& in) {
  if (in.size() % 4 != 0 || in.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/=") !=
                                std::string::npos)
    return std::nullopt;
  std::string out(in.size() / 4 * 3, '\0');
  const int n = EVP_DecodeBlock(reinterpret_cast<unsigned char*>(out.data()),
                                reinterpret_cast<const unsigned char*>(in.data()), static_cast<int>(in.size()));
  if (n < 0) return std::nullopt;
  // EVP_DecodeBlock counts the padding as zero bytes.
  std::size_t pad = 0;
  for (auto it = in.rbegin(); it != in.rend() && *it == '=' && pad < 2; ++it) ++pad;
  out.resize(static_cast<std::size_t>(n) - pad);
  return out;
}

bool valid_id(const std::string& id) {
  return id.size() == 16 && id.find_first_not_of("0123456789abcdef") == std::string::npos;
}

fs::path job_dir(const ServiceOptions& o, const std::string& id) { return o.data / "jobs" / id; }

// The job's one catalogue item, or nothing when its catalogue cannot be read.
std::optional<batch::Item> job_item(const fs::path& dir) {
  // A job's catalogue never changes once submitted: read (and its files
  // hashed) once, not on every look of a live stream, 10 times a second.
  static std::mutex m;
  static std::map<std::string, batch::Item> known;
  {
    std::lock_guard lock(m);
    if (const auto it = known.find(dir.string()); it != known.end()) return it->second;
  }
  try {
    const batch::Item item = batch::load_catalogue(dir / "catalogue.json").items.at(0);
    std::lock_guard lock(m);
    known.emplace(dir.string(), item);
    return item;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// A name a client may give a file it sends: letters, digits, '.', '_', '-',
// not starting with '.', at most 100 bytes, ending in one of `extensions`
// (any case): nothing that could leave the job's folder.
bool safe_file_name(const std::string& name, std::initializer_list<const char*> extensions) {
  if (name.empty() || name.size() > 100 || name[0] == '.' ||
      name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789._-") != std::string::npos)
    return false;
  const std::string ext = fs::path(name).extension().string();
  return std::any_of(extensions.begin(), extensions.end(), [&](const char* e) { return iequals(ext, e); });
}

// A scene job (docs/server.md, "Scene jobs"): its scene in input/scene.json,
// run by `vgd simulate`, its trajectory in out/scene.trj.
bool is_scene_job(const fs::path& dir) {
  std::error_code ec;
  return fs::exists(dir / "input" / "scene.json", ec);
}

// The files a finished scene job offers (its trajectory, with its size and
// SHA-256), listed once when it passes in out/files.json, read on each look.
void list_scene_files(const fs::path& dir) {
  const std::string bytes = read_file(dir / "out" / "scene.trj");
  const json files = json::array(
      {{{"path", "scene.trj"}, {"bytes", bytes.size()}, {"sha256", batch::sha256_hex(bytes)}}});
  write_file_atomic(dir / "out" / "files.json", files.dump(2));
}
json scene_files(const fs::path& dir) {
  try {
    const json j = json::parse(read_file(dir / "out" / "files.json"), nullptr, false);
    return j.is_array() ? j : json::array();
  } catch (const Error&) {
    return json::array();
  }
}

// Keys a scene job may not use: each names a file (materials' XVC documents,
// garments, body files) or writes one (OBJ frames) on the server. Returns the
// JSON path of the first, or "".
std::string file_key(const json& j, const std::string& path) {
  if (j.is_object()) {
    for (const auto& [k, v] : j.items()) {
      const std::string here = path + "." + k;
      if (k == "xvc" || k == "file" || k == "path" || k == "garment" || k == "output") return here;
      if (auto deeper = file_key(v, here); !deeper.empty()) return deeper;
    }
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i)
      if (auto deeper = file_key(j[i], path + "[" + std::to_string(i) + "]"); !deeper.empty()) return deeper;
  }
  return "";
}

// Why a scene job's worker ended without its trajectory: the last message
// vgd wrote in the log.
std::string last_message(const fs::path& log) {
  std::string text;
  try {
    text = read_file(log);
  } catch (const Error&) {
    return "";
  }
  std::string last;
  for (const auto& line : split(text, '\n'))
    if (line.rfind("vgd", 0) == 0 || line.find("error") != std::string::npos) last = line;
  return last;
}

// The last progress line vgd dress wrote in the item's log:
// "[####....] settling  t 0.64 s  seams 140/140  KE 6.4e-08 J/particle  wall 5.3 s".
json progress_of(const fs::path& log) {
  std::string text;
  try {
    text = read_file(log);
  } catch (const Error&) {
    return nullptr;
  }
  std::string last;
  for (const auto& line : split(text, '\n'))
    if (!line.empty() && line[0] == '[' && line.find("] ") != std::string::npos) last = line;
  if (last.empty()) return nullptr;
  json p;
  const auto words = split(last.substr(last.find("] ") + 2), ' ');
  std::vector<std::string> w;
  for (const auto& x : words)
    if (!x.empty()) w.push_back(x);
  if (!w.empty()) p["stage"] = w[0];
  for (std::size_t i = 1; i + 1 < w.size(); ++i) {
    if (w[i] == "t") p["simulated_s"] = parse_double(w[i + 1]).value_or(0.0);
    if (w[i] == "wall") p["wall_s"] = parse_double(w[i + 1]).value_or(0.0);
    if (w[i] == "KE") p["kinetic_energy_j"] = parse_double(w[i + 1]).value_or(0.0);
    if (w[i] == "seams") {
      const auto ab = split(w[i + 1], '/');
      if (ab.size() == 2) {
        p["seams_closed"] = parse_int(ab[0]).value_or(0);
        p["seam_pairs"] = parse_int(ab[1]).value_or(0);
      }
    }
  }
  return p;
}

json job_json(const Job& j) {
  json o = {{"id", j.id},           {"state", to_string(j.state)}, {"name", j.name},
            {"created", j.created}, {"started", j.started},        {"finished", j.finished},
            {"attempts", j.attempts}};
  o["failure"] = j.failure_class.empty() ? json(nullptr) : json{{"class", j.failure_class}, {"message", j.message}};
  return o;
}

const char* content_type(const fs::path& p) {
  const std::string e = to_lower(p.extension().string());
  if (e == ".json") return "application/json";
  if (e == ".png") return "image/png";
  if (e == ".glb") return "model/gltf-binary";
  if (e == ".wrl") return "model/vrml";
  if (e == ".txt" || e == ".obj") return "text/plain; charset=utf-8";
  if (e == ".xvc") return "application/xml";
  return "application/octet-stream";
}

}  // namespace

fs::path Service::three_dir() const {
#ifdef VGD_THREE_DIR
  if (o_.three_dir.empty()) return VGD_THREE_DIR;
#endif
  return o_.three_dir;
}

Service::Service(ServiceOptions options) : o_(std::move(options)), store_(o_.data) {
  requeued_ = store_.requeue_running();
  runner_ = std::thread([this] { run(); });
}

Service::~Service() { stop(); }

void Service::stop() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_one();
  if (runner_.joinable()) runner_.join();
}

void Service::run() {
  struct Running {
    std::string id;
    batch::Process process;
  };
  std::vector<std::unique_ptr<Running>> running;
  while (!stop_) {
    // Reap.
    for (auto it = running.begin(); it != running.end();) {
      Running& r = **it;
      bool cancel = false;
      {
        std::lock_guard lock(mutex_);
        cancel = cancels_.count(r.id) > 0;
      }
      if (cancel) r.process.kill();
      if (!r.process.poll()) {
        ++it;
        continue;
      }
      const fs::path dir = job_dir(o_, r.id);
      if (cancel) {
        store_.set_state(r.id, JobState::cancelled, "", "cancelled while running");
        std::lock_guard lock(mutex_);
        cancels_.erase(r.id);
      } else if (is_scene_job(dir)) {
        std::error_code ec;
        const auto res = r.process.result();
        bool listed = false;
        if (res.ok() && fs::exists(dir / "out" / "scene.trj", ec)) {
          try {
            list_scene_files(dir);
            listed = true;
          } catch (const Error& e) {
            store_.set_state(r.id, JobState::failed, "output", e.what());
          }
        }
        if (listed) {
          store_.set_state(r.id, JobState::passed);
        } else if (!res.ok() || !fs::exists(dir / "out" / "scene.trj", ec)) {
          std::string msg = last_message(dir / "worker.log");
          const std::string what = "the worker " + res.describe();
          const std::string cls = res.timed_out ? "time-out"
                                  : res.signal != 0 ? "crash"
                                  : msg.find("diverg") != std::string::npos || msg.find("non-finite") != std::string::npos
                                      ? "diverged"
                                      : "bad input";
          // vgd's own message when it ended with one; how the worker ended otherwise.
          const bool said = res.signal == 0 && !res.timed_out && !msg.empty();
          store_.set_state(r.id, JobState::failed, cls, said ? msg : what + (msg.empty() ? "" : " (" + msg + ")"));
        }
      } else if (const auto item = job_item(dir)) {
        const auto s = batch::item_status(dir / "out", *item, /*checksums=*/false);
        if (s.state == batch::ItemState::passed)
          store_.set_state(r.id, JobState::passed);
        else if (s.state == batch::ItemState::failed)
          store_.set_state(r.id, JobState::failed, s.manifest->failure_class, s.manifest->failure_message);
        else
          store_.set_state(r.id, JobState::failed, "crash",
                           "the worker " + r.process.result().describe() + " before it finished");
      } else {
        store_.set_state(r.id, JobState::failed, "bad input", "the job's catalogue cannot be read");
      }
      it = running.erase(it);
    }
    // Start.
    while (static_cast<int>(running.size()) < std::max(1, o_.workers)) {
      const auto next = store_.next_queued();
      if (!next) break;
      const fs::path dir = job_dir(o_, next->id);
      store_.set_state(next->id, JobState::running);
      try {
        if (is_scene_job(dir)) {
          batch::ProcessOptions po;
          po.log = dir / "worker.log";
          po.deadline_s = o_.scene_wall_limit;
          po.memory_mb = o_.scene_memory_mb;
          std::error_code mkdir_ec;  // a folder that cannot be made: vgd simulate says so, the job fails
          fs::create_directories(dir / "out", mkdir_ec);
          running.push_back(std::make_unique<Running>(Running{
              next->id, batch::Process(o_.exe, {"simulate", (dir / "input" / "scene.json").string(), "--trj",
                                                (dir / "out" / "scene.trj").string()},
                                       po)}));
          continue;
        }
        const auto item = job_item(dir);
        if (!item) throw Error((dir / "catalogue.json").string(), "", "the job's catalogue cannot be read");
        batch::ProcessOptions po;
        po.log = dir / "worker.log";
        const auto c = batch::load_catalogue(dir / "catalogue.json");
        po.deadline_s = c.settings.wall_limit + 120.0;
        running.push_back(std::make_unique<Running>(Running{
            next->id, batch::Process(o_.exe, {"batch", "item", (dir / "catalogue.json").string(), "-o",
                                              (dir / "out").string(), "--index", "0"},
                                     po)}));
      } catch (const Error& e) {
        store_.set_state(next->id, JobState::failed, "bad input", e.what());
      }
    }
    // Until a job is submitted or cancelled, or 20 ms (a worker's end).
    std::unique_lock lock(mutex_);
    wake_.wait_for(lock, std::chrono::milliseconds(20), [this] { return woken_ || stop_; });
    woken_ = false;
  }
  // Stopping: running jobs go back to the queue for the next start.
  for (auto& r : running) {
    r->process.kill();
    r->process.wait();
    store_.set_state(r->id, JobState::queued);
  }
}

Response Service::handle(const Request& req) {
  Response r = [&]() -> Response {
    try {
      std::string path = req.target.substr(0, req.target.find('?'));
      // The browser page and its three.js: no token (nothing of a job's in them).
      if (path == "/" || path == "/index.html") {
        if (req.method != "GET") return error(405, "GET only");
        return {200, "text/html; charset=utf-8", std::string(browser_page()), {}};
      }
      if (path == "/web/three/three.module.js" || path == "/web/three/three.core.js") {
        const fs::path f = three_dir() / fs::path(path).filename();
        if (three_dir().empty() || !fs::is_regular_file(f))
          return error(404, "three.js is not installed for this server (give --three with its build folder)");
        Response js;
        js.content_type = "text/javascript";
        js.file = f;
        return js;
      }
      const auto parts = split(path, '/');  // "", "v1", ...
      if (parts.size() < 3 || !parts[0].empty() || parts[1] != "v1") return error(404, "no such route: " + path);
      const std::string& what = parts[2];
      if (!(what == "health" && parts.size() == 3))
        if (auto refused = check_token(req.authorization)) return *refused;
      if (what == "health" && parts.size() == 3) {
        if (req.method != "GET") return error(405, "GET only");
        json jobs;
        for (auto s : {JobState::queued, JobState::running, JobState::passed, JobState::failed, JobState::cancelled})
          jobs[to_string(s)] = store_.count(s);
        return json_response(200, {{"status", "ok"}, {"version", kVersion}, {"jobs", jobs}});
      }
      if (what == "metrics" && parts.size() == 3) return metrics();
      if (what != "jobs") return error(404, "no such route: " + path);
      if (parts.size() == 3) {
        if (req.method == "POST") return submit(req.body, req.client);
        if (req.method != "GET") return error(405, "GET or POST");
        json list = json::array();
        for (const auto& j : store_.list()) list.push_back(job_json(j));
        return json_response(200, list);
      }
      const std::string& id = parts[3];
      if (!valid_id(id)) return error(404, "no job '" + printable(id) + "'");
      if (parts.size() == 4) {
        if (req.method != "GET") return error(405, "GET only");
        return job(id);
      }
      if (parts.size() == 5 && parts[4] == "cancel") {
        if (req.method != "POST") return error(405, "POST only");
        return cancel(id);
      }
      if (parts.size() >= 6 && parts[4] == "files") {
        if (req.method != "GET") return error(405, "GET only");
        std::string rel;
        for (std::size_t k = 5; k < parts.size(); ++k) rel += (k > 5 ? "/" : "") + parts[k];
        return file(id, rel);
      }
      return error(404, "no such route: " + path);
    } catch (const Error& e) {
      return error(500, e.what());
    } catch (const std::exception& e) {
      return error(500, std::string("internal error: ") + e.what());
    }
  }();
  std::lock_guard lock(mutex_);
  ++responses_[r.status];
  return r;
}

std::optional<Response> Service::check_token(const std::string& authorization) const {
  if (o_.token.empty()) return std::nullopt;
  const std::string prefix = "Bearer ";
  if (authorization.rfind(prefix, 0) != 0) return error(401, "this server needs a token: Authorization: Bearer <token>");
  const std::string given = authorization.substr(prefix.size());
  // Constant time in the token's length: every byte compared.
  unsigned diff = given.size() != o_.token.size() ? 1u : 0u;
  for (std::size_t k = 0; k < o_.token.size(); ++k)
    diff |= static_cast<unsigned char>(o_.token[k]) ^ static_cast<unsigned char>(k < given.size() ? given[k] : 0);
  if (diff != 0) return error(403, "the token is not this server's");
  return std::nullopt;
}

std::optional<Service::Trajectory> Service::trajectory(const std::string& id) {
  if (!valid_id(id)) return std::nullopt;
  const auto j = store_.get(id);
  if (!j) return std::nullopt;
  Trajectory t;
  t.state = to_string(j->state);
  t.finished = j->state == JobState::passed || j->state == JobState::failed || j->state == JobState::cancelled;
  const fs::path dir = job_dir(o_, id);
  std::error_code ec;
  if (is_scene_job(dir)) {
    t.file = dir / "out" / "scene.trj";
    if (!fs::exists(t.file, ec)) t.file += ".partial";
    return t;
  }
  const auto item = job_item(dir);
  if (!item) return t;
  const fs::path done = batch::item_dir(dir / "out", item->id);
  const fs::path partial = done.string() + ".partial";
  if (fs::exists(done / "drape.trj", ec)) t.file = done / "drape.trj";
  else if (fs::exists(partial / "drape.trj", ec)) t.file = partial / "drape.trj";
  else t.file = partial / "drape.trj.partial";
  return t;
}

std::string Service::progress(const std::string& id) {
  if (!valid_id(id)) return "";
  if (is_scene_job(job_dir(o_, id))) {
    // vgd simulate writes no progress lines to a log; the frames say how far it is.
    const auto j = store_.get(id);
    return j && j->state == JobState::running ? R"({"stage":"simulating"})" : "";
  }
  const auto item = job_item(job_dir(o_, id));
  if (!item) return "";
  const json p = progress_of(job_dir(o_, id) / "out" / "items" / (item->id + ".partial") / "log.txt");
  return p.is_null() ? "" : p.dump();
}

void Service::count_stream(long long frames, long long dropped) {
  std::lock_guard lock(mutex_);
  ++streams_;
  streamed_frames_ += frames;
  dropped_frames_ += dropped;
}

Response Service::submit(const std::string& body, const std::string& client) {
  const json j = json::parse(body, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return error(400, "the request is not a JSON object");
  if (j.contains("scene")) return submit_scene(j, client);
  for (const auto& [k, v] : j.items())
    if (k != "name" && k != "document" && k != "settings" && k != "avatar")
      return error(400, "unknown key '" + printable(k) + "' (known: name, document, settings, avatar)");
  if (!j.contains("document") || !j["document"].is_string() || j["document"].get<std::string>().empty())
    return error(400, "document: missing (the XVC document's text)");
  const std::string doc_text = j["document"];
  if (doc_text.size() > o_.max_document)
    return error(413, "document: " + std::to_string(doc_text.size()) + " bytes, more than the server's limit of " +
                          std::to_string(o_.max_document));
  std::string name = j.value("name", "garment.xvc");
  if (!j.value("name", json("garment.xvc")).is_string()) return error(400, "name: expected a string");
  if (!safe_file_name(name, {".xvc"}))
    return error(400, "name: '" + printable(name) + "' is not a file name ending in .xvc (letters, digits, '.', '_', '-')");
  if (auto refused = refuse_when_full(client)) return *refused;
  try {
    xvc::load_string(doc_text, name);
  } catch (const Error& e) {
    return error(400, e.what());
  }
  // Settings: a one-item catalogue (docs/batch.md) checked by the catalogue reader.
  const json s = j.value("settings", json::object());
  if (!s.is_object()) return error(400, "settings: expected an object");
  json cat = {{"name", "job"}};
  json settings = {{"wall_limit", 900}};
  for (const auto& [k, v] : s.items()) {
    if (k == "size" || k == "fabric" || k == "body_size" || k == "body_table" || k == "outputs" || k == "views" ||
        k == "preview_size")
      continue;
    if (k == "quality" || k == "model" || k == "time_limit" || k == "spacing" || k == "wall_limit" ||
        k == "memory_mb") {
      settings[k] = v;
      continue;
    }
    return error(400, "settings." + printable(k) +
                          ": unknown (known: size, fabric, body_size, body_table, quality, model, time_limit, "
                          "spacing, wall_limit, memory_mb, outputs, views, preview_size)");
  }
  if (s.contains("time_limit") && s["time_limit"].is_number() && s["time_limit"].get<double>() > 60)
    return error(400, "settings.time_limit: more than the server's 60 simulated seconds");
  if (s.contains("memory_mb") && s["memory_mb"].is_number() && s["memory_mb"].get<double>() > 16384)
    return error(400, "settings.memory_mb: more than the server's 16384 MB");
  cat["settings"] = settings;
  cat["styles"] = json::array({{{"id", fs::path(name).stem().string()}, {"file", "input/" + name}}});
  cat["sizes"] = json::array({s.value("size", json("sample"))});
  cat["fabrics"] = json::array({s.value("fabric", json("garment"))});
  if (s.contains("body_size")) {
    json a = {{"id", "body"}, {"mannequin", s["body_size"]}};
    if (s.contains("body_table")) a["table"] = s["body_table"];
    cat["avatars"] = json::array({a});
  }
  // An uploaded body: {"name": "scan.glb", "data": BASE64, "unit", "up", "facing"}.
  std::string avatar_name, avatar_bytes;
  if (j.contains("avatar")) {
    const json& a = j["avatar"];
    if (!a.is_object() || !a.contains("name") || !a["name"].is_string() || !a.contains("data") || !a["data"].is_string())
      return error(400, "avatar: expected {\"name\": \"body.glb\", \"data\": BASE64, \"unit\", \"up\", \"facing\"}");
    for (const auto& [k, v] : a.items())
      if (k != "name" && k != "data" && k != "unit" && k != "up" && k != "facing")
        return error(400, "avatar." + printable(k) + ": unknown (known: name, data, unit, up, facing)");
    avatar_name = a["name"];
    if (!safe_file_name(avatar_name, {".obj", ".ply", ".stl", ".glb", ".gltf", ".fbx", ".dae"}))
      return error(400, "avatar.name: '" + printable(avatar_name) +
                            "' is not a body file name (letters, digits, '.', '_', '-'; .obj .ply .stl .glb .gltf .fbx .dae)");
    if (s.contains("body_size")) return error(400, "avatar: give an uploaded body or settings.body_size, not both");
    const auto decoded = base64_decode(a["data"].get<std::string>());
    if (!decoded) return error(400, "avatar.data: not base64");
    avatar_bytes = *decoded;
    json entry = {{"id", fs::path(avatar_name).stem().string()}, {"file", "input/" + avatar_name}};
    for (const char* k : {"unit", "up", "facing"})
      if (a.contains(k)) entry[k] = a[k];
    cat["avatars"] = json::array({entry});
  }
  cat["outputs"] = s.value("outputs", json::array({"certificate", "trj", "wvt", "glb", "previews"}));
  if (s.contains("views")) cat["views"] = s["views"];
  if (s.contains("preview_size")) cat["preview_size"] = s["preview_size"];

  const std::string id = new_id();
  const fs::path dir = job_dir(o_, id);
  write_file_atomic(dir / "input" / name, doc_text);
  if (!avatar_name.empty()) write_file_atomic(dir / "input" / avatar_name, avatar_bytes);
  write_file_atomic(dir / "catalogue.json", cat.dump(2));
  try {
    batch::load_catalogue(dir / "catalogue.json");
  } catch (const Error& e) {
    std::error_code ec;
    fs::remove_all(dir, ec);
    const auto& d = e.diagnostic();
    std::string field = d.entity;
    if (field.rfind("sizes", 0) == 0) field = "settings.size";
    if (field.rfind("fabrics", 0) == 0) field = "settings.fabric";
    if (field.rfind("avatars", 0) == 0) field = avatar_name.empty() ? "settings.body_size" : "avatar" + field.substr(10);
    return error(400, field + ": " + d.message);
  }
  return queue(id, name, client);
}

// 429 when this client or the whole queue has as many jobs as allowed.
std::optional<Response> Service::refuse_when_full(const std::string& client) {
  if (store_.active_of(client) >= o_.max_per_client)
    return error(429, "this client has " + std::to_string(store_.active_of(client)) +
                          " jobs queued or running (the server's limit per client is " +
                          std::to_string(o_.max_per_client) + "): wait for some to finish");
  if (store_.count(JobState::queued) >= o_.max_queued)
    return error(429, "the queue is full (" + std::to_string(o_.max_queued) + " jobs): try again later");
  return std::nullopt;
}

// A job accepted: queued in the database, the runner woken.
Response Service::queue(const std::string& id, const std::string& name, const std::string& client) {
  Job job;
  job.id = id;
  job.name = name;
  job.client = client;
  store_.insert(job);
  {
    std::lock_guard lock(mutex_);
    ++submitted_;
    woken_ = true;
  }
  wake_.notify_one();
  return json_response(202, {{"id", id}, {"state", "queued"}});
}

// A scene job: {"name": "x.json", "scene": {...}} (docs/scene.md), run by
// `vgd simulate`. Self-contained: materials inline, grids of cloth, a
// mannequin or a simple solid; nothing that names a file on the server.
Response Service::submit_scene(const json& j, const std::string& client) {
  for (const auto& [k, v] : j.items())
    if (k != "name" && k != "scene") return error(400, "unknown key '" + printable(k) + "' in a scene job (known: name, scene)");
  if (!j["scene"].is_object()) return error(400, "scene: expected the scene's JSON object (docs/scene.md)");
  if (!j.value("name", json("scene.json")).is_string()) return error(400, "name: expected a string");
  const std::string name = j.value("name", "scene.json");
  if (!safe_file_name(name, {".json"}))
    return error(400, "name: '" + printable(name) + "' is not a file name ending in .json (letters, digits, '.', '_', '-')");
  const std::string text = j["scene"].dump(2, ' ', false, json::error_handler_t::replace);
  if (text.size() > o_.max_document)
    return error(413, "scene: " + std::to_string(text.size()) + " bytes, more than the server's limit of " +
                          std::to_string(o_.max_document));
  if (const std::string k = file_key(j["scene"], "scene"); !k.empty())
    return error(400, k + ": a scene job cannot name files on the server (give materials inline, cloth as grids, "
                          "the body as a mannequin or a solid; submit an XVC document for garments)");
  if (auto refused = refuse_when_full(client)) return *refused;
  scene::SceneDef def;
  try {
    def = scene::parse_scene(text, name);
  } catch (const Error& e) {
    return error(400, e.what());
  }
  long particles = 0;
  for (const auto& c : def.cloth) {
    if (!c.grid) return error(400, "scene.cloth: '" + printable(c.name) + "' is not a grid (a scene job's cloth is)");
    particles += static_cast<long>(c.grid->nu) * c.grid->nv;
  }
  if (particles > o_.max_particles)
    return error(400, "scene.cloth: " + std::to_string(particles) + " particles, more than the server's " +
                          std::to_string(o_.max_particles));
  if (!(def.run.duration <= o_.max_simulated_s))
    return error(400, "scene.frames.duration: " + format_fixed(def.run.duration, 2) + " s, more than the server's " +
                          format_fixed(o_.max_simulated_s, 0) + " simulated seconds");
  const std::string id = new_id();
  const fs::path dir = job_dir(o_, id);
  write_file_atomic(dir / "input" / "scene.json", text);
  return queue(id, name, client);
}

Response Service::job(const std::string& id) {
  const auto j = store_.get(id);
  if (!j) return error(404, "no job '" + id + "'");
  json o = job_json(*j);
  const fs::path dir = job_dir(o_, id);
  o["kind"] = is_scene_job(dir) ? "scene" : "garment";
  if (is_scene_job(dir)) {
    if (j->state == JobState::passed) o["files"] = scene_files(dir);
  } else if (const auto item = job_item(dir)) {
    const fs::path items = dir / "out" / "items";
    if (j->state == JobState::running) o["progress"] = progress_of(items / (item->id + ".partial") / "log.txt");
    const auto s = batch::item_status(dir / "out", *item, /*checksums=*/false);
    if (s.manifest) {
      o["certificate"] = s.manifest->certificate.empty() ? json(nullptr) : json::parse(s.manifest->certificate);
      o["wall_s"] = s.manifest->wall_s;
      json files = json::array();
      for (const auto& f : s.manifest->files) files.push_back({{"path", f.path}, {"bytes", f.bytes}, {"sha256", f.sha256}});
      o["files"] = files;
    }
  }
  return json_response(200, o);
}

Response Service::cancel(const std::string& id) {
  const auto j = store_.get(id);
  if (!j) return error(404, "no job '" + id + "'");
  if (j->state == JobState::queued) {
    store_.set_state(id, JobState::cancelled, "", "cancelled while queued");
    return json_response(200, {{"id", id}, {"state", "cancelled"}});
  }
  if (j->state == JobState::running) {
    {
      std::lock_guard lock(mutex_);
      cancels_[id] = true;
      woken_ = true;
    }
    wake_.notify_one();
    return json_response(202, {{"id", id}, {"state", "cancelling"}});
  }
  return error(409, "job " + id + " has finished (" + to_string(j->state) + "): nothing to cancel");
}

Response Service::file(const std::string& id, const std::string& path) {
  const auto j = store_.get(id);
  if (!j) return error(404, "no job '" + id + "'");
  const fs::path dir = job_dir(o_, id);
  if (is_scene_job(dir)) {
    // Only its trajectory, once the job passed: no other path can be named.
    if (j->state != JobState::passed) return error(404, "job " + id + " has no results yet (" + to_string(j->state) + ")");
    if (path != "scene.trj") return error(404, "job " + id + " has no file '" + printable(path) + "'");
    Response r;
    r.content_type = content_type(path);
    r.file = dir / "out" / "scene.trj";
    return r;
  }
  const auto item = job_item(dir);
  if (!item) return error(404, "job " + id + " has no results");
  const auto s = batch::item_status(dir / "out", *item, /*checksums=*/false);
  if (!s.manifest) return error(404, "job " + id + " has no results yet (" + to_string(j->state) + ")");
  // Only the files its manifest lists: no path outside the job can be named.
  for (const auto& f : s.manifest->files)
    if (f.path == path) {
      Response r;
      r.content_type = content_type(path);
      r.file = batch::item_dir(dir / "out", item->id) / f.path;
      return r;
    }
  return error(404, "job " + id + " has no file '" + printable(path) + "'");
}

Response Service::metrics() {
  std::string t;
  t += "# HELP vgd_jobs Jobs by state.\n# TYPE vgd_jobs gauge\n";
  for (auto s : {JobState::queued, JobState::running, JobState::passed, JobState::failed, JobState::cancelled})
    t += std::string("vgd_jobs{state=\"") + to_string(s) + "\"} " + std::to_string(store_.count(s)) + "\n";
  std::lock_guard lock(mutex_);
  t += "# HELP vgd_jobs_submitted_total Jobs accepted since the server started.\n"
       "# TYPE vgd_jobs_submitted_total counter\nvgd_jobs_submitted_total " + std::to_string(submitted_) + "\n";
  t += "# HELP vgd_http_responses_total Responses by status code since the server started.\n"
       "# TYPE vgd_http_responses_total counter\n";
  for (const auto& [code, n] : responses_)
    t += "vgd_http_responses_total{code=\"" + std::to_string(code) + "\"} " + std::to_string(n) + "\n";
  t += "# HELP vgd_streams_total Live frame streams ended.\n# TYPE vgd_streams_total counter\nvgd_streams_total " +
       std::to_string(streams_) + "\n";
  t += "# HELP vgd_stream_frames_total Frames sent to viewers.\n# TYPE vgd_stream_frames_total counter\n"
       "vgd_stream_frames_total " + std::to_string(streamed_frames_) + "\n";
  t += "# HELP vgd_stream_frames_dropped_total Frames a slow viewer skipped (never the stored result's).\n"
       "# TYPE vgd_stream_frames_dropped_total counter\nvgd_stream_frames_dropped_total " +
       std::to_string(dropped_frames_) + "\n";
  t += "# HELP vgd_workers Worker processes at most.\n# TYPE vgd_workers gauge\nvgd_workers " +
       std::to_string(o_.workers) + "\n";
  return {200, "text/plain; version=0.0.4", t, {}};
}

}  // namespace vgd::net
