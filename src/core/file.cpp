#include "vgd/core/file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "vgd/core/diagnostics.hpp"

namespace vgd {

std::string read_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw Error(path.string(), "", "file not found");
  if (std::filesystem::is_directory(path, ec))
    throw Error(path.string(), "", "is a directory, expected a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string(), "", std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw Error(path.string(), "", "read failed");
  return std::move(ss).str();
}

namespace {

// Writes all of `content` to the open descriptor; false with errno set on failure.
bool write_all(int fd, std::string_view content) {
  const char* p = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

void write_file_atomic(const std::filesystem::path& path, std::string_view content) {
  namespace fs = std::filesystem;
  const fs::path target = path.has_parent_path() ? path : fs::path(".") / path;
  std::error_code ec;
  // A target that is not a regular file (/dev/null, a FIFO, a terminal) is
  // written in place: renaming over it would replace the device or pipe with
  // a file of the content (as root, /dev/null itself).
  if (struct stat st{}; ::stat(target.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode)) {
    const int fd = ::open(target.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) throw Error(path.string(), "", std::string("cannot open: ") + std::strerror(errno));
    if (!write_all(fd, content)) {
      const int err = errno;
      ::close(fd);
      throw Error(path.string(), "", std::string("write failed: ") + std::strerror(err));
    }
    if (::close(fd) != 0) throw Error(path.string(), "", std::string("close failed: ") + std::strerror(errno));
    return;
  }
  fs::create_directories(target.parent_path(), ec);
  if (ec) throw Error(path.string(), "", "cannot create directory: " + ec.message());

  // mkstemp gives a unique name in the same directory, so rename() stays atomic.
  std::string tmpl = (target.parent_path() / ("." + target.filename().string() + ".tmp-XXXXXX")).string();
  int fd = ::mkstemp(tmpl.data());
  if (fd < 0) throw Error(path.string(), "", std::string("cannot create temporary file: ") + std::strerror(errno));

  auto fail = [&](const char* what) {
    const int err = errno;
    ::close(fd);
    ::unlink(tmpl.c_str());
    throw Error(path.string(), "", std::string(what) + ": " + std::strerror(err));
  };
  if (!write_all(fd, content)) fail("write failed");
  if (::fsync(fd) != 0) fail("fsync failed");
  // mkstemp creates 0600; give the file the usual permissions (umask applies).
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  if (::close(fd) != 0) {
    ::unlink(tmpl.c_str());
    throw Error(path.string(), "", std::string("close failed: ") + std::strerror(errno));
  }
  if (::rename(tmpl.c_str(), target.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmpl.c_str());
    throw Error(path.string(), "", std::string("cannot rename into place: ") + std::strerror(err));
  }
}

}  // namespace vgd
