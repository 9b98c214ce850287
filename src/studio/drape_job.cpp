#include "drape_job.hpp"

#include <omp.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <nlohmann/json.hpp>

#include "vgd/core/strings.hpp"
#include "vgd/scene/build.hpp"

namespace vgd::studio {

namespace {

// Thrown from the progress callback to end a run the user stopped; the
// engine's own failures are SimulationErrors and end in the certificate.
struct StopRequested {};

class LiveSink : public sim::FrameSink {
 public:
  LiveSink(std::mutex& m, LiveCloth& cloth, bool& fresh) : m_(m), cloth_(cloth), fresh_(fresh) {}
  void begin(const sim::Model& model) override {
    std::lock_guard lock(m_);
    cloth_.triangles = model.triangles;
    cloth_.triangle_piece = model.triangle_piece;
    cloth_.pieces = model.pieces;
    cloth_.uv.clear();
    for (const auto& q : model.uv) cloth_.uv.push_back({q.x(), q.y()});
    cloth_.representative.clear();
    cloth_.positions.clear();
  }
  void merged(int, const std::vector<int>& representative) override {
    std::lock_guard lock(m_);
    cloth_.representative = representative;
  }
  void frame(int, double t, const sim::VecX& x) override {
    std::lock_guard lock(m_);
    cloth_.t = t;
    cloth_.positions.resize(static_cast<std::size_t>(x.size() / 3));
    for (std::size_t i = 0; i < cloth_.positions.size(); ++i)
      cloth_.positions[i] = {static_cast<float>(x[3 * i]), static_cast<float>(x[3 * i + 1]),
                             static_cast<float>(x[3 * i + 2])};
    fresh_ = true;
  }

 private:
  std::mutex& m_;
  LiveCloth& cloth_;
  bool& fresh_;
};

std::string outcome(const dress::Certificate& c) {
  return c.stop_reason == "error"
             ? "the drape failed: " + c.stop_message
             : "stopped at " + c.stop_reason + " after " + format_fixed(c.simulated_s, 2) + " s simulated (" +
                   format_fixed(c.wall_s, 1) + " s wall); " + std::to_string(c.triangle_intersections) +
                   " crossing triangle pairs, max penetration " + format_fixed(c.max_penetration * 1000, 2) + " mm";
}

}  // namespace

bool LiveJob::running() const {
  std::lock_guard lock(m_);
  return status_.running;
}

DrapeStatus LiveJob::status() const {
  std::lock_guard lock(m_);
  return status_;
}

bool LiveJob::take_cloth(LiveCloth& out) {
  std::lock_guard lock(m_);
  if (!cloth_new_) return false;
  out = cloth_;
  cloth_new_ = false;
  return true;
}

bool LiveJob::take_body(mesh::SurfaceMesh& out) {
  std::lock_guard lock(m_);
  if (!body_new_ || !body_) return false;
  out = *body_;
  body_new_ = false;
  return true;
}

std::optional<dress::Certificate> LiveJob::take_certificate() {
  std::lock_guard lock(m_);
  auto c = std::move(cert_);
  cert_.reset();
  return c;
}

void LiveJob::begin(double time_limit, const std::string& stage) {
  std::lock_guard lock(m_);
  status_ = {};
  status_.running = true;
  status_.stage = stage;
  status_.time_limit = time_limit;
  cert_.reset();
}

void LiveJob::finish(const std::string& stage, const std::string& message) {
  std::lock_guard lock(m_);
  status_.running = false;
  status_.paused = false;
  status_.stage = stage;
  status_.message = message;
}

void LiveJob::show_body(body::Avatar avatar) {
  std::lock_guard lock(m_);
  status_.body_notes = avatar.notes;
  body_ = std::move(avatar.surface);
  body_new_ = true;
}

DrapeJob::~DrapeJob() {
  request_stop();
  wait();
}

void DrapeJob::request_stop() {
  stop_ = true;
  {
    std::lock_guard lock(m_);  // a run held by Pause wakes and stops
  }
  resume_.notify_all();
}

void DrapeJob::set_paused(bool paused) {
  {
    std::lock_guard lock(m_);
    if (!status_.running) return;
    status_.paused = paused;
    steps_ = 0;
  }
  resume_.notify_all();
}

void DrapeJob::step() {
  {
    std::lock_guard lock(m_);
    if (!status_.paused) return;
    ++steps_;
  }
  resume_.notify_all();
}

void DrapeJob::hold_if_paused() {
  std::unique_lock lock(m_);
  resume_.wait(lock, [&] { return stop_ || !status_.paused || steps_ > 0; });
  if (status_.paused && steps_ > 0) --steps_;
}

void DrapeJob::start(scene::SceneDef def, int threads) {
  wait();
  stop_ = false;
  {
    std::lock_guard lock(m_);
    status_.paused = false;
    steps_ = 0;
  }
  begin(def.run.duration, "placing");
  thread_ = std::thread([this, def = std::move(def), threads]() mutable { run(std::move(def), threads); });
}

void DrapeJob::wait() {
  if (thread_.joinable()) thread_.join();
}

void DrapeJob::run(scene::SceneDef def, int threads) {
  omp_set_num_threads(threads > 0 ? threads : omp_get_num_procs());
  try {
    if (def.avatar) {
      // The body first, so the preview shows it while the garment is placed.
      show_body(scene::build_avatar(def));
    }
    LiveSink sink(m_, cloth_, cloth_new_);
    auto progress = [&](const dress::DrapeStageProgress& p) {
      {
        std::lock_guard lock(m_);
        status_.stage = p.stage;
        status_.t = p.t;
        status_.time_limit = p.time_limit;
        status_.wall_s = p.wall_s;
        status_.seams_closed = p.seams_closed;
        status_.seam_pairs = p.seam_pairs;
        status_.seams_waiting = p.seams_waiting;
      }
      // After each frame (the placing call comes before the first): held here while paused.
      if (p.stage != "placing") hold_if_paused();
      if (stop_) throw StopRequested{};
    };
    dress::DrapeResult r = dress::run_drape(def, {&sink}, progress);
    // As vgd dress: a drape that failed only caught in the crease between an
    // arm and the torso is draped again holding the touching cloth once sewn.
    std::string again;
    auto& held = def.integrator.settings;
    if (!held.hold_contacts && !held.hold_contacts_once_sewn)
      if (const auto at = dress::caught_at_armpit(r.certificate)) {
        again = "draped again, the touching cloth held once sewn: the first drape failed only where the cloth is "
                "caught in the crease between " + *at + "; ";
        held.hold_contacts_once_sewn = true;
        r = dress::run_drape(def, {&sink}, progress);
      }
    const auto& c = r.certificate;
    const std::string msg = again + outcome(c);
    {
      std::lock_guard lock(m_);
      cert_ = c;
    }
    finish(c.stop_reason == "error" ? "failed" : "done", msg);
  } catch (const StopRequested&) {
    finish("stopped", "the drape was stopped");
  } catch (const std::exception& e) {
    finish("failed", std::string("the drape could not run: ") + e.what());
  }
}

RemoteJob::~RemoteJob() {
  request_stop();
  wait();
}

void RemoteJob::start(net::Client client, net::JobRequest job, scene::SceneDef body, double time_limit) {
  wait();
  {
    std::lock_guard lock(m_);
    stop_ = false;
    id_.clear();
    client_ = client;
  }
  begin(time_limit, "submitting");
  thread_ = std::thread([this, client = std::move(client), job = std::move(job), body = std::move(body)]() mutable {
    run(std::move(client), std::move(job), std::move(body));
  });
}

void RemoteJob::request_stop() {
  std::lock_guard lock(m_);
  if (stop_ || !status_.running) return;
  stop_ = true;
  // Before the server took it, run() cancels it as soon as it has an id.
  if (id_.empty() || !client_ || canceller_.joinable()) return;
  // The request on its own thread: the window never waits on the network.
  canceller_ = std::thread([c = *client_, id = id_] {
    try {
      c.cancel(id);
    } catch (const std::exception&) {
      // Finished meanwhile, or the server went: the stream's end says which.
    }
  });
}

void RemoteJob::wait() {
  if (thread_.joinable()) thread_.join();
  if (canceller_.joinable()) canceller_.join();
}

std::string RemoteJob::id() const {
  std::lock_guard lock(m_);
  return id_;
}

void RemoteJob::run(net::Client client, net::JobRequest job, scene::SceneDef def) {
  using nlohmann::json;
  std::string id;
  try {
    id = client.submit(job);
  } catch (const std::exception& e) {
    finish("failed", std::string("failed: ") + e.what());
    return;
  }
  bool cancel_now = false;
  {
    std::lock_guard lock(m_);
    id_ = id;
    status_.stage = "queued";
    cancel_now = stop_;
  }
  if (cancel_now) {
    try {
      client.cancel(id);
    } catch (const std::exception&) {
    }
  }
  // The job's body, built here for the preview (as the server builds it)
  // while the server starts.
  try {
    if (def.avatar) show_body(scene::build_avatar(def));
  } catch (const std::exception& e) {
    std::lock_guard lock(m_);
    status_.body_notes = {std::string("the body cannot be shown here: ") + e.what()};
  }
  std::string state;
  long long dropped = 0, corrupted = 0;
  std::size_t particles = 0;
  try {
    client.watch(
        id,
        [&](const std::string& text) {
          const json j = json::parse(text, nullptr, false);
          if (!j.is_object()) return;
          const std::string type = j.value("type", "");
          std::lock_guard lock(m_);
          if (type == "topology") {
            cloth_ = {};
            particles = j.value("particles", std::size_t{0});
            const auto& t = j.value("triangles", json::array());
            for (std::size_t k = 0; k + 2 < t.size(); k += 3)
              cloth_.triangles.push_back({t[k].get<int>(), t[k + 1].get<int>(), t[k + 2].get<int>()});
            for (const auto& p : j.value("pieces", json::array())) cloth_.pieces.push_back(p.get<std::string>());
            for (const auto& p : j.value("triangle_piece", json::array())) cloth_.triangle_piece.push_back(p.get<int>());
            if (cloth_.triangle_piece.size() != cloth_.triangles.size()) cloth_.triangle_piece.assign(cloth_.triangles.size(), 0);
          } else if (type == "progress" && j.contains("progress") && j["progress"].is_object()) {
            const json& p = j["progress"];
            status_.stage = p.value("stage", status_.stage);
            status_.t = p.value("simulated_s", status_.t);
            status_.wall_s = p.value("wall_s", status_.wall_s);
            status_.seams_closed = p.value("seams_closed", status_.seams_closed);
            status_.seam_pairs = p.value("seam_pairs", status_.seam_pairs);
          } else if (type == "dropped") {
            dropped = j.value("total", dropped);
          } else if (type == "end") {
            state = j.value("state", "");
          }
        },
        [&](const net::FrameMessage& f) {
          if (!f.checksum_ok) {
            ++corrupted;
            return;
          }
          std::lock_guard lock(m_);
          if (particles == 0 || f.positions.size() != 3 * particles) return;
          cloth_.t = f.t;
          cloth_.positions.resize(particles);
          for (std::size_t i = 0; i < particles; ++i)
            cloth_.positions[i] = {f.positions[3 * i], f.positions[3 * i + 1], f.positions[3 * i + 2]};
          cloth_new_ = true;
          if (status_.stage == "queued") status_.stage = "running";
        });
  } catch (const std::exception& e) {
    finish("failed", "job " + id + ": the stream of its frames broke: " + e.what());
    return;
  }
  std::string seen = "";
  if (dropped > 0) seen += "; " + std::to_string(dropped) + " frames not shown (the preview read slower than they came)";
  if (corrupted > 0) seen += "; " + std::to_string(corrupted) + " frames failed their checksum and were not shown";
  if (state == "cancelled") {
    finish("stopped", "job " + id + " was cancelled on the server" + seen);
    return;
  }
  // The outcome: the job's certificate when it has one, else its failure.
  std::optional<dress::Certificate> cert;
  std::string failure;
  try {
    const json j = json::parse(client.get("/v1/jobs/" + id), nullptr, false);
    if (j.is_object() && j.contains("failure") && j["failure"].is_object())
      failure = j["failure"].value("class", "") + ": " + j["failure"].value("message", "");
    if (j.is_object() && j.contains("files") && j["files"].is_array())
      for (const auto& f : j["files"])
        if (f.is_object() && f.value("path", "") == "certificate.json")
          cert = dress::certificate_from_json(client.get("/v1/jobs/" + id + "/files/certificate.json"),
                                              "job " + id + ": certificate.json");
  } catch (const std::exception& e) {
    finish("failed", "job " + id + " ended " + state + ", but its outcome could not be read: " + e.what());
    return;
  }
  if (!cert) {
    finish("failed", "job " + id + " " + (state.empty() ? "ended" : state) + (failure.empty() ? "" : ": " + failure) + seen);
    return;
  }
  {
    std::lock_guard lock(m_);
    cert_ = cert;
  }
  finish(cert->stop_reason == "error" ? "failed" : "done", outcome(*cert) + " on the server (job " + id + ")" + seen);
}

}  // namespace vgd::studio
