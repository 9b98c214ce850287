#include "drape_job.hpp"

#include <omp.h>

#include <cstdio>
#include <cstdlib>
#include <exception>

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

}  // namespace

DrapeJob::~DrapeJob() {
  request_stop();
  wait();
}

void DrapeJob::start(scene::SceneDef def, int threads) {
  wait();
  stop_ = false;
  {
    std::lock_guard lock(m_);
    status_ = {};
    status_.running = true;
    status_.stage = "placing";
    status_.time_limit = def.run.duration;
    cert_.reset();
  }
  thread_ = std::thread([this, def = std::move(def), threads]() mutable { run(std::move(def), threads); });
}

void DrapeJob::wait() {
  if (thread_.joinable()) thread_.join();
}

bool DrapeJob::running() const {
  std::lock_guard lock(m_);
  return status_.running;
}

DrapeStatus DrapeJob::status() const {
  std::lock_guard lock(m_);
  return status_;
}

bool DrapeJob::take_cloth(LiveCloth& out) {
  std::lock_guard lock(m_);
  if (!cloth_new_) return false;
  out = cloth_;
  cloth_new_ = false;
  return true;
}

bool DrapeJob::take_body(mesh::SurfaceMesh& out) {
  std::lock_guard lock(m_);
  if (!body_new_ || !body_) return false;
  out = *body_;
  body_new_ = false;
  return true;
}

std::optional<dress::Certificate> DrapeJob::take_certificate() {
  std::lock_guard lock(m_);
  auto c = std::move(cert_);
  cert_.reset();
  return c;
}

void DrapeJob::run(scene::SceneDef def, int threads) {
  omp_set_num_threads(threads > 0 ? threads : omp_get_num_procs());
  auto finish = [&](const std::string& stage, const std::string& message) {
    std::lock_guard lock(m_);
    status_.running = false;
    status_.stage = stage;
    status_.message = message;
  };
  try {
    if (def.avatar) {
      // The body first, so the preview shows it while the garment is placed.
      body::Avatar avatar = scene::build_avatar(def);
      std::lock_guard lock(m_);
      status_.body_notes = avatar.notes;
      body_ = std::move(avatar.surface);
      body_new_ = true;
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
      }
      if (stop_) throw StopRequested{};
    };
    dress::DrapeResult r = dress::run_drape(def, {&sink}, progress);
    const auto& c = r.certificate;
    std::string msg = c.stop_reason == "error"
                          ? "the drape failed: " + c.stop_message
                          : "stopped at " + c.stop_reason + " after " + format_fixed(c.simulated_s, 2) + " s simulated (" +
                                format_fixed(c.wall_s, 1) + " s wall); " + std::to_string(c.triangle_intersections) +
                                " crossing triangle pairs, max penetration " +
                                format_fixed(c.max_penetration * 1000, 2) + " mm";
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

}  // namespace vgd::studio
