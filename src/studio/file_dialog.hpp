#pragma once
// The desktop's own file dialogs for the studio (File > Open..., Save as...,
// Export VRML...), run as a program that answers as zenity does: the chosen
// path on stdout and exit 0, exit 1 when the user cancels. Private to
// src/studio.
#include <filesystem>
#include <string>
#include <vector>

namespace vgd::studio {

struct FileDialogAnswer {
  enum class Kind { chosen, cancelled, unavailable } kind = Kind::unavailable;
  std::filesystem::path path;  // chosen
  std::string why;             // unavailable: what went wrong ("no such program", "exit 5")
};

// What the dialog is for: the title, whether it saves (asks before
// overwriting), the file to start at, and its filters ("XVC documents | *.xvc").
struct FileDialogRequest {
  std::string title;
  bool save = false;
  std::filesystem::path start;
  std::vector<std::string> filters;
};

// zenity's arguments for the request.
std::vector<std::string> zenity_arguments(const FileDialogRequest& request);

// Runs `program` with the request's arguments, blocking until it answers
// (the dialog is modal); its stderr is discarded (GTK's warnings).
FileDialogAnswer run_file_dialog(const std::filesystem::path& program, const FileDialogRequest& request);

}  // namespace vgd::studio
