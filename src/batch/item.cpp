// One work item: its commands, its manifest, its state (item.hpp).
#include "vgd/batch/item.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <fstream>
#include <nlohmann/json.hpp>

#include "vgd/batch/process.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/core/version.hpp"

namespace vgd::batch {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string join(const std::vector<std::string>& v, const char* sep) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
  return s;
}

// The key figures of a certificate.json, for the manifest and the summary.
json certificate_figures(const json& c) {
  json f;
  f["passed"] = c.value("passed", false);
  if (c.contains("stop")) {
    f["stop_reason"] = c["stop"].value("reason", "");
    f["simulated_s"] = c["stop"].value("simulated_s", 0.0);
    f["drape_wall_s"] = c["stop"].value("wall_s", 0.0);
  }
  int closed = 0, pairs = 0;
  if (c.contains("seams"))
    for (const auto& s : c["seams"]) closed += s.value("closed", 0), pairs += s.value("pairs", 0);
  f["seams_closed"] = closed;
  f["seam_pairs"] = pairs;
  if (c.contains("penetration")) f["max_penetration_mm"] = 1000.0 * c["penetration"].value("max_m", 0.0);
  f["crossings"] = c.value("triangle_intersections", -1);
  if (c.contains("cloth")) f["particles"] = c["cloth"].value("particles", 0);
  double strain = 0.0;
  if (c.contains("strain"))
    for (const auto& p : c["strain"])
      for (const char* d : {"warp", "weft"})
        if (p.contains(d)) strain = std::max(strain, p[d].value("p95", 0.0));
  f["strain_p95_max"] = strain;
  json failures = json::array();
  if (c.contains("failures"))
    for (const auto& x : c["failures"]) failures.push_back(x.value("class", ""));
  f["failures"] = failures;
  return f;
}

// The last line of a log that says what went wrong ("vgd: error: ...").
std::string last_error_line(const fs::path& log) {
  std::string text;
  try {
    text = read_file(log);
  } catch (const Error&) {
    return "";
  }
  std::string found;
  for (const auto& line : split(text, '\n'))
    if (line.find("error:") != std::string::npos || line.find("check failed:") != std::string::npos) found = line;
  found = std::string(trim(found));
  for (const char* lead : {"vgd: error: ", "vgd: "})
    if (found.rfind(lead, 0) == 0) return found.substr(std::string(lead).size());
  return found;
}

void list_files(const fs::path& root, std::vector<FileEntry>& out) {
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.is_regular_file() && e.path().filename() != "manifest.json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    FileEntry fe;
    fe.path = f.lexically_relative(root).generic_string();
    fe.bytes = fs::file_size(f);
    fe.sha256 = sha256_file(f);
    out.push_back(std::move(fe));
  }
}

// Moves the finished `partial` folder to `final` (an older one of the same
// id, a failed run redone, is replaced).
void publish(const fs::path& partial, const fs::path& final) {
  std::error_code ec;
  if (fs::exists(final, ec)) {
    const fs::path old = final.string() + ".old";
    fs::remove_all(old, ec);
    fs::rename(final, old, ec);
    if (ec) throw Error(final.string(), "", "cannot move the earlier result aside: " + ec.message());
    fs::rename(partial, final, ec);
    if (ec) throw Error(final.string(), "", "cannot publish the item: " + ec.message());
    fs::remove_all(old, ec);
    return;
  }
  fs::rename(partial, final, ec);
  if (ec) throw Error(final.string(), "", "cannot publish the item: " + ec.message());
}

Manifest base_manifest(const Catalogue& c, const Item& item) {
  Manifest m;
  m.id = item.id, m.name = item.name, m.index = item.index, m.size = item.size;
  m.style = c.styles[item.style].id;
  m.fabric = c.fabrics[item.fabric].id;
  m.avatar = c.avatars[item.avatar].id;
  m.vgd_version = kVersion;
  return m;
}

}  // namespace

std::string failure_class_of_check(const std::string& kind) {
  if (kind == "penetration") return "body penetration";
  if (kind == "error") return "diverged";
  return kind;  // no rest, seams open, open side, self-intersection, over-stretched, displaced
}

std::vector<Step> item_steps(const Catalogue& c, const Item& item, const fs::path& dir) {
  const Style& st = c.styles[item.style];
  const Fabric& fa = c.fabrics[item.fabric];
  const Avatar& av = c.avatars[item.avatar];
  const Outputs& o = c.outputs;
  const bool need_trj = o.trj || o.wvt || o.vrml || o.vrml_animated || o.glb;
  std::vector<Step> steps;
  Step dress{"dress", {"dress", st.file.string(), "-o", dir.string(), "--quality", c.settings.quality,
                       "--time-limit", format_double(c.settings.time_limit), "--model", c.settings.model}};
  auto& a = dress.args;
  if (item.size != "sample") a.insert(a.end(), {"--size", item.size});
  if (!st.seams.empty()) a.insert(a.end(), {"--seams", st.seams.string()});
  if (c.settings.spacing > 0) a.insert(a.end(), {"--spacing", format_double(c.settings.spacing)});
  if (!fa.file.empty()) {
    a.insert(a.end(), {"--material", fa.file.string()});
    if (!fa.material.empty()) a.insert(a.end(), {"--material-id", fa.material});
  }
  if (av.kind == Avatar::Kind::mannequin) {
    a.insert(a.end(), {"--body-size", av.size});
    if (!av.table.empty()) a.insert(a.end(), {"--body-table", av.table});
  } else if (av.kind == Avatar::Kind::file) {
    a.insert(a.end(), {"--avatar", av.file.string(), "--unit", av.unit, "--up", av.up, "--facing", av.facing});
  } else if (av.kind == Avatar::Kind::measurements) {
    // The body made first, as vgd mannequin makes it, in vgd's frame.
    Step body{"mannequin", {"mannequin", "-o", (dir / "body.obj").string()}};
    if (!av.sex.empty()) body.args.insert(body.args.end(), {"--sex", av.sex});
    for (const auto& [k, x] : av.measurements) {
      std::string opt = "--" + k;
      std::replace(opt.begin(), opt.end(), '_', '-');
      body.args.insert(body.args.end(), {opt, format_double(x)});
    }
    steps.push_back(std::move(body));
    a.insert(a.end(), {"--avatar", (dir / "body.obj").string(), "--unit", "m", "--up", "y", "--facing", "+z"});
  }
  if (need_trj) a.insert(a.end(), {"--trj", (dir / "drape.trj").string()});
  if (o.previews)
    a.insert(a.end(), {"--views", join(o.views, ","), "--preview-size", std::to_string(o.preview_size)});
  else
    a.push_back("--no-previews");
  steps.push_back(std::move(dress));
  const std::string trj = (dir / "drape.trj").string();
  if (o.wvt) steps.push_back({"compress", {"compress", trj, "-o", (dir / "drape.wvt").string()}});
  const std::vector<std::string> looks = {"--document", (dir / "garment.xvc").string(), "--avatar",
                                          (dir / "avatar.obj").string()};
  if (o.vrml || o.glb) {
    Step ex{"export", {"export", trj}};
    if (o.vrml) ex.args.insert(ex.args.end(), {"--vrml", "static", "-o", (dir / "garment.wrl").string()});
    if (o.glb) ex.args.insert(ex.args.end(), {"--gltf", (dir / "garment.glb").string()});
    ex.args.insert(ex.args.end(), looks.begin(), looks.end());
    steps.push_back(std::move(ex));
  }
  if (o.vrml_animated) {
    Step ex{"export-animated",
            {"export", trj, "--vrml", "animated", "--decimate", "2", "-o", (dir / "garment-animated.wrl.gz").string()}};
    ex.args.insert(ex.args.end(), looks.begin(), looks.end());
    steps.push_back(std::move(ex));
  }
  // Threads per item (vgd's --threads; OMP_NUM_THREADS is not read).
  for (auto& step : steps) step.args.insert(step.args.begin(), {"--threads", std::to_string(c.settings.threads)});
  return steps;
}

std::string to_json(const Manifest& m) {
  json j;
  j["format"] = "vgd-batch-item/1";
  j["id"] = m.id, j["index"] = m.index, j["name"] = m.name;
  j["style"] = m.style, j["size"] = m.size, j["fabric"] = m.fabric, j["avatar"] = m.avatar;
  j["state"] = m.state;
  j["failure"] = m.state == "passed" ? json(nullptr)
                                     : json{{"class", m.failure_class}, {"message", m.failure_message}};
  j["wall_s"] = m.wall_s;
  j["started"] = m.started, j["finished"] = m.finished;
  j["vgd_version"] = m.vgd_version;
  j["certificate"] = m.certificate.empty() ? json(nullptr) : json::parse(m.certificate);
  json steps = json::array();
  for (const auto& st : m.steps) steps.push_back({{"name", st.name}, {"wall_s", st.wall_s}, {"result", st.result}});
  j["steps"] = steps;
  json files = json::array();
  for (const auto& f : m.files) files.push_back({{"path", f.path}, {"bytes", f.bytes}, {"sha256", f.sha256}});
  j["files"] = files;
  return j.dump(2) + "\n";
}

Manifest manifest_from_json(const std::string& text, const std::string& file) {
  try {
    const json j = json::parse(text);
    if (j.value("format", "") != "vgd-batch-item/1") throw Error(file, "format", "not a vgd batch item manifest");
    Manifest m;
    m.id = j.at("id"), m.index = j.at("index"), m.name = j.at("name");
    m.style = j.at("style"), m.size = j.at("size"), m.fabric = j.at("fabric"), m.avatar = j.at("avatar");
    m.state = j.at("state");
    if (m.state != "passed" && m.state != "failed") throw Error(file, "state", "'" + m.state + "' is not passed or failed");
    if (!j.at("failure").is_null()) {
      m.failure_class = j["failure"].at("class");
      m.failure_message = j["failure"].at("message");
    }
    m.wall_s = j.at("wall_s");
    m.started = j.at("started"), m.finished = j.at("finished"), m.vgd_version = j.at("vgd_version");
    if (!j.at("certificate").is_null()) m.certificate = j["certificate"].dump();
    for (const auto& st : j.value("steps", json::array()))
      m.steps.push_back({st.at("name"), st.at("wall_s"), st.at("result")});
    for (const auto& f : j.at("files")) m.files.push_back({f.at("path"), f.at("bytes"), f.at("sha256")});
    return m;
  } catch (const json::exception& e) {
    throw Error(file, "", json_error_message(e.what(), "not a readable manifest"));
  }
}

const char* to_string(ItemState s) {
  switch (s) {
    case ItemState::pending: return "pending";
    case ItemState::partial: return "partial";
    case ItemState::passed: return "passed";
    case ItemState::failed: return "failed";
  }
  return "?";
}

fs::path item_dir(const fs::path& out, const std::string& id) { return out / "items" / id; }

ItemStatus item_status(const fs::path& out, const Item& item, bool checksums) {
  ItemStatus s;
  const fs::path dir = item_dir(out, item.id);
  std::error_code ec;
  const bool partial = fs::exists(dir.string() + ".partial", ec);
  if (!fs::exists(dir / "manifest.json", ec)) {
    s.state = partial || fs::exists(dir, ec) ? ItemState::partial : ItemState::pending;
    if (s.state == ItemState::partial) s.problem = "no manifest.json: the item did not finish";
    return s;
  }
  try {
    Manifest m = manifest_from_json(read_file(dir / "manifest.json"), (dir / "manifest.json").string());
    if (m.id != item.id) throw Error((dir / "manifest.json").string(), "id", "is " + m.id + ", not " + item.id);
    for (const auto& f : m.files) {
      const fs::path p = dir / f.path;
      if (f.path.find("..") != std::string::npos) throw Error(p.string(), "", "a path outside the item");
      if (!fs::is_regular_file(p, ec)) throw Error(p.string(), "", "missing");
      if (fs::file_size(p, ec) != f.bytes)
        throw Error(p.string(), "", std::to_string(fs::file_size(p, ec)) + " bytes, the manifest says " +
                                        std::to_string(f.bytes));
      if (checksums && sha256_file(p) != f.sha256) throw Error(p.string(), "", "its SHA-256 is not the manifest's");
    }
    s.state = m.state == "passed" ? ItemState::passed : ItemState::failed;
    s.manifest = std::move(m);
  } catch (const Error& e) {
    s.state = ItemState::partial;
    s.problem = e.what();
  }
  return s;
}

void record_failure(const fs::path& out, const Catalogue& c, const Item& item, const std::string& failure_class,
                    const std::string& message) {
  Manifest m = base_manifest(c, item);
  m.state = "failed";
  m.failure_class = failure_class;
  m.failure_message = message;
  m.started = m.finished = utc_now();
  const fs::path partial = item_dir(out, item.id).string() + ".partial";
  std::error_code ec;
  fs::remove_all(partial, ec);
  fs::create_directories(partial, ec);
  write_file_atomic(partial / "manifest.json", to_json(m));
  publish(partial, item_dir(out, item.id));
}

ItemOutcome run_item(const Catalogue& c, const Item& item, const fs::path& out, const RunItemOptions& options) {
  ItemOutcome outcome;
  const fs::path final = item_dir(out, item.id);
  if (!options.force) {
    const ItemStatus s = item_status(out, item);
    if (s.state == ItemState::passed || (s.state == ItemState::failed && !options.retry_failed)) {
      outcome.skipped = true;
      outcome.manifest = *s.manifest;
      return outcome;
    }
  }
  const fs::path partial = final.string() + ".partial";
  std::error_code ec;
  fs::remove_all(partial, ec);
  fs::create_directories(partial, ec);
  if (ec) throw Error(partial.string(), "", "cannot make the item's folder: " + ec.message());

  Manifest m = base_manifest(c, item);
  m.started = utc_now();
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path log = partial / "log.txt";
  write_file_atomic(log, "vgd batch item " + std::to_string(item.index) + " (" + item.id + "): " + item.name + "\n");
  ProcessOptions po;
  po.log = log;
  po.env = {{"OMP_WAIT_POLICY", "PASSIVE"}};
  po.memory_mb = c.settings.memory_mb;
  bool drape_ran = false;
  for (const Step& step : item_steps(c, item, partial)) {
    const double used = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    po.deadline_s = std::max(1.0, c.settings.wall_limit - used);
    {
      std::ofstream l(log, std::ios::app);
      l << "$ vgd";
      for (const auto& a : step.args) l << ' ' << a;
      l << '\n';
    }
    const ProcessResult r = run_process(options.exe, step.args, po);
    m.steps.push_back({step.name, r.wall_s, r.describe()});
    if (step.name == "mannequin" && !r.ok()) {
      m.failure_class = r.timed_out ? "time-out" : r.signal != 0 ? "crash" : "bad input";
      m.failure_message = "vgd mannequin " + r.describe() + ": " + last_error_line(log);
      break;
    }
    if (step.name == "dress") {
      if (r.timed_out) {
        m.failure_class = "time-out";
        m.failure_message = "the drape " + r.describe() + " (settings.wall_limit " +
                            format_double(c.settings.wall_limit) + " s)";
        break;
      }
      if (r.signal != 0) {
        m.failure_class = "crash";
        m.failure_message = "vgd dress " + r.describe();
        break;
      }
      if (fs::exists(partial / "certificate.json", ec)) {
        drape_ran = true;
        const json cert = json::parse(read_file(partial / "certificate.json"), nullptr, false);
        if (!cert.is_discarded()) {
          const json fig = certificate_figures(cert);
          m.certificate = fig.dump();
          if (!fig["passed"].get<bool>()) {
            // The first check that failed names the class (certificate.hpp's fixed order).
            const json first = cert.contains("failures") && !cert["failures"].empty() ? cert["failures"][0] : json();
            m.failure_class = failure_class_of_check(first.is_object() ? first.value("class", "") : "");
            m.failure_message = first.is_object() ? first.value("detail", "") : "";
            if (m.failure_class.empty()) m.failure_class = "check failed";
          }
        }
      }
      if (r.exit_code != 0 && r.exit_code != 3 && m.failure_class.empty()) {
        m.failure_message = last_error_line(log);
        m.failure_class = m.failure_message.find("bad_alloc") != std::string::npos
                              ? "out of memory"
                              : drape_ran ? "diverged" : "bad input";
        if (m.failure_class == "out of memory")
          m.failure_message = "past settings.memory_mb (" + std::to_string(c.settings.memory_mb) + " MB of address space): " +
                              m.failure_message;
        if (m.failure_message.empty()) m.failure_message = "vgd dress " + r.describe();
      }
      if (!drape_ran) break;
      continue;
    }
    if (!r.ok() && m.failure_class.empty()) {
      m.failure_class = r.timed_out ? "time-out" : r.signal != 0 ? "crash" : "output";
      m.failure_message = "vgd " + step.name + " " + r.describe() + ": " + last_error_line(log);
    }
  }
  if (!c.outputs.trj) fs::remove(partial / "drape.trj", ec);
  fs::remove(partial / "drape.trj.partial", ec);
  m.state = m.failure_class.empty() ? "passed" : "failed";
  m.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  m.finished = utc_now();
  list_files(partial, m.files);
  write_file_atomic(partial / "manifest.json", to_json(m));
  publish(partial, final);
  outcome.manifest = std::move(m);
  return outcome;
}

}  // namespace vgd::batch
