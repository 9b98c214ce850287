#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "fixtures.hpp"

using namespace vgd::xvc;
using namespace vgd::xvc::test;

TEST(Parameters, MeshParametersAreKnownWithTheirUnits) {
  const std::pair<const char*, const char*> expected[] = {
      {"mesh.spacing", "m"}, {"mesh.turn_angle", "deg"}, {"mesh.min_angle", "deg"}, {"mesh.max_area", "m2"}};
  for (const auto& [name, unit] : expected) {
    const auto* spec = find_parameter_spec(name);
    ASSERT_NE(spec, nullptr) << name;
    EXPECT_EQ(spec->unit, unit);
  }
  EXPECT_EQ(find_parameter_spec("mesh.nope"), nullptr);
}

TEST(Parameters, AbsentParameterReadsAsNothing) {
  const Document doc = from_style(full_style());
  EXPECT_FALSE(get_parameter(doc, "mesh.spacing"));
}

TEST(Parameters, SetThenGetGivesTheValueBack) {
  Document doc;
  set_parameter(doc, "mesh.spacing", 0.0125);
  set_parameter(doc, "mesh.max_area", 3e-5, "m2");
  EXPECT_EQ(get_parameter(doc, "mesh.spacing"), 0.0125);
  EXPECT_EQ(get_parameter(doc, "mesh.max_area"), 3e-5);
  // Stored as GARMENT-level PARAMETERs, before the containers.
  EXPECT_EQ(doc.root().children[0].tag, "PARAMETER");
  EXPECT_EQ(doc.root().children[0].attribute("unit"), "m");
  EXPECT_EQ(doc.root().children[1].attribute("unit"), "m2");
  EXPECT_EQ(doc.root().children[2].tag, "PATTERNS");
}

TEST(Parameters, SettingAgainChangesTheSameElement) {
  Document doc;
  set_parameter(doc, "mesh.turn_angle", 30);
  const std::string id(doc.root().children[0].id());
  set_parameter(doc, "mesh.turn_angle", 45);
  EXPECT_EQ(doc.root().children[0].id(), id);
  EXPECT_EQ(doc.root().children[1].tag, "PATTERNS");
  EXPECT_EQ(get_parameter(doc, "mesh.turn_angle"), 45.0);
}

TEST(Parameters, WrongUnitIsRefused) {
  Document doc;
  try {
    set_parameter(doc, "mesh.spacing", 10, "deg");
    FAIL() << "expected an error";
  } catch (const vgd::Error& e) {
    EXPECT_NE(std::string(e.what()).find("mesh.spacing is in m, not deg"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(get_parameter(doc, "mesh.spacing"));
}

TEST(Parameters, OutOfRangeAndNonFiniteValuesAreRefused) {
  Document doc;
  EXPECT_THROW(set_parameter(doc, "mesh.spacing", 0.0), vgd::Error);
  EXPECT_THROW(set_parameter(doc, "mesh.spacing", -0.01), vgd::Error);
  EXPECT_THROW(set_parameter(doc, "mesh.min_angle", 34), vgd::Error);
  EXPECT_THROW(set_parameter(doc, "mesh.turn_angle", std::numeric_limits<double>::quiet_NaN()), vgd::Error);
  EXPECT_THROW(set_parameter(doc, "x.y", std::numeric_limits<double>::infinity(), "1"), vgd::Error);
  EXPECT_EQ(save_string(doc), save_string(Document{}));
}

TEST(Parameters, UnknownParametersNeedAnSiUnit) {
  Document doc;
  EXPECT_THROW(set_parameter(doc, "sim.damping", 0.5), vgd::Error);
  EXPECT_THROW(set_parameter(doc, "sim.damping", 0.5, "furlong"), vgd::Error);
  EXPECT_THROW(set_parameter(doc, "bad name", 0.5, "1"), vgd::Error);
  set_parameter(doc, "sim.damping", 0.5, "1/s");
  EXPECT_EQ(get_parameter(doc, "sim.damping"), 0.5);
}

TEST(Parameters, SetParameterIsUndoable) {
  Document doc = from_style(full_style());
  const std::string before = save_string(doc);
  UndoStack stack(doc);
  const std::string id = stack.execute(std::make_unique<SetParameter>("mesh.spacing", 0.02));
  EXPECT_EQ(doc.find(id)->attribute("name"), "mesh.spacing");
  stack.undo();
  EXPECT_EQ(save_string(doc), before);
  stack.redo();
  EXPECT_EQ(get_parameter(doc, "mesh.spacing"), 0.02);
}
