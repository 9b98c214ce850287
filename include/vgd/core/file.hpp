#pragma once
// File helpers shared by every reader and writer.
//
// Writes never touch the user's existing file until the new content is complete:
// content goes to a temporary file beside the target, is flushed to disk and then
// renamed over the target (atomic on POSIX file systems). A failed write leaves the
// old file as it was and removes the temporary.
#include <filesystem>
#include <string>
#include <string_view>

namespace vgd {

// Reads a whole file. Throws vgd::Error naming the file when it cannot be read.
std::string read_file(const std::filesystem::path& path);

// Writes `content` to `path` atomically (temporary file + fsync + rename).
// Creates missing parent directories. A path that names something other than a
// regular file or directory (/dev/null, a FIFO) is written in place, never
// replaced. Throws vgd::Error on failure.
void write_file_atomic(const std::filesystem::path& path, std::string_view content);

}  // namespace vgd
