#include <gtest/gtest.h>

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
