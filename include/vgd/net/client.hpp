#pragma once
// A client of vgd-server (docs/server.md), for `vgd remote` and the studio:
// HTTP/1.1 requests and the live frames' WebSocket, over Boost.Beast.
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "vgd/net/frames.hpp"

namespace vgd::net {

struct ServerUrl {
  std::string host = "127.0.0.1";
  std::string port = "8765";
};
// "http://host:port" (or "host:port"); throws vgd::Error for another scheme
// (https: put a reverse proxy's address here only over a trusted network).
ServerUrl parse_server_url(const std::string& url);

// Standard base64 (RFC 4648), for uploading a body file with a job.
std::string base64_encode(std::string_view bytes);

// A job as POST /v1/jobs takes it (docs/server.md, "Submit"): a garment
// (the document and the settings that differ from the server's defaults,
// empty or 0: not sent, with an uploaded body file when `avatar_name` is not
// empty), or a scene (`scene`: a scene file's JSON text, docs/scene.md; the
// other fields unused).
struct JobRequest {
  std::string name = "garment.xvc";  // the document's (or scene's) file name
  std::string document;              // the XVC text
  std::string scene;                 // or a self-contained scene's JSON text
  std::string size, quality, model, fabric, body_size, body_table;
  double time_limit = 0, spacing = 0;  // s simulated, m
  std::vector<std::string> outputs;    // certificate, trj, wvt, vrml, vrml-animated, glb, previews
  std::string avatar_name, avatar_bytes;  // a body file (its name and contents)
  std::string unit = "auto", up = "auto", facing = "auto";
};
std::string to_json(const JobRequest& job);

struct Reply {
  int status = 0;
  std::string content_type, body;
};

class Client {
 public:
  Client(ServerUrl url, std::string token = "");
  // One request; throws vgd::Error naming the server when it cannot be reached.
  Reply request(const std::string& method, const std::string& target, const std::string& body = "") const;
  // Reads /v1/jobs/{id}/frames to its end, calling back per message: text
  // messages as JSON text, frames parsed. Throws vgd::Error when the server
  // refuses the stream or cannot be reached.
  // Submits a job; returns its id. Throws vgd::Error with the server's
  // message when it refuses the job (400, 413, 429, ...).
  std::string submit(const JobRequest& job) const;
  // Asks the server to cancel a job; throws vgd::Error when it refuses.
  void cancel(const std::string& id) const;
  // GET `target` as JSON text; throws vgd::Error with the server's message
  // unless it answers 200.
  std::string get(const std::string& target) const;
  void watch(const std::string& id, const std::function<void(const std::string& json_text)>& on_text,
             const std::function<void(const FrameMessage&)>& on_frame) const;

 private:
  ServerUrl url_;
  std::string token_;
};

}  // namespace vgd::net
