// Catalogues: validation with the field named, expansion in a fixed order,
// item ids that follow the inputs' content and nothing else.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "support/errors.hpp"
#include "support/test_paths.hpp"
#include "vgd/batch/catalogue.hpp"
#include "vgd/batch/run.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"

namespace vgd::test {
namespace {

namespace fs = std::filesystem;
namespace batch = vgd::batch;
using nlohmann::json;

// A folder with two styles (copies of the shipped skirt, one recoloured), a
// fabric document and a body file, and a catalogue naming them.
struct Folder {
  fs::path dir;
  explicit Folder(const std::string& name) : dir(scratch_dir(name)) {
    const std::string skirt = read_file(source_dir() / "data/garments/a-line-skirt.xvc");
    write_file_atomic(dir / "styles/skirt.xvc", skirt);
    write_file_atomic(dir / "styles/skirt-red.xvc", skirt + "<!-- red -->\n");
    write_file_atomic(dir / "fabrics/jersey.xvc", read_file(source_dir() / "data/materials/cotton-jersey.xvc"));
    write_file_atomic(dir / "bodies/scan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  }
  fs::path write(const json& j, const std::string& name = "catalogue.json") const {
    write_file_atomic(dir / name, j.dump(2));
    return dir / name;
  }
};

json two_styles() {
  return {{"name", "spring"},
          {"styles", {{{"id", "skirt"}, {"file", "styles/skirt.xvc"}},
                      {{"id", "red"}, {"file", "styles/skirt-red.xvc"}, {"sizes", {"40"}}}}},
          {"sizes", {"36", "38", "42"}},
          {"fabrics", {"garment", "denim", {{"id", "jersey"}, {"file", "fabrics/jersey.xvc"}}}},
          {"avatars", {"mannequin", {{"id", "w40"}, {"mannequin", "40"}}}}};
}

TEST(Catalogue, ExpandsStyleBySizeByFabricByAvatarInAFixedOrder) {
  Folder f("batch-expand");
  const auto c = batch::load_catalogue(f.write(two_styles()));
  // skirt: 3 sizes x 3 fabrics x 2 avatars; red: its own 1 size x 3 x 2.
  ASSERT_EQ(c.items.size(), 18u + 6u);
  EXPECT_EQ(c.items[0].name, "skirt 36 garment mannequin");
  EXPECT_EQ(c.items[1].name, "skirt 36 garment w40");
  EXPECT_EQ(c.items[2].name, "skirt 36 denim mannequin");
  EXPECT_EQ(c.items[6].name, "skirt 38 garment mannequin");
  EXPECT_EQ(c.items[18].name, "red 40 garment mannequin");
  for (std::size_t i = 0; i < c.items.size(); ++i) {
    EXPECT_EQ(c.items[i].index, static_cast<int>(i));
    EXPECT_EQ(c.items[i].id.size(), 16u);
  }
  EXPECT_EQ(c.fabrics[1].file.filename(), "denim.xvc") << "a shipped material by its name";
  EXPECT_TRUE(c.fabrics[0].file.empty()) << "the garment's own";
  EXPECT_EQ(c.avatars[1].kind, batch::Avatar::Kind::mannequin);
  EXPECT_EQ(c.avatars[1].size, "40");
  EXPECT_THROW(batch::item_at(c, 24), Error);
  EXPECT_EQ(&batch::item_at(c, 23), &c.items[23]);
}

TEST(Catalogue, ItemIdsFollowTheInputsContentNotTheirPaths) {
  Folder f("batch-ids");
  const auto a = batch::load_catalogue(f.write(two_styles()));
  const auto again = batch::load_catalogue(f.dir / "catalogue.json");
  for (std::size_t i = 0; i < a.items.size(); ++i) EXPECT_EQ(a.items[i].id, again.items[i].id);

  // The same files in another folder: the same ids.
  Folder g("batch-ids-moved");
  const auto moved = batch::load_catalogue(g.write(two_styles()));
  for (std::size_t i = 0; i < a.items.size(); ++i) EXPECT_EQ(a.items[i].id, moved.items[i].id);

  // One style's file edited: only its items change.
  write_file_atomic(g.dir / "styles/skirt-red.xvc", read_file(g.dir / "styles/skirt-red.xvc") + "<!-- edit -->\n");
  const auto edited = batch::load_catalogue(g.dir / "catalogue.json");
  int changed = 0;
  for (std::size_t i = 0; i < a.items.size(); ++i) {
    const bool red = a.items[i].name.rfind("red ", 0) == 0;
    EXPECT_EQ(a.items[i].id != edited.items[i].id, red) << a.items[i].name;
    changed += a.items[i].id != edited.items[i].id;
  }
  EXPECT_EQ(changed, 6);

  // A setting that changes every drape changes every id; the catalogue's
  // name and a style's id (names only) change none.
  json j = two_styles();
  j["settings"] = {{"time_limit", 4}};
  const auto slower = batch::load_catalogue(f.write(j, "b.json"));
  for (std::size_t i = 0; i < a.items.size(); ++i) EXPECT_NE(a.items[i].id, slower.items[i].id);
  j = two_styles();
  j["name"] = "autumn";
  j["styles"][0]["id"] = "a-line";
  const auto renamed = batch::load_catalogue(f.write(j, "c.json"));
  for (std::size_t i = 0; i < a.items.size(); ++i) EXPECT_EQ(a.items[i].id, renamed.items[i].id);
  EXPECT_EQ(renamed.items[0].name, "a-line 36 garment mannequin");

  // A style's seam file is one of its inputs: editing it redoes its items only.
  j = two_styles();
  write_file_atomic(f.dir / "styles/red.seams.json", "{\"seams\": []}");
  j["styles"][1]["seams"] = "styles/red.seams.json";
  const auto with_seams = batch::load_catalogue(f.write(j, "d.json"));
  EXPECT_EQ(with_seams.styles[1].seams.filename(), "red.seams.json");
  write_file_atomic(f.dir / "styles/red.seams.json", "{\"seams\": [ ]}");
  const auto seams_edited = batch::load_catalogue(f.dir / "d.json");
  for (std::size_t i = 0; i < a.items.size(); ++i) {
    const bool red = a.items[i].name.rfind("red ", 0) == 0;
    EXPECT_EQ(with_seams.items[i].id != a.items[i].id, red) << a.items[i].name;
    EXPECT_EQ(seams_edited.items[i].id != with_seams.items[i].id, red) << a.items[i].name;
  }
}

TEST(Catalogue, BadCataloguesAreRefusedNamingTheField) {
  Folder f("batch-bad");
  struct Case {
    std::function<void(json&)> edit;
    std::string field, words;
  };
  const std::vector<Case> cases = {
      {[](json& j) { j["stlyes"] = j["styles"]; }, "stlyes", "unknown key"},
      {[](json& j) { j["styles"][1]["file"] = "styles/nope.dxf"; }, "styles[1].file", "no such file"},
      {[](json& j) { j["styles"][1]["seams"] = "nope.json"; }, "styles[1].seams", "no such file"},
      {[](json& j) { j["styles"][1]["id"] = "skirt"; }, "styles[1].id", "id of an earlier entry"},
      {[](json& j) { j["styles"] = json::array(); }, "styles", "non-empty list"},
      {[](json& j) { j["sizes"] = {"38", "38"}; }, "sizes[1]", "twice"},
      {[](json& j) { j["fabrics"][1] = "velvet"; }, "fabrics[1]", "nor a shipped material"},
      {[](json& j) { j["avatars"][0] = "me"; }, "avatars[0]", "must be \"mannequin\""},
      {[](json& j) { j["avatars"][1]["file"] = "bodies/scan.obj"; }, "avatars[1]", "give one of"},
      {[](json& j) { j["avatars"][1] = {{"file", "bodies/scan.obj"}, {"unit", "feet"}}; }, "avatars[1].unit",
       "not one of"},
      {[](json& j) { j["settings"] = {{"quality", "best"}}; }, "settings.quality", "not one of"},
      {[](json& j) { j["avatars"][1] = {{"id", "anna"}, {"measurements", {{"hip", 98}}}}; },
       "avatars[1].measurements.hip", "out of range"},
      {[](json& j) { j["avatars"][1] = {{"id", "anna"}, {"measurements", {{"hips", 0.98}}}}; },
       "avatars[1].measurements.hips", "unknown key"},
      {[](json& j) { j["avatars"][1] = {{"id", "anna"}, {"measurements", {{"sex", "f"}}}}; },
       "avatars[1].measurements.sex", "not female or male"},
      {[](json& j) { j["settings"] = {{"spacing", 0.0015}}; }, "settings.spacing", "m, not cm"},
      {[](json& j) { j["settings"] = {{"time_limit", -1}}; }, "settings.time_limit", "out of range"},
      {[](json& j) { j["outputs"] = {"certificate", "fbx"}; }, "outputs[1]", "not one of"},
      {[](json& j) { j["views"] = {"top"}; }, "views[0]", "not one of"},
      {[](json& j) { j["styles"][1]["id"] = "a/b"; }, "styles[1].id", "may not hold '/'"},
      {[](json& j) {
         j["styles"][1] = {{"id", "copy"}, {"file", "styles/skirt.xvc"}};
       },
       "styles", "are the same drape"},
  };
  for (const auto& k : cases) {
    json j = two_styles();
    k.edit(j);
    const auto file = f.write(j);
    try {
      batch::load_catalogue(file);
      ADD_FAILURE() << "accepted: " << j.dump();
    } catch (const Error& e) {
      EXPECT_EQ(e.diagnostic().entity, k.field) << e.what();
      EXPECT_NE(std::string(e.what()).find(k.words), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("catalogue.json"), std::string::npos) << e.what();
    }
  }
  write_file_atomic(f.dir / "broken.json", "{\"styles\": [");
  EXPECT_THROW(batch::load_catalogue(f.dir / "broken.json"), Error);
}

TEST(Slurm, TheArrayCoversTheItemsWithTheCataloguesLimits) {
  EXPECT_EQ(batch::array_ranges({0, 1, 2, 3, 4, 5}), "0-5");
  EXPECT_EQ(batch::array_ranges({9, 3, 7, 10, 11, 3}), "3,7,9-11");
  EXPECT_EQ(batch::array_ranges({4}), "4");
  Folder f("batch-slurm");
  json j = two_styles();
  j["settings"] = {{"wall_limit", 600}, {"memory_mb", 3000}, {"threads", 2}};
  const auto c = batch::load_catalogue(f.write(j));
  batch::SlurmOptions o;
  o.exe = "/opt/vgd/bin/vgd";
  o.max_running = 8;
  const std::string s = batch::slurm_script(c, f.dir / "out", o);
  EXPECT_NE(s.find("#SBATCH --array=0-23%8\n"), std::string::npos) << s;
  EXPECT_NE(s.find("#SBATCH --mem=3000M\n"), std::string::npos) << s;
  EXPECT_NE(s.find("#SBATCH --cpus-per-task=2\n"), std::string::npos) << s;
  EXPECT_NE(s.find("#SBATCH --time=15\n"), std::string::npos) << "600 s and 300 s of margin: " << s;
  EXPECT_NE(s.find("exec '/opt/vgd/bin/vgd' batch item"), std::string::npos) << s;
  EXPECT_NE(s.find("--index \"$SLURM_ARRAY_TASK_ID\""), std::string::npos) << s;
  o.indices = {3, 7, 8};
  EXPECT_NE(batch::slurm_script(c, f.dir / "out", o).find("--array=3,7-8%8\n"), std::string::npos);
  o.indices = {24};
  EXPECT_THROW(batch::slurm_script(c, f.dir / "out", o), Error);
  // Above the cluster's MaxArraySize: task ids offset, the item is the task id plus the offset.
  o.indices = {20, 21, 23};
  o.offset = 20;
  const std::string off = batch::slurm_script(c, f.dir / "out", o);
  EXPECT_NE(off.find("--array=0-1,3%8\n"), std::string::npos) << off;
  EXPECT_NE(off.find("--index \"$((SLURM_ARRAY_TASK_ID + 20))\""), std::string::npos) << off;
}

TEST(Slurm, MoreItemsThanTheArraySizeGoInArraysWithOffsets) {
  std::vector<int> all(2500);
  for (int i = 0; i < 2500; ++i) all[static_cast<std::size_t>(i)] = i;
  const auto a = batch::slurm_arrays(all, 1001);
  ASSERT_EQ(a.size(), 3u);
  EXPECT_EQ(a[0].offset, 0);
  EXPECT_EQ(a[1].offset, 1001);
  EXPECT_EQ(a[2].offset, 2002);
  EXPECT_EQ(a[0].indices.size() + a[1].indices.size() + a[2].indices.size(), 2500u);
  EXPECT_EQ(a[2].indices.back() - a[2].offset, 497);
  const auto small = batch::slurm_arrays({7, 3, 900}, 1001);
  ASSERT_EQ(small.size(), 1u);
  EXPECT_EQ(small[0].offset, 0) << "below the limit: task id = item index";
  const auto sparse = batch::slurm_arrays({5, 1500, 1501}, 1001);
  ASSERT_EQ(sparse.size(), 2u);
  EXPECT_EQ(sparse[1].offset, 1500);
  EXPECT_EQ(sparse[1].indices, (std::vector<int>{1500, 1501}));
}

TEST(Slurm, TheIndexComesFromTheSchedulersVariable) {
  unsetenv("SLURM_ARRAY_TASK_ID");
  unsetenv("JOB_COMPLETION_INDEX");
  unsetenv("PBS_ARRAY_INDEX");
  EXPECT_EQ(batch::index_from_environment(), -1);
  setenv("PBS_ARRAY_INDEX", "5", 1);
  EXPECT_EQ(batch::index_from_environment(), 5);
  setenv("JOB_COMPLETION_INDEX", "2", 1);
  EXPECT_EQ(batch::index_from_environment(), 2);
  setenv("SLURM_ARRAY_TASK_ID", "7", 1);
  EXPECT_EQ(batch::index_from_environment(), 7);
  setenv("SLURM_ARRAY_TASK_ID", "seven", 1);
  EXPECT_THROW(batch::index_from_environment(), Error);
  unsetenv("SLURM_ARRAY_TASK_ID");
  unsetenv("JOB_COMPLETION_INDEX");
  unsetenv("PBS_ARRAY_INDEX");
}

TEST(Sha256, MatchesTheStandardsTestVectors) {
  // FIPS 180-2, appendix B.1 and the empty message.
  EXPECT_EQ(batch::sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(batch::sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  const auto dir = scratch_dir("batch-sha");
  write_file_atomic(dir / "abc", "abc");
  EXPECT_EQ(batch::sha256_file(dir / "abc"), batch::sha256_hex("abc"));
  EXPECT_THROW(batch::sha256_file(dir / "none"), Error);
}

}  // namespace
}  // namespace vgd::test
