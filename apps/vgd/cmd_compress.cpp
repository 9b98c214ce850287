// vgd compress / decompress / trj info: trajectories (.trj, docs/formats/trj.md)
// and their wavelet compression (.wvt, docs/formats/wvt.md), seed 002 §3.3.1.
//
//   vgd compress skirt.trj -o skirt.wvt --max-error-mm 1   sizes, ratio, measured error
//   vgd decompress skirt.wvt -o back.trj                   a .trj with the same topology and times
//   vgd trj info skirt.trj                                 counts, duration, size, warnings (.trj or .wvt)
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/io/trj/trj.hpp"
#include "vgd/io/wvt/wvt.hpp"

namespace cmd_compress {
namespace {

namespace trj = vgd::io::trj;
namespace wvt = vgd::io::wvt;
namespace fs = std::filesystem;

std::string fixed(double v, int d) { return vgd::format_fixed(v, d); }

// "3.41 MB", "169 kB", "812 B" (decimal units).
std::string bytes_text(double b) {
  if (b >= 1e6) return fixed(b / 1e6, 2) + " MB";
  if (b >= 1e3) return fixed(b / 1e3, 1) + " kB";
  return fixed(b, 0) + " B";
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// ---- vgd compress ----
struct CompressOptions {
  std::string input, output, transform = "cdf53";
  double max_error_mm = 1.0;
  int levels = -1;
  bool json = false;
};

vgd::cli::Registrar compress_reg{"compress", 70, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("compress", "Compress a trajectory (.trj) into a .wvt under a vertex error bound");
  auto o = std::make_shared<CompressOptions>();
  sub->add_option("TRJ", o->input, "Trajectory written by vgd drape/simulate --trj")->required()->check(CLI::ExistingFile);
  sub->add_option("-o,--output", o->output, "The .wvt file to write")->required();
  sub->add_option("--max-error-mm", o->max_error_mm,
                  "Largest distance between a decoded vertex and the original, mm (default 1); measured after "
                  "encoding, never exceeded")
      ->check(CLI::Range(0.0001, 1e6));
  sub->add_option("--levels", o->levels,
                  "Wavelet levels along time (default: measured — full depth or none, whichever codes smaller)")
      ->check(CLI::Range(0, 64));
  sub->add_option("--wavelet", o->transform, "Integer wavelet along time: cdf53 (default) or haar")
      ->check(CLI::IsMember({"cdf53", "haar"}));
  sub->add_flag("--json", o->json, "Print the figures as JSON on stdout");
  sub->footer("The ratio is measured against the .trj's position payload (frames × particles × 3 × 4 bytes); "
              "the whole-file ratio is printed too. Exit codes: 0 ok, 1 bad input.");
  return vgd::cli::Command{sub, [o, &common]() -> int {
    const auto t0 = std::chrono::steady_clock::now();
    if (wvt::is_wvt_file(o->input))
      throw vgd::Error(o->input, "", "this is already a compressed trajectory (.wvt); vgd decompress reads it");
    trj::TrjReader reader(o->input);
    vgd::cli::print_diagnostics(reader.warnings(), common);
    const trj::Trajectory t = reader.read_all();
    const double read_s = seconds_since(t0);
    wvt::EncodeOptions opts;
    opts.max_error_m = o->max_error_mm * 1e-3;
    opts.source = o->input;
    opts.levels = o->levels;
    opts.transform = o->transform == "haar" ? wvt::EncodeOptions::Transform::haar : wvt::EncodeOptions::Transform::cdf53;
    wvt::EncodeStats s;
    wvt::write_wvt(o->output, t, opts, &s);
    const double posn = s.position_bytes > 0 ? 100.0 * (1.0 - static_cast<double>(s.position_stream_bytes) / s.position_bytes) : 0.0;
    const double file = reader.file_size() > 0 ? 100.0 * (1.0 - static_cast<double>(s.output_bytes) / reader.file_size()) : 0.0;
    if (o->json) {
      vgd::cli::print_json({{"input", o->input},
                            {"output", o->output},
                            {"frames", t.frame_count()},
                            {"particles", t.topology.num_particles},
                            {"trj_bytes", reader.file_size()},
                            {"trj_position_bytes", s.position_bytes},
                            {"wvt_bytes", s.output_bytes},
                            {"wvt_position_bytes", s.position_stream_bytes},
                            {"position_reduction_percent", posn},
                            {"file_reduction_percent", file},
                            {"max_error_bound_mm", o->max_error_mm},
                            {"max_error_measured_mm", s.max_error_m * 1e3},
                            {"step_mm", s.step_m * 1e3},
                            {"wavelet_levels", s.levels},
                            {"read_s", read_s},
                            {"encode_s", s.seconds},
                            {"warnings", vgd::cli::to_json(reader.warnings())}});
    } else if (!common.quiet) {
      std::printf("%s -> %s: %d frames x %d particles\n", o->input.c_str(), o->output.c_str(), t.frame_count(),
                  t.topology.num_particles);
      std::printf("  positions %s -> %s (%s %% smaller); whole file %s -> %s (%s %% smaller)\n",
                  bytes_text(static_cast<double>(s.position_bytes)).c_str(),
                  bytes_text(static_cast<double>(s.position_stream_bytes)).c_str(), fixed(posn, 2).c_str(),
                  bytes_text(static_cast<double>(reader.file_size())).c_str(),
                  bytes_text(static_cast<double>(s.output_bytes)).c_str(), fixed(file, 2).c_str());
      std::printf("  max vertex error %s mm measured (bound %s mm, grid step %s mm, %d wavelet levels); "
                  "encoded in %s s\n",
                  fixed(s.max_error_m * 1e3, 4).c_str(), vgd::format_double(o->max_error_mm).c_str(),
                  fixed(s.step_m * 1e3, 4).c_str(), s.levels, fixed(s.seconds, 2).c_str());
      std::fflush(stdout);
    }
    return vgd::cli::kOk;
  }};
}};

// ---- vgd decompress ----
struct DecompressOptions {
  std::string input, output;
};

vgd::cli::Registrar decompress_reg{"decompress", 71, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("decompress", "Decode a .wvt back into a trajectory (.trj)");
  auto o = std::make_shared<DecompressOptions>();
  sub->add_option("WVT", o->input, "Compressed trajectory written by vgd compress")->required()->check(CLI::ExistingFile);
  sub->add_option("-o,--output", o->output, "The .trj file to write")->required();
  sub->footer("The .trj has the same topology, merges and frame times; positions are within the bound the .wvt "
              "was made with. Exit codes: 0 ok, 1 bad input.");
  return vgd::cli::Command{sub, [o, &common]() -> int {
    const auto t0 = std::chrono::steady_clock::now();
    const trj::Trajectory t = wvt::read_wvt(o->input);
    const double decode_s = seconds_since(t0);
    trj::write_trj(o->output, t);
    if (!common.quiet) {
      std::printf("%s -> %s: %d frames x %d particles, %s; decoded in %s s\n", o->input.c_str(), o->output.c_str(),
                  t.frame_count(), t.topology.num_particles,
                  bytes_text(static_cast<double>(fs::file_size(o->output))).c_str(), fixed(decode_s, 2).c_str());
      std::fflush(stdout);
    }
    return vgd::cli::kOk;
  }};
}};

// ---- vgd trj info ----
struct InfoOptions {
  std::string input;
  bool json = false;
};

vgd::cli::Registrar trj_reg{"trj", 72, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("trj", "Inspect trajectories (.trj and .wvt)");
  sub->require_subcommand(1);
  auto o = std::make_shared<InfoOptions>();
  auto* info = sub->add_subcommand("info", "Counts, duration, size and warnings of a .trj or .wvt");
  info->add_option("FILE", o->input, "A .trj or .wvt file")->required()->check(CLI::ExistingFile);
  info->add_flag("--json", o->json, "Print as JSON on stdout");
  info->footer("A .trj that a crashed run left (FILE.partial) reads up to its last whole frame, with a warning. "
               "Exit codes: 0 ok, 1 bad input.");
  return vgd::cli::Command{sub, [o, &common]() -> int {
    nlohmann::json j{{"file", o->input}};
    vgd::Diagnostics warnings;
    if (wvt::is_wvt_file(o->input)) {
      const wvt::Info w = wvt::read_info(vgd::read_file(o->input), o->input);
      j.update({{"format", "wvt"},
                {"version", std::to_string(w.version_major) + "." + std::to_string(w.version_minor)},
                {"particles", w.num_particles},
                {"triangles", w.num_triangles},
                {"pieces", w.num_pieces},
                {"merges", w.num_merges},
                {"frames", w.frame_count},
                {"duration_s", w.frame_count > 1 ? w.last_time - w.first_time : 0.0},
                {"bytes", w.file_size},
                {"position_bytes", w.position_stream_bytes},
                {"max_error_bound_mm", w.max_error_m * 1e3},
                {"max_error_measured_mm", w.measured_error_m * 1e3},
                {"step_mm", w.step_m * 1e3},
                {"wavelet_levels", w.levels}});
    } else {
      trj::TrjReader r(o->input);
      warnings = r.warnings();
      j.update({{"format", "trj"},
                {"version", std::to_string(r.version_major()) + "." + std::to_string(r.version_minor())},
                {"particles", r.num_particles()},
                {"triangles", r.topology().triangles.size()},
                {"pieces", r.topology().pieces.size()},
                {"merges", r.topology().merges.size()},
                {"frames", r.frame_count()},
                {"duration_s", r.duration()},
                {"bytes", r.file_size()},
                {"position_bytes", r.position_bytes()},
                {"complete", r.complete()},
                {"run_ok", r.run_ok()}});
    }
    if (o->json) {
      j["warnings"] = vgd::cli::to_json(warnings);
      vgd::cli::print_json(j);
      return vgd::cli::kOk;
    }
    vgd::cli::print_diagnostics(warnings, common);
    std::printf("%s: %s %s, %d particles, %d triangles, %d pieces, %d merged particles\n", o->input.c_str(),
                j["format"].get<std::string>().c_str(), j["version"].get<std::string>().c_str(),
                j["particles"].get<int>(), j["triangles"].get<int>(), j["pieces"].get<int>(), j["merges"].get<int>());
    std::printf("  %d frames over %s s; %s (positions %s)\n", j["frames"].get<int>(),
                fixed(j["duration_s"].get<double>(), 3).c_str(), bytes_text(j["bytes"].get<double>()).c_str(),
                bytes_text(j["position_bytes"].get<double>()).c_str());
    if (j["format"] == "wvt") {
      std::printf("  error bound %s mm, measured %s mm when encoded (grid step %s mm, %d wavelet levels)\n",
                  vgd::format_double(j["max_error_bound_mm"].get<double>()).c_str(),
                  fixed(j["max_error_measured_mm"].get<double>(), 4).c_str(),
                  fixed(j["step_mm"].get<double>(), 4).c_str(), j["wavelet_levels"].get<int>());
    } else {
      std::printf("  %s%s\n", j["complete"].get<bool>() ? "complete" : "incomplete (no end marker)",
                  j["complete"].get<bool>() && !j["run_ok"].get<bool>() ? "; the run that wrote it failed" : "");
    }
    std::fflush(stdout);
    return vgd::cli::kOk;
  }};
}};

}  // namespace
}  // namespace cmd_compress
