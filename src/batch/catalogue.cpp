// Reading a catalogue.json and expanding it into work items (catalogue.hpp).
#include "vgd/batch/catalogue.hpp"

#include <openssl/evp.h>

#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>

#include "vgd/core/data.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"

namespace vgd::batch {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct Digest {
  Digest() : ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free) {
    if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1)
      throw Error("", "", "SHA-256 is not available (OpenSSL)");
  }
  void update(const void* data, std::size_t n) { EVP_DigestUpdate(ctx.get(), data, n); }
  std::string hex() {
    unsigned char md[EVP_MAX_MD_SIZE];
    unsigned int len = 0;
    EVP_DigestFinal_ex(ctx.get(), md, &len);
    static const char* digits = "0123456789abcdef";
    std::string s;
    for (unsigned i = 0; i < len; ++i) {
      s += digits[md[i] >> 4];
      s += digits[md[i] & 15];
    }
    return s;
  }
  std::unique_ptr<EVP_MD_CTX, void (*)(EVP_MD_CTX*)> ctx;
};

// Reading with the catalogue's name and the field's path in every error.
struct Reader {
  std::string file;
  fs::path base;

  [[noreturn]] void fail(const std::string& field, const std::string& message) const {
    throw Error(file, field, message);
  }
  void only_keys(const json& j, const std::string& field, std::initializer_list<const char*> keys) const {
    if (!j.is_object()) fail(field, "expected an object");
    for (const auto& [k, v] : j.items()) {
      bool known = false;
      for (const char* key : keys) known = known || k == key;
      if (!known) {
        std::string list;
        for (const char* key : keys) list += (list.empty() ? "" : ", ") + std::string(key);
        fail(field.empty() ? k : field + "." + k, "unknown key (known here: " + list + ")");
      }
    }
  }
  std::string string(const json& j, const std::string& field) const {
    if (!j.is_string()) fail(field, "expected a string");
    const std::string s = j.get<std::string>();
    if (s.empty()) fail(field, "is empty");
    return s;
  }
  double number(const json& j, const std::string& field, double lo, double hi) const {
    if (!j.is_number()) fail(field, "expected a number");
    const double v = j.get<double>();
    if (!(v >= lo && v <= hi))
      fail(field, format_double(v) + " is out of range (" + format_double(lo) + " to " + format_double(hi) + ")");
    return v;
  }
  fs::path existing_file(const json& j, const std::string& field) const {
    const fs::path p = base / string(j, field);
    std::error_code ec;
    if (!fs::is_regular_file(p, ec)) fail(field, "no such file: " + p.string());
    return fs::absolute(p).lexically_normal();
  }
  std::string id(const json& j, const std::string& field) const {
    const std::string s = string(j, field);
    for (char c : s)
      if (static_cast<unsigned char>(c) < 0x20 || c == '/' || c == '\\' || c == '"')
        fail(field, "'" + printable(s) + "': an id may not hold '/', '\\', '\"' or control characters");
    return s;
  }
  std::vector<std::string> strings(const json& j, const std::string& field) const {
    if (!j.is_array() || j.empty()) fail(field, "expected a non-empty list of strings");
    std::vector<std::string> out;
    std::set<std::string> seen;
    for (std::size_t i = 0; i < j.size(); ++i) {
      out.push_back(string(j[i], field + "[" + std::to_string(i) + "]"));
      if (!seen.insert(out.back()).second) fail(field + "[" + std::to_string(i) + "]", "'" + out.back() + "' twice");
    }
    return out;
  }
};

template <class T>
void unique_ids(const Reader& r, const std::vector<T>& list, const std::string& field) {
  std::set<std::string> seen;
  for (std::size_t i = 0; i < list.size(); ++i)
    if (!seen.insert(list[i].id).second)
      r.fail(field + "[" + std::to_string(i) + "].id", "'" + list[i].id + "' is the id of an earlier entry");
}

}  // namespace

std::string sha256_hex(std::string_view bytes) {
  Digest d;
  d.update(bytes.data(), bytes.size());
  return d.hex();
}

std::string sha256_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(file.string(), "", "cannot be read");
  Digest d;
  std::vector<char> buf(1 << 16);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    if (in.gcount() > 0) d.update(buf.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw Error(file.string(), "", "read error");
  return d.hex();
}

Catalogue load_catalogue(const fs::path& file) {
  Catalogue c;
  c.file = fs::absolute(file).lexically_normal();
  Reader r{file.string(), c.file.parent_path()};
  const std::string text = read_file(file);
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    throw Error(file.string(), "", json_error_message(e.what(), "not valid JSON"));
  }
  r.only_keys(j, "", {"name", "styles", "sizes", "fabrics", "avatars", "settings", "outputs", "views", "preview_size"});
  c.name = j.contains("name") ? r.id(j["name"], "name") : c.file.stem().string();

  // Styles.
  if (!j.contains("styles") || !j["styles"].is_array() || j["styles"].empty())
    r.fail("styles", "expected a non-empty list of styles ({\"id\": ..., \"file\": ...})");
  const std::vector<std::string> sizes =
      j.contains("sizes") ? r.strings(j["sizes"], "sizes") : std::vector<std::string>{"sample"};
  for (std::size_t i = 0; i < j["styles"].size(); ++i) {
    const std::string f = "styles[" + std::to_string(i) + "]";
    const json& s = j["styles"][i];
    r.only_keys(s, f, {"id", "file", "sizes", "seams"});
    Style st;
    if (!s.contains("file")) r.fail(f + ".file", "missing: the style's DXF or XVC file");
    st.file = r.existing_file(s["file"], f + ".file");
    st.id = s.contains("id") ? r.id(s["id"], f + ".id") : st.file.stem().string();
    st.sizes = s.contains("sizes") ? r.strings(s["sizes"], f + ".sizes") : sizes;
    st.sha256 = sha256_file(st.file);
    if (s.contains("seams")) {
      st.seams = r.existing_file(s["seams"], f + ".seams");
      st.sha256 = sha256_hex(st.sha256 + " " + sha256_file(st.seams));
    }
    c.styles.push_back(std::move(st));
  }
  unique_ids(r, c.styles, "styles");

  // Fabrics: "garment", a shipped material's name, or {id, file, material}.
  const json fabrics = j.contains("fabrics") ? j["fabrics"] : json::array({"garment"});
  if (!fabrics.is_array() || fabrics.empty()) r.fail("fabrics", "expected a non-empty list");
  for (std::size_t i = 0; i < fabrics.size(); ++i) {
    const std::string f = "fabrics[" + std::to_string(i) + "]";
    const json& v = fabrics[i];
    Fabric fa;
    if (v.is_string()) {
      fa.id = r.id(v, f);
      if (fa.id != "garment") {
        try {
          fa.file = data_file("materials/" + fa.id + ".xvc");
        } catch (const Error&) {
          r.fail(f, "'" + fa.id + "' is neither \"garment\" nor a shipped material (data/materials/*.xvc); "
                    "give {\"id\": ..., \"file\": ..., \"material\": ...} for a fabric of your own");
        }
      }
    } else {
      r.only_keys(v, f, {"id", "file", "material"});
      if (!v.contains("file")) r.fail(f + ".file", "missing: the XVC document holding the MATERIAL");
      fa.file = r.existing_file(v["file"], f + ".file");
      fa.id = v.contains("id") ? r.id(v["id"], f + ".id") : fa.file.stem().string();
      if (v.contains("material")) fa.material = r.string(v["material"], f + ".material");
    }
    if (!fa.file.empty()) fa.sha256 = sha256_file(fa.file);
    c.fabrics.push_back(std::move(fa));
  }
  unique_ids(r, c.fabrics, "fabrics");

  // Avatars: "mannequin" (the item's size), {id, mannequin, table} or {id, file, unit, up, facing}.
  const json avatars = j.contains("avatars") ? j["avatars"] : json::array({"mannequin"});
  if (!avatars.is_array() || avatars.empty()) r.fail("avatars", "expected a non-empty list");
  for (std::size_t i = 0; i < avatars.size(); ++i) {
    const std::string f = "avatars[" + std::to_string(i) + "]";
    const json& v = avatars[i];
    Avatar a;
    if (v.is_string()) {
      a.id = r.id(v, f);
      if (a.id != "mannequin")
        r.fail(f, "'" + a.id + "': a string here must be \"mannequin\" (the mannequin of each item's size); "
                  "give {\"id\": ..., \"mannequin\": SIZE} or {\"id\": ..., \"file\": ...} for another body");
    } else {
      r.only_keys(v, f, {"id", "mannequin", "table", "file", "unit", "up", "facing", "measurements"});
      if (int(v.contains("mannequin")) + int(v.contains("file")) + int(v.contains("measurements")) != 1)
        r.fail(f, "give one of \"mannequin\": SIZE, \"measurements\": {...} or \"file\": a body mesh");
      if (v.contains("measurements")) {
        // A measurement set, metres (vgd mannequin's options: what is not given is derived).
        a.kind = Avatar::Kind::measurements;
        const std::string mf = f + ".measurements";
        const json& ms = v["measurements"];
        r.only_keys(ms, mf, {"sex", "height", "bust", "under_bust", "waist", "hip", "shoulder", "neck", "arm", "inseam"});
        if (ms.empty()) r.fail(mf, "give at least one measurement (height, bust, waist, hip, ...), in metres");
        for (const auto& [k, x] : ms.items()) {
          if (k == "sex") {
            a.sex = r.string(x, mf + ".sex");
            if (a.sex != "female" && a.sex != "male") r.fail(mf + ".sex", "'" + a.sex + "' is not female or male");
            continue;
          }
          const double hi = k == "height" ? 2.5 : 2.0;
          a.measurements.push_back({k, r.number(x, mf + "." + k, 0.05, hi)});
        }
        a.id = v.contains("id") ? r.id(v["id"], f + ".id") : "measured-" + std::to_string(i);
        if (v.contains("table") || v.contains("unit") || v.contains("up") || v.contains("facing"))
          r.fail(f, "table, unit, up and facing are not for a measurement set (metres, the mannequin's pose)");
      } else if (v.contains("mannequin")) {
        a.kind = Avatar::Kind::mannequin;
        a.size = r.string(v["mannequin"], f + ".mannequin");
        if (v.contains("table")) a.table = r.string(v["table"], f + ".table");
        a.id = v.contains("id") ? r.id(v["id"], f + ".id") : "mannequin-" + a.size;
        if (v.contains("unit") || v.contains("up") || v.contains("facing"))
          r.fail(f, "unit, up and facing are for a body file, not a mannequin");
      } else {
        a.kind = Avatar::Kind::file;
        a.file = r.existing_file(v["file"], f + ".file");
        a.id = v.contains("id") ? r.id(v["id"], f + ".id") : a.file.stem().string();
        if (v.contains("table")) r.fail(f + ".table", "a table is for a mannequin, not a body file");
        const auto one_of = [&](const char* key, std::initializer_list<const char*> allowed) {
          if (!v.contains(key)) return std::string("auto");
          const std::string s = r.string(v[key], f + "." + key);
          for (const char* x : allowed)
            if (s == x) return s;
          std::string list;
          for (const char* x : allowed) list += (list.empty() ? "" : ", ") + std::string(x);
          r.fail(f + "." + key, "'" + s + "' is not one of " + list);
        };
        a.unit = one_of("unit", {"auto", "m", "dm", "cm", "mm", "in"});
        a.up = one_of("up", {"auto", "x", "y", "z", "-x", "-y", "-z"});
        a.facing = one_of("facing", {"auto", "+z", "-z", "+x", "-x"});
        a.sha256 = sha256_file(a.file);
      }
    }
    c.avatars.push_back(std::move(a));
  }
  unique_ids(r, c.avatars, "avatars");

  // Settings.
  if (j.contains("settings")) {
    const json& s = j["settings"];
    r.only_keys(s, "settings", {"quality", "model", "time_limit", "spacing", "wall_limit", "memory_mb", "threads"});
    auto& st = c.settings;
    if (s.contains("quality")) {
      st.quality = r.string(s["quality"], "settings.quality");
      if (st.quality != "preview" && st.quality != "standard" && st.quality != "precise")
        r.fail("settings.quality", "'" + st.quality + "' is not one of preview, standard, precise");
    }
    if (s.contains("model")) {
      st.model = r.string(s["model"], "settings.model");
      if (st.model != "mass-spring" && st.model != "strain-rosette")
        r.fail("settings.model", "'" + st.model + "' is not one of mass-spring, strain-rosette");
    }
    if (s.contains("time_limit")) st.time_limit = r.number(s["time_limit"], "settings.time_limit", 0.01, 600);
    if (s.contains("spacing")) st.spacing = r.number(s["spacing"], "settings.spacing", 0.0, 0.2);
    if (s.contains("spacing") && st.spacing > 0 && st.spacing < 0.003)
      r.fail("settings.spacing", "below 3 mm (m, not cm: 0.015 is 1.5 cm)");
    if (s.contains("wall_limit")) st.wall_limit = r.number(s["wall_limit"], "settings.wall_limit", 1, 7 * 86400);
    if (s.contains("memory_mb"))
      st.memory_mb = static_cast<int>(r.number(s["memory_mb"], "settings.memory_mb", 64, 1 << 20));
    if (s.contains("threads")) st.threads = static_cast<int>(r.number(s["threads"], "settings.threads", 1, 256));
  }

  // Outputs.
  if (j.contains("outputs")) {
    auto& o = c.outputs;
    o.previews = false;
    const auto list = r.strings(j["outputs"], "outputs");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string& s = list[i];
      if (s == "certificate") continue;
      else if (s == "trj") o.trj = true;
      else if (s == "wvt") o.wvt = true;
      else if (s == "vrml") o.vrml = true;
      else if (s == "vrml-animated") o.vrml_animated = true;
      else if (s == "glb") o.glb = true;
      else if (s == "previews") o.previews = true;
      else
        r.fail("outputs[" + std::to_string(i) + "]", "'" + s + "' is not one of certificate, trj, wvt, vrml, "
                                                             "vrml-animated, glb, previews");
    }
  }
  if (j.contains("views")) {
    c.outputs.views = r.strings(j["views"], "views");
    for (std::size_t i = 0; i < c.outputs.views.size(); ++i) {
      const auto& v = c.outputs.views[i];
      if (v != "front" && v != "back" && v != "left" && v != "right" && v != "three-quarter")
        r.fail("views[" + std::to_string(i) + "]", "'" + v + "' is not one of front, back, left, right, three-quarter");
    }
  }
  if (j.contains("preview_size"))
    c.outputs.preview_size = static_cast<int>(r.number(j["preview_size"], "preview_size", 64, 4096));

  // Items: style × size × fabric × avatar. What makes an item's result is
  // hashed; what only names it (ids, paths) is not.
  const json settings = {{"quality", c.settings.quality}, {"model", c.settings.model},
                         {"time_limit", c.settings.time_limit}, {"spacing", c.settings.spacing}};
  const json outputs = {{"trj", c.outputs.trj},       {"wvt", c.outputs.wvt},
                        {"vrml", c.outputs.vrml},     {"vrml_animated", c.outputs.vrml_animated},
                        {"glb", c.outputs.glb},       {"previews", c.outputs.previews},
                        {"views", c.outputs.views},   {"preview_size", c.outputs.preview_size}};
  std::map<std::string, int> by_id;
  for (std::size_t si = 0; si < c.styles.size(); ++si) {
    const Style& st = c.styles[si];
    for (const auto& size : st.sizes)
      for (std::size_t fi = 0; fi < c.fabrics.size(); ++fi)
        for (std::size_t ai = 0; ai < c.avatars.size(); ++ai) {
          const Fabric& fa = c.fabrics[fi];
          const Avatar& av = c.avatars[ai];
          json key = {{"style", st.sha256},    {"style_type", to_lower(st.file.extension().string())},
                      {"size", size},          {"fabric", fa.sha256},
                      {"material", fa.material}, {"settings", settings},
                      {"outputs", outputs}};
          key["avatar"] = {{"kind", static_cast<int>(av.kind)}, {"size", av.size},   {"table", av.table},
                           {"file", av.sha256},                 {"unit", av.unit},   {"up", av.up},
                           {"facing", av.facing},               {"type", to_lower(av.file.extension().string())}};
          if (av.kind == Avatar::Kind::measurements) {
            key["avatar"]["sex"] = av.sex;
            for (const auto& [k, x] : av.measurements) key["avatar"]["m_" + k] = x;
          }
          Item it;
          it.index = static_cast<int>(c.items.size());
          it.id = sha256_hex(key.dump()).substr(0, 16);
          it.name = st.id + " " + size + " " + fa.id + " " + av.id;
          it.style = static_cast<int>(si), it.fabric = static_cast<int>(fi), it.avatar = static_cast<int>(ai);
          it.size = size;
          const auto [at, fresh] = by_id.emplace(it.id, it.index);
          if (!fresh)
            r.fail("styles", "items " + std::to_string(at->second) + " (" + c.items[at->second].name + ") and " +
                                 std::to_string(it.index) + " (" + it.name +
                                 ") are the same drape: the same files and settings");
          c.items.push_back(std::move(it));
        }
  }
  return c;
}

const Item& item_at(const Catalogue& catalogue, int index) {
  if (index < 0 || index >= static_cast<int>(catalogue.items.size()))
    throw Error(catalogue.file.string(), "", "no item " + std::to_string(index) + ": the catalogue has " +
                                                 std::to_string(catalogue.items.size()) + " items (0 to " +
                                                 std::to_string(catalogue.items.size() - 1) + ")");
  return catalogue.items[static_cast<std::size_t>(index)];
}

}  // namespace vgd::batch
