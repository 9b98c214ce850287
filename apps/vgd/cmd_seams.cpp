// vgd seams: list, suggest, add, delete and apply seams of an XVC document
// (xvc/seams.hpp). Every change goes through the undoable commands and is checked;
// the output is written atomically, only when every change succeeded.
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "cli.hpp"
#include "vgd/core/file.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/xvc/commands.hpp"
#include "vgd/xvc/io.hpp"
#include "vgd/xvc/seams.hpp"
#include "vgd/xvc/style.hpp"

namespace cmd_seams {
namespace {

struct Options {
  std::string input, output, size, name, plan_file;
  std::string from;
  std::vector<std::string> to, ids;
  bool json = false, apply = false, reverse = false;
  double min_score = 0.5;
};

std::string piece_of(const vgd::xvc::Document& doc, const std::string& pattern) {
  const auto* p = doc.find(pattern);
  return p ? std::string(p->attribute("piece")) + " " + std::string(p->attribute("size")) : pattern;
}

nlohmann::json hems_json(const std::vector<vgd::xvc::HemRef>& hems) {
  auto a = nlohmann::json::array();
  for (const auto& h : hems)
    a.push_back({{"pattern", h.pattern}, {"from", h.from}, {"to", h.to}, {"direction", h.reverse ? "reverse" : "forward"},
                 {"length_m", h.length}, {"notches", h.notches}});
  return a;
}

std::string hems_text(const vgd::xvc::Document& doc, const std::vector<vgd::xvc::HemRef>& hems) {
  std::string s;
  for (std::size_t i = 0; i < hems.size(); ++i) {
    const auto& h = hems[i];
    s += (i == 0 ? "" : (i == 1 ? "  <->  " : " + ")) + piece_of(doc, h.pattern) + " " + h.from +
         (h.to != h.from ? ".." + h.to : "") + (h.reverse ? " rev" : " fwd");
  }
  return s;
}

// PATTERN:A..B or PATTERN:A, where A and B are C2DSEQ ids or 0-based stretch indices.
vgd::xvc::HemRef parse_hem(const vgd::xvc::Document& doc, const std::string& spec, bool reverse) {
  const auto colon = spec.rfind(':');
  if (colon == std::string::npos) throw vgd::Error("", spec, "a hem is PATTERN:STRETCH..STRETCH, e.g. pattern1:seq2..seq3");
  vgd::xvc::HemRef h;
  h.pattern = spec.substr(0, colon);
  const auto* p = doc.find(h.pattern);
  if (!p || p->tag != "PATTERN") throw vgd::Error(doc.name(), h.pattern, "no PATTERN with this id");
  const auto range = spec.substr(colon + 1);
  const auto dots = range.find("..");
  const std::string a = range.substr(0, dots), b = dots == std::string::npos ? a : range.substr(dots + 2);
  const auto st = vgd::xvc::boundary_stretches(*p);
  auto resolve = [&](const std::string& t) {
    if (const auto k = vgd::parse_int(t)) {
      if (*k < 0 || static_cast<std::size_t>(*k) >= st.size())
        throw vgd::Error(doc.name(), h.pattern, "has " + std::to_string(st.size()) + " boundary stretches; no stretch " + t);
      return st[static_cast<std::size_t>(*k)].id;
    }
    for (const auto& s : st)
      if (s.id == t) return s.id;
    throw vgd::Error(doc.name(), h.pattern, "no boundary stretch " + t + " in this pattern");
  };
  h.from = resolve(a);
  h.to = resolve(b);
  h.reverse = reverse;
  return h;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw vgd::Error(path, "", "cannot read the file");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

vgd::cli::Registrar reg{"seams", 35, [](CLI::App& app, vgd::cli::Common& common) {
  auto* sub = app.add_subcommand("seams", "List, suggest, add, delete or apply the seams of an XVC document");
  sub->require_subcommand(1);
  auto o = std::make_shared<Options>();
  auto* list = sub->add_subcommand("list", "List the SEAMs with their hems and lengths");
  auto* suggest = sub->add_subcommand("suggest", "Suggest seams from piece names, lengths and notches");
  auto* add = sub->add_subcommand("add", "Add one SEAM: --from hem sewn to the --to hem(s), in order");
  auto* del = sub->add_subcommand("delete", "Delete SEAMs by id");
  auto* apply = sub->add_subcommand("apply", "Add the seams of a seam file (JSON: pieces by name, stretches by index)");
  for (auto* c : {list, suggest, add, del, apply}) c->add_option("FILE", o->input, "XVC document")->required()->check(CLI::ExistingFile);
  for (auto* c : {list, suggest}) c->add_flag("--json", o->json, "Print JSON on stdout");
  suggest->add_option("--size", o->size, "Only this size (default: every size)");
  suggest->add_option("--min-score", o->min_score, "Drop suggestions scoring below this (0..1)")->capture_default_str();
  suggest->add_flag("--apply", o->apply, "Add the suggestions as SEAMs and write -o");
  for (auto* c : {suggest, add, del, apply}) c->add_option("-o,--output", o->output, "XVC file to write (atomically)");
  add->add_option("--from", o->from, "Hem A: PATTERN:STRETCH[..STRETCH] (C2DSEQ ids or 0-based indices)")->required();
  add->add_option("--to", o->to, "Hem B: PATTERN:STRETCH[..STRETCH]; repeat for a concatenation")->required();
  add->add_flag("--reverse", o->reverse, "Sew the --to hems against their contour (the usual, untwisted choice)");
  add->add_option("--name", o->name, "Seam name");
  del->add_option("ID", o->ids, "SEAM ids")->required();
  list->add_option("--seam-file", o->output, "Also write the seams of one size (--size, default the sample) as a "
                                            "seam file (JSON: pieces by name, stretches by index) for seams apply "
                                            "or vgd dress --seams");
  list->add_option("--size", o->size, "The size --seam-file takes its seams from (default: the sample size)");
  apply->add_option("SEAMFILE", o->plan_file, "Seam file (JSON)")->required()->check(CLI::ExistingFile);
  apply->add_option("--size", o->size, "Only this size (default: every size)");

  return vgd::cli::Command{sub, [o, &common, list, suggest, add, del, apply]() -> int {
    auto doc = vgd::xvc::load_file(o->input);
    auto write = [&](const std::string& what) {
      if (o->output.empty()) throw vgd::Error("", "seams", "-o OUT.xvc is required to " + what);
      vgd::xvc::save_file(doc, o->output);
      vgd::cli::say(common, "wrote " + o->output + ": " + what);
    };
    if (list->parsed()) {
      const auto seams = vgd::xvc::list_seams(doc);
      if (!o->output.empty()) {
        std::string size = o->size;
        if (size.empty())
          if (const auto* g = doc.container("GRADATIONS")) size = std::string(g->attribute("sample_size"));
        const auto plans = vgd::xvc::seams_as_plans(doc, size);
        vgd::write_file_atomic(o->output, vgd::xvc::seam_plans_to_json(plans));
        vgd::cli::say(common, "wrote " + o->output + ": " + std::to_string(plans.size()) + " seams of size " + size);
      }
      if (o->json) {
        auto a = nlohmann::json::array();
        for (const auto& s : seams) a.push_back({{"id", s.id}, {"name", s.name}, {"hems", hems_json(s.hems)}});
        vgd::cli::print_json(a);
      } else {
        for (const auto& s : seams) {
          double b = 0;
          for (std::size_t i = 1; i < s.hems.size(); ++i) b += s.hems[i].length;
          std::cout << s.id << "  " << (s.name.empty() ? "(no name)" : s.name) << "  " << hems_text(doc, s.hems)
                    << "  lengths " << vgd::format_fixed(s.hems.at(0).length * 1000, 1) << " / "
                    << vgd::format_fixed(b * 1000, 1) << " mm\n";
        }
      }
      return vgd::cli::kOk;
    }
    if (suggest->parsed()) {
      vgd::xvc::SeamOptions opts;
      opts.size = o->size;
      opts.min_score = o->min_score;
      const auto s = vgd::xvc::suggest_seams(doc, opts);
      if (o->json) {
        auto a = nlohmann::json::array();
        for (const auto& x : s)
          a.push_back({{"name", x.name}, {"size", x.size}, {"hems", hems_json(x.hems)}, {"length_a_m", x.length_a},
                       {"length_b_m", x.length_b}, {"ease_m", x.ease}, {"notches_a", x.notches_a},
                       {"notches_b", x.notches_b}, {"notches_matched", x.notches_matched}, {"score", x.score},
                       {"reason", x.reason}});
        vgd::cli::print_json(a);
      } else {
        std::cout << "size  seam               score  A mm     B mm     ease mm  notches  hems\n";
        for (const auto& x : s) {
          std::string name = x.name;
          name.resize(18, ' ');
          std::cout << x.size << "    " << name << " " << vgd::format_fixed(x.score, 2) << "   "
                    << vgd::format_fixed(x.length_a * 1000, 1) << "    " << vgd::format_fixed(x.length_b * 1000, 1)
                    << "    " << vgd::format_fixed(x.ease * 1000, 1) << "     " << x.notches_matched << "/"
                    << std::max(x.notches_a, x.notches_b) << "      " << hems_text(doc, x.hems) << "\n";
        }
      }
      if (o->apply) {
        std::vector<vgd::xvc::Node> nodes;
        for (const auto& x : s) nodes.push_back(vgd::xvc::seam_node(x));
        vgd::xvc::AddSeams cmd(nodes);
        vgd::xvc::execute(doc, cmd);
        write(std::to_string(nodes.size()) + " seams added");
      }
      return vgd::cli::kOk;
    }
    if (add->parsed()) {
      std::vector<vgd::xvc::HemRef> hems{parse_hem(doc, o->from, false)};
      for (const auto& t : o->to) hems.push_back(parse_hem(doc, t, o->reverse));
      vgd::xvc::AddSeams cmd({vgd::xvc::seam_node(o->name, hems)});
      const auto id = vgd::xvc::execute(doc, cmd);
      write("added " + id);
      return vgd::cli::kOk;
    }
    if (del->parsed()) {
      std::vector<std::unique_ptr<vgd::xvc::Command>> cmds;
      for (const auto& id : o->ids) {
        const auto* n = doc.find(id);
        if (!n) throw vgd::Error(doc.name(), id, "no element with this id");
        if (n->tag != "SEAM") throw vgd::Error(doc.name(), id, id + " is a " + n->tag + ", not a SEAM");
        cmds.push_back(std::make_unique<vgd::xvc::DeleteNode>(id));
      }
      vgd::xvc::Batch batch("Delete seams", std::move(cmds));
      vgd::xvc::execute(doc, batch);
      write("deleted " + std::to_string(o->ids.size()) + " seams");
      return vgd::cli::kOk;
    }
    if (apply->parsed()) {
      const auto plans = vgd::xvc::parse_seam_plans(read_text(o->plan_file), o->plan_file);
      vgd::xvc::AddSeams cmd(vgd::xvc::plan_seam_nodes(doc, plans, o->size));
      vgd::xvc::execute(doc, cmd);
      write("seams of " + o->plan_file + " added");
      return vgd::cli::kOk;
    }
    return vgd::cli::kUsage;
  }};
}};

}  // namespace
}  // namespace cmd_seams
