#include "vgd/render/looks.hpp"

#include <cmath>
#include <filesystem>

#include "vgd/core/strings.hpp"
#include "vgd/io/vrml/looks.hpp"
#include "vgd/render/image.hpp"

namespace vgd::render {

void apply_looks(const std::vector<Mesh*>& pieces, const xvc::Document& doc, bool textures, Diagnostics& diags,
                 TextureCache* cache) {
  namespace fs = std::filesystem;
  std::vector<std::string> names;
  for (const auto* m : pieces) names.push_back(m->name);
  const auto looks = io::vrml::looks_from_xvc(doc, names, &diags);
  const fs::path doc_dir = fs::path(doc.name()).parent_path();
  TextureCache local;
  TextureCache& loaded = cache ? *cache : local;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    Mesh& m = *pieces[i];
    const auto& look = looks[i];
    // looks_from_xvc marks a look the document did not colour "default".
    if (look.source.rfind("default", 0) != 0)
      m.colour = {static_cast<float>(look.colour.r), static_cast<float>(look.colour.g), static_cast<float>(look.colour.b)};
    if (!textures || look.texture.empty()) continue;
    if (m.uv.empty()) {
      diags.warn("", m.name, "no texture coordinates (a garment.obj from an older vgd drape: drape again): flat colour");
      continue;
    }
    const fs::path named = look.texture;
    const fs::path file = named.is_absolute() || doc_dir.empty() ? named : doc_dir / named;
    const std::string key = file.string() + "|" + format_double(look.repeat_u) + "|" + format_double(look.repeat_v) +
                            "|" + format_double(look.rotation_deg);
    auto& texture = loaded[key];
    if (!texture) {
      auto t = std::make_shared<Texture>();
      try {
        t->image = read_png(file);
      } catch (const Error& e) {
        throw Error(file.string(), "", "cannot read the texture of piece " + m.name + " (" + doc.name() +
                                           "): " + e.diagnostic().message + "; --no-texture draws flat colours");
      }
      t->repeat_m = {look.repeat_u, look.repeat_v};
      t->rotation_rad = look.rotation_deg * M_PI / 180.0;
      texture = std::move(t);
    }
    m.texture = texture;
    m.colour = {1, 1, 1};
  }
}

}  // namespace vgd::render
