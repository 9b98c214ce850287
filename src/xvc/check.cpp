// vgd's own rules on an XVC tree (validate.hpp): the vocabulary of rules.cpp, then the
// cross-element rules an XSD cannot state well (ids, references, units).
#include <algorithm>
#include <map>
#include <set>
#include <unordered_map>

#include "rules.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/xvc/validate.hpp"

namespace vgd::xvc {

namespace {
using detail::ElementRule;
using detail::find_rule;

// Values quoted in messages are cut so one bad attribute cannot flood a report.
std::string quote(std::string_view v) {
  if (v.size() > 40) return "\"" + std::string(v.substr(0, 37)) + "...\"";
  return "\"" + std::string(v) + "\"";
}

// One element in document order with what the cross-element rules need to know.
struct Item {
  const Node* node = nullptr;
  const Node* parent = nullptr;
  const Node* pattern = nullptr;  // the enclosing PATTERN, if any
  std::size_t parent_item = 0;    // index of the parent's Item (the root points at itself)
  int k = 1;                      // 1-based position among siblings of the same tag
};

class Checker {
 public:
  explicit Checker(std::string_view file) : file_(file) {}

  Diagnostics run(const Node& root) {
    // The root decides whether this is an XVC document at all.
    if (root.tag != "GARMENT") {
      out_.error(file_, root.tag, "the root element is " + root.tag + "; an XVC document has GARMENT as its root",
                 root.line);
      return std::move(out_);
    }
    walk(root, nullptr, nullptr, 0, 1);
    for (std::size_t i = 0; i < items_.size(); ++i) cross_check(items_[i]);
    check_blocks();
    // Report in file order so the first message is the first problem a reader meets.
    auto items = out_.items();
    std::stable_sort(items.begin(), items.end(), [](const Diagnostic& a, const Diagnostic& b) { return a.line < b.line; });
    Diagnostics sorted;
    for (auto& d : items) sorted.add(std::move(d));
    return sorted;
  }

 private:
  void error(const Item& it, std::string msg) { out_.error(file_, entity(it), std::move(msg), it.node->line); }
  void warn(const Item& it, std::string msg) { out_.warn(file_, entity(it), std::move(msg), it.node->line); }

  // How messages name an element: its id, else its owner's name + "/TAG[k]". Built only
  // when reported, since most elements (every C2D) never are.
  std::string entity(const Item& it) const {
    if (const auto* id = it.node->find_attribute("id"); id && detail::is_id_text(*id)) return *id;
    if (!it.parent) return it.node->tag;
    return entity(items_[it.parent_item]) + "/" + it.node->tag + "[" + std::to_string(it.k) + "]";
  }

  const Item* lookup(std::string_view id) const {
    const auto it = ids_.find(std::string(id));
    return it == ids_.end() ? nullptr : &items_[it->second];
  }

  // ---- pass 1: vocabulary, attributes, children, ids -------------------------------
  void walk(const Node& n, const Node* parent, const Node* pattern, std::size_t parent_item, int k) {
    const auto* id = n.find_attribute("id");
    if (n.tag == "PATTERN") pattern = &n;
    const std::size_t self = items_.size();
    items_.push_back({&n, parent, pattern, parent_item, k});
    const ElementRule* rule = find_rule(n.tag);
    check_attributes(items_[self], rule);
    if (id && detail::is_id_text(*id)) {
      const auto [it, fresh] = ids_.emplace(*id, self);
      if (!fresh) {
        const auto& first = items_[it->second];
        error(items_[self], "id " + *id + " is already used" +
                                (first.node->line > 0 ? " at line " + std::to_string(first.node->line) : "") +
                                "; ids must be unique");
      }
    }
    check_children(items_[self], rule);
    // Children are named after this element when they have no id of their own.
    std::map<std::string_view, int> seen;
    for (const auto& c : n.children) {
      const int ck = ++seen[c.tag];
      if (find_rule(c.tag)) walk(c, &n, pattern, self, ck);
    }
  }

  void check_attributes(const Item& it, const ElementRule* rule) {
    const Node& n = *it.node;
    std::set<std::string_view> names;
    for (const auto& a : n.attributes) {
      if (!names.insert(a.name).second) error(it, "attribute " + a.name + " appears twice");
      if (const auto p = detail::text_problem(a.value); !p.empty()) error(it, "attribute " + a.name + " " + p);
      const auto* ar = rule->attribute(a.name);
      if (!ar) {
        error(it, "unknown attribute " + a.name + " on " + n.tag);
        continue;
      }
      if (const auto p = detail::value_problem(*ar, a.value); !p.empty())
        error(it, a.name + " " + quote(a.value) + " " + p);
    }
    for (const auto& ar : rule->attributes)
      if (ar.required && !n.has_attribute(ar.name)) error(it, n.tag + " needs attribute " + std::string(ar.name));
  }

  void check_children(const Item& it, const ElementRule* rule) {
    const Node& n = *it.node;
    std::vector<int> counts(rule->children.size(), 0);
    int rank = 0;
    for (const auto& c : n.children) {
      const int r = rule->child_rank(c.tag);
      if (r < 0) {
        if (!find_rule(c.tag))
          out_.error(file_, entity(it), "unknown element " + c.tag + " in " + n.tag, c.line ? c.line : n.line);
        else
          out_.error(file_, entity(it), "a " + n.tag + " cannot hold a " + c.tag, c.line ? c.line : n.line);
        continue;
      }
      if (r < rank)
        out_.error(file_, entity(it),
                   c.tag + " must come before " + std::string(rule->children[static_cast<std::size_t>(rank)].tag) +
                       " in a " + n.tag,
                   c.line ? c.line : n.line);
      rank = std::max(rank, r);
      const auto& cr = rule->children[static_cast<std::size_t>(r)];
      if (++counts[static_cast<std::size_t>(r)] == cr.max + 1)
        out_.error(file_, entity(it), "a " + n.tag + " holds at most " + std::to_string(cr.max) + " " + c.tag,
                   c.line ? c.line : n.line);
    }
    for (std::size_t i = 0; i < counts.size(); ++i)
      if (counts[i] < rule->children[i].min)
        error(it, "a " + n.tag + " needs at least " + std::to_string(rule->children[i].min) + " " +
                      std::string(rule->children[i].tag) + ", it has " + std::to_string(counts[i]));
  }

  // ---- pass 2: rules across elements -------------------------------------------------
  void cross_check(const Item& it) {
    const Node& n = *it.node;
    if (n.tag == "GARMENT") check_version(it);
    else if (n.tag == "HEM") check_hem(it);
    else if (n.tag == "SIZE") check_size(it);
    else if (n.tag == "ASSOCIATION") check_association(it);
    else if (n.tag == "POSITION") check_position(it);
    else if (n.tag == "C2DSEQ") check_sequence(it);
    else if (n.tag == "PARAMETER") check_parameter(it);
  }

  void check_version(const Item& it) {
    const auto v = it.node->attribute("version");
    const auto dot = v.find('.');
    if (dot != std::string_view::npos && v.substr(0, dot) != kFormatVersion.substr(0, kFormatVersion.find('.')))
      error(it, "format version " + std::string(v) + " is not supported; vgd reads version " +
                    std::string(kFormatVersion.substr(0, kFormatVersion.find('.'))) + ".x");
  }

  // The element a reference names, after reporting a missing one.
  const Item* target(const Item& it, std::string_view attr) {
    const auto* v = it.node->find_attribute(attr);
    if (!v || !detail::is_id_text(*v)) return nullptr;  // reported in pass 1
    const Item* t = lookup(*v);
    if (!t) error(it, std::string(attr) + " names " + *v + ", which is not in the document");
    return t;
  }

  void check_hem(const Item& it) {
    const Item* ends[2] = {target(it, "from"), target(it, "to")};
    const char* names[2] = {"from", "to"};
    bool ok = true;
    for (int k = 0; k < 2; ++k) {
      const Item* t = ends[k];
      if (!t) {
        ok = false;
        continue;
      }
      const std::string id(t->node->id());
      if (t->node->tag != "C2DSEQ") {
        error(it, std::string(names[k]) + " names " + id + ", a " + t->node->tag +
                      "; a hem must name a boundary C2DSEQ");
        ok = false;
      } else if (const auto role = t->node->attribute("role"); !role.empty() && role != "boundary") {
        error(it, std::string(names[k]) + " names " + id + ", a " + std::string(role) +
                      " C2DSEQ; a hem must name a boundary C2DSEQ");
        ok = false;
      }
    }
    if (ok && ends[0]->pattern != ends[1]->pattern)
      error(it, "from and to lie in different patterns (" + std::string(ends[0]->pattern->id()) + ", " +
                    std::string(ends[1]->pattern->id()) + "); a hem runs along one pattern");
  }

  void check_size(const Item& it) {
    const Node& n = *it.node;
    const bool in_run = it.parent && it.parent->tag == "GRADATIONS";
    const Node* gradations = in_run ? it.parent : nullptr;
    if (!in_run && it.parent && it.parent->tag == "GRADATION") gradations = items_[it.parent_item].parent;
    // The sample flag must agree with the size the GRADATIONS container names.
    if (detail::parse_bool(n.attribute("sample")).value_or(false) && gradations &&
        gradations->attribute("sample_size") != n.attribute("name"))
      error(it, "size " + quote(n.attribute("name")) + " is marked sample, but the sample size is " +
                    quote(gradations->attribute("sample_size")));
    if (!n.has_attribute("pattern")) return;
    if (in_run) {
      error(it, "a SIZE of the size run (directly in GRADATIONS) names no pattern; list patterns in a GRADATION");
      return;
    }
    const Item* t = target(it, "pattern");
    if (!t) return;
    const Node& p = *t->node;
    if (p.tag != "PATTERN") {
      error(it, "pattern names " + std::string(p.id()) + ", a " + p.tag + ", not a PATTERN");
      return;
    }
    if (p.attribute("size") != n.attribute("name"))
      error(it, "names pattern " + std::string(p.id()) + " of size " + quote(p.attribute("size")) +
                    " under size " + quote(n.attribute("name")));
    if (it.parent && it.parent->tag == "GRADATION" && p.attribute("piece") != it.parent->attribute("piece"))
      error(it, "names pattern " + std::string(p.id()) + " of piece " + quote(p.attribute("piece")) +
                    " in the gradation of piece " + quote(it.parent->attribute("piece")));
  }

  void check_association(const Item& it) {
    const Item* t = target(it, "ref");
    if (!t) return;
    const std::string want = to_upper(it.node->attribute("role"));
    if (!want.empty() && t->node->tag != want)
      error(it, "ref names " + std::string(t->node->id()) + ", a " + t->node->tag + ", but role " +
                    quote(it.node->attribute("role")) + " needs a " + want);
  }

  void check_position(const Item& it) {
    const Node& n = *it.node;
    // Arrangements (arrangement.hpp) belong to a PATTERN and say where it goes.
    const bool arrangement = n.attribute("type") == "arrangement";
    if (n.attribute("type") == "sheet") {
      if (!it.pattern || (it.parent && it.parent->tag != "PATTERN")) error(it, "a sheet position belongs inside a PATTERN");
      if (it.parent) {
        int sheets = 0;
        for (const auto& c : it.parent->children) sheets += c.tag == "POSITION" && c.attribute("type") == "sheet";
        if (sheets > 1) error(it, "a PATTERN has one sheet position, not " + std::to_string(sheets));
      }
    }
    if (n.attribute("type") == "pin" && (!it.pattern || (it.parent && it.parent->tag != "PATTERN")))
      error(it, "a pin belongs inside a PATTERN");
    if (arrangement) {
      if (!it.pattern || (it.parent && it.parent->tag != "PATTERN")) error(it, "an arrangement belongs inside a PATTERN");
      for (const char* a : {"segment", "side", "height"})
        if (!n.has_attribute(a)) error(it, std::string("an arrangement needs ") + a);
    } else {
      for (const char* a : {"segment", "side", "height", "clearance", "flip", "around"})
        if (n.has_attribute(a)) error(it, std::string(a) + " applies only to arrangements");
    }
    if (n.has_attribute("pattern"))
      if (const Item* t = target(it, "pattern"); t && t->node->tag != "PATTERN")
        error(it, "pattern names " + std::string(t->node->id()) + ", a " + t->node->tag + ", not a PATTERN");
    if (const auto v = parse_int(n.attribute("vertex")); v && *v >= 0) {
      if (!it.pattern) {
        error(it, "vertex applies only to notches of a PATTERN");
      } else if (const auto count = boundary_count(*it.pattern); static_cast<std::size_t>(*v) >= count) {
        error(it, "vertex " + std::to_string(*v) + " is beyond the boundary of " + std::string(it.pattern->id()) +
                      ", which has " + std::to_string(count) + " points");
      }
    }
  }

  void check_sequence(const Item& it) {
    const Node& n = *it.node;
    const std::string role = n.has_attribute("role") ? std::string(n.attribute("role")) : "boundary";
    const auto points = std::count_if(n.children.begin(), n.children.end(), [](const Node& c) { return c.tag == "C2D"; });
    if (role == "boundary") {
      if (points == 0) error(it, "a boundary C2DSEQ needs at least one C2D");
      if (n.has_attribute("closed"))
        error(it, "closed does not apply to a boundary C2DSEQ (the PATTERN's closed attribute says it)");
    } else if (role == "grain" || role == "mirror" || role == "grade") {
      if (points != 2)
        error(it, "a " + role + " line has exactly 2 C2D, this one has " + std::to_string(points));
      if (n.has_attribute("closed")) error(it, "closed does not apply to a " + role + " line");
      // One line of each of these kinds per pattern: a piece has one grain line.
      if (it.pattern) {
        for (const auto& sib : it.pattern->children) {
          if (&sib == &n) break;
          if (sib.tag == "C2DSEQ" && sib.attribute("role") == role) {
            error(it, "a PATTERN has at most one " + role + " line");
            break;
          }
        }
      }
    }
  }

  void check_parameter(const Item& it) {
    const Node& n = *it.node;
    const auto name = n.attribute("name");
    // Names are keys: two parameters of one owner with one name would be ambiguous.
    if (it.parent) {
      for (const auto& sib : it.parent->children) {
        if (&sib == &n) break;
        if (sib.tag == "PARAMETER" && sib.attribute("name") == name) {
          error(it, "parameter " + std::string(name) + " is set twice in " + it.parent->tag);
          break;
        }
      }
    }
    const auto* spec = find_parameter_spec(name);
    if (!spec) return;
    const auto unit = n.attribute("unit");
    if (n.has_attribute("unit") && unit != spec->unit)
      error(it, std::string(name) + " is in " + std::string(spec->unit) + ", not " + quote(unit));
    if (const auto v = parse_double(n.attribute("value")); v && (*v <= spec->min || *v > spec->max))
      error(it, std::string(name) + " " + format_double(*v) + " is out of range: it must be greater than " +
                    format_double(spec->min) + " and at most " + format_double(spec->max) + " " +
                    std::string(spec->unit));
  }

  // Two blocks of one name are legal XML but break the DXF round trip.
  void check_blocks() {
    std::unordered_map<std::string, const Item*> blocks;
    for (const auto& it : items_) {
      if (it.node->tag != "PATTERN" || it.node->attribute("block").empty()) continue;
      const auto [pos, fresh] = blocks.emplace(std::string(it.node->attribute("block")), &it);
      if (!fresh)
        warn(it, "block " + quote(it.node->attribute("block")) + " is also the block of " +
                     std::string(pos->second->node->id()));
    }
  }

  // Points of a pattern's boundary, counted once per pattern.
  std::size_t boundary_count(const Node& pattern) {
    const auto [pos, fresh] = boundary_counts_.emplace(&pattern, 0);
    if (!fresh) return pos->second;
    std::size_t& count = pos->second;
    for (const auto& c : pattern.children)
      if (c.tag == "C2DSEQ" && (!c.has_attribute("role") || c.attribute("role") == "boundary"))
        count += static_cast<std::size_t>(
            std::count_if(c.children.begin(), c.children.end(), [](const Node& p) { return p.tag == "C2D"; }));
    return count;
  }

  static std::string to_upper(std::string_view s) {
    std::string out(s);
    for (auto& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return out;
  }

  std::string file_;
  Diagnostics out_;
  std::vector<Item> items_;
  std::unordered_map<std::string, std::size_t> ids_;
  std::unordered_map<const Node*, std::size_t> boundary_counts_;
};
}  // namespace

Diagnostics check(const Node& root, std::string_view file) { return Checker(file).run(root); }

Diagnostics check(const Document& doc) { return check(doc.root(), doc.name()); }

}  // namespace vgd::xvc
