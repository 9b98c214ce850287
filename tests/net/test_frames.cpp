// Live frames over WebSocket (docs/server.md, "Live frames"): a viewer that
// connects as the job is submitted gets the topology and every frame (or is
// told how many it skipped), each with a good checksum, in order, up to the
// last frame of the stored trajectory; a viewer that joins after the end
// gets the latest frame first. The frame message round-trips.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <cstring>
#include <fcntl.h>
#include <thread>
#include <utility>  // before Asio (Boost 1.74)
#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

#include "support/server_process.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/io/trj/trj.hpp"
#include "vgd/net/frames.hpp"

namespace vgd::test {
namespace {

namespace fs = std::filesystem;
namespace asio = boost::asio;
namespace beast = boost::beast;
namespace websocket = beast::websocket;
using nlohmann::json;

struct Stream {
  json topology, end;
  std::vector<net::FrameMessage> frames;
  long long dropped = 0;
};

// Reads a job's live frames to the end. A slow viewer: a 4 kB receive
// buffer, and nothing read until `before_reading` returns.
Stream watch(int port, const std::string& id, const std::function<void()>& before_reading = {}) {
  Stream s;
  asio::io_context ioc;
  asio::ip::tcp::resolver resolver(ioc);
  websocket::stream<asio::ip::tcp::socket> ws(ioc);
  if (before_reading) {
    ws.next_layer().open(asio::ip::tcp::v4());
    ws.next_layer().set_option(asio::socket_base::receive_buffer_size(4096));
  }
  ws.next_layer().connect({asio::ip::make_address("127.0.0.1"), static_cast<unsigned short>(port)});
  ws.handshake("127.0.0.1", "/v1/jobs/" + id + "/frames");
  if (before_reading) before_reading();
  for (;;) {
    beast::flat_buffer buf;
    boost::system::error_code ec;
    ws.read(buf, ec);
    if (ec) break;
    const std::string msg = beast::buffers_to_string(buf.data());
    if (ws.got_binary()) {
      s.frames.push_back(net::parse_frame_message(msg));
      continue;
    }
    const json j = json::parse(msg);
    if (j["type"] == "topology") s.topology = j;
    if (j["type"] == "dropped") s.dropped += j["count"].get<long long>();
    if (j["type"] == "end") s.end = j;
  }
  return s;
}

// Minimal HTTP (Connection: close) for the submit and the download.
std::string http(int port, const std::string& method, const std::string& target, const std::string& body = "") {
  asio::io_context ioc;
  asio::ip::tcp::socket sock(ioc);
  sock.connect({asio::ip::make_address("127.0.0.1"), static_cast<unsigned short>(port)});
  const std::string req = method + " " + target + " HTTP/1.1\r\nHost: x\r\nConnection: close\r\nContent-Length: " +
                          std::to_string(body.size()) + "\r\n\r\n" + body;
  asio::write(sock, asio::buffer(req));
  std::string in;
  boost::system::error_code ec;
  char b[65536];
  for (std::size_t n; (n = sock.read_some(asio::buffer(b), ec)) > 0 || !ec;) in.append(b, n);
  const auto at = in.find("\r\n\r\n");
  return at == std::string::npos ? "" : in.substr(at + 4);
}

// The shipped skirt, coarse and quick, recording its trajectory.
json skirt_job() {
  return {{"name", "skirt.xvc"},
          {"document", read_file(source_dir() / "data/garments/a-line-skirt.xvc")},
          {"settings",
           {{"size", "38"}, {"quality", "preview"}, {"spacing", 0.03}, {"time_limit", 3},
            {"outputs", {"certificate", "trj"}}}}};
}

TEST(ServerFrames, AViewerGetsEveryFrameInOrderWithItsChecksum) {
  const auto dir = scratch_dir("net-frames");
  ServerProcess server(dir);
  const int port = server.port;
  ASSERT_GT(port, 0);
  const json job = skirt_job();
  const std::string id = json::parse(http(port, "POST", "/v1/jobs", job.dump()))["id"];
  const Stream live = watch(port, id);
  EXPECT_EQ(live.end["state"], "passed") << live.end.dump();
  EXPECT_GT(live.topology["particles"].get<int>(), 500);
  EXPECT_EQ(live.topology["triangles"].size() % 3, 0u);
  const int frames = live.end["frames"];
  ASSERT_GT(frames, 5);
  ASSERT_FALSE(live.frames.empty());
  for (std::size_t k = 0; k < live.frames.size(); ++k) {
    EXPECT_TRUE(live.frames[k].checksum_ok) << k;
    EXPECT_EQ(live.frames[k].positions.size(), 3u * live.topology["particles"].get<std::size_t>());
    if (k > 0) {
      EXPECT_GT(live.frames[k].seq, live.frames[k - 1].seq);
    }
  }
  EXPECT_EQ(live.frames.front().seq, 0u) << "connected before the first frame: every frame from the first";
  EXPECT_EQ(live.frames.back().seq, static_cast<std::uint32_t>(frames - 1));
  EXPECT_EQ(static_cast<long long>(live.frames.size()) + live.dropped, frames) << "each frame sent or counted as skipped";
  EXPECT_EQ(live.end["sent"].get<long long>(), static_cast<long long>(live.frames.size()));
  // The stored trajectory holds every frame, and the last one is the one streamed last.
  const std::string trj = http(port, "GET", "/v1/jobs/" + id + "/files/drape.trj");
  const auto reader = io::trj::TrjReader::from_bytes(trj, "drape.trj");
  EXPECT_EQ(reader.frame_count(), frames);
  EXPECT_EQ(reader.positions(frames - 1), live.frames.back().positions);
  // A viewer joining after the end: the topology and the latest frame.
  const Stream late = watch(port, id);
  ASSERT_EQ(late.frames.size(), 1u);
  EXPECT_EQ(late.frames[0].seq, static_cast<std::uint32_t>(frames - 1));
  EXPECT_EQ(late.end["state"], "passed");
  // The chunked-HTTP fallback (no WebSocket): the same messages, each
  // [u32 length][u8 kind][payload].
  {
    FILE* p = popen(("curl -s http://127.0.0.1:" + std::to_string(port) + "/v1/jobs/" + id + "/frames").c_str(), "r");
    ASSERT_NE(p, nullptr);
    std::string raw;
    char buf[65536];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) raw.append(buf, n);
    pclose(p);
    std::vector<std::pair<int, std::string>> messages;
    for (std::size_t at = 0; at + 5 <= raw.size();) {
      std::uint32_t n = 0;
      std::memcpy(&n, raw.data() + at, 4);
      ASSERT_LE(at + 5 + n, raw.size());
      messages.emplace_back(raw[at + 4], raw.substr(at + 5, n));
      at += 5 + n;
    }
    ASSERT_EQ(messages.size(), 3u) << "topology, the latest frame, end";
    EXPECT_EQ(json::parse(messages[0].second)["type"], "topology");
    EXPECT_EQ(messages[1].first, 1);
    const auto f = net::parse_frame_message(messages[1].second);
    EXPECT_TRUE(f.checksum_ok);
    EXPECT_EQ(f.seq, static_cast<std::uint32_t>(frames - 1));
    EXPECT_EQ(json::parse(messages[2].second)["state"], "passed");
  }
}

// Two viewers on one job get the same frames; a job cancelled while they
// watch ends both streams with "cancelled".
TEST(ServerFrames, TwoViewersOnOneJobAndACancelWhileStreaming) {
  const auto dir = scratch_dir("net-frames-two");
  ServerProcess server(dir);
  const int port = server.port;
  ASSERT_GT(port, 0);
  const json job = skirt_job();
  // Both watch one job to its end.
  const std::string a = json::parse(http(port, "POST", "/v1/jobs", job.dump()))["id"];
  Stream first, second;
  std::thread t1([&] { first = watch(port, a); });
  std::thread t2([&] { second = watch(port, a); });
  t1.join();
  t2.join();
  EXPECT_EQ(first.end["state"], "passed");
  EXPECT_EQ(second.end["state"], "passed");
  ASSERT_FALSE(first.frames.empty());
  ASSERT_FALSE(second.frames.empty());
  EXPECT_EQ(first.frames.back().seq, second.frames.back().seq);
  EXPECT_EQ(first.frames.back().positions, second.frames.back().positions);
  // A job cancelled while streaming: the stream ends, saying so.
  json longer = job;
  longer["settings"]["time_limit"] = 30;
  longer["settings"]["quality"] = "precise";
  const std::string b = json::parse(http(port, "POST", "/v1/jobs", longer.dump()))["id"];
  Stream cancelled;
  std::thread t3([&] { cancelled = watch(port, b); });
  for (int i = 0; i < 300; ++i) {
    const json j = json::parse(http(port, "GET", "/v1/jobs/" + b), nullptr, false);
    if (j.is_object() && j.contains("progress") && j["progress"].is_object()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  http(port, "POST", "/v1/jobs/" + b + "/cancel");
  t3.join();
  EXPECT_EQ(cancelled.end["state"], "cancelled") << cancelled.end.dump();
}

// A scene job streams as a drape does: every frame of `vgd simulate`'s
// trajectory, in order, the last one the stored one; its progress says it is
// simulating.
TEST(ServerFrames, ASceneJobStreamsEveryFrame) {
  const auto dir = scratch_dir("net-frames-scene");
  ServerProcess server(dir);
  const int port = server.port;
  ASSERT_GT(port, 0);
  const json scene = json::parse(read_file(source_dir() / "data/scenes/cloth-on-sphere.json"));
  const std::string id = json::parse(http(port, "POST", "/v1/jobs", json{{"scene", scene}}.dump()))["id"];
  const Stream live = watch(port, id);
  EXPECT_EQ(live.end["state"], "passed") << live.end.dump();
  EXPECT_EQ(live.topology["particles"], 400);
  EXPECT_EQ(live.topology["triangles"].size(), 3u * 722u);
  ASSERT_EQ(live.end["frames"], 13);
  ASSERT_FALSE(live.frames.empty());
  for (const auto& f : live.frames) EXPECT_TRUE(f.checksum_ok);
  // A viewer that finds frames already written starts at the latest (a late
  // joiner): from there on, each frame sent or counted as skipped.
  EXPECT_EQ(static_cast<long long>(live.frames.size()) + live.dropped, 13 - live.frames.front().seq);
  const std::string trj = http(port, "GET", "/v1/jobs/" + id + "/files/scene.trj");
  const auto reader = io::trj::TrjReader::from_bytes(trj, "scene.trj");
  EXPECT_EQ(reader.positions(12), live.frames.back().positions);
  // The cloth came to rest on the sphere (radius 0.15 m): its centre particle
  // sits on the top, not fallen past it.
  const auto& x = live.frames.back().positions;
  const std::size_t centre = 10 * 20 + 10;
  EXPECT_NEAR(x[3 * centre + 1], 0.15, 0.02);
}

// A viewer that reads far slower than the frames come (here: not at all
// until the job has ended) is told how many frames it skipped, still gets
// the last one, and slows nothing: the job ends while it is not reading, a
// viewer beside it keeps up, and the stored trajectory has every frame.
TEST(ServerFrames, ASlowViewerIsToldWhatItSkippedAndSlowsNothing) {
  const auto dir = scratch_dir("net-frames-slow");
  ServerProcess server(dir);
  const int port = server.port;
  ASSERT_GT(port, 0);
  // 251 frames of 3 600 particles (43 kB each, 10.8 MB in all: more than
  // loopback's socket buffers hold for a viewer that does not read).
  json scene = json::parse(read_file(source_dir() / "data/scenes/cloth-on-sphere.json"));
  scene["cloth"][0]["grid"]["particles"] = {60, 60};
  scene["frames"] = {{"fps", 100}, {"duration", "2.5 s"}};
  const std::string id = json::parse(http(port, "POST", "/v1/jobs", json{{"scene", scene}}.dump()))["id"];
  auto finished = [&] {
    const json j = json::parse(http(port, "GET", "/v1/jobs/" + id), nullptr, false);
    const std::string st = j.is_object() ? j.value("state", "") : "";
    return st == "passed" || st == "failed";
  };
  Stream slow, fast;
  bool ended_while_not_reading = false;
  std::thread t1([&] {
    slow = watch(port, id, [&] {
      for (int i = 0; i < 1200 && !finished(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
      ended_while_not_reading = finished();
    });
  });
  std::thread t2([&] { fast = watch(port, id); });
  t1.join();
  t2.join();
  EXPECT_TRUE(ended_while_not_reading) << "the job ran to its end while a viewer did not read";
  const std::string trj = http(port, "GET", "/v1/jobs/" + id + "/files/scene.trj");
  const auto reader = io::trj::TrjReader::from_bytes(trj, "scene.trj");
  ASSERT_EQ(reader.frame_count(), 251) << "0 to 2.5 s at 100 fps";
  EXPECT_EQ(slow.end["frames"], 251);
  EXPECT_GT(slow.dropped, 0) << "the slow viewer was told it skipped frames";
  ASSERT_FALSE(slow.frames.empty());
  // From the frame it joined at (the latest one written when it first looked,
  // if any were), each frame sent or counted as skipped.
  EXPECT_EQ(static_cast<long long>(slow.frames.size()) + slow.dropped, 251 - slow.frames.front().seq)
      << "each frame sent or counted as skipped";
  EXPECT_EQ(slow.frames.back().seq, 250u);
  EXPECT_EQ(slow.frames.back().positions, reader.positions(250));
  for (const auto& f : slow.frames) EXPECT_TRUE(f.checksum_ok);
  // The viewer beside it reads as the frames come (here it gets every one;
  // on a machine too busy to run its thread for half a second it may skip
  // some, and is told): the slow one did not hold it back.
  ASSERT_FALSE(fast.frames.empty());
  EXPECT_LT(fast.dropped, slow.dropped);
  EXPECT_EQ(static_cast<long long>(fast.frames.size()) + fast.dropped, 251 - fast.frames.front().seq);
  EXPECT_EQ(fast.frames.back().seq, 250u);
}

TEST(ServerFrames, AFrameMessageRoundTripsAndACorruptOneIsSeen) {
  const std::vector<float> x = {0.1f, 0.2f, 0.3f, -1.5f, 2.25f, 1e-3f};
  std::string m = net::frame_message(7, 0.28, x);
  EXPECT_EQ(m.size(), 24u + 6 * 4);
  auto f = net::parse_frame_message(m);
  EXPECT_EQ(f.seq, 7u);
  EXPECT_DOUBLE_EQ(f.t, 0.28);
  EXPECT_EQ(f.positions, x);
  EXPECT_TRUE(f.checksum_ok);
  m[30] ^= 1;
  EXPECT_FALSE(net::parse_frame_message(m).checksum_ok);
  EXPECT_THROW(net::parse_frame_message(m.substr(0, 30)), Error);
  EXPECT_THROW(net::parse_frame_message("VGDX" + m.substr(4)), Error);
}

}  // namespace
}  // namespace vgd::test
