// Size tables as data: the shipped tables load, lookups find the right table,
// bad tables are reported with file, line and column.
#include <gtest/gtest.h>

#include "support/test_paths.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/body/sizes.hpp"
#include "vgd/body/mannequin.hpp"

using namespace vgd;
using namespace vgd::body;

TEST(BodySizes, ShippedTablesLoadAndArePlausible) {
  for (const auto& name : size_table_names()) {
    const auto rows = load_size_table(size_table_file(name));
    EXPECT_GE(rows.size(), 8u) << name;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      EXPECT_NO_THROW(check_measurements(rows[i], name)) << name << " " << rows[i].label;
      if (i > 0) {
        EXPECT_GT(rows[i].bust, rows[i - 1].bust) << name << " " << rows[i].label;
      }
    }
  }
}

TEST(BodySizes, FindSizeSearchesInOrder) {
  const auto w38 = find_size("38");
  EXPECT_EQ(w38.sex, "female");
  EXPECT_DOUBLE_EQ(w38.bust, 0.88);
  EXPECT_DOUBLE_EQ(w38.waist, 0.72);
  EXPECT_DOUBLE_EQ(w38.hip, 0.97);
  EXPECT_NEAR(w38.inseam, 0.464 * 1.68, 1e-12);  // derived
  EXPECT_EQ(find_size("50").sex, "female");
  const auto m50 = find_size("50", "en13402-men");
  EXPECT_EQ(m50.sex, "male");
  EXPECT_DOUBLE_EQ(m50.bust, 1.00);
  EXPECT_DOUBLE_EQ(m50.under_bust, m50.bust);
  const auto a10 = find_size("10", "astm-d5585-misses");
  EXPECT_NEAR(a10.bust, 37.25 * 0.0254, 1e-12);
  EXPECT_NEAR(a10.neck, 14.875 * 0.0254, 1e-12);
  try {
    find_size("99");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("available"), std::string::npos) << e.what();
  }
  EXPECT_THROW(find_size("38", "no-such-table"), Error);
}

TEST(BodySizes, BadTablesNameFileLineAndColumn) {
  const auto dir = test::scratch_dir("body_sizes_bad");
  write_file_atomic(dir / "t.csv", "size,height_cm,bust_cm,waist_cm,hip_cm\n38,168,88,seventy,97\n");
  try {
    load_size_table(dir / "t.csv");
    FAIL();
  } catch (const Error& e) {
    const std::string w = e.what();
    EXPECT_NE(w.find("t.csv:2"), std::string::npos) << w;
    EXPECT_NE(w.find("column 4 'waist'"), std::string::npos) << w;
  }
  write_file_atomic(dir / "u.csv", "size,height,bust_cm,waist_cm,hip_cm\n38,168,88,72,97\n");
  EXPECT_THROW(load_size_table(dir / "u.csv"), Error);
  write_file_atomic(dir / "v.csv", "size,height_cm,bust_cm,hip_cm\n38,168,88,97\n");
  EXPECT_THROW(load_size_table(dir / "v.csv"), Error);
  write_file_atomic(dir / "w.csv", "");
  EXPECT_THROW(load_size_table(dir / "w.csv"), Error);
}

TEST(BodySizes, EveryShippedSizeMakesAMannequin) {
  // Calibration only (the mesh is tested in test_mannequin): every size's trunk
  // girths must be reachable.
  for (const auto& name : size_table_names())
    for (const auto& m : load_size_table(size_table_file(name))) {
      const MannequinSdf sdf(m);
      const auto& lm = sdf.landmarks();
      EXPECT_NEAR(sdf.girth_at(lm.bust) / m.bust, 1.0, 0.005) << name << " " << m.label;
      EXPECT_NEAR(sdf.girth_at(lm.waist) / m.waist, 1.0, 0.005) << name << " " << m.label;
      EXPECT_NEAR(sdf.girth_at(lm.hip) / m.hip, 1.0, 0.005) << name << " " << m.label;
    }
}
