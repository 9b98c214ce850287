#pragma once
// The simulation server on the network (docs/server.md): HTTP/1.1 with
// keep-alive (Boost.Beast) in front of net::Service. One thread per
// connection; a connection idle for 30 s is closed; a request body larger
// than the limit is answered 413 without being read.
#include <memory>
#include <string>

#include "vgd/net/service.hpp"

namespace vgd::net {

class HttpServer {
 public:
  // Binds host:port (port 0: any free port; see port()). Throws vgd::Error
  // naming the address when it cannot listen.
  HttpServer(Service& service, const std::string& host, unsigned short port, std::size_t max_body = 64u << 20);
  ~HttpServer();
  unsigned short port() const;
  // Serves until stop(). stop() may be called from any thread.
  void run();
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vgd::net
