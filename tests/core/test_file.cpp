#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "support/test_paths.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"

namespace fs = std::filesystem;

TEST(AtomicWrite, ReplacesContentAndLeavesNoTemporary) {
  const auto dir = vgd::test::scratch_dir("atomic_write");
  const auto path = dir / "out.txt";
  vgd::write_file_atomic(path, "first");
  vgd::write_file_atomic(path, "second");
  EXPECT_EQ(vgd::read_file(path), "second");
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1) << "a temporary file was left behind";
}

TEST(AtomicWrite, FailedRenameKeepsWhatWasThereAndCleansUp) {
  // The target is a non-empty directory: the final rename must fail (even as root),
  // the directory and its content must survive and no temporary may remain.
  const auto dir = vgd::test::scratch_dir("atomic_fail");
  const auto target = dir / "garment.xvc";
  fs::create_directories(target);
  vgd::write_file_atomic(target / "keep.txt", "precious");
  try {
    vgd::write_file_atomic(target, "replacement");
    FAIL() << "expected an error";
  } catch (const vgd::Error& e) {
    EXPECT_NE(std::string(e.what()).find("garment.xvc"), std::string::npos) << e.what();
  }
  EXPECT_EQ(vgd::read_file(target / "keep.txt"), "precious");
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 1) << "a temporary file was left behind";
}

// A pipe (as /dev/null or a terminal) named as the output is written into,
// not replaced by a file: renaming over /dev/null as root replaced the device.
TEST(AtomicWrite, APipeIsWrittenIntoNotReplaced) {
  const auto dir = vgd::test::scratch_dir("atomic_fifo");
  const auto fifo = dir / "out.pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // The reading end, open before the write (the content fits the pipe's buffer).
  const int in = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(in, 0);
  vgd::write_file_atomic(fifo, "through the pipe");
  char buf[64] = {};
  const ssize_t n = ::read(in, buf, sizeof buf);
  ::close(in);
  EXPECT_EQ(std::string(buf, n > 0 ? static_cast<std::size_t>(n) : 0), "through the pipe");
  struct stat st {};
  ASSERT_EQ(::stat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode)) << "the pipe was replaced";
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 1) << "a temporary file was left behind";
}

TEST(ReadFile, MissingFileNamesTheFile) {
  try {
    vgd::read_file("/nonexistent/garment.dxf");
    FAIL() << "expected an error";
  } catch (const vgd::Error& e) {
    EXPECT_EQ(e.diagnostic().file, "/nonexistent/garment.dxf");
    EXPECT_NE(e.diagnostic().message.find("not found"), std::string::npos);
  }
}

TEST(Diagnostic, FormatsFileLineEntityMessage) {
  vgd::Diagnostic d{vgd::Severity::warning, "a.dxf", "FRONT_38", "open boundary", 12};
  EXPECT_EQ(d.format(), "a.dxf:12: FRONT_38: open boundary");
}
