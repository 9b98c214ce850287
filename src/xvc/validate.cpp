// XSD validation through libxml2, merged with vgd's own rules (check.cpp).
#include "vgd/xvc/validate.hpp"

#include <libxml/parser.h>
#include <libxml/tree.h>
#include <libxml/xmlerror.h>
#include <libxml/xmlschemas.h>

#include <algorithm>
#include <cstdlib>
#include <memory>

#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/xvc/io.hpp"
#include "xml_syntax.hpp"

#ifndef VGD_XVC_SOURCE_SCHEMA_DIR
#define VGD_XVC_SOURCE_SCHEMA_DIR ""
#endif
#ifndef VGD_XVC_INSTALL_SCHEMA_DIR
#define VGD_XVC_INSTALL_SCHEMA_DIR ""
#endif

namespace vgd::xvc {

namespace {
namespace fs = std::filesystem;

// What libxml2 reported during one call.
struct Collector {
  std::string file;
  std::vector<Diagnostic> items;
};

// How a message names the element libxml2 complains about: its id, else its tag.
std::string entity_of(const void* node) {
  auto* n = static_cast<xmlNodePtr>(const_cast<void*>(node));
  if (n && n->type == XML_ATTRIBUTE_NODE) n = n->parent;
  if (!n || n->type != XML_ELEMENT_NODE) return "";
  if (xmlChar* id = xmlGetProp(n, reinterpret_cast<const xmlChar*>("id"))) {
    std::string s(reinterpret_cast<const char*>(id));
    xmlFree(id);
    if (!s.empty()) return s;
  }
  return reinterpret_cast<const char*>(n->name);
}

// libxml2's structured-error callback; its parameter became const in 2.12, so the
// type is deduced from the setter it is passed to.
template <class ErrorPtr>
void collect(void* user, ErrorPtr err) {
  auto* c = static_cast<Collector*>(user);
  if (!err || !c) return;
  std::string msg = err->message ? err->message : "unknown problem";
  while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' ')) msg.pop_back();
  const Severity sev = err->level == XML_ERR_WARNING ? Severity::warning : Severity::error;
  // libxml2 says "entity reference loop" for an entity that expands without
  // bound (the "billion laughs") as well as for one that refers to itself.
  if (msg.find("entity reference loop") != std::string::npos)
    msg = "an entity refers to itself or expands into too much text; the document is refused (an XVC document "
          "needs no entities of its own)";
  if (msg.rfind("Input is not proper UTF-8", 0) == 0)
    msg = "the text is not UTF-8 (" + (msg.find("Bytes:") != std::string::npos ? msg.substr(msg.find("Bytes:")) : msg) +
          "); save the document as UTF-8";
  // The same message for the same line once.
  for (const auto& d : c->items)
    if (d.line == err->line && d.message == msg) return;
  c->items.push_back({sev, c->file, entity_of(err->node), std::move(msg), err->line});
}

// Silences libxml2's default printing to stderr for the lifetime of the object and
// routes errors to a Collector instead; the previous handlers come back afterwards.
class ErrorScope {
 public:
  explicit ErrorScope(Collector& c)
      : structured_(xmlStructuredError),
        structured_ctx_(xmlStructuredErrorContext),
        generic_(xmlGenericError),
        generic_ctx_(xmlGenericErrorContext) {
    xmlSetStructuredErrorFunc(&c, collect);
    xmlSetGenericErrorFunc(nullptr, silent);
  }
  ~ErrorScope() {
    xmlSetStructuredErrorFunc(structured_ctx_, structured_);
    xmlSetGenericErrorFunc(generic_ctx_, generic_);
  }
  ErrorScope(const ErrorScope&) = delete;
  ErrorScope& operator=(const ErrorScope&) = delete;

 private:
  static void silent(void*, const char*, ...) {}
  xmlStructuredErrorFunc structured_;
  void* structured_ctx_;
  xmlGenericErrorFunc generic_;
  void* generic_ctx_;
};

struct DocFree {
  void operator()(xmlDoc* d) const { xmlFreeDoc(d); }
};
struct SchemaFree {
  void operator()(xmlSchema* s) const { xmlSchemaFree(s); }
};

// XVC has no DTD; a DOCTYPE could only bring entities that readers expand differently.
std::optional<Diagnostic> doctype_problem(xmlDoc* doc, const std::string& file) {
  const xmlDtd* dtd = doc->intSubset ? doc->intSubset : doc->extSubset;
  if (!dtd) return std::nullopt;
  return Diagnostic{Severity::error, file, "", "malformed XML: a DOCTYPE declaration has no place in an XVC document",
                    static_cast<int>(xmlGetLineNo(const_cast<xmlNode*>(reinterpret_cast<const xmlNode*>(dtd))))};
}

std::unique_ptr<xmlSchema, SchemaFree> load_schema(const fs::path& xsd) {
  const std::string text = read_file(xsd);  // a clear error when it is missing
  Collector c{xsd.string(), {}};
  ErrorScope scope(c);
  xmlSchemaParserCtxtPtr pc = xmlSchemaNewMemParserCtxt(text.data(), static_cast<int>(text.size()));
  if (!pc) throw Error(xsd.string(), "", "cannot create a schema parser");
  xmlSchemaSetParserStructuredErrors(pc, collect, &c);
  std::unique_ptr<xmlSchema, SchemaFree> schema(xmlSchemaParse(pc));
  xmlSchemaFreeParserCtxt(pc);
  if (!schema) {
    const auto* first = c.items.empty() ? nullptr : &c.items.front();
    throw Error(xsd.string(), "", "the schema is broken: " + (first ? first->message : std::string("unknown problem")),
                first ? first->line : 0);
  }
  return schema;
}

// libxml2's view: well-formedness, then the XSD. Returns false when not well-formed.
bool xsd_check(std::string_view xml, const std::string& file, const fs::path& xsd, Diagnostics& out) {
  auto schema = load_schema(xsd);
  Collector c{file, {}};
  ErrorScope scope(c);
  // No network, no external entities: a document is checked as it stands.
  std::unique_ptr<xmlDoc, DocFree> doc(
      xmlReadMemory(xml.data(), static_cast<int>(xml.size()), file.c_str(), nullptr, XML_PARSE_NONET));
  if (!doc) {
    if (c.items.empty()) c.items.push_back({Severity::error, file, "", "the XML is not well-formed", 0});
    for (auto& d : c.items) {
      d.message = "malformed XML: " + d.message;
      out.add(std::move(d));
    }
    return false;
  }
  if (auto d = doctype_problem(doc.get(), file)) {
    out.add(std::move(*d));
    return false;
  }
  c.items.clear();  // parser warnings about a well-formed file are not ours to report
  xmlSchemaValidCtxtPtr vc = xmlSchemaNewValidCtxt(schema.get());
  if (!vc) throw Error(xsd.string(), "", "cannot create a schema validator");
  xmlSchemaSetValidStructuredErrors(vc, collect, &c);
  const int rc = xmlSchemaValidateDoc(vc, doc.get());
  xmlSchemaFreeValidCtxt(vc);
  if (rc != 0 && c.items.empty()) c.items.push_back({Severity::error, file, "", "the document does not match the schema", 0});
  for (auto& d : c.items) out.add(std::move(d));
  return true;
}
}  // namespace

namespace detail {
std::optional<Diagnostic> xml_syntax_error(std::string_view xml, const std::string& file) {
  Collector c{file, {}};
  ErrorScope scope(c);
  std::unique_ptr<xmlDoc, DocFree> doc(
      xmlReadMemory(xml.data(), static_cast<int>(xml.size()), file.c_str(), nullptr, XML_PARSE_NONET));
  if (doc) return doctype_problem(doc.get(), file);
  for (auto& d : c.items)
    if (d.severity == Severity::error) {
      d.message = "malformed XML: " + d.message;
      d.entity.clear();
      return d;
    }
  return Diagnostic{Severity::error, file, "", "malformed XML", 0};
}
}  // namespace detail

Diagnostics validate_string(std::string_view xml, std::string_view name_for_messages, const fs::path& xsd) {
  const std::string file(name_for_messages);
  Diagnostics schema;
  if (!xsd_check(xml, file, xsd, schema)) return schema;

  // vgd's rules on the same text.
  Diagnostics rules;
  try {
    rules = check(parse_tree(xml, file), file);
  } catch (const Error& e) {
    rules.add(e.diagnostic());
  }

  // One message per line: the rule's wording is the clearer one, so it wins.
  std::vector<Diagnostic> all = rules.items();
  for (const auto& d : schema.items()) {
    const bool covered = std::any_of(all.begin(), all.end(), [&](const Diagnostic& r) {
      return r.severity == Severity::error && r.line == d.line && d.line > 0;
    });
    if (!covered) all.push_back(d);
  }
  std::stable_sort(all.begin(), all.end(), [](const Diagnostic& a, const Diagnostic& b) { return a.line < b.line; });
  Diagnostics out;
  for (auto& d : all) out.add(std::move(d));
  return out;
}

Diagnostics validate_file(const fs::path& xvc, const fs::path& xsd) {
  return validate_string(read_file(xvc), xvc.string(), xsd);
}

fs::path find_schema_file(std::string_view filename) {
  std::vector<fs::path> tried;
  auto consider = [&](const fs::path& dir) -> std::optional<fs::path> {
    if (dir.empty()) return std::nullopt;
    const fs::path p = dir / filename;
    tried.push_back(p);
    std::error_code ec;
    if (fs::is_regular_file(p, ec)) return p;
    return std::nullopt;
  };
  // The user's choice first, then this build's source tree, then the installed copy.
  if (const char* env = std::getenv("VGD_SCHEMA_DIR"); env && *env)
    if (auto p = consider(env)) return *p;
  if (auto p = consider(VGD_XVC_SOURCE_SCHEMA_DIR)) return *p;
  if (auto p = consider(VGD_XVC_INSTALL_SCHEMA_DIR)) return *p;
  std::string list;
  for (const auto& t : tried) list += (list.empty() ? "" : ", ") + t.string();
  throw Error("", std::string(filename),
              "cannot find " + std::string(filename) + " (tried " + (list.empty() ? "nothing" : list) +
                  "); set VGD_SCHEMA_DIR to the folder holding it");
}

fs::path default_schema_path() { return find_schema_file("xvc.xsd"); }

}  // namespace vgd::xvc
