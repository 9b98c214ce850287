// Materials from XVC MATERIAL modules: parameters converted to SI (Pa and
// kg/m³ through the thickness), and unknown or invalid values refused with a
// message naming the file, the module and the parameter.
#include <gtest/gtest.h>

#include "fixtures.hpp"
#include "support/test_paths.hpp"
#include "vgd/core/file.hpp"
#include "vgd/scene/material.hpp"
#include "vgd/xvc/io.hpp"

using namespace vgd;
using namespace vgd::scene;

namespace {

// A document holding one MATERIAL "m1" with these PARAMETER lines.
std::string document(const std::string& parameters) {
  return "<?xml version=\"1.0\"?>\n<GARMENT id=\"garment\" version=\"1.0\">\n  <MATERIALS id=\"materials\">\n"
         "    <MATERIAL id=\"m1\" name=\"test cloth\">\n" +
         parameters + "    </MATERIAL>\n  </MATERIALS>\n</GARMENT>\n";
}

std::string param(int id, const std::string& name, const std::string& value, const std::string& unit) {
  return "      <PARAMETER id=\"p" + std::to_string(id) + "\" name=\"" + name + "\" value=\"" + value + "\" unit=\"" +
         unit + "\"/>\n";
}

MaterialDef from(const std::string& params) {
  return material_from_xvc(xvc::load_string(document(params), "cloth.xvc"), "m1", "cloth.xvc");
}

}  // namespace

TEST(XvcMaterial, ParametersArriveInSI) {
  const auto m = from(param(1, "density", "0.15", "kg/m2") + param(2, "spring.warp", "1800", "N/m") +
                      param(3, "spring.damping", "0.1", "kg/s") + param(4, "B_warp", "1e-05", "N.m") +
                      param(5, "E_warp", "5000", "N/m") + param(6, "nu_warp_weft", "0.3", "1"));
  EXPECT_EQ(m.name, "test cloth");
  EXPECT_DOUBLE_EQ(m.density, 0.15);
  ASSERT_TRUE(m.mass_spring);
  EXPECT_DOUBLE_EQ(m.mass_spring->warp, 1800.0);
  EXPECT_DOUBLE_EQ(m.mass_spring->damping, 0.1);
  EXPECT_DOUBLE_EQ(m.mass_spring->weft, sim::MassSpringMaterial{}.weft);  // not given: the default
  ASSERT_TRUE(m.orthotropic);
  EXPECT_DOUBLE_EQ(m.orthotropic->E_warp, 5000.0);
  EXPECT_DOUBLE_EQ(m.orthotropic->B_warp, 1e-5);
  EXPECT_DOUBLE_EQ(m.orthotropic->nu_warp_weft, 0.3);
}

TEST(XvcMaterial, PerVolumeValuesAreConvertedThroughTheThickness) {
  // A 3-D modulus of 10 MPa and 300 kg/m³ at 0.5 mm: 5000 N/m and 0.15 kg/m². The
  // thickness may come after the values it converts.
  const auto m = from(param(1, "E_warp", "1e7", "Pa") + param(2, "density", "300", "kg/m3") +
                      param(3, "thickness", "0.0005", "m"));
  EXPECT_DOUBLE_EQ(m.orthotropic->E_warp, 5000.0);
  EXPECT_DOUBLE_EQ(m.density, 0.15);
  EXPECT_DOUBLE_EQ(orthotropic_of(m).thickness, 0.0005);
  EXPECT_DOUBLE_EQ(orthotropic_of(m).density, 0.15);
}

TEST(XvcMaterial, AnUnknownParameterNamesFileModuleAndParameter) {
  try {
    from(param(1, "density", "0.1", "kg/m2") + param(2, "stiffness", "3", "N/m"));
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.diagnostic().file, "cloth.xvc");
    EXPECT_EQ(e.diagnostic().entity, "MATERIAL m1, PARAMETER stiffness");
    EXPECT_EQ(e.diagnostic().line, 6);
    EXPECT_NE(e.diagnostic().message.find("unknown material parameter 'stiffness'"), std::string::npos) << e.what();
  }
}

TEST(XvcMaterial, AUnitOfTheWrongKindIsRefused) {
  scene::test::expect_error([] { from(param(1, "spring.warp", "1800", "N")); }, "cloth.xvc",
                            "MATERIAL m1, PARAMETER spring.warp", "the unit is N, but spring.warp needs N/m");
  scene::test::expect_error([] { from(param(1, "density", "0.1", "kg")); }, "cloth.xvc",
                            "MATERIAL m1, PARAMETER density", "needs kg/m2");
  scene::test::expect_error([] { from(param(1, "E_warp", "1e7", "Pa")); }, "cloth.xvc",
                            "MATERIAL m1, PARAMETER E_warp", "no thickness");
}

TEST(XvcMaterial, AnInvalidValueIsRefused) {
  scene::test::expect_error([] { from(param(1, "density", "-0.1", "kg/m2")); }, "cloth.xvc",
                            "MATERIAL m1, PARAMETER density", "must be > 0");
  scene::test::expect_error([] { from(param(1, "spring.shear", "-5", "N/m")); }, "cloth.xvc",
                            "MATERIAL m1, PARAMETER spring.shear", "must be >= 0");
}

TEST(XvcMaterial, AMissingModuleIsNamed) {
  const auto doc = xvc::load_string(document(param(1, "density", "0.1", "kg/m2")), "cloth.xvc");
  scene::test::expect_error([&] { material_from_xvc(doc, "silk", "cloth.xvc"); }, "cloth.xvc", "silk",
                            "no MATERIAL with this id in the document (materials: m1)");
  scene::test::expect_error([&] { material_from_xvc(doc, "p1", "cloth.xvc"); }, "cloth.xvc", "p1",
                            "is a PARAMETER, not a MATERIAL");
}

TEST(XvcMaterial, ASceneReadsItsMaterialFromAnXvcFileBesideIt) {
  const auto dir = vgd::test::scratch_dir("scene_xvc_material");
  write_file_atomic(dir / "fabrics" / "cloth.xvc",
                    document(param(1, "particle_mass", "0.02", "kg") + param(2, "spring.warp", "150", "N/m")));
  auto j = scene::test::tiny_scene();
  j["materials"]["cloth"] = {{"xvc", "fabrics/cloth.xvc"}, {"id", "m1"}};
  write_file_atomic(dir / "scene.json", j.dump(2));
  const Scene s = build(load_scene(dir / "scene.json"));
  EXPECT_DOUBLE_EQ(s.system->model().mass[0], 0.02);
  EXPECT_DOUBLE_EQ(s.pieces[0].material.mass_spring->warp, 150.0);

  // The errors of an XVC material name the XVC file; a missing file, the scene's field.
  j["materials"]["cloth"] = {{"xvc", "fabrics/cloth.xvc"}, {"id", "m2"}};
  write_file_atomic(dir / "scene.json", j.dump(2));
  scene::test::expect_error([&] { build(load_scene(dir / "scene.json")); }, (dir / "fabrics/cloth.xvc").string(), "m2",
                            "no MATERIAL with this id");
  j["materials"]["cloth"] = {{"xvc", "fabrics/none.xvc"}, {"id", "m1"}};
  write_file_atomic(dir / "scene.json", j.dump(2));
  scene::test::expect_error([&] { build(load_scene(dir / "scene.json")); }, (dir / "scene.json").string(),
                            "materials.cloth.xvc", "no such file");
}

TEST(XvcMaterial, ShippedMaterialsServeBothModels) {
  for (const char* name : {"seed-flag", "shirting"}) {
    const auto m = load_xvc_material(vgd::test::source_dir() / "data" / "materials" / (std::string(name) + ".xvc"), name);
    EXPECT_EQ(mass_spring_problem(m), "") << name;
    EXPECT_EQ(orthotropic_problem(m), "") << name;
  }
}

// Two plies of a fabric (a rib cut double and folded): twice the mass and
// every stiffness, one ply's twist rigidity twice (not the derived value of
// a ply twice as thick), the ratios and the limit as they are.
TEST(LayeredMaterial, TwoPliesHaveTwiceTheMassAndStiffness) {
  const auto doc = vgd::xvc::load_file(vgd::test::source_dir() / "data/materials/cotton-rib.xvc");
  const MaterialDef one = material_from_xvc(doc, "cotton-rib", "cotton-rib.xvc");
  ASSERT_TRUE(one.mass_spring && one.orthotropic);
  const MaterialDef two = layered(one, 2);
  EXPECT_DOUBLE_EQ(two.density, 2 * one.density);
  EXPECT_DOUBLE_EQ(two.thickness, 2 * one.thickness);
  EXPECT_DOUBLE_EQ(two.mass_spring->warp, 2 * one.mass_spring->warp);
  EXPECT_DOUBLE_EQ(two.mass_spring->weft, 2 * one.mass_spring->weft);
  EXPECT_DOUBLE_EQ(two.mass_spring->shear, 2 * one.mass_spring->shear);
  EXPECT_DOUBLE_EQ(two.mass_spring->bend_warp, 2 * one.mass_spring->bend_warp);
  EXPECT_DOUBLE_EQ(two.mass_spring->damping, 2 * one.mass_spring->damping);
  EXPECT_DOUBLE_EQ(two.orthotropic->E_warp, 2 * one.orthotropic->E_warp);
  EXPECT_DOUBLE_EQ(two.orthotropic->E_weft, 2 * one.orthotropic->E_weft);
  EXPECT_DOUBLE_EQ(two.orthotropic->G, 2 * one.orthotropic->G);
  EXPECT_DOUBLE_EQ(two.orthotropic->B_weft, 2 * one.orthotropic->B_weft);
  EXPECT_DOUBLE_EQ(two.orthotropic->nu_warp_weft, one.orthotropic->nu_warp_weft);
  EXPECT_DOUBLE_EQ(vgd::sim::twist_rigidity(orthotropic_of(two)), 2 * vgd::sim::twist_rigidity(orthotropic_of(one)));
  EXPECT_EQ(orthotropic_problem(two), "");
  EXPECT_NE(two.name.find("2 layers"), std::string::npos);
}
