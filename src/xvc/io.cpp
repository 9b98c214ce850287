// Loading (tinyxml2) and saving (a small writer of our own, for one exact layout).
#include "vgd/xvc/io.hpp"

#include <tinyxml2.h>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "xml_syntax.hpp"

namespace vgd::xvc {

namespace {

// tinyxml2's error names are for programmers; these are for the person with the file.
std::string describe(tinyxml2::XMLError e) {
  using namespace tinyxml2;
  switch (e) {
    case XML_ERROR_PARSING_ELEMENT: return "malformed element";
    case XML_ERROR_PARSING_ATTRIBUTE: return "malformed attribute";
    case XML_ERROR_PARSING_TEXT: return "malformed text";
    case XML_ERROR_PARSING_CDATA: return "malformed CDATA section";
    case XML_ERROR_PARSING_COMMENT: return "malformed comment";
    case XML_ERROR_PARSING_DECLARATION: return "malformed declaration";
    case XML_ERROR_PARSING_UNKNOWN: return "malformed markup";
    case XML_ERROR_EMPTY_DOCUMENT: return "the document is empty";
    case XML_ERROR_MISMATCHED_ELEMENT: return "an end tag does not match its start tag";
    case XML_ERROR_PARSING: return "the XML is not well-formed";
    default: return std::string("cannot parse XML (") + XMLDocument::ErrorIDToName(e) + ")";
  }
}

// The detail tinyxml2 appends after "Line number=N: " (e.g. "XMLElement name=PATTERN").
std::string detail_of(const tinyxml2::XMLDocument& xml) {
  std::string s = xml.ErrorStr() ? xml.ErrorStr() : "";
  const auto pos = s.find("Line number=");
  if (pos == std::string::npos) return "";
  const auto colon = s.find(": ", pos);
  return colon == std::string::npos ? "" : s.substr(colon + 2);
}

// tinyxml2 element -> Node; text other than whitespace has no place in XVC.
Node convert(const tinyxml2::XMLElement& e, std::string_view file) {
  Node n;
  n.tag = e.Name();
  n.line = e.GetLineNum();
  for (const auto* a = e.FirstAttribute(); a; a = a->Next()) {
    if (n.has_attribute(a->Name()))
      throw Error(std::string(file), n.tag, std::string("attribute ") + a->Name() + " appears twice", a->GetLineNum());
    n.attributes.push_back({a->Name(), a->Value()});
  }
  for (const auto* c = e.FirstChild(); c; c = c->NextSibling()) {
    if (const auto* ce = c->ToElement()) {
      n.children.push_back(convert(*ce, file));
    } else if (const auto* t = c->ToText(); t && !trim(t->Value()).empty()) {
      const std::string id(n.id());
      throw Error(std::string(file), id.empty() ? n.tag : id,
                  "unexpected text " + std::string(trim(t->Value()).substr(0, 30)) + " in " + n.tag +
                      "; XVC keeps all data in attributes",
                  t->GetLineNum());
    }
  }
  return n;
}

// XML attribute escaping; tab, CR and LF as references so a reader keeps them exactly
// (a literal one would be normalised to a space).
void append_escaped(std::string& out, std::string_view v) {
  for (const char c : v) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\t': out += "&#9;"; break;
      case '\n': out += "&#10;"; break;
      case '\r': out += "&#13;"; break;
      default: out += c;
    }
  }
}

void write(std::string& out, const Node& n, int depth) {
  out.append(static_cast<std::size_t>(depth) * 2, ' ');
  out += '<';
  out += n.tag;
  for (const auto& a : n.attributes) {
    out += ' ';
    out += a.name;
    out += "=\"";
    append_escaped(out, a.value);
    out += '"';
  }
  if (n.children.empty()) {
    out += "/>\n";
    return;
  }
  out += ">\n";
  for (const auto& c : n.children) write(out, c, depth + 1);
  out.append(static_cast<std::size_t>(depth) * 2, ' ');
  out += "</";
  out += n.tag;
  out += ">\n";
}

}  // namespace

Node parse_tree(std::string_view xml, std::string_view name_for_messages) {
  const std::string file(name_for_messages);
  // libxml2 decides what is well-formed: tinyxml2 alone accepts "a<b" in an attribute,
  // unknown entities and a second root element (which it would silently drop).
  if (auto d = detail::xml_syntax_error(xml, file)) throw Error(std::move(*d));
  tinyxml2::XMLDocument parsed(true, tinyxml2::PRESERVE_WHITESPACE);
  if (const auto e = parsed.Parse(xml.data(), xml.size()); e != tinyxml2::XML_SUCCESS) {
    std::string msg = "malformed XML: " + describe(e);
    if (const auto d = detail_of(parsed); !d.empty()) msg += " (" + d + ")";
    throw Error(file, "", msg, parsed.ErrorLineNum());
  }
  const auto* root = parsed.RootElement();
  if (!root) throw Error(file, "", "malformed XML: no root element");
  return convert(*root, file);
}

Document load_string(std::string_view xml, std::string_view name_for_messages) {
  return Document(parse_tree(xml, name_for_messages), std::string(name_for_messages));
}

Document load_file(const std::filesystem::path& path) {
  const std::string text = read_file(path);
  return load_string(text, path.string());
}

std::string save_string(const Document& doc) {
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  write(out, doc.root(), 0);
  return out;
}

void save_file(const Document& doc, const std::filesystem::path& path) {
  write_file_atomic(path, save_string(doc));
}

}  // namespace vgd::xvc
