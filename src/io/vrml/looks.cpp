// Piece looks from the XVC document's MATERIAL, TEXTURE and ASSOCIATION elements.
#include "vgd/io/vrml/looks.hpp"

#include "vgd/core/strings.hpp"

namespace vgd::io::vrml {

namespace {

double number(const xvc::Node& n, const char* attribute, double fallback) {
  const auto v = parse_double(n.attribute(attribute));
  return v ? *v : fallback;
}

const xvc::Node* child(const xvc::Node& n, std::string_view tag) {
  for (const auto& c : n.children)
    if (c.tag == tag) return &c;
  return nullptr;
}

// The material's colour into `look`; false when it has none.
bool apply_material(const xvc::Node& material, PieceLook& look) {
  const xvc::Node* c = child(material, "COLORRGBA");
  if (!c) return false;
  look.colour = {number(*c, "r", 0.8), number(*c, "g", 0.8), number(*c, "b", 0.8), number(*c, "a", 1.0)};
  const std::string name(material.attribute("name"));
  look.source = std::string(material.id()) + (name.empty() ? "" : " (" + name + ")");
  return true;
}

void apply_texture(const xvc::Node& texture, PieceLook& look) {
  look.texture = std::string(texture.attribute("file"));
  if (const xvc::Node* s = child(texture, "SCALE2D")) {
    look.repeat_u = number(*s, "x", look.repeat_u);
    look.repeat_v = number(*s, "y", look.repeat_v);
  }
  if (const xvc::Node* r = child(texture, "ROTATION2D")) look.rotation_deg = number(*r, "angle", 0.0);
  look.source += (look.source.empty() ? "" : ", ") + std::string("texture ") + std::string(texture.id());
}

}  // namespace

std::vector<PieceLook> looks_from_xvc(const xvc::Document& doc, const std::vector<std::string>& pieces,
                                      Diagnostics* diagnostics) {
  // The document-wide look: its only coloured MATERIAL, else the default. A
  // MATERIAL of scope "piece" is the look of the pieces that name it only.
  PieceLook garment_look;
  garment_look.source = "default";
  if (const xvc::Node* materials = doc.container("MATERIALS")) {
    std::vector<const xvc::Node*> coloured;
    for (const auto& m : materials->children)
      if (m.tag == "MATERIAL" && child(m, "COLORRGBA") && m.attribute("scope") != "piece") coloured.push_back(&m);
    if (coloured.size() == 1) apply_material(*coloured.front(), garment_look);
  }

  std::vector<PieceLook> looks;
  const auto patterns = doc.patterns();
  for (const auto& name : pieces) {
    const xvc::Node* pattern = nullptr;
    for (const auto* p : patterns)
      if (p->attribute("piece") == name || p->attribute("block") == name || p->id() == name) {
        pattern = p;
        break;
      }
    PieceLook look = garment_look;
    if (!pattern) {
      if (diagnostics)
        diagnostics->info(doc.name(), name, "no PATTERN of that piece name: the garment's look (" + look.source +
                                                ") is used");
      looks.push_back(look);
      continue;
    }
    // The pattern's own associations win over the document-wide look.
    for (const auto& a : pattern->children) {
      if (a.tag != "ASSOCIATION") continue;
      const xvc::Node* target = doc.find(a.attribute("ref"));
      if (!target) continue;
      if (a.attribute("role") == "material" && target->tag == "MATERIAL") {
        PieceLook own = look;
        own.source.clear();
        if (apply_material(*target, own)) look = own;
      } else if (a.attribute("role") == "texture" && target->tag == "TEXTURE") {
        apply_texture(*target, look);
      }
    }
    looks.push_back(look);
  }
  return looks;
}

}  // namespace vgd::io::vrml
