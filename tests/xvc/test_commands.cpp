#include <gtest/gtest.h>

#include <set>

#include "fixtures.hpp"

using namespace vgd::xvc;
using namespace vgd::xvc::test;

namespace {
// Every id in the document, failing on a repeat.
std::set<std::string> all_ids(const Document& doc) {
  std::set<std::string> ids;
  auto walk = [&](auto&& self, const Node& n) -> void {
    if (n.has_attribute("id")) {
      EXPECT_TRUE(ids.insert(std::string(n.id())).second) << "repeated id " << n.id();
    }
    for (const auto& c : n.children) self(self, c);
  };
  walk(walk, doc.root());
  return ids;
}

// The message of the vgd::Error `f` throws.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const vgd::Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a vgd::Error";
  return "";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }
}  // namespace

TEST(UndoStack, UndoRestoresTheExactPreviousDocument) {
  Document doc = full_document();
  UndoStack stack(doc);
  std::vector<std::string> history{save_string(doc)};
  stack.execute(std::make_unique<DeletePattern>("pattern2"));
  history.push_back(save_string(doc));
  stack.execute(std::make_unique<CopyPattern>("pattern1"));
  history.push_back(save_string(doc));
  stack.execute(std::make_unique<MirrorPattern>("pattern1"));
  history.push_back(save_string(doc));
  stack.execute(std::make_unique<SetParameter>("mesh.spacing", 0.02));
  history.push_back(save_string(doc));
  stack.execute(std::make_unique<SetAttribute>("pattern1", "fabric", std::nullopt));
  history.push_back(save_string(doc));
  stack.execute(std::make_unique<DeleteNode>("seq3"));  // a boundary stretch with notch vertices after it
  history.push_back(save_string(doc));
  for (std::size_t i = history.size() - 1; i > 0; --i) {
    ASSERT_TRUE(stack.can_undo());
    stack.undo();
    EXPECT_EQ(save_string(doc), history[i - 1]) << "after undoing step " << i;
  }
  EXPECT_FALSE(stack.can_undo());
  // Redo replays to the same texts.
  for (std::size_t i = 1; i < history.size(); ++i) {
    stack.redo();
    EXPECT_EQ(save_string(doc), history[i]) << "after redoing step " << i;
  }
  EXPECT_FALSE(stack.can_redo());
}

TEST(UndoStack, NewCommandDropsTheRedoList) {
  Document doc = full_document();
  UndoStack stack(doc);
  stack.execute(std::make_unique<DeletePattern>("pattern2"));
  stack.undo();
  EXPECT_TRUE(stack.can_redo());
  EXPECT_EQ(stack.redo_label(), "Delete pattern pattern2");
  stack.execute(std::make_unique<DeletePattern>("pattern3"));
  EXPECT_FALSE(stack.can_redo());
  EXPECT_EQ(stack.undo_label(), "Delete pattern pattern3");
  EXPECT_NE(doc.find("pattern2"), nullptr);
}

TEST(UndoStack, RefusedCommandLeavesDocumentAndHistoryUntouched) {
  Document doc = full_document();
  UndoStack stack(doc);
  const std::string before = save_string(doc);
  EXPECT_THROW(stack.execute(std::make_unique<DeletePattern>("nope")), vgd::Error);
  EXPECT_THROW(stack.execute(std::make_unique<DeleteNode>("hem1")), vgd::Error);  // seam would keep 1 hem
  EXPECT_EQ(save_string(doc), before);
  EXPECT_FALSE(stack.can_undo());
}

TEST(UndoStack, CommandThatChangesNothingIsNotRecorded) {
  Document doc = full_document();
  UndoStack stack(doc);
  stack.execute(std::make_unique<SetParameter>("mesh.spacing", 0.01));  // already 0.01 m
  EXPECT_FALSE(stack.can_undo());
}

TEST(UndoStack, KeepsAtMostItsLimit) {
  Document doc;
  UndoStack stack(doc, 3);
  for (int i = 1; i <= 5; ++i) stack.execute(std::make_unique<SetParameter>("mesh.spacing", 0.001 * i));
  int undos = 0;
  while (stack.can_undo()) {
    stack.undo();
    ++undos;
  }
  EXPECT_EQ(undos, 3);
  EXPECT_EQ(get_parameter(doc, "mesh.spacing"), 0.002);
}

TEST(Commands, NoSuchIdIsAClearError) {
  Document doc = full_document();
  DeleteNode cmd("ghost");
  EXPECT_TRUE(contains(error_of([&] { execute(doc, cmd); }), "no element with id ghost"));
}

TEST(Commands, WrongElementTypeIsAClearError) {
  Document doc = full_document();
  DeletePattern del("seam1");
  EXPECT_TRUE(contains(error_of([&] { execute(doc, del); }), "seam1 is a SEAM, not a PATTERN"));
  MirrorPattern mirror("seq1");
  EXPECT_TRUE(contains(error_of([&] { execute(doc, mirror); }), "seq1 is a C2DSEQ, not a PATTERN"));
}

TEST(DeleteNode, RootCannotBeDeleted) {
  Document doc;
  DeleteNode cmd("garment");
  EXPECT_TRUE(contains(error_of([&] { execute(doc, cmd); }), "root cannot be deleted"));
}

TEST(DeleteNode, DeletingAStretchDropsItsHemsSeamsAndRenumbersNotches) {
  Document doc = full_document();
  // pattern1: stretches seq1 [0], seq2 [1,2], seq3 [3,4], ...; the first notch sits on vertex 2.
  const std::string notch = "pos1";
  ASSERT_EQ(doc.find(notch)->attribute("vertex"), "2");
  DeleteNode del_seq1("seq1");
  execute(doc, del_seq1);
  EXPECT_EQ(doc.find(notch)->attribute("vertex"), "1");  // one point fewer before it
  DeleteNode del_seq2("seq2");                           // the stretch holding it, and hem1
  execute(doc, del_seq2);
  EXPECT_FALSE(doc.find(notch)->has_attribute("vertex"));
  EXPECT_EQ(doc.find("hem1"), nullptr);
  EXPECT_EQ(doc.find("seam1"), nullptr) << "a seam left with one hem is deleted with it";
  EXPECT_FALSE(check(doc).has_errors()) << dump(check(doc));
}

TEST(AddNode, AddsAtTheSchemaPlaceWithFreshIds) {
  Document doc = from_style(full_style());
  const std::string expected = doc.fresh_id("seq");
  AddNode add("pattern1", Node{"C2DSEQ", {{"role", "internal"}}, {Node{"C2D", {{"x", "0"}, {"y", "0"}}, {}}}});
  const std::string id = execute(doc, add);
  EXPECT_EQ(id, expected);
  // After the last C2DSEQ, before the POSITIONs.
  const Node& p = *doc.find("pattern1");
  std::size_t at = 0;
  while (p.children[at].id() != id) ++at;
  EXPECT_EQ(p.children[at - 1].tag, "C2DSEQ");
  EXPECT_EQ(p.children[at + 1].tag, "POSITION");
  all_ids(doc);
}

TEST(AddNode, RefusesAnIdAlreadyUsedAndAWrongParent) {
  Document doc = full_document();
  AddNode taken("seams", Node{"SEAM", {{"id", "pattern1"}}, {}});
  EXPECT_TRUE(contains(error_of([&] { execute(doc, taken); }), "id pattern1 is already used"));
  AddNode wrong("pattern1", Node{"SEAM", {}, {}});
  EXPECT_TRUE(contains(error_of([&] { execute(doc, wrong); }), "a PATTERN cannot hold a SEAM"));
  AddNode second_container("garment", Node{"PATTERNS", {}, {}});
  EXPECT_TRUE(contains(error_of([&] { execute(doc, second_container); }), "at most 1 PATTERNS"));
  AddNode bad_index("seams", Node{"SEAM", {}, {}}, 99);
  EXPECT_TRUE(contains(error_of([&] { execute(doc, bad_index); }), "index 99 is beyond"));
}

TEST(AddNode, ExplicitIndexOutOfSchemaOrderIsRefused) {
  Document doc = from_style(full_style());
  AddNode add("pattern1", Node{"ANNOTATION", {{"text", "late"}}, {}}, doc.find("pattern1")->children.size());
  EXPECT_TRUE(contains(error_of([&] { execute(doc, add); }), "must come before"));
}

TEST(CopyPasteNode, PasteGivesFreshIdsToTheCopyAndItsDescendants) {
  Document doc = full_document();
  const Node clip = copy_node(doc, "pattern1");
  const auto before = all_ids(doc);
  PasteNode paste("patterns", clip);
  const std::string first = execute(doc, paste);
  const std::string second = execute(doc, paste);  // pasting twice gives two copies
  EXPECT_NE(first, second);
  const auto after = all_ids(doc);
  for (const auto& id : before) EXPECT_TRUE(after.count(id)) << "id " << id << " changed or vanished";
  // Each paste added as many ids as the subtree holds, none reused.
  std::set<std::string> clip_ids;
  auto walk = [&](auto&& self, const Node& n) -> void {
    if (n.has_attribute("id")) clip_ids.insert(std::string(n.id()));
    for (const auto& c : n.children) self(self, c);
  };
  walk(walk, clip);
  EXPECT_EQ(after.size(), before.size() + 2 * clip_ids.size());
  EXPECT_EQ(doc.find(first)->children.size(), clip.children.size());
}

TEST(CopyPasteNode, ReferencesOutsideThePasteAreKept) {
  Document doc = full_document();
  PasteNode paste("seams", copy_node(doc, "seam1"));
  const Node& seam = *doc.find(execute(doc, paste));
  EXPECT_NE(seam.children[0].id(), "hem1");
  EXPECT_EQ(seam.children[0].attribute("from"), doc.find("hem1")->attribute("from"));
}

TEST(CopyPasteNode, ReferencesIntoThePasteFollowTheCopy) {
  Document doc = from_style(full_style());
  Node p = copy_node(doc, "pattern5");
  p.children.push_back(Node{"ASSOCIATION", {{"id", "self_ref"}, {"ref", "pattern5"}, {"role", "pattern"}}, {}});
  PasteNode paste("patterns", p);
  const std::string id = execute(doc, paste);
  EXPECT_EQ(doc.find(id)->children.back().attribute("ref"), id);
  EXPECT_EQ(doc.find("self_ref"), nullptr) << "pasted ids are always fresh";
}

TEST(CopyNode, UnknownIdIsAnError) {
  const Document doc;
  EXPECT_THROW(copy_node(doc, "x"), vgd::Error);
}

TEST(SetAttribute, ChangesValuesButNeverIds) {
  Document doc = full_document();
  SetAttribute fabric("pattern1", "fabric", std::string("linen"));
  execute(doc, fabric);
  EXPECT_EQ(doc.find("pattern1")->attribute("fabric"), "linen");
  SetAttribute id("pattern1", "id", std::string("p"));
  EXPECT_TRUE(contains(error_of([&] { execute(doc, id); }), "ids cannot be changed"));
  SetAttribute bad("pattern1", "quantity", std::string("-3"));
  EXPECT_TRUE(contains(error_of([&] { execute(doc, bad); }), "refused"));
  EXPECT_EQ(doc.find("pattern1")->attribute("quantity"), "2");
}

TEST(Batch, StepsValidOnlyTogetherSucceedAsOne) {
  Document doc = from_style(full_style());
  const std::string before = save_string(doc);
  // Renaming a piece alone leaves its gradation naming the old one: refused.
  SetAttribute alone("pattern1", "piece", std::string("FRONT LEFT"));
  EXPECT_TRUE(contains(error_of([&] { execute(doc, alone); }), "in the gradation of piece"));
  // Renamed everywhere at once: accepted, and one undo step.
  std::vector<std::unique_ptr<Command>> steps;
  steps.push_back(std::make_unique<SetAttribute>("pattern1", "piece", std::string("FRONT LEFT")));
  steps.push_back(std::make_unique<SetAttribute>("pattern3", "piece", std::string("FRONT LEFT")));
  steps.push_back(std::make_unique<SetAttribute>("grad1", "piece", std::string("FRONT LEFT")));
  UndoStack stack(doc);
  stack.execute(std::make_unique<Batch>("Rename FRONT", std::move(steps)));
  EXPECT_EQ(to_style(doc).pieces[2].name, "FRONT LEFT");
  EXPECT_EQ(stack.undo_label(), "Rename FRONT");
  stack.undo();
  EXPECT_EQ(save_string(doc), before);
}

TEST(Ids, StableAcrossEditsAndSaves) {
  Document doc = full_document();
  const auto before = all_ids(doc);
  UndoStack stack(doc);
  stack.execute(std::make_unique<CopyPattern>("pattern2"));
  stack.execute(std::make_unique<MirrorPattern>("pattern3", MirrorAxis::vertical));
  stack.execute(std::make_unique<SetParameter>("mesh.min_angle", 28));
  const auto after = all_ids(doc);
  for (const auto& id : before) EXPECT_TRUE(after.count(id)) << id;
  const Document reloaded = load_string(save_string(doc), "r.xvc");
  EXPECT_EQ(all_ids(reloaded), after);
  EXPECT_EQ(save_string(reloaded), save_string(doc));
}
