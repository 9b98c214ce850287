// vgd mannequin: the parametric body from a standard size or from measurements,
// written as a mesh (obj, ply, stl, glb, gltf, dae) with a short report.
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>

#include "cli.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/body/avatar_io.hpp"
#include "vgd/body/sizes.hpp"
#include "vgd/body/mannequin.hpp"
#include "vgd/scene/units.hpp"

namespace cmd_mannequin {
namespace {

struct Options {
  std::string size, table, output, sex;
  std::string height, bust, under_bust, waist, hip, shoulder, neck, arm, inseam;
  int triangles = 10000;
  double arm_angle = 45.0, arm_forward = 0.0;
  bool list = false, json = false;
};

// "1.68", "168cm", "1680 mm", "66in" -> metres; a bare number is in metres.
std::optional<double> length(const std::string& text) {
  if (const auto v = vgd::parse_double(text)) return *v;
  const auto q = vgd::scene::parse_quantity(text);
  if (!q || q->dimension != vgd::scene::dim::length) {
    // Inches are not a scene unit: accept them here, they are common for body sizes.
    const std::string t(vgd::trim(text));
    if (t.size() > 2 && vgd::iequals(t.substr(t.size() - 2), "in"))
      if (const auto v = vgd::parse_double(t.substr(0, t.size() - 2))) return *v * 0.0254;
    return std::nullopt;
  }
  return q->value;
}

std::string length_text(const std::string& text) {
  return length(text) ? "" : "expected a length, e.g. 1.68, 168cm or 66in (got '" + text + "')";
}

vgd::cli::Registrar reg{"mannequin", 60, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("mannequin", "Generate the parametric mannequin from a size or body measurements");
  auto o = std::make_shared<Options>();
  sub->add_option("--size", o->size, "Size label from a table (e.g. 38; see --list-sizes)");
  sub->add_option("--table", o->table, "Size table: en13402-women, en13402-men, astm-d5585-misses, or a CSV file");
  sub->add_option("-o,--output", o->output, "Mesh to write (atomically): .obj .ply .stl .glb .gltf .dae");
  sub->add_option("--sex", o->sex, "Body template: female or male")->check(CLI::IsMember({"female", "male"}));
  auto len = [&](const char* name, std::string& target, const char* what) {
    sub->add_option(name, target, what)->check(length_text);
  };
  len("--height", o->height, "Height (e.g. 1.68 or 168cm)");
  len("--bust", o->bust, "Bust girth (chest for men)");
  len("--under-bust", o->under_bust, "Under-bust girth");
  len("--waist", o->waist, "Waist girth");
  len("--hip", o->hip, "Hip girth");
  len("--shoulder", o->shoulder, "Shoulder width");
  len("--neck", o->neck, "Neck base girth");
  len("--arm", o->arm, "Arm length, shoulder point to wrist");
  len("--inseam", o->inseam, "Inseam (crotch height)");
  sub->add_option("--triangles", o->triangles, "Triangles aimed at (5000-20000)")->check(CLI::Range(5000, 20000))
      ->capture_default_str();
  sub->add_option("--arm-angle", o->arm_angle, "Arms' angle from the vertical, deg: 45 an A-pose, 90 a T-pose (opened further if the chest needs it)")
      ->check(CLI::Range(15.0, 90.0))->capture_default_str();
  sub->add_option("--arm-forward", o->arm_forward, "Arms swung forward from the frontal plane, deg (0-60)")
      ->check(CLI::Range(0.0, 60.0))->capture_default_str();
  sub->add_flag("--list-sizes", o->list, "List the sizes of the tables and exit");
  sub->add_flag("--json", o->json, "Print the report as JSON on stdout");
  sub->footer("Without --size the body starts from the default (EN 13402-3 women's 38 on 1.68 m) and the measurements\n"
              "given replace its values; measurements not given are derived (data/bodies/README.md).\n"
              "A body meshed once is kept in the cache ($VGD_CACHE_DIR, else $XDG_CACHE_HOME/vgd or ~/.cache/vgd;\n"
              "VGD_CACHE_DIR=off keeps none) and read back from it, the same mesh (docs/avatar.md, \"The cache\").\n"
              "Exit codes: 0 ok, 1 bad measurements or write failure, 2 usage.");
  return vgd::cli::Command{sub, [o, &common]() -> int {
    if (o->list) {
      const auto names = o->table.empty() ? vgd::body::size_table_names() : std::vector<std::string>{o->table};
      nlohmann::json j = nlohmann::json::object();
      for (const auto& n : names) {
        const auto path = n.find('/') != std::string::npos || n.ends_with(".csv") ? std::filesystem::path(n)
                                                                                    : vgd::body::size_table_file(n);
        const auto rows = vgd::body::load_size_table(path);
        if (!o->json) std::printf("%s:\n  %-6s %-6s %7s %7s %7s %7s\n", n.c_str(), "size", "sex", "height", "bust", "waist", "hip");
        for (const auto& r : rows) {
          if (o->json)
            j[n].push_back({{"size", r.label}, {"sex", r.sex}, {"height_m", r.height}, {"bust_m", r.bust},
                            {"waist_m", r.waist}, {"hip_m", r.hip}});
          else
            std::printf("  %-6s %-6s %7.3f %7.3f %7.3f %7.3f\n", r.label.c_str(), r.sex.c_str(), r.height, r.bust, r.waist, r.hip);
        }
      }
      if (o->json) vgd::cli::print_json(j);
      return vgd::cli::kOk;
    }
    if (o->output.empty()) throw CLI::ValidationError("--output", "required unless --list-sizes is given");
    vgd::body::BodyMeasurements m;
    if (!o->size.empty()) m = vgd::body::find_size(o->size, o->table);
    const bool custom = !o->height.empty() || !o->bust.empty() || !o->under_bust.empty() || !o->waist.empty() ||
                        !o->hip.empty() || !o->shoulder.empty() || !o->neck.empty() || !o->arm.empty() ||
                        !o->inseam.empty() || !o->sex.empty();
    if (custom) {
      if (o->size.empty()) m.label = "custom";
      if (!o->sex.empty()) m.sex = o->sex;
      // Values that follow from the height or the bust are derived again unless given.
      const bool new_height = !o->height.empty(), new_bust = !o->bust.empty();
      if (new_height) m.height = *length(o->height);
      if (new_bust) m.bust = *length(o->bust);
      if (new_height || new_bust || !o->sex.empty()) {
        if (new_height || !o->sex.empty()) m.arm_length = m.inseam = 0;
        m.shoulder_width = 0;
        if (new_bust || !o->sex.empty()) m.neck = m.under_bust = 0;
      }
      auto set = [](const std::string& t, double& v) {
        if (!t.empty()) v = *length(t);
      };
      set(o->under_bust, m.under_bust), set(o->waist, m.waist), set(o->hip, m.hip), set(o->shoulder, m.shoulder_width);
      set(o->neck, m.neck), set(o->arm, m.arm_length), set(o->inseam, m.inseam);
      vgd::body::complete_measurements(m);
    }
    vgd::body::MannequinOptions mo;
    mo.target_triangles = o->triangles;
    mo.arm_angle_deg = o->arm_angle;
    mo.arm_forward_deg = o->arm_forward;
    const auto t0 = std::chrono::steady_clock::now();
    const auto avatar = vgd::body::make_mannequin(m, mo);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    vgd::body::export_avatar(avatar, o->output);
    auto report = vgd::body::report_avatar(avatar);
    report.file = o->output;
    report.format = std::filesystem::path(o->output).extension().string().substr(1);
    if (o->json) {
      auto j = nlohmann::json::parse(vgd::body::to_json(report));
      j["measurements"] = {{"label", m.label},           {"sex", m.sex},           {"height_m", m.height},
                           {"bust_m", m.bust},           {"under_bust_m", m.under_bust}, {"waist_m", m.waist},
                           {"hip_m", m.hip},             {"shoulder_width_m", m.shoulder_width}, {"neck_m", m.neck},
                           {"arm_length_m", m.arm_length}, {"inseam_m", m.inseam}};
      j["milliseconds"] = ms;
      vgd::cli::print_json(j);
    } else {
      std::printf("mannequin %s (%s): height %.3f m, bust %.3f, waist %.3f, hip %.3f m\n", m.label.c_str(), m.sex.c_str(),
                  m.height, m.bust, m.waist, m.hip);
      std::printf("%d vertices, %d triangles, %s, %zu segments; wrote %s\n", report.vertices, report.triangles,
                  report.watertight ? "watertight" : "NOT watertight", avatar.segments.size(), o->output.c_str());
      std::fflush(stdout);
    }
    vgd::cli::say(common, "vgd: generated the mannequin in " + std::to_string(static_cast<long>(ms)) + " ms");
    return vgd::cli::kOk;
  }};
}};

}  // namespace
}  // namespace cmd_mannequin
