// A catalogue run's state, summaries and contact sheet (report.hpp).
#include "vgd/batch/report.hpp"

#include <nlohmann/json.hpp>
#include <set>

#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/io/vrml/web.hpp"

namespace vgd::batch {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string html(const std::string& s) { return html_escape(s); }

json figures(const ItemStatus& s) {
  if (!s.manifest || s.manifest->certificate.empty()) return json::object();
  return json::parse(s.manifest->certificate, nullptr, false);
}

bool has_file(const ItemStatus& s, const std::string& path) {
  if (!s.manifest) return false;
  for (const auto& f : s.manifest->files)
    if (f.path == path) return true;
  return false;
}

}  // namespace

std::vector<int> Status::unfinished() const {
  std::vector<int> v;
  for (std::size_t i = 0; i < items.size(); ++i)
    if (items[i].state == ItemState::pending || items[i].state == ItemState::partial) v.push_back(static_cast<int>(i));
  return v;
}

std::vector<int> Status::failed_indices() const {
  std::vector<int> v;
  for (std::size_t i = 0; i < items.size(); ++i)
    if (items[i].state == ItemState::failed) v.push_back(static_cast<int>(i));
  return v;
}

Status status(const Catalogue& c, const fs::path& out, bool checksums) {
  Status s;
  for (const Item& item : c.items) {
    s.items.push_back(item_status(out, item, checksums));
    const ItemStatus& is = s.items.back();
    switch (is.state) {
      case ItemState::pending: ++s.pending; break;
      case ItemState::partial: ++s.partial; break;
      case ItemState::passed: ++s.passed; break;
      case ItemState::failed:
        ++s.failed;
        s.failed_by_class[is.manifest->failure_class].push_back(item.index);
        break;
    }
  }
  return s;
}

std::string summary_csv(const Catalogue& c, const Status& s) {
  std::string o =
      "index,id,style,size,fabric,avatar,state,failure_class,failure_message,seams_closed,seam_pairs,"
      "max_penetration_mm,crossings,strain_p95_max,simulated_s,wall_s,preview\n";
  for (const Item& item : c.items) {
    const ItemStatus& is = s.items[static_cast<std::size_t>(item.index)];
    const json f = figures(is);
    auto num = [&](const char* k, int d) { return f.contains(k) ? format_fixed(f[k].get<double>(), d) : std::string(); };
    const std::string preview = "items/" + item.id + "/previews/" + c.outputs.views.front() + ".png";
    o += std::to_string(item.index) + "," + item.id + "," + csv_field(c.styles[item.style].id) + "," +
         csv_field(item.size) + "," + csv_field(c.fabrics[item.fabric].id) + "," + csv_field(c.avatars[item.avatar].id) +
         "," + to_string(is.state) + "," + csv_field(is.manifest ? is.manifest->failure_class : "") + "," +
         csv_field(is.manifest ? is.manifest->failure_message : is.problem) + "," +
         (f.contains("seams_closed") ? std::to_string(f["seams_closed"].get<int>()) : "") + "," +
         (f.contains("seam_pairs") ? std::to_string(f["seam_pairs"].get<int>()) : "") + "," +
         num("max_penetration_mm", 2) + "," + (f.contains("crossings") ? std::to_string(f["crossings"].get<int>()) : "") +
         "," + num("strain_p95_max", 4) + "," + num("simulated_s", 2) + "," +
         (is.manifest ? format_fixed(is.manifest->wall_s, 1) : "") + "," +
         (has_file(is, "previews/" + c.outputs.views.front() + ".png") ? preview : "") + "\n";
  }
  return o;
}

std::string summary_json(const Catalogue& c, const Status& s) {
  json j;
  j["catalogue"] = c.file.string();
  j["name"] = c.name;
  j["counts"] = {{"items", c.items.size()}, {"passed", s.passed}, {"failed", s.failed},
                 {"partial", s.partial},    {"pending", s.pending}};
  json by_class = json::object();
  for (const auto& [k, v] : s.failed_by_class) by_class[k] = v;
  j["failed_by_class"] = by_class;
  json items = json::array();
  for (const Item& item : c.items) {
    const ItemStatus& is = s.items[static_cast<std::size_t>(item.index)];
    json e = {{"index", item.index},
              {"id", item.id},
              {"style", c.styles[item.style].id},
              {"size", item.size},
              {"fabric", c.fabrics[item.fabric].id},
              {"avatar", c.avatars[item.avatar].id},
              {"state", to_string(is.state)},
              {"dir", "items/" + item.id}};
    if (is.manifest) {
      e["failure"] = is.manifest->state == "passed"
                         ? json(nullptr)
                         : json{{"class", is.manifest->failure_class}, {"message", is.manifest->failure_message}};
      e["wall_s"] = is.manifest->wall_s;
      e["certificate"] = figures(is);
      json files = json::array();
      for (const auto& f : is.manifest->files) files.push_back(f.path);
      e["files"] = files;
    } else if (!is.problem.empty()) {
      e["problem"] = is.problem;
    }
    items.push_back(e);
  }
  j["items"] = items;
  return j.dump(2) + "\n";
}

std::string contact_sheet_html(const Catalogue& c, const Status& s, bool viewer_pages) {
  std::set<std::string> styles, sizes, fabrics, avatars;
  for (const Item& item : c.items) {
    styles.insert(c.styles[item.style].id), sizes.insert(item.size);
    fabrics.insert(c.fabrics[item.fabric].id), avatars.insert(c.avatars[item.avatar].id);
  }
  std::string o;
  o += "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>" + html(c.name) +
       " — vgd catalogue</title>\n<style>\n"
       "body{font:14px system-ui,sans-serif;margin:1em;background:#f4f4f4;color:#222}\n"
       "header{display:flex;gap:1em;align-items:baseline;flex-wrap:wrap}\n"
       "#cards{display:grid;grid-template-columns:repeat(auto-fill,minmax(220px,1fr));gap:12px;margin-top:1em}\n"
       ".card{background:#fff;border-radius:6px;padding:8px;box-shadow:0 1px 3px #0002}\n"
       ".card img{width:100%;aspect-ratio:1;object-fit:contain;background:#ddd;display:block}\n"
       ".noimg{width:100%;aspect-ratio:1;background:#ddd;display:flex;align-items:center;justify-content:center;color:#777}\n"
       ".badge{display:inline-block;padding:1px 6px;border-radius:3px;color:#fff;font-weight:600}\n"
       ".passed{background:#2a7d2a}.failed{background:#b02a2a}.pending,.partial{background:#888}\n"
       ".fig{color:#555;font-size:12px}\n"
       "</style></head><body>\n<header><h1>" + html(c.name) + "</h1><span id=\"counts\">" +
       std::to_string(c.items.size()) + " items: " + std::to_string(s.passed) + " passed, " +
       std::to_string(s.failed) + " failed, " + std::to_string(s.pending + s.partial) + " not finished</span></header>\n";
  o += "<form id=\"filters\">\n";
  const auto select = [&](const char* key, const char* label, const std::set<std::string>& values) {
    o += "<label>" + std::string(label) + " <select name=\"" + key + "\"><option value=\"\">all</option>";
    for (const auto& v : values) o += "<option>" + html(v) + "</option>";
    o += "</select></label>\n";
  };
  select("style", "style", styles);
  select("size", "size", sizes);
  select("fabric", "fabric", fabrics);
  select("avatar", "body", avatars);
  select("state", "state", {"passed", "failed", "partial", "pending"});
  o += "<span id=\"shown\"></span></form>\n<div id=\"cards\">\n";
  const std::string view = c.outputs.views.front();
  for (const Item& item : c.items) {
    const ItemStatus& is = s.items[static_cast<std::size_t>(item.index)];
    const json f = figures(is);
    const std::string dir = "items/" + item.id + "/";
    const std::string state = to_string(is.state);
    o += "<div class=\"card\" data-style=\"" + html(c.styles[item.style].id) + "\" data-size=\"" + html(item.size) +
         "\" data-fabric=\"" + html(c.fabrics[item.fabric].id) + "\" data-avatar=\"" +
         html(c.avatars[item.avatar].id) + "\" data-state=\"" + state + "\">\n";
    if (has_file(is, "previews/" + view + ".png"))
      o += "<img loading=\"lazy\" src=\"" + html(dir + "previews/" + view + ".png") + "\" alt=\"" + html(item.name) + "\">\n";
    else
      o += "<div class=\"noimg\">no preview</div>\n";
    o += "<div><span class=\"badge " + state + "\">" + state + "</span> <b>" + html(c.styles[item.style].id) +
         "</b> " + html(item.size) + "</div>\n<div>" + html(c.fabrics[item.fabric].id) + " · " +
         html(c.avatars[item.avatar].id) + "</div>\n";
    if (is.manifest && is.manifest->state == "failed")
      o += "<div class=\"fig\"><b>" + html(is.manifest->failure_class) + "</b>: " +
           html(is.manifest->failure_message) + "</div>\n";
    if (f.contains("seam_pairs"))
      o += "<div class=\"fig\">seams " + std::to_string(f["seams_closed"].get<int>()) + "/" +
           std::to_string(f["seam_pairs"].get<int>()) + " · penetration " +
           format_fixed(f.value("max_penetration_mm", 0.0), 1) + " mm · crossings " +
           std::to_string(f.value("crossings", -1)) + " · strain p95 " +
           format_fixed(100 * f.value("strain_p95_max", 0.0), 1) + " %</div>\n";
    if (is.manifest)
      o += "<div class=\"fig\">" + format_fixed(f.value("simulated_s", 0.0), 2) + " s simulated, " +
           format_fixed(is.manifest->wall_s, 1) + " s wall</div>\n";
    std::string links;
    for (const auto& [file, label] : std::vector<std::pair<std::string, std::string>>{
             {"certificate.json", "certificate"}, {"garment.wrl", "VRML"}, {"garment-animated.wrl.gz", "animated"},
             {"garment.glb", "glTF"}, {"drape.wvt", "wvt"}, {"drape.trj", "trj"}, {"log.txt", "log"}})
      if (has_file(is, file)) links += " <a href=\"" + html(dir + file) + "\">" + label + "</a>";
    if (viewer_pages && has_file(is, "garment.wrl")) links = " <a href=\"web/" + item.id + ".html\">3-D view</a>" + links;
    if (!links.empty()) o += "<div class=\"fig\">" + links + "</div>\n";
    o += "</div>\n";
  }
  o += "</div>\n<script>\n"
       "const form=document.getElementById('filters');\n"
       "function apply(){const f=new FormData(form);let n=0;\n"
       " for(const c of document.querySelectorAll('.card')){let ok=true;\n"
       "  for(const [k,v] of f.entries()) if(v&&c.dataset[k]!==v) ok=false;\n"
       "  c.hidden=!ok; if(ok) n++;}\n"
       " document.getElementById('shown').textContent=n+' shown';}\n"
       "form.addEventListener('change',apply);apply();\n"
       "</script>\n</body></html>\n";
  return o;
}

int write_summary(const Catalogue& c, const fs::path& out, const Status& s, const fs::path& x_ite_dist) {
  namespace vrml = vgd::io::vrml;
  std::vector<vrml::WebEntry> pages;
  const fs::path x_ite = x_ite_dist.empty() ? vrml::default_x_ite_dir() : x_ite_dist;
  if (!x_ite.empty() && fs::is_regular_file(x_ite / "x_ite.min.js")) {
    for (const Item& item : c.items) {
      const ItemStatus& is = s.items[static_cast<std::size_t>(item.index)];
      if (!has_file(is, "garment.wrl")) continue;
      vrml::WebEntry e;
      e.name = item.id;
      e.title = item.name;
      const std::string dir = "../items/" + item.id + "/";
      e.wrl = dir + "garment.wrl";
      for (const auto& [file, label] : std::vector<std::pair<std::string, std::string>>{
               {"garment-animated.wrl.gz", "VRML, animated"}, {"garment.glb", "glTF (.glb)"},
               {"drape.wvt", "trajectory (.wvt)"}, {"certificate.json", "certificate"}})
        if (has_file(is, file)) e.downloads.push_back({label, dir + file});
      e.facts = {{"style", c.styles[item.style].id}, {"size", item.size}, {"fabric", c.fabrics[item.fabric].id},
                 {"body", c.avatars[item.avatar].id}, {"state", to_string(is.state)}};
      if (is.manifest && !is.manifest->failure_class.empty()) e.facts.push_back({"failure", is.manifest->failure_class});
      pages.push_back(std::move(e));
    }
    if (!pages.empty()) vrml::write_web_catalogue(out / "web", pages, x_ite);
  }
  write_file_atomic(out / "summary.csv", summary_csv(c, s));
  write_file_atomic(out / "summary.json", summary_json(c, s));
  write_file_atomic(out / "index.html", contact_sheet_html(c, s, !pages.empty()));
  return static_cast<int>(pages.size());
}

}  // namespace vgd::batch
