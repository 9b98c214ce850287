// HTTP/1.1 for the simulation server, with Boost.Beast (http.hpp). The only
// translation unit that includes Beast and Asio.
#include "vgd/net/http.hpp"

#include <sys/socket.h>

#include <atomic>
#include <cctype>
#include <cstring>
#include <functional>
#include <utility>  // before Asio: Boost 1.74's awaitable.hpp uses std::exchange without it
#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <nlohmann/json.hpp>
#include <thread>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/version.hpp"
#include "vgd/io/trj/trj.hpp"
#include "vgd/net/frames.hpp"

namespace vgd::net {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
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
    boost::system::error_code aec;
    const auto remote = socket.remote_endpoint(aec);
    const std::string client = aec ? std::string("?") : remote.address().to_string();
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
      if (websocket::is_upgrade(req) || is_frames_target(std::string(req.target()))) {
        stream_frames(std::move(socket), req);
        return;
      }
      Request r{std::string(req.method_string()), std::string(req.target()), req.body(),
                std::string(req[http::field::authorization]), client};
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

  // GET /v1/jobs/{id}/frames as a WebSocket (frames.hpp): the topology, the
  // latest frame, then each new one as the worker writes it to the job's
  // trajectory; a viewer more than kBehind frames behind skips to the
  // latest and is told how many it skipped (the frames a worker writes
  // between two looks, 100 ms apart, are far fewer).
  void stream_frames(tcp::socket socket, const http::request<http::string_body>& req) {
    boost::system::error_code ec;
    const std::string full(req.target());
    const std::string target = full.substr(0, full.find('?'));
    const std::string query = full.size() > target.size() ? full.substr(target.size() + 1) : "";
    const std::string prefix = "/v1/jobs/", suffix = "/frames";
    std::string id;
    if (target.rfind(prefix, 0) == 0 && target.size() > prefix.size() + suffix.size() &&
        target.compare(target.size() - suffix.size(), suffix.size(), suffix) == 0)
      id = target.substr(prefix.size(), target.size() - prefix.size() - suffix.size());
    // A browser's WebSocket cannot send headers: the token may come as ?token=.
    std::string authorization(req[http::field::authorization]);
    if (authorization.empty() && query.rfind("token=", 0) == 0) {
      std::string t;
      const std::string v = query.substr(6, query.find('&') == std::string::npos ? std::string::npos : query.find('&') - 6);
      for (std::size_t k = 0; k < v.size(); ++k) {
        if (v[k] == '%' && k + 2 < v.size() && std::isxdigit(static_cast<unsigned char>(v[k + 1])) &&
            std::isxdigit(static_cast<unsigned char>(v[k + 2]))) {
          t += static_cast<char>(std::stoi(v.substr(k + 1, 2), nullptr, 16));
          k += 2;
        } else {
          t += v[k] == '+' ? ' ' : v[k];
        }
      }
      authorization = "Bearer " + t;
    }
    if (auto refused = service.check_token(authorization)) {
      write(socket, refused->status, refused->body, false, ec);
      return;
    }
    const auto where = id.empty() ? std::nullopt : service.trajectory(id);
    if (!where) {
      write(socket, 404, "{\"error\": \"no job's frames at " + target + "\"}\n", false, ec);
      return;
    }
    if (websocket::is_upgrade(req)) {
      websocket::stream<tcp::socket> ws(std::move(socket));
      ws.accept(req, ec);
      if (ec) return;
      pump(id, [&](bool binary, const std::string& msg) {
        ws.binary(binary);
        ws.write(asio::buffer(msg), ec);
        return !ec;
      });
      ws.close(websocket::close_code::normal, ec);
      return;
    }
    // The chunked-HTTP fallback, for clients without WebSocket: the same
    // messages, each as [u32 length][u8 kind: 0 text, 1 binary][payload].
    http::response<http::empty_body> res{http::status::ok, req.version()};
    res.set(http::field::server, std::string("vgd-server/") + kVersion);
    res.set(http::field::content_type, "application/x-vgd-frames");
    res.chunked(true);
    res.keep_alive(false);
    http::response_serializer<http::empty_body> sr{res};
    http::write_header(socket, sr, ec);
    if (ec) return;
    pump(id, [&](bool binary, const std::string& msg) {
      std::string framed(5, '\0');
      const auto n = static_cast<std::uint32_t>(msg.size());
      std::memcpy(framed.data(), &n, 4);
      framed[4] = binary ? 1 : 0;
      framed += msg;
      asio::write(socket, http::make_chunk(asio::buffer(framed)), ec);
      return !ec;
    });
    asio::write(socket, http::make_chunk_last(), ec);
    socket.shutdown(tcp::socket::shutdown_send, ec);
  }

  static bool is_frames_target(const std::string& full) {
    const std::string target = full.substr(0, full.find('?'));
    return target.rfind("/v1/jobs/", 0) == 0 && target.size() > 16 &&
           target.compare(target.size() - 7, 7, "/frames") == 0;
  }

  // The frames of job `id`, sent as messages (frames.hpp) until the job ends.
  void pump(const std::string& id, const std::function<bool(bool binary, const std::string&)>& send) {
    constexpr int kBehind = 64;
    bool topology_sent = false;
    int next = -1;  // the next frame to send; -1: not decided until the first look at the file
    bool first_look = true;
    std::string last_progress;
    bool ok = true;
    long long sent = 0, dropped = 0;
    int frames = 0;
    std::string state;
    for (;;) {
      const auto t = service.trajectory(id);
      if (!t) break;
      state = t->state;
      std::error_code fec;
      const bool there = std::filesystem::exists(t->file, fec);
      if (first_look && !there) next = 0;  // here before the first frame: every frame from the first
      first_look = false;
      if (there) {
        try {
          const io::trj::TrjReader reader(t->file);
          frames = reader.frame_count();
          if (!topology_sent) {
            if (!send(false, topology_message(reader.topology()))) ok = false;
            if (!ok) break;
            topology_sent = true;
          }
          if (frames > 0) {
            if (next < 0) next = frames - 1;  // a viewer that joined late: the latest first
            if (frames - next > kBehind) {    // behind: skip to the latest
              dropped += frames - 1 - next;
              const nlohmann::json d = {{"type", "dropped"}, {"count", frames - 1 - next}, {"total", dropped}};
              ok = send(false, d.dump());
              next = frames - 1;
            }
            for (; next < frames && ok; ++next) {
              ok = send(true, frame_message(static_cast<std::uint32_t>(next), reader.time(next), reader.positions(next)));
              ++sent;
            }
            if (!ok) break;
          }
        } catch (const Error&) {
          // A frame still being written, or a file renamed under us: read again.
        }
      }
      if (!t->finished) {
        // The stage, seams and energy with the frames (for a progress bar).
        const std::string p = service.progress(id);
        if (!p.empty() && p != last_progress) {
          if (!send(false, "{\"type\": \"progress\", \"progress\": " + p + "}")) break;
          last_progress = p;
        }
      }
      if (t->finished) {
        // The last look after the job ended: nothing more will come.
        const auto again = service.trajectory(id);
        if (again && again->file == t->file) break;
        continue;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    const nlohmann::json end = {{"type", "end"}, {"state", state}, {"frames", frames}, {"sent", sent}, {"dropped", dropped}};
    if (ok) send(false, end.dump());
    service.count_stream(sent, dropped);
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
