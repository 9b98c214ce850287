// vgd-server's client (client.hpp). Beast here as in http.cpp.
#include "vgd/net/client.hpp"

#include <openssl/evp.h>

#include <utility>  // before Asio: Boost 1.74's awaitable.hpp uses std::exchange without it
#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include <nlohmann/json.hpp>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/version.hpp"

namespace vgd::net {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;

std::string base64_encode(std::string_view bytes) {
  std::string out(4 * ((bytes.size() + 2) / 3), '\0');
  const int n = EVP_EncodeBlock(reinterpret_cast<unsigned char*>(out.data()),
                                reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<int>(bytes.size()));
  out.resize(static_cast<std::size_t>(n));
  return out;
}

ServerUrl parse_server_url(const std::string& url) {
  std::string rest = url;
  if (rest.rfind("http://", 0) == 0) rest = rest.substr(7);
  else if (rest.find("://") != std::string::npos)
    throw Error(url, "", "only http:// addresses (TLS: a reverse proxy in front of vgd-server, docs/server.md)");
  while (!rest.empty() && rest.back() == '/') rest.pop_back();
  ServerUrl u;
  const auto colon = rest.rfind(':');
  if (colon == std::string::npos) {
    u.host = rest;
    u.port = "80";
  } else {
    u.host = rest.substr(0, colon);
    u.port = rest.substr(colon + 1);
  }
  if (u.host.size() > 2 && u.host.front() == '[' && u.host.back() == ']') u.host = u.host.substr(1, u.host.size() - 2);
  if (u.host.empty() || u.port.empty() || u.port.find_first_not_of("0123456789") != std::string::npos)
    throw Error(url, "", "not a server address (http://HOST:PORT)");
  return u;
}

Client::Client(ServerUrl url, std::string token) : url_(std::move(url)), token_(std::move(token)) {}

Reply Client::request(const std::string& method, const std::string& target, const std::string& body) const {
  asio::io_context ioc;
  tcp::resolver resolver(ioc);
  beast::tcp_stream stream(ioc);
  boost::system::error_code ec;
  const auto where = resolver.resolve(url_.host, url_.port, ec);
  if (!ec) stream.connect(where, ec);
  const std::string server = "http://" + url_.host + ":" + url_.port;
  if (ec) throw Error(server, "", "cannot reach the server: " + ec.message());
  http::request<http::string_body> req{http::string_to_verb(method), target, 11};
  req.set(http::field::host, url_.host);
  req.set(http::field::user_agent, std::string("vgd/") + kVersion);
  if (!token_.empty()) req.set(http::field::authorization, "Bearer " + token_);
  if (!body.empty()) req.set(http::field::content_type, "application/json");
  req.body() = body;
  req.prepare_payload();
  http::write(stream, req, ec);
  beast::flat_buffer buffer;
  http::response_parser<http::string_body> parser;
  parser.body_limit(std::uint64_t{1} << 32);
  if (!ec) http::read(stream, buffer, parser, ec);
  if (ec) throw Error(server, target, "no answer: " + ec.message());
  stream.socket().shutdown(tcp::socket::shutdown_both, ec);
  auto& res = parser.get();
  return {static_cast<int>(res.result_int()), std::string(res[http::field::content_type]), std::move(res.body())};
}

std::string to_json(const JobRequest& job) {
  using nlohmann::json;
  if (!job.scene.empty()) {
    json scene = json::parse(job.scene, nullptr, false);
    if (scene.is_discarded()) throw Error(job.name, "", "not JSON (a scene file is, docs/scene.md)");
    return json{{"name", job.name}, {"scene", scene}}.dump(-1, ' ', false, json::error_handler_t::replace);
  }
  json settings = json::object();
  if (!job.size.empty()) settings["size"] = job.size;
  if (!job.quality.empty()) settings["quality"] = job.quality;
  if (job.time_limit > 0) settings["time_limit"] = job.time_limit;
  if (job.spacing > 0) settings["spacing"] = job.spacing;
  if (!job.model.empty()) settings["model"] = job.model;
  if (!job.fabric.empty()) settings["fabric"] = job.fabric;
  if (!job.body_size.empty()) settings["body_size"] = job.body_size;
  if (!job.body_table.empty()) settings["body_table"] = job.body_table;
  if (!job.outputs.empty()) settings["outputs"] = job.outputs;
  json req = {{"name", job.name}, {"document", job.document}, {"settings", settings}};
  if (!job.avatar_name.empty())
    req["avatar"] = {{"name", job.avatar_name},
                     {"data", base64_encode(job.avatar_bytes)},
                     {"unit", job.unit},
                     {"up", job.up},
                     {"facing", job.facing}};
  return req.dump(-1, ' ', false, json::error_handler_t::replace);
}

namespace {

// The server's error message ({"error": "..."}), else its body.
std::string refusal(const Reply& r) {
  const auto j = nlohmann::json::parse(r.body, nullptr, false);
  if (j.is_object() && j.contains("error") && j["error"].is_string()) return j["error"].get<std::string>();
  return r.body.substr(0, 300);
}

}  // namespace

std::string Client::submit(const JobRequest& job) const {
  const Reply r = request("POST", "/v1/jobs", to_json(job));
  if (r.status != 202 && r.status != 200)
    throw Error(job.name, "", "the server refused the job (HTTP " + std::to_string(r.status) + "): " + refusal(r));
  const auto j = nlohmann::json::parse(r.body, nullptr, false);
  if (!j.is_object() || !j.contains("id") || !j["id"].is_string())
    throw Error("http://" + url_.host + ":" + url_.port, "/v1/jobs", "the answer has no job id: " + r.body.substr(0, 200));
  return j["id"].get<std::string>();
}

void Client::cancel(const std::string& id) const {
  const Reply r = request("POST", "/v1/jobs/" + id + "/cancel");
  if (r.status != 200 && r.status != 202)
    throw Error("job " + id, "", "the server refused to cancel it (HTTP " + std::to_string(r.status) + "): " + refusal(r));
}

std::string Client::get(const std::string& target) const {
  const Reply r = request("GET", target);
  if (r.status != 200)
    throw Error("http://" + url_.host + ":" + url_.port, target,
                "HTTP " + std::to_string(r.status) + ": " + refusal(r));
  return r.body;
}

void Client::watch(const std::string& id, const std::function<void(const std::string&)>& on_text,
                   const std::function<void(const FrameMessage&)>& on_frame) const {
  asio::io_context ioc;
  tcp::resolver resolver(ioc);
  websocket::stream<tcp::socket> ws(ioc);
  boost::system::error_code ec;
  const std::string server = "http://" + url_.host + ":" + url_.port;
  const auto where = resolver.resolve(url_.host, url_.port, ec);
  if (!ec) asio::connect(ws.next_layer(), where, ec);
  if (ec) throw Error(server, "", "cannot reach the server: " + ec.message());
  ws.set_option(websocket::stream_base::decorator([this](websocket::request_type& req) {
    req.set(http::field::user_agent, std::string("vgd/") + kVersion);
    if (!token_.empty()) req.set(http::field::authorization, "Bearer " + token_);
  }));
  websocket::response_type res;
  ws.handshake(res, url_.host, "/v1/jobs/" + id + "/frames", ec);
  if (ec)
    throw Error(server, "job " + id, "the server refused the frames' stream (HTTP " +
                                         std::to_string(res.result_int()) + "): " + res.body());
  for (;;) {
    beast::flat_buffer buf;
    ws.read(buf, ec);
    if (ec) break;  // closed at the end
    const std::string msg = beast::buffers_to_string(buf.data());
    if (ws.got_binary()) on_frame(parse_frame_message(msg));
    else on_text(msg);
  }
}

}  // namespace vgd::net
