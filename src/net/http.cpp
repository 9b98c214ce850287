// HTTP/1.1 for the simulation server, with Boost.Beast (http.hpp). The only
// translation unit that includes Beast and Asio.
#include "vgd/net/http.hpp"

#include <sys/socket.h>

#include <atomic>
#include <utility>  // before Asio: Boost 1.74's awaitable.hpp uses std::exchange without it
#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <thread>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/version.hpp"

namespace vgd::net {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using tcp = asio::ip::tcp;

struct HttpServer::Impl {
  Service& service;
  std::size_t max_body;
  asio::io_context ioc;
  tcp::acceptor acceptor{ioc};
  std::atomic<int> connections{0};

  Impl(Service& s, std::size_t limit) : service(s), max_body(limit) {}

  void accept() {
    acceptor.async_accept([this](boost::system::error_code ec, tcp::socket socket) {
      if (ec) {
        if (ec != asio::error::operation_aborted && acceptor.is_open()) accept();
        return;
      }
      // An idle or slow client cannot hold its thread for ever.
      timeval tv{30, 0};
      ::setsockopt(socket.native_handle(), SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
      ::setsockopt(socket.native_handle(), SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
      std::thread([this, s = std::move(socket)]() mutable {
        try {
          serve(std::move(s));
        } catch (const std::exception&) {
          // A connection's failure ends that connection only.
        }
      }).detach();
      accept();
    });
  }

  void serve(tcp::socket socket) {
    ++connections;
    beast::flat_buffer buffer;
    boost::system::error_code ec;
    for (;;) {
      http::request_parser<http::string_body> parser;
      parser.body_limit(max_body);
      http::read(socket, buffer, parser, ec);
      if (ec == http::error::end_of_stream || ec == asio::error::eof || ec == asio::error::connection_reset) break;
      if (ec == http::error::body_limit) {
        write(socket, 413, R"({"error": "the request body is larger than the server's limit"})" "\n", false, ec);
        break;
      }
      if (ec) {
        if (ec != asio::error::would_block && ec != asio::error::try_again && ec != asio::error::timed_out)
          write(socket, 400, "{\"error\": \"not an HTTP request: " + ec.message() + "\"}\n", false, ec);
        break;
      }
      auto& req = parser.get();
      Request r{std::string(req.method_string()), std::string(req.target()), req.body(),
                std::string(req[http::field::authorization])};
      Response out = service.handle(r);
      std::string body = std::move(out.body);
      if (!out.file.empty()) {
        try {
          body = read_file(out.file);
        } catch (const Error& e) {
          out.status = 500, out.content_type = "application/json";
          body = std::string("{\"error\": \"cannot read the result file\"}\n");
        }
      }
      const bool keep = req.keep_alive();
      write(socket, out.status, body, keep, ec, out.content_type, req.version(), req.method() == http::verb::head);
      if (ec || !keep) break;
    }
    socket.shutdown(tcp::socket::shutdown_send, ec);
    --connections;
  }

  static void write(tcp::socket& socket, int status, const std::string& body, bool keep, boost::system::error_code& ec,
                    const std::string& type = "application/json", unsigned version = 11, bool head = false) {
    http::response<http::string_body> res{static_cast<http::status>(status), version};
    res.set(http::field::server, std::string("vgd-server/") + kVersion);
    res.set(http::field::content_type, type);
    res.keep_alive(keep);
    res.body() = head ? std::string() : body;
    res.prepare_payload();
    http::write(socket, res, ec);
  }
};

HttpServer::HttpServer(Service& service, const std::string& host, unsigned short port, std::size_t max_body)
    : impl_(std::make_unique<Impl>(service, max_body)) {
  boost::system::error_code ec;
  const auto address = asio::ip::make_address(host, ec);
  if (ec) throw Error(host, "", "not an IP address: " + ec.message());
  const tcp::endpoint ep{address, port};
  auto& a = impl_->acceptor;
  a.open(ep.protocol(), ec);
  if (!ec) a.set_option(asio::socket_base::reuse_address(true), ec);
  if (!ec) a.bind(ep, ec);
  if (!ec) a.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) throw Error(host + ":" + std::to_string(port), "", "cannot listen: " + ec.message());
}

HttpServer::~HttpServer() = default;

unsigned short HttpServer::port() const { return impl_->acceptor.local_endpoint().port(); }

void HttpServer::run() {
  impl_->accept();
  impl_->ioc.run();
}

void HttpServer::stop() {
  asio::post(impl_->ioc, [this] {
    boost::system::error_code ec;
    impl_->acceptor.close(ec);
  });
  impl_->ioc.stop();
}

}  // namespace vgd::net
