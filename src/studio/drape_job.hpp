#pragma once
// The studio's drape on a worker thread: dress::run_drape with a sink that
// keeps the latest frame for the live preview, progress for the bar, and a
// stop request honoured at the next frame. Private to src/studio.
#include <atomic>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "vgd/mesh/surface.hpp"
#include "vgd/dress/drape.hpp"
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

class DrapeJob {
 public:
  ~DrapeJob();
  // Starts the drape of `def` (threads: OpenMP threads of the engine). The
  // previous run must have finished.
  void start(scene::SceneDef def, int threads);
  void request_stop() { stop_ = true; }
  void wait();
  bool running() const;
  DrapeStatus status() const;

  // The newest geometry when it changed since the last call (else false).
  bool take_cloth(LiveCloth& out);
  bool take_body(mesh::SurfaceMesh& out);
  // The certificate once, when a run finished with one.
  std::optional<dress::Certificate> take_certificate();

 private:
  void run(scene::SceneDef def, int threads);

  std::thread thread_;
  std::atomic<bool> stop_{false};
  mutable std::mutex m_;
  DrapeStatus status_;
  LiveCloth cloth_;
  bool cloth_new_ = false;
  std::optional<mesh::SurfaceMesh> body_;
  bool body_new_ = false;
  std::optional<dress::Certificate> cert_;
};

}  // namespace vgd::studio
