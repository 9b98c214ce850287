// SVG through schemas/xvc-to-svg.xsl: in-process with libxslt when the build found it,
// else (and always in render_svg_with_xsltproc) by running the xsltproc program.
#include "vgd/xvc/svg.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/validate.hpp"

#ifdef VGD_XVC_HAVE_LIBXSLT
#include <libexslt/exslt.h>
#include <libxml/parser.h>
#include <libxslt/transform.h>
#include <libxslt/xslt.h>
#include <libxslt/xsltInternals.h>
#include <libxslt/xsltutils.h>
#endif

extern char** environ;

namespace vgd::xvc {

namespace fs = std::filesystem;

fs::path default_stylesheet_path() { return find_schema_file("xvc-to-svg.xsl"); }

bool svg_uses_libxslt() {
#ifdef VGD_XVC_HAVE_LIBXSLT
  return true;
#else
  return false;
#endif
}

namespace {

// ---- xsltproc ----------------------------------------------------------------------

// A private temporary directory, removed with everything in it at scope end.
class TempDir {
 public:
  TempDir() {
    std::string tmpl = (fs::temp_directory_path() / "vgd-svg-XXXXXX").string();
    if (!::mkdtemp(tmpl.data())) throw Error("", "", std::string("cannot create a temporary directory: ") + std::strerror(errno));
    path_ = tmpl;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string run_xsltproc(const Document& doc, const fs::path& xsl, const StylesheetParams& params) {
  TempDir tmp;
  const fs::path in = tmp.path() / "in.xvc", out = tmp.path() / "out.svg", err = tmp.path() / "stderr.txt";
  write_file_atomic(in, save_string(doc));
  const std::string xsl_s = xsl.string(), in_s = in.string(), out_s = out.string(), err_s = err.string();
  // No shell: the arguments go to the program as they are.
  std::vector<std::string> args{"xsltproc", "--nonet", "-o", out_s};
  for (const auto& [name, value] : params) args.insert(args.end(), {"--stringparam", name, value});
  args.insert(args.end(), {xsl_s, in_s});
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_s.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, "xsltproc", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw Error("", "xsltproc", std::string("cannot run xsltproc: ") + std::strerror(rc));
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw Error("", "xsltproc", std::string("waiting for xsltproc failed: ") + std::strerror(errno));
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::string msg;
    std::error_code ec;
    if (fs::exists(err, ec)) msg = read_file(err);
    while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' ')) msg.pop_back();
    throw Error(xsl.string(), "xsltproc", "the SVG transformation failed" + (msg.empty() ? "" : ": " + msg));
  }
  return read_file(out);
}

// ---- libxslt -----------------------------------------------------------------------

#ifdef VGD_XVC_HAVE_LIBXSLT
// libxslt reports through printf-style callbacks; collect the text instead of printing.
void gather(void* ctx, const char* fmt, ...) {
  char buf[1024];
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  static_cast<std::string*>(ctx)->append(buf);
}

std::string run_libxslt(const Document& doc, const fs::path& xsl, const StylesheetParams& params) {
  const std::string xml = save_string(doc);
  const std::string style_text = read_file(xsl);  // a clear error when it is missing
  std::string errors;
  static const bool registered = [] {
    exsltRegisterAll();  // exsl:node-set and math:* used by the stylesheet
    return true;
  }();
  (void)registered;
  // Collect messages instead of printing them; the previous handlers come back after.
  struct Restore {
    xmlGenericErrorFunc xml_func = xmlGenericError;
    void* xml_ctx = xmlGenericErrorContext;
    xmlGenericErrorFunc xslt_func = xsltGenericError;
    void* xslt_ctx = xsltGenericErrorContext;
    ~Restore() {
      xmlSetGenericErrorFunc(xml_ctx, xml_func);
      xsltSetGenericErrorFunc(xslt_ctx, xslt_func);
    }
  } restore;
  xmlSetGenericErrorFunc(&errors, gather);
  xsltSetGenericErrorFunc(&errors, gather);
  auto fail = [&](const std::string& what) {
    std::string msg = errors;
    while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' ')) msg.pop_back();
    return Error(xsl.string(), "", what + (msg.empty() ? "" : ": " + msg));
  };

  xmlDocPtr style_doc = xmlReadMemory(style_text.data(), static_cast<int>(style_text.size()), xsl.string().c_str(),
                                      nullptr, XML_PARSE_NONET);
  if (!style_doc) throw fail("the stylesheet is not well-formed XML");
  xsltStylesheetPtr style = xsltParseStylesheetDoc(style_doc);  // owns style_doc from here
  if (!style) {
    xmlFreeDoc(style_doc);
    throw fail("the stylesheet cannot be used");
  }
  xmlDocPtr in = xmlReadMemory(xml.data(), static_cast<int>(xml.size()), "document.xvc", nullptr, XML_PARSE_NONET);
  if (!in) {
    xsltFreeStylesheet(style);
    throw fail("the document could not be read back");
  }
  // libxslt takes parameters as XPath expressions: quote each value as a string.
  std::vector<std::string> texts;
  for (const auto& [name, value] : params) {
    if (value.find('\'') != std::string::npos && value.find('"') != std::string::npos) {
      xmlFreeDoc(in);
      xsltFreeStylesheet(style);
      throw Error(xsl.string(), name, "a stylesheet parameter cannot hold both kinds of quote");
    }
    const char q = value.find('\'') == std::string::npos ? '\'' : '"';
    texts.push_back(name);
    texts.push_back(q + value + q);
  }
  std::vector<const char*> pv;
  for (const auto& t : texts) pv.push_back(t.c_str());
  pv.push_back(nullptr);
  xmlDocPtr result = xsltApplyStylesheet(style, in, pv.data());
  xmlFreeDoc(in);
  if (!result) {
    xsltFreeStylesheet(style);
    throw fail("the SVG transformation failed");
  }
  xmlChar* buf = nullptr;
  int len = 0;
  const int rc = xsltSaveResultToString(&buf, &len, result, style);
  xmlFreeDoc(result);
  xsltFreeStylesheet(style);
  if (rc != 0 || !buf) {
    if (buf) xmlFree(buf);
    throw fail("the SVG could not be written");
  }
  std::string svg(reinterpret_cast<const char*>(buf), static_cast<std::size_t>(len));
  xmlFree(buf);
  return svg;
}
#endif

}  // namespace

std::string render_svg_with_xsltproc(const Document& doc, const fs::path& xsl, const StylesheetParams& params) {
  return run_xsltproc(doc, xsl, params);
}

std::string render_svg(const Document& doc, const fs::path& xsl, const StylesheetParams& params) {
#ifdef VGD_XVC_HAVE_LIBXSLT
  return run_libxslt(doc, xsl, params);
#else
  return run_xsltproc(doc, xsl, params);
#endif
}

}  // namespace vgd::xvc
