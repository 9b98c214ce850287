// vgd mesh: meshes every piece of one size of an XVC document (seed 002 §2) and
// prints a per-piece summary; optionally writes Triangle's .node/.ele/.poly files.
//
// Parameters come from the document's PARAMETERs (mesh.spacing m, mesh.turn_angle
// deg, mesh.min_angle deg, mesh.max_area m²), overridden by the options given here.
#include <chrono>
#include <cstdio>
#include <memory>

#include "cli.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/mesh/mesh.hpp"
#include "vgd/mesh/quality.hpp"
#include "vgd/mesh/triangle_io.hpp"
#include "vgd/xvc/document.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/style.hpp"

namespace cmd_mesh {
namespace {

struct Options {
  std::string input, size, piece, triangle_dir;
  double spacing = 0, turn_angle = 0, min_angle = 0, max_area = 0;
  bool json = false, no_boundary_split = false;
  CLI::Option *spacing_opt = nullptr, *turn_opt = nullptr, *angle_opt = nullptr, *area_opt = nullptr;
};

// A file name from a block name: path separators and control characters become '_'.
std::string file_stem(const std::string& block) {
  std::string s = block.empty() ? "piece" : block;
  for (char& c : s)
    if (c == '/' || c == '\\' || static_cast<unsigned char>(c) < 32) c = '_';
  return s;
}

// Document parameters, then command-line overrides.
vgd::mesh::MeshOptions mesh_options(const vgd::xvc::Document& doc, const Options& o) {
  vgd::mesh::MeshOptions m;
  auto pick = [&](CLI::Option* opt, double given, const char* param, double& target) {
    if (opt->count() > 0) {
      target = given;
    } else if (const auto v = vgd::xvc::get_parameter(doc, param)) {
      target = *v;
    }
  };
  pick(o.spacing_opt, o.spacing, "mesh.spacing", m.resample.spacing_m);
  pick(o.turn_opt, o.turn_angle, "mesh.turn_angle", m.resample.turn_angle_deg);
  pick(o.angle_opt, o.min_angle, "mesh.min_angle", m.min_angle_deg);
  pick(o.area_opt, o.max_area, "mesh.max_area", m.max_area_m2);
  m.split_boundary = !o.no_boundary_split;
  return m;
}

vgd::cli::Registrar reg{"mesh", 50, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("mesh", "Mesh the pieces of one size with quality triangles (CGAL)");
  auto o = std::make_shared<Options>();
  sub->add_option("FILE", o->input, "XVC document")->required();
  o->spacing_opt = sub->add_option("--spacing", o->spacing, "Contour point spacing, m (default mesh.spacing, else 0.01)")
                       ->check(CLI::PositiveNumber);
  o->turn_opt = sub->add_option("--turn-angle", o->turn_angle,
                                "Corner angle that splits the contour into sides, deg (mesh.turn_angle, else 30)")
                    ->check(CLI::Range(0.0, 180.0));
  o->angle_opt = sub->add_option("--min-angle", o->min_angle, "Smallest triangle angle, deg (mesh.min_angle, else 25)")
                     ->check(CLI::Range(1.0, 33.0));
  o->area_opt = sub->add_option("--max-area", o->max_area,
                                "Largest triangle area, m² (mesh.max_area, else 0.60 × spacing²)")
                    ->check(CLI::PositiveNumber);
  sub->add_option("--size", o->size, "Size to mesh (default: the sample size)");
  sub->add_option("--piece", o->piece, "Only this piece (piece name or block name)");
  sub->add_option("--triangle-files", o->triangle_dir, "Write BLOCK.1.node/.ele/.poly per piece into this directory");
  sub->add_flag("--no-boundary-split", o->no_boundary_split,
                "Never add points on the contour (Triangle -Y); triangles next to it may miss the bounds");
  sub->add_flag("--json", o->json, "Print the summary as JSON on stdout");
  sub->footer("Exit codes: 0 every piece meshed, 1 a piece or the input failed, 3 a mesh failed its checks.");
  return vgd::cli::Command{sub, [o, &common]() -> int {
    const auto doc = vgd::xvc::load_file(o->input);
    vgd::pattern::Style style = vgd::xvc::to_style(doc);
    const vgd::mesh::MeshOptions opts = mesh_options(doc, *o);

    // Keep only the asked piece, by piece or block name.
    if (!o->piece.empty()) {
      std::erase_if(style.pieces, [&](const auto& p) { return p.name != o->piece && p.block != o->piece; });
      if (style.pieces.empty()) throw vgd::Error(o->input, o->piece, "no piece or block of that name");
    }

    // Mesh, timed.
    vgd::Diagnostics diag;
    const auto t0 = std::chrono::steady_clock::now();
    const auto meshes = vgd::mesh::mesh_style(style, o->size, opts, diag);
    diag.name_file(o->input);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

    // Check each mesh and write its files when asked.
    std::vector<vgd::mesh::QualityReport> reports;
    bool all_valid = true;
    for (const auto& m : meshes) {
      reports.push_back(vgd::mesh::check_mesh(m, opts.min_angle_deg));
      if (!reports.back().valid()) {
        all_valid = false;
        diag.error(o->input, m.piece, "the mesh failed its checks: " + reports.back().problems.front());
      }
      if (!o->triangle_dir.empty())
        vgd::mesh::write_triangle_files(m, std::filesystem::path(o->triangle_dir) / (file_stem(m.piece) + ".1"));
    }

    // Report: JSON or a table.
    const std::string size = o->size.empty() ? style.sample_size : o->size;
    if (o->json) {
      auto pieces = nlohmann::json::array();
      for (std::size_t i = 0; i < meshes.size(); ++i) {
        const auto& m = meshes[i];
        const auto& q = reports[i];
        pieces.push_back({{"block", m.piece},
                          {"contour_points", m.contours.empty() ? 0 : m.contours[0].points.size()},
                          {"cutouts", m.contours.empty() ? 0 : m.contours.size() - 1},
                          {"nodes", q.nodes},
                          {"triangles", q.triangles},
                          {"boundary_steiner_nodes", q.boundary_steiner_nodes},
                          {"min_angle_deg", q.min_angle_deg},
                          {"min_angle_away_from_sharp_deg", q.min_angle_away_from_sharp_deg},
                          {"sharp_corners", q.sharp_corners},
                          {"max_area_m2", q.max_area_m2},
                          {"area_m2", q.mesh_area_m2},
                          {"valid", q.valid()}});
      }
      vgd::cli::print_json({{"file", o->input},
                            {"size", size},
                            {"options",
                             {{"spacing_m", opts.resample.spacing_m},
                              {"turn_angle_deg", opts.resample.turn_angle_deg},
                              {"min_angle_deg", opts.min_angle_deg},
                              {"max_area_m2", vgd::mesh::effective_max_area(opts)},
                              {"split_boundary", opts.split_boundary}}},
                            {"pieces", pieces},
                            {"milliseconds", ms},
                            {"diagnostics", vgd::cli::to_json(diag)}});
    } else {
      vgd::cli::print_diagnostics(diag, common);
      std::printf("%-28s %7s %7s %8s %9s %9s %10s\n", "block", "contour", "nodes", "triangles", "min angle",
                  "steiner", "area m2");
      std::size_t nodes = 0, triangles = 0;
      for (std::size_t i = 0; i < meshes.size(); ++i) {
        const auto& q = reports[i];
        nodes += q.nodes, triangles += q.triangles;
        std::printf("%-28s %7zu %7zu %8zu %9.2f %9d %10.5f%s\n", meshes[i].piece.c_str(),
                    meshes[i].contours[0].points.size(), q.nodes, q.triangles, q.min_angle_deg,
                    q.boundary_steiner_nodes, q.mesh_area_m2, q.valid() ? "" : "  INVALID");
      }
      std::printf("%zu pieces of size %s: %zu nodes, %zu triangles\n", meshes.size(), size.c_str(), nodes, triangles);
      std::fflush(stdout);
    }
    vgd::cli::say(common, "vgd: meshed " + std::to_string(meshes.size()) + " pieces in " +
                              std::to_string(static_cast<long>(ms)) + " ms (spacing " +
                              vgd::format_double(opts.resample.spacing_m) + " m, min angle " +
                              vgd::format_double(opts.min_angle_deg) + "°)" +
                              (o->triangle_dir.empty() ? "" : "; Triangle files in " + o->triangle_dir));
    if (!all_valid) return vgd::cli::kCheckFailed;
    return diag.has_errors() ? vgd::cli::kFailed : vgd::cli::kOk;
  }};
}};

}  // namespace
}  // namespace cmd_mesh
