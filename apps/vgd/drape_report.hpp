#pragma once
// Runs a drape and reports it as vgd drape does: a progress bar per stage,
// the body's import notes and the build's diagnostics before the run,
// garment.obj, avatar.obj and certificate.json in the output folder, the
// summary on stdout (or the certificate with `json`), failed checks and
// warnings on stderr. Returns the exit code: kOk passed, kCheckFailed a check
// failed, kFailed the run stopped with an error.
#include <filesystem>
#include <string>

#include "cli.hpp"
#include "vgd/dress/drape.hpp"

namespace vgd::cli {

struct DrapeRun {
  dress::DrapeOptions options;
  std::string names;          // the garments, for messages ("a.xvc + b.xvc")
  std::string avatar_label;   // the body file as given, for its notes ("" for a mannequin)
  std::filesystem::path output = "out";
  bool frames = false;        // also every frame as OBJ in output/frames/
  std::string trj;            // also a trajectory file
  bool json = false;          // the certificate on stdout instead of the summary
  bool json_later = false;    // with json: nothing on stdout (the caller prints the certificate it keeps)
};

int drape_and_report(const DrapeRun& run, const Common& common);

// The body of --avatar FILE with its --unit, --up and --facing, as a drape's avatar.
scene::AvatarDef avatar_file(const std::string& file, const std::string& unit, const std::string& up,
                             const std::string& facing);

}  // namespace vgd::cli
