// libFuzzer target for vgd-server's request handling (docs/server.md):
// any method, target and body answered by net::Service::handle with a status
// and a JSON (or text) answer — never a crash, never a job accepted from a
// request that is not a valid submission. The input is split at the first
// two newlines: METHOD \n TARGET \n BODY. The service runs no worker (its
// vgd is /bin/false) and keeps its database in a temporary folder.
// Build: make fuzz; run: build-fuzz/tests/fuzz/vgd_fuzz_server_requests tests/fuzz/corpus/server
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "vgd/net/service.hpp"

namespace {

vgd::net::Service& service() {
  static std::unique_ptr<vgd::net::Service> s = [] {
    vgd::net::ServiceOptions o;
    o.data = std::filesystem::temp_directory_path() / ("vgd-fuzz-server-" + std::to_string(::getpid()));
    o.exe = "/bin/false";
    o.workers = 1;
    o.max_queued = 1 << 30;
    o.max_per_client = 1 << 30;
    return std::make_unique<vgd::net::Service>(o);
  }();
  return *s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string in(reinterpret_cast<const char*>(data), size);
  const auto a = in.find('\n');
  const auto b = a == std::string::npos ? std::string::npos : in.find('\n', a + 1);
  vgd::net::Request r;
  r.method = in.substr(0, a);
  r.target = a == std::string::npos ? "" : in.substr(a + 1, b == std::string::npos ? std::string::npos : b - a - 1);
  r.body = b == std::string::npos ? "" : in.substr(b + 1);
  const auto res = service().handle(r);
  if (res.status < 200 || res.status > 599) __builtin_trap();
  if (res.body.empty() && res.file.empty()) __builtin_trap();  // every answer says something
  return 0;
}
