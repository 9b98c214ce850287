// The web catalogue pages (web.hpp): plain HTML, X_ITE's <x3d-canvas>.
#include "vgd/io/vrml/web.hpp"

#include <system_error>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"

namespace vgd::io::vrml {

namespace fs = std::filesystem;

namespace {

std::string html(const std::string& s) { return html_escape(s); }

// A relative URL from a file name: spaces and the few characters HTML attributes mind, escaped.
std::string url(const std::string& file) {
  std::string o;
  for (char c : file) {
    if (c == ' ') o += "%20";
    else if (c == '"' || c == '<' || c == '>' || c == '#' || c == '%' || c == '?') {
      static const char* hex = "0123456789ABCDEF";
      o += '%', o += hex[(static_cast<unsigned char>(c) >> 4) & 15], o += hex[static_cast<unsigned char>(c) & 15];
    } else o += c;
  }
  return o;
}

constexpr const char* kStyle =
    "body{font-family:system-ui,sans-serif;margin:0;background:#eef0f4;color:#222}"
    "header{padding:.6em 1em;background:#fff;border-bottom:1px solid #ccd}"
    "header a{color:#335;text-decoration:none}h1{font-size:1.3em;margin:.2em 0}"
    "main{padding:1em}x3d-canvas{display:block;width:100%;height:72vh;background:#edeff3}"
    "table{border-collapse:collapse;margin-top:.8em}td{padding:.15em .8em .15em 0}"
    "ul.cat{list-style:none;padding:0;display:flex;flex-wrap:wrap;gap:1em}"
    "ul.cat li{background:#fff;border:1px solid #ccd;border-radius:6px;padding:.8em 1.2em}";

}  // namespace

std::string page_stem(const std::string& name) {
  std::string s;
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
                    c == '_' || c == '.';
    s += ok ? c : '_';
  }
  if (s.empty() || s[0] == '.') s = "garment" + s;
  return s;
}

std::string garment_page(const WebEntry& e) {
  std::string o = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  o += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  o += "<title>" + html(e.title) + " - vgd</title>\n<link rel=\"icon\" href=\"data:,\">\n";
  o += "<script src=\"x_ite/x_ite.min.js\"></script>\n<style>" + std::string(kStyle) + "</style>\n</head>\n<body>\n";
  o += "<header><a href=\"index.html\">&larr; catalogue</a><h1>" + html(e.title) + "</h1></header>\n<main>\n";
  // X_ITE shows the VRML; drag to turn, wheel to zoom (EXAMINE navigation).
  o += "<x3d-canvas id=\"scene\" src=\"" + url(e.wrl) +
       "\" splashScreen=\"false\" notifications=\"false\" contextMenu=\"false\"></x3d-canvas>\n";
  if (!e.facts.empty()) {
    o += "<table>\n";
    for (const auto& [k, v] : e.facts) o += "<tr><td>" + html(k) + "</td><td>" + html(v) + "</td></tr>\n";
    o += "</table>\n";
  }
  o += "<p>Files: <a href=\"" + url(e.wrl) + "\">" + html(e.wrl) + "</a>";
  for (const auto& [label, file] : e.downloads) o += " · <a href=\"" + url(file) + "\">" + html(label) + "</a>";
  o += "</p>\n</main>\n</body>\n</html>\n";
  return o;
}

std::string index_page(const std::vector<WebEntry>& entries, const std::string& title) {
  std::string o = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  o += "<title>" + html(title) + "</title>\n<link rel=\"icon\" href=\"data:,\">\n<style>" + std::string(kStyle) + "</style>\n</head>\n<body>\n";
  o += "<header><h1>" + html(title) + "</h1></header>\n<main>\n<ul class=\"cat\">\n";
  for (const auto& e : entries) {
    o += "<li><a href=\"" + url(page_stem(e.name) + ".html") + "\">" + html(e.title) + "</a>";
    for (const auto& [k, v] : e.facts)
      if (k == "pieces" || k == "triangles") o += "<br><small>" + html(v) + " " + html(k) + "</small>";
    o += "</li>\n";
  }
  o += "</ul>\n<p><small>Made by vgd; 3-D view by X_ITE (x_ite/).</small></p>\n</main>\n</body>\n</html>\n";
  return o;
}

fs::path default_x_ite_dir() {
#ifdef VGD_X_ITE_DIR
  return VGD_X_ITE_DIR;
#else
  return {};
#endif
}

void write_web_catalogue(const fs::path& dir, const std::vector<WebEntry>& entries, const fs::path& x_ite_dist) {
  if (x_ite_dist.empty() || !fs::is_regular_file(x_ite_dist / "x_ite.min.js"))
    throw Error(x_ite_dist.string(), "", "X_ITE not found (no x_ite.min.js here): run .ci/install-deps, or give "
                                         "--x-ite with the dist/ folder of the npm package x_ite");
  std::error_code ec;
  fs::create_directories(dir / "x_ite", ec);
  if (!ec) fs::copy(x_ite_dist, dir / "x_ite", fs::copy_options::recursive | fs::copy_options::update_existing, ec);
  if (ec) throw Error(dir.string(), "", "cannot copy X_ITE into the folder: " + ec.message());
  for (const auto& e : entries) write_file_atomic(dir / (page_stem(e.name) + ".html"), garment_page(e));
  write_file_atomic(dir / "index.html", index_page(entries));
}

}  // namespace vgd::io::vrml
