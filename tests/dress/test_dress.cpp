// dress::build: a scene's garments dressed on its body, then the scene built.
#include <gtest/gtest.h>

#include "support/test_paths.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/dress/drape.hpp"
#include "vgd/dress/dress.hpp"
#include "vgd/scene/build.hpp"

namespace vgd::dress {
namespace {

// Garments in layers read their order from the body's distance grid at rest:
// a moving body (effects.collision.body_velocity) is refused, naming the
// field; the same scene with the body at rest builds.
TEST(DressBuild, LayeredGarmentsOnAMovingBodyAreRefused) {
  DrapeOptions d;
  d.garment = vgd::test::source_dir() / "data/garments/a-line-skirt.xvc";
  d.over = {vgd::test::source_dir() / "data/garments/t-shirt.xvc"};
  d.spacing = 0.03;  // coarse: only the build is tested
  scene::SceneDef def = drape_scene(d);
  ASSERT_TRUE(def.effects.collision);
  EXPECT_NO_THROW(dress::build(def));
  def.effects.collision->velocity = sim::Vec3(0, 0.1, 0);
  try {
    dress::build(def);
    ADD_FAILURE() << "a layered scene on a moving body was built";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("body_velocity"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("at rest"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vgd::dress
