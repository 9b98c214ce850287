// The contact sheet in a browser: headless Chromium (tests/web/contact_sheet.mjs)
// shows a card per item with its preview loaded, and the filters show only
// the items chosen. Skipped with a message when node, playwright-core or
// chromium are absent (.ci/install-deps installs them).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "support/command.hpp"
#include "support/test_paths.hpp"
#include "vgd/batch/catalogue.hpp"
#include "vgd/batch/item.hpp"
#include "vgd/batch/report.hpp"
#include "vgd/core/file.hpp"

namespace vgd::test {
namespace {

namespace fs = std::filesystem;
namespace batch = vgd::batch;
using nlohmann::json;

const fs::path kWeb = VGD_WEB_TESTS_DIR;

TEST(ContactSheet, ABrowserShowsEveryCardWithItsPreviewAndFiltersThem) {
  if (std::system("node --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "SKIPPED: node not found";
  if (!fs::is_regular_file(kWeb / "node_modules/playwright-core/package.json"))
    GTEST_SKIP() << "SKIPPED: playwright-core not in " << kWeb / "node_modules" << " (run .ci/install-deps)";
  if (!fs::is_regular_file("/usr/bin/chromium")) GTEST_SKIP() << "SKIPPED: /usr/bin/chromium not installed";
  const auto dir = scratch_dir("batch-contact-sheet");
  write_file_atomic(dir / "skirt.xvc", read_file(source_dir() / "data/garments/a-line-skirt.xvc"));
  write_file_atomic(dir / "catalogue.json", json{{"name", "sheet"},
                                                 {"styles", {{{"id", "skirt"}, {"file", "skirt.xvc"}}}},
                                                 {"sizes", {"36", "38"}},
                                                 {"fabrics", {"garment", "denim"}},
                                                 {"outputs", {"certificate", "previews"}},
                                                 {"views", {"front"}}}
                                                .dump());
  const auto c = batch::load_catalogue(dir / "catalogue.json");
  ASSERT_EQ(c.items.size(), 4u);
  const fs::path out = dir / "out";
  setenv("FAKE_PNG", (source_dir() / "tests/golden/a-line-skirt/front.png").string().c_str(), 1);
  for (const auto& item : c.items) {
    setenv("FAKE_VGD", item.index == 2 ? "check-failed" : "pass", 1);
    batch::RunItemOptions o;
    o.exe = source_dir() / "tests/batch/fake_vgd.sh";
    batch::run_item(c, item, out, o);
  }
  unsetenv("FAKE_VGD");
  unsetenv("FAKE_PNG");
  batch::write_summary(c, out, batch::status(c, out));
  const std::string text = command_output("cd '" + kWeb.string() + "' && node contact_sheet.mjs '" + out.string() +
                               "' '{\"size\": \"38\", \"state\": \"failed\"}'");
  const json r = json::parse(text, nullptr, false);
  ASSERT_FALSE(r.is_discarded()) << text;
  EXPECT_TRUE(r["errors"].empty()) << r["errors"].dump();
  EXPECT_EQ(r["cards"], 4);
  EXPECT_EQ(r["shown"], 4);
  EXPECT_EQ(r["images"], 4);
  EXPECT_EQ(r["loaded"], 4) << "every preview image loads";
  EXPECT_EQ(r["counts"], "4 items: 3 passed, 1 failed, 0 not finished");
  EXPECT_EQ(r["filtered"]["size=38"], 2);
  EXPECT_EQ(r["filtered"]["state=failed"], 1) << "size 38 and failed";
  EXPECT_EQ(r["filtered"]["state=failed label"], "1 shown");
}

}  // namespace
}  // namespace vgd::test
