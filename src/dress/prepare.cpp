#include "vgd/dress/prepare.hpp"

#include <algorithm>
#include <cctype>
#include <set>

#include "vgd/body/sizes.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/xvc/arrangement.hpp"
#include "vgd/xvc/commands.hpp"
#include "vgd/xvc/seams.hpp"

namespace vgd::dress {

namespace {

std::vector<std::string> tokens(const std::string& s) {
  std::vector<std::string> out;
  std::string cur;
  for (const char ch : s) {
    if (std::isalnum(static_cast<unsigned char>(ch))) {
      cur += static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    } else if (!cur.empty()) {
      out.push_back(cur);
      cur.clear();
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

bool starts(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace

std::string size_table_from_name(const std::string& style_name) {
  bool men = false, women = false;
  for (const auto& t : tokens(style_name)) {
    if (t == "W" || t == "WM" || t == "WMN" || starts(t, "WOMEN") || starts(t, "LADIES") || starts(t, "FEMALE") ||
        starts(t, "WOMAN"))
      women = true;
    else if (t == "M" || t == "MEN" || t == "MENS" || t == "MAN" || starts(t, "MALE"))
      men = true;
  }
  if (men == women) return "";
  return men ? "en13402-men" : "en13402-women";
}

Preparation prepare_garment(xvc::Document& doc, const PrepareOptions& options) {
  const std::string file = doc.name();
  Preparation out;
  std::string sample;
  if (const auto* grads = doc.container("GRADATIONS")) sample = std::string(grads->attribute("sample_size"));
  const auto patterns_of = [&](const std::string& size) {
    std::vector<const xvc::Node*> v;
    for (const auto* p : doc.patterns())
      if (p->attribute("size") == size) v.push_back(p);
    return v;
  };
  out.size = !options.size.empty() ? options.size : sample;
  if (out.size.empty() && !doc.patterns().empty()) out.size = std::string(doc.patterns().front()->attribute("size"));
  const auto mine = patterns_of(out.size);
  if (mine.empty()) throw Error(file, "size " + out.size, "the document has no pattern of size '" + out.size + "'");

  // Seams: vgd's suggestions when the document has none.
  if (xvc::list_seams(doc).empty()) {
    xvc::SeamOptions so;
    so.size = !sample.empty() && !patterns_of(sample).empty() ? sample : out.size;
    so.min_score = options.min_score;
    const auto suggested = xvc::suggest_seams(doc, so);
    std::vector<xvc::Node> nodes;
    for (const auto& s : suggested) {
      nodes.push_back(xvc::seam_node(s));
      std::string hems;
      for (std::size_t k = 0; k < s.hems.size(); ++k) {
        const auto* p = doc.find(s.hems[k].pattern);
        hems += (k == 0 ? "" : k == 1 ? " to " : " + ") + std::string(p ? p->attribute("piece") : s.hems[k].pattern);
      }
      out.decisions.push_back("seam '" + s.name + "' suggested at size " + so.size + ": " + hems + ", ease " +
                              format_fixed(1000 * s.ease, 1) + " mm, score " + format_fixed(s.score, 2));
    }
    if (!nodes.empty()) xvc::execute(doc, *std::make_unique<xvc::AddSeams>(std::move(nodes)));
    out.seams_added = static_cast<int>(suggested.size());
    if (suggested.empty())
      out.decisions.push_back("no SEAM in the document and none suggested at size " + so.size);
  }

  // Pieces: sewn by some seam, and arranged round the body by a rule or the document.
  std::set<std::string> sewn;
  for (const auto& s : xvc::list_seams(doc))
    for (const auto& h : s.hems)
      if (const auto* p = doc.find(h.pattern)) sewn.insert(std::string(p->attribute("piece")));
  std::set<std::string> arranged;
  for (const auto& [id, list] : xvc::suggest_arrangements(doc))
    if (!list.empty())
      if (const auto* p = doc.find(id)) arranged.insert(std::string(p->attribute("piece")));
  for (const auto* p : mine)
    if (!xvc::arrangements_of(*p).empty()) arranged.insert(std::string(p->attribute("piece")));
  for (const auto* p : mine) {
    const std::string name(p->attribute("piece"));
    if (mine.size() > 1 && !sewn.count(name)) {
      out.left_out.push_back(name);
      out.decisions.push_back("piece " + name + " left out: no seam sews it");
    } else if (!arranged.count(name)) {
      out.left_out.push_back(name);
      out.decisions.push_back("piece " + name + " left out: no rule places it round the body (give it an arrangement "
                              "with 'vgd place --set \"" + name + "=SEGMENT:SIDE:HEIGHT\"')");
    } else {
      out.pieces.push_back(name);
    }
  }
  // Alternatives: several sleeve patterns (a short and a full sleeve, a
  // one-piece and a two-piece set) are one sleeve drawn several ways. Those
  // sewn to the body pieces (an armhole) are the garment's; with none sewn
  // there, the first in the document is. The others are left out.
  {
    auto category = [&](const std::string& name) {
      for (const auto* p : mine)
        if (p->attribute("piece") == name) return std::string(p->attribute("category"));
      return std::string();
    };
    // A LEFT and a RIGHT sleeve are a pair, not alternatives.
    auto sided = [](const std::string& name) {
      const std::string n = to_upper(name);
      return n.find("LEFT") != std::string::npos || n.find("RIGHT") != std::string::npos;
    };
    std::vector<std::string> sleeves;
    for (const auto& name : out.pieces)
      if (xvc::is_sleeve_name(name, category(name)) && !sided(name)) sleeves.push_back(name);
    if (sleeves.size() > 1) {
      std::set<std::string> on_body;  // sleeves with a seam to a piece that is not a sleeve
      for (const auto& s : xvc::list_seams(doc)) {
        std::set<std::string> names;
        for (const auto& h : s.hems)
          if (const auto* p = doc.find(h.pattern)) names.insert(std::string(p->attribute("piece")));
        const bool body = std::any_of(names.begin(), names.end(), [&](const std::string& n) {
          return std::find(sleeves.begin(), sleeves.end(), n) == sleeves.end();
        });
        if (body)
          for (const auto& n : names)
            if (std::find(sleeves.begin(), sleeves.end(), n) != sleeves.end()) on_body.insert(n);
      }
      std::vector<std::string> chosen;
      for (const auto& n : sleeves)
        if (on_body.count(n)) chosen.push_back(n);
      if (chosen.empty()) chosen.push_back(sleeves.front());
      std::string list;
      for (const auto& n : chosen) list += (list.empty() ? "" : ", ") + n;
      for (const auto& n : sleeves) {
        if (std::find(chosen.begin(), chosen.end(), n) != chosen.end()) continue;
        out.pieces.erase(std::find(out.pieces.begin(), out.pieces.end(), n));
        out.left_out.push_back(n);
        out.decisions.push_back("piece " + n + " left out: an alternative to the sleeve " + list +
                                (on_body.empty() ? " (the first in the document; no sleeve is sewn to an armhole)"
                                                 : " (sewn to the armholes)"));
      }
    }
  }
  if (out.pieces.empty()) {
    std::string names;
    for (const auto* p : mine) names += (names.empty() ? "" : ", ") + std::string(p->attribute("piece"));
    throw Error(file, "size " + out.size,
                "nothing to drape: no seam vgd can find sews the pieces of this size together (" + names +
                    "); add seams with 'vgd seams add' or a seam file with 'vgd seams apply', and arrangements "
                    "with 'vgd place'");
  }

  // The body: the size table from the style's name, the garment's size
  // when that table has it, else the table's middle size.
  const std::string style(doc.root().attribute("name"));
  out.body_table = !options.body_table.empty() ? options.body_table : size_table_from_name(style);
  std::string why = !options.body_table.empty() ? "as asked"
                    : out.body_table.empty()    ? "the style's name '" + style + "' says neither men nor women; choose with --body-table"
                                                : "the style's name '" + style + "'";
  out.body_size = !options.body_size.empty() ? options.body_size : out.size;
  if (options.body_size.empty()) {
    try {
      body::find_size(out.size, out.body_table);
    } catch (const Error&) {
      const std::string table = !out.body_table.empty() ? out.body_table : body::size_table_names().front();
      const auto rows = body::load_size_table(body::size_table_file(table));
      if (!rows.empty()) {
        out.body_size = rows[rows.size() / 2].label;
        out.body_table = table;
        why += "; the table has no size '" + out.size + "': its middle size, choose with --body-size";
      }
    }
  }
  out.decisions.push_back("body: the mannequin of size " + out.body_size + " from " +
                          (out.body_table.empty() ? std::string("the first size table that has it") : out.body_table) +
                          " (" + why + ")");
  return out;
}

}  // namespace vgd::dress
