// vgd avatar: what an avatar file holds (report) and format conversion (convert).
#include <cstdio>
#include <memory>

#include "cli.hpp"
#include "vgd/body/avatar_io.hpp"
#include "vgd/core/strings.hpp"

namespace cmd_avatar {
namespace {

struct Options {
  std::string input, output, unit = "auto", up = "auto", facing = "auto";
  bool json = false;
};

vgd::body::AvatarImportOptions import_options(const Options& o) {
  vgd::body::AvatarImportOptions io;
  io.unit = o.unit, io.up = o.up, io.facing = o.facing;
  return io;
}

void add_import_options(CLI::App* sub, const std::shared_ptr<Options>& o) {
  sub->add_option("--unit", o->unit, "File unit: auto, m, dm, cm, mm, in")->capture_default_str();
  sub->add_option("--up", o->up, "File up axis: auto, x, y, z, -x, -y, -z")->capture_default_str();
  sub->add_option("--facing", o->facing, "Where the body faces once +Y is up: auto (from the feet), +z, -z, +x, -x")->capture_default_str();
}

vgd::cli::Registrar reg{"avatar", 61, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("avatar", "Report on or convert an avatar mesh (OBJ, PLY, STL, glTF/GLB, FBX, Collada)");
  sub->require_subcommand(1);
  auto o = std::make_shared<Options>();
  auto* report = sub->add_subcommand("report", "Triangles, bounding box, height, watertightness, unit and up axis used");
  report->add_option("FILE", o->input, "Avatar mesh")->required();
  report->add_flag("--json", o->json, "Print the report as JSON on stdout");
  add_import_options(report, o);
  auto* convert = sub->add_subcommand("convert", "Normalise (metres, +Y up, facing +Z, feet on y = 0) and write another format");
  convert->add_option("FILE", o->input, "Avatar mesh")->required();
  convert->add_option("-o,--output", o->output, "Output: .obj .ply .stl .glb .gltf .dae (atomically)")->required();
  add_import_options(convert, o);
  sub->footer("Exit codes: 0 ok, 1 unreadable or bad file (the message says why), 2 usage.");
  return vgd::cli::Command{sub, [o, report, &common]() -> int {
    vgd::body::AvatarReport r;
    const auto avatar = vgd::body::import_avatar(o->input, import_options(*o), &r);
    if (report->parsed()) {
      if (o->json) {
        vgd::cli::print_json(nlohmann::json::parse(vgd::body::to_json(r)));
      } else {
        std::printf("%s: %d meshes, %d vertices, %d triangles%s\n", r.file.c_str(), r.meshes, r.vertices, r.triangles,
                    r.welded_vertices ? (" (" + std::to_string(r.welded_vertices) + " vertices welded)").c_str() : "");
        std::printf("height %.4f m; box (%.4f, %.4f, %.4f) – (%.4f, %.4f, %.4f) m\n", r.height, r.box.min.x(), r.box.min.y(),
                    r.box.min.z(), r.box.max.x(), r.box.max.y(), r.box.max.z());
        std::printf("unit %s (%s: %s); up %s (%s: %s)\n", r.unit.c_str(), r.unit_guessed ? "guessed" : "known",
                    r.unit_reason.c_str(), r.up.c_str(), r.up_guessed ? "guessed" : "known", r.up_reason.c_str());
        std::printf("facing %s (%s: %s)\n", r.facing.c_str(), r.facing_guessed ? "guessed" : "known",
                    r.facing_reason.c_str());
        std::printf("%s: %d boundary, %d non-manifold, %d inconsistent edges\n", r.watertight ? "watertight" : "NOT watertight",
                    r.boundary_edges, r.non_manifold_edges, r.inconsistent_edges);
        std::string segs;
        for (const auto& s : r.segments) segs += (segs.empty() ? "" : ", ") + s;
        std::printf("segments: %s\n", segs.empty() ? "none found" : segs.c_str());
        if (r.measuring) {
          const auto& m = r.measuring->measurements;
          const auto& l = r.measuring->landmarks;
          auto cm = [](double v) { return v > 0 ? vgd::format_fixed(100 * v, 1) + " cm" : std::string("-"); };
          std::printf("measured: height %s, bust %s, under-bust %s, waist %s, hip %s, neck %s, shoulders %s, arm %s, inseam %s\n",
                      cm(m.height).c_str(), cm(m.bust).c_str(), cm(m.under_bust).c_str(), cm(m.waist).c_str(),
                      cm(m.hip).c_str(), cm(m.neck).c_str(), cm(m.shoulder_width).c_str(), cm(m.arm_length).c_str(),
                      cm(m.inseam).c_str());
          std::printf("landmark heights: neck %s, shoulders %s, bust %s, waist %s, hip %s, crotch %s, knee %s, ankle %s; arms: %s\n",
                      cm(l.neck).c_str(), cm(l.shoulder).c_str(), cm(l.bust).c_str(), cm(l.waist).c_str(),
                      cm(l.hip).c_str(), cm(l.crotch).c_str(), cm(l.knee).c_str(), cm(l.ankle).c_str(),
                      l.left_arm && l.right_arm ? "both" : l.left_arm ? "left only" : l.right_arm ? "right only" : "none");
          for (const auto& [side, arm] : {std::pair{"left", &l.left_arm}, {"right", &l.right_arm}})
            if (*arm) {
              const auto& a = **arm;
              const double along = (a.wrist - a.shoulder).norm();
              const auto from = [](bool skeleton) { return skeleton ? "the file's skeleton" : "the surface"; };
              std::printf("%s elbow: %s from the shoulder joint, %.0f %% of the way to the wrist (%s; the shoulder "
                          "joint from %s, the wrist from %s)\n",
                          side, cm((a.elbow - a.shoulder).norm()).c_str(),
                          along > 0 ? 100 * (a.elbow - a.shoulder).norm() / along : 0.0,
                          a.elbow_from_skeleton ? "the file's skeleton"
                          : a.elbow_on_surface  ? "where the arm's girth bends"
                                                : "not shown by the surface: put at 56 %",
                          from(a.shoulder_from_skeleton), from(a.wrist_from_skeleton));
            }
        }
        if (r.nearest)
          std::printf("nearest size: %s %s (%s; height %.1f, bust %.1f, waist %.1f, hip %.1f cm; %.1f cm RMS off)\n",
                      r.nearest->table.c_str(), r.nearest->size.label.c_str(), r.nearest->size.sex.c_str(),
                      100 * r.nearest->size.height, 100 * r.nearest->size.bust, 100 * r.nearest->size.waist,
                      100 * r.nearest->size.hip, 100 * r.nearest->rms);
        for (const auto& n : r.notes) std::printf("note: %s\n", n.c_str());
        std::fflush(stdout);
      }
      return vgd::cli::kOk;
    }
    vgd::body::export_avatar(avatar, o->output);
    vgd::cli::say(common, "wrote " + o->output + ": " + std::to_string(r.triangles) + " triangles, height " +
                              std::to_string(r.height) + " m (unit " + r.unit + ", up " + r.up + ")");
    return vgd::cli::kOk;
  }};
}};

}  // namespace
}  // namespace cmd_avatar
