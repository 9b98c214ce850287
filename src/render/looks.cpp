#include "vgd/render/looks.hpp"

#include <cmath>

#include "vgd/core/strings.hpp"
#include "vgd/render/image.hpp"

namespace vgd::render {

void apply_looks(const std::vector<Mesh*>& pieces, const std::vector<Look>& looks, bool textures, Diagnostics& diags,
                 TextureCache* cache) {
  TextureCache local;
  TextureCache& loaded = cache ? *cache : local;
  for (std::size_t i = 0; i < pieces.size() && i < looks.size(); ++i) {
    Mesh& m = *pieces[i];
    const Look& look = looks[i];
    if (look.colour) m.colour = *look.colour;
    if (!textures || look.texture.empty()) continue;
    if (m.uv.empty()) {
      diags.warn("", m.name, "no texture coordinates (a garment.obj from an older vgd drape: drape again): flat colour");
      continue;
    }
    const std::string key = look.texture.string() + "|" + format_double(look.repeat_m[0]) + "|" +
                            format_double(look.repeat_m[1]) + "|" + format_double(look.rotation_deg);
    auto& texture = loaded[key];
    if (!texture) {
      auto t = std::make_shared<Texture>();
      try {
        t->image = read_png(look.texture);
      } catch (const Error& e) {
        throw Error(look.texture.string(), "", "cannot read the texture of piece " + m.name + ": " +
                                                   e.diagnostic().message + "; --no-texture draws flat colours");
      }
      t->repeat_m = look.repeat_m;
      t->rotation_rad = look.rotation_deg * M_PI / 180.0;
      texture = std::move(t);
    }
    m.texture = texture;
    m.colour = {1, 1, 1};
  }
}

}  // namespace vgd::render
