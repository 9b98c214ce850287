// 3-D model files through the vgd_assimp module, opened on first use
// (model_file.hpp).
#include "vgd/body/model_file.hpp"

#include <dlfcn.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstring>

#include <cstdlib>
#include <mutex>
#include <string>
#include <thread>

#include "assimp/module_api.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"

namespace vgd::body {

namespace {

namespace fs = std::filesystem;

constexpr const char* kModule = "libvgd_assimp.so";

// Opens the module once per process and keeps it open. Throws vgd::Error
// naming `file` and the places tried when it cannot be opened.
const assimp_module::Api& api(const std::string& file) {
  static std::once_flag once;
  static const assimp_module::Api* found = nullptr;
  static std::string problem;
  std::call_once(once, [] {
    std::string tried;
    std::vector<fs::path> dirs;
    if (const char* env = std::getenv("VGD_MODULE_DIR"); env && *env) dirs.emplace_back(env);
    dirs.emplace_back(VGD_BUILD_MODULE_DIR);
    dirs.emplace_back(VGD_INSTALL_MODULE_DIR);
    for (const auto& d : dirs) {
      const fs::path p = d / kModule;
      std::error_code ec;
      if (!fs::is_regular_file(p, ec)) {
        tried += (tried.empty() ? "" : ", ") + p.string();
        continue;
      }
      void* lib = ::dlopen(p.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!lib) {
        const char* e = ::dlerror();
        problem = "cannot open " + p.string() + ": " + (e ? e : "unknown reason");
        return;
      }
      using Entry = const assimp_module::Api* (*)();
      const auto entry = reinterpret_cast<Entry>(::dlsym(lib, "vgd_assimp_module_api"));
      const assimp_module::Api* a = entry ? entry() : nullptr;
      if (!a || a->version != assimp_module::kApiVersion || !a->read || !a->write) {
        problem = p.string() + " is not this vgd's assimp module (rebuild vgd)";
        return;
      }
      found = a;
      return;
    }
    problem = "cannot find vgd's assimp module " + std::string(kModule) + " (tried " + tried +
              "); set VGD_MODULE_DIR to the folder that holds it";
  });
  if (!found) throw Error(file, "", problem);
  return *found;
}

// The child's answer: assimp's reason (empty on success), then the model.
// Native byte order: the two processes are the same program.
struct Writer {
  std::string out;
  template <class T>
  void pod(const T& v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); }
  void str(const std::string& s) { pod(static_cast<std::uint64_t>(s.size())), out += s; }
};
struct Reader {
  const std::string& in;
  std::size_t at = 0;
  bool ok = true;
  template <class T>
  T pod() {
    T v{};
    if (!ok || in.size() - at < sizeof v) return ok = false, v;
    std::memcpy(&v, in.data() + at, sizeof v);
    at += sizeof v;
    return v;
  }
  std::string str() {
    const auto n = pod<std::uint64_t>();
    if (!ok || in.size() - at < n) return ok = false, std::string();
    std::string s = in.substr(at, n);
    at += n;
    return s;
  }
  // A count of items of at least `each` bytes that the rest can hold.
  std::uint64_t count(std::size_t each) {
    const auto n = pod<std::uint64_t>();
    if (ok && n > (in.size() - at) / std::max<std::size_t>(each, 1)) ok = false;
    return ok ? n : 0;
  }
};

std::string encode(const std::string& why, const ModelFile& m) {
  Writer w;
  w.str(why);
  w.pod(static_cast<std::uint64_t>(m.surface.vertices.size()));
  for (const auto& v : m.surface.vertices) w.pod(v.x()), w.pod(v.y()), w.pod(v.z());
  w.pod(static_cast<std::uint64_t>(m.surface.triangles.size()));
  for (const auto& t : m.surface.triangles) w.pod(t[0]), w.pod(t[1]), w.pod(t[2]);
  w.pod(static_cast<std::uint64_t>(m.meshes.size()));
  for (const auto& mm : m.meshes) {
    w.str(mm.name), w.str(mm.node);
    w.pod(mm.first_vertex), w.pod(mm.vertices), w.pod(mm.first_triangle), w.pod(mm.triangles), w.pod(mm.skinned);
  }
  w.pod(static_cast<std::uint64_t>(m.joints.size()));
  for (const auto& j : m.joints) w.str(j.name), w.pod(j.position.x()), w.pod(j.position.y()), w.pod(j.position.z());
  w.pod(m.dropped);
  w.pod(static_cast<std::uint64_t>(m.metadata.size()));
  for (const auto& [k, v] : m.metadata) w.str(k), w.pod(v);
  return std::move(w.out);
}

bool decode(const std::string& bytes, std::string& why, ModelFile& m) {
  Reader r{bytes};
  why = r.str();
  m.surface.vertices.resize(r.count(3 * sizeof(double)));
  for (auto& v : m.surface.vertices) {
    const double x = r.pod<double>(), y = r.pod<double>(), z = r.pod<double>();
    v = Eigen::Vector3d(x, y, z);
  }
  m.surface.triangles.resize(r.count(3 * sizeof(int)));
  for (auto& t : m.surface.triangles) t[0] = r.pod<int>(), t[1] = r.pod<int>(), t[2] = r.pod<int>();
  m.meshes.resize(r.count(2 * sizeof(std::uint64_t)));
  for (auto& mm : m.meshes) {
    mm.name = r.str(), mm.node = r.str();
    mm.first_vertex = r.pod<int>(), mm.vertices = r.pod<int>(), mm.first_triangle = r.pod<int>();
    mm.triangles = r.pod<int>(), mm.skinned = r.pod<bool>();
  }
  m.joints.resize(r.count(sizeof(std::uint64_t)));
  for (auto& j : m.joints) {
    j.name = r.str();
    const double x = r.pod<double>(), y = r.pod<double>(), z = r.pod<double>();
    j.position = Eigen::Vector3d(x, y, z);
  }
  m.dropped = r.pod<int>();
  const auto n = r.count(sizeof(std::uint64_t));
  for (std::uint64_t i = 0; i < n && r.ok; ++i) {
    std::string k = r.str();
    m.metadata[k] = r.pod<double>();
  }
  return r.ok && r.at == bytes.size();
}

bool write_all(int fd, const std::string& bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

// assimp's reasons, said as vgd says them where assimp's wording is its own
// code's ("Cannot parse string \"\" as a real number: does not start with
// digit or decimal point followed by digit.").
std::string in_words(std::string why) {
  const std::string parse = "Cannot parse string \"";
  if (const auto p = why.find(parse); p != std::string::npos) {
    const auto q = why.find("\" as a real number", p + parse.size());
    if (q != std::string::npos) {
      const std::string found = why.substr(p + parse.size(), q - p - parse.size());
      return why.substr(0, p) + "a number was expected" +
             (found.empty() ? std::string(" and the line ends or holds none") : ", found \"" + found + "\"");
    }
  }
  return why;
}

// The error for a file assimp did not read, from its reason: a file in a
// format it reads whose model holds nothing (an STL with no facets, an OBJ of
// points) is said to be empty, not "a format vgd cannot read".
std::string not_read(const std::string& why) {
  const std::string validation = "Validation failed: ";
  if (why.rfind(validation, 0) == 0) {
    const std::string rest = why.substr(validation.size());
    for (const char* empty : {"contains no faces", "contains no vertices"})
      if (rest.find(empty) != std::string::npos) return "the file holds no triangles (assimp: " + rest + ")";
    return "the model in it is not valid (assimp's check: " + rest + ")";
  }
  return "not a 3-D model vgd can read (OBJ, PLY, STL, glTF/GLB, FBX, Collada): " + in_words(why);
}

// s: the reading time allowed (ModelReadOptions::time_limit_s).
double time_limit_s(const fs::path& path, const ModelReadOptions& options) {
  if (options.time_limit_s > 0.0) return options.time_limit_s;
  std::error_code ec;
  const auto bytes = fs::file_size(path, ec);
  return 5.0 + (ec ? 0.0 : static_cast<double>(bytes) / 1e6);
}

// An OBJ face with more corners than the limit is refused before assimp sees
// it: assimp triangulates a polygon in time that grows faster than its size
// (a face of a million corners reads for minutes).
void check_obj_faces(const fs::path& path, const std::string& file, std::size_t max_corners) {
  std::string ext = to_lower(path.extension().string());
  if (ext != ".obj") return;
  std::string text;
  try {
    text = read_file(path);
  } catch (const Error&) {
    return;  // the reader says why
  }
  int line = 0;
  for (std::size_t at = 0; at < text.size();) {
    ++line;
    std::size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    std::string_view l(text.data() + at, end - at);
    at = end + 1;
    std::size_t i = 0;
    while (i < l.size() && (l[i] == ' ' || l[i] == '\t')) ++i;
    if (i + 1 >= l.size() || l[i] != 'f' || (l[i + 1] != ' ' && l[i + 1] != '\t')) continue;
    std::size_t corners = 0;
    bool in_word = false;
    for (std::size_t k = i + 1; k < l.size(); ++k) {
      const bool space = l[k] == ' ' || l[k] == '\t' || l[k] == '\r';
      corners += !space && !in_word;
      in_word = !space;
    }
    if (corners > max_corners)
      throw Error(file, "face", "a face with " + std::to_string(corners) + " corners, more than the " +
                                    std::to_string(max_corners) + " vgd reads in one face", line);
  }
}

}  // namespace

ModelFile read_model_file(const fs::path& path, const ModelReadOptions& options) {
  const std::string file = path.string();
  check_obj_faces(path, file, options.max_face_corners);
  const assimp_module::Api& a = api(file);
  // assimp runs in a child process: some damaged files make it abort or
  // crash (an assertion in its post-processing on a mangled PLY, found by
  // fuzzing), which must not take the studio or a batch run down with it.
  // The child sends back the model (or assimp's reason) through a pipe.
  const pid_t parent = ::getpid();
  int fds[2];
  if (::pipe(fds) != 0) throw Error(file, "", std::string("cannot read it: pipe: ") + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]), ::close(fds[1]);
    throw Error(file, "", std::string("cannot read it: fork: ") + std::strerror(errno));
  }
  if (pid == 0) {
    ::close(fds[0]);
    // The parent's crash handlers (a fuzzer's, a debugger's) are not the
    // child's: a crash in assimp ends the child, and the parent reports it.
    for (const int sig : {SIGABRT, SIGSEGV, SIGBUS, SIGILL, SIGFPE}) std::signal(sig, SIG_DFL);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // no reader left spinning when the caller is gone
    if (::getppid() != parent) ::_exit(5);  // the caller died before the line above
    int code = 0;
    try {
      ModelFile out;
      const std::string why = a.read(path, options, out);
      const std::string bytes = encode(why, out);
      code = write_all(fds[1], bytes) ? 0 : 3;
      ::close(fds[1]);  // the caller goes on at once; this process's teardown is not its wait
    } catch (...) {
      code = 4;
    }
    ::_exit(code);
  }
  ::close(fds[1]);
  std::string bytes;
  char buf[1 << 16];
  const double limit_s = time_limit_s(path, options);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(limit_s);
  bool late = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      late = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno != EINTR) break;
    if (ready <= 0) continue;
    const ssize_t n = ::read(fds[0], buf, sizeof buf);
    if (n > 0) bytes.append(buf, static_cast<std::size_t>(n));
    else if (n == 0 || errno != EINTR) break;
  }
  ::close(fds[0]);
  if (late) ::kill(pid, SIGKILL);
  ModelFile out;
  std::string why;
  if (!late && decode(bytes, why, out)) {
    // A whole answer: the child is done but for its exit, which can take tens
    // of milliseconds (unmapping what assimp allocated); it is reaped aside.
    std::thread([pid] {
      int st = 0;
      while (::waitpid(pid, &st, 0) < 0 && errno == EINTR) {
      }
    }).detach();
    if (!why.empty()) throw Error(file, "", not_read(why));
    return out;
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (late)
    throw Error(file, "", "not read: assimp had not finished reading it after " + format_fixed(limit_s, 1) +
                              " s, the limit for a file of its size (a damaged file it loops on)");
  if (WIFSIGNALED(status))
    throw Error(file, "", "not a 3-D model vgd can read: assimp crashed reading it (signal " +
                              std::to_string(WTERMSIG(status)) + ", " + strsignal(WTERMSIG(status)) +
                              "): the file is damaged or uses what assimp cannot read");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw Error(file, "", "cannot read it: the reading process failed (exit " + std::to_string(WEXITSTATUS(status)) + ")");
  throw Error(file, "", "cannot read it: the reading process sent back an incomplete model");
}

void write_model_file(const mesh::SurfaceMesh& surface, const std::vector<Eigen::Vector3d>& normals,
                      const fs::path& path, const std::string& format_id) {
  const std::string file = path.string();
  VGD_ASSERT(normals.size() == surface.vertices.size(), "one normal per vertex");
  const std::string why = api(file).write(surface, normals, path, format_id);
  if (!why.empty()) throw Error(file, "", "writing failed: " + why);
}

}  // namespace vgd::body
