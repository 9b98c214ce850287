#pragma once
// A client of vgd-server (docs/server.md), for `vgd remote` and the studio:
// HTTP/1.1 requests and the live frames' WebSocket, over Boost.Beast.
#include <functional>
#include <string>
#include <string_view>

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
  void watch(const std::string& id, const std::function<void(const std::string& json_text)>& on_text,
             const std::function<void(const FrameMessage&)>& on_frame) const;

 private:
  ServerUrl url_;
  std::string token_;
};

}  // namespace vgd::net
