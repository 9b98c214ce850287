#pragma once
// The studio's drapes on a worker thread: here, dress::run_drape with a sink
// that keeps the latest frame for the live preview, progress for the bar, and
// a stop request honoured at the next frame; or on a vgd-server, its frames'
// stream read into the same preview. Private to src/studio.
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "vgd/mesh/surface.hpp"
#include "vgd/dress/drape.hpp"
#include "vgd/net/client.hpp"
#include "vgd/studio/studio.hpp"

namespace vgd::studio {

// What the preview needs of the cloth: its triangles once, positions per frame.
struct LiveCloth {
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> triangle_piece;
  std::vector<std::string> pieces;
  std::vector<std::array<double, 2>> uv;        // material coordinates, m (texture coordinates on export)
  std::vector<int> representative;              // seam merges so far (FrameSink::merged); empty = none
  std::vector<std::array<float, 3>> positions;  // m
  double t = 0;                                 // s simulated
};

// A drape the studio follows: its progress, the newest cloth and body for the
// preview, the certificate once it ends. Run here (DrapeJob) or on a
// vgd-server (RemoteJob); the studio draws both the same way.
class LiveJob {
 public:
  virtual ~LiveJob() = default;
  // Ends the run at the next frame (here) or cancels the job (server).
  virtual void request_stop() = 0;
  virtual void wait() = 0;
  // A drape run here can be held after a frame and run on frame by frame
  // (a server's runs on by itself: these do nothing there).
  virtual bool pausable() const { return false; }
  virtual void set_paused(bool) {}
  virtual void step() {}
  bool running() const;
  DrapeStatus status() const;

  // The newest geometry when it changed since the last call (else false).
  bool take_cloth(LiveCloth& out);
  bool take_body(mesh::SurfaceMesh& out);
  // The certificate once, when a run finished with one.
  std::optional<dress::Certificate> take_certificate();

 protected:
  // The run's start and end, for the status.
  void begin(double time_limit, const std::string& stage);
  void finish(const std::string& stage, const std::string& message);
  void show_body(body::Avatar avatar);

  mutable std::mutex m_;
  DrapeStatus status_;
  LiveCloth cloth_;
  bool cloth_new_ = false;
  std::optional<mesh::SurfaceMesh> body_;
  bool body_new_ = false;
  std::optional<dress::Certificate> cert_;
};

// The drape on a worker thread of this process.
class DrapeJob : public LiveJob {
 public:
  ~DrapeJob() override;
  // Starts the drape of `def` (threads: OpenMP threads of the engine). The
  // previous run must have finished.
  void start(scene::SceneDef def, int threads);
  void request_stop() override;
  void wait() override;
  bool pausable() const override { return true; }
  // Held after the next frame until resumed; step() lets one more frame through.
  void set_paused(bool paused) override;
  void step() override;

 private:
  void run(scene::SceneDef def, int threads);
  // Called after each frame on the run's thread: waits while paused.
  void hold_if_paused();

  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::condition_variable resume_;
  int steps_ = 0;  // frames let through while paused (guarded by m_)
};

// The drape as a job of a vgd-server (docs/server.md): submitted, then its
// frames' stream read on a worker thread into the preview as they come; the
// body is built here from the same definition (the server does not send it);
// the certificate is the job's certificate.json. Stopping cancels the job.
class RemoteJob : public LiveJob {
 public:
  ~RemoteJob() override;
  // `body`: the scene whose avatar is shown (the job's body); may have none.
  void start(net::Client client, net::JobRequest job, scene::SceneDef body, double time_limit);
  void request_stop() override;
  void wait() override;
  // The job's id once the server took it ("" before).
  std::string id() const;

 private:
  void run(net::Client client, net::JobRequest job, scene::SceneDef body);

  std::thread thread_, canceller_;
  std::optional<net::Client> client_;
  std::string id_;
  bool stop_ = false;  // under m_
};

}  // namespace vgd::studio
