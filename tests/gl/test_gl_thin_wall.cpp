// Light must not pass a thin wall: two closed rooms 2 cm apart, a light in one. GPU shooting
// accepts a point whose pixel shows another face only when that face meets the point's own at a
// corner and lies within a pixel's depth of it (a convex edge); any face within a pixel's depth
// would let the first room's light through the 2 cm into the second, a few metres from the
// shooters at 64 pixels. Skips, saying why, when no OpenGL 4.5 context can be made.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "gl/gl_parity.h"
#include "gl/gl_test_context.h"
#include "luxel/solve.h"
#include "scene/builtin/builtin_scenes.h"

namespace {

using luxel::SolveOptions;
using luxel::Vec3;

constexpr float kWallNear = 1.99f, kWallFar = 2.01f;  // room A ends, room B begins (x)

luxel::Scene twoRooms() {
  luxel::Scene s;
  s.name = "two-rooms";
  s.materials.push_back(luxel::Material{.name = "paint", .reflectance = luxel::Rgb(0.7f)});
  s.materials.push_back(luxel::Material{.name = "light", .reflectance = luxel::Rgb(0.0f), .emission = luxel::Rgb(5.0f)});
  luxel::Mesh rooms{.name = "rooms"};
  luxel::builtin::addInwardBox(rooms, Vec3(0, 0, 0), Vec3(kWallNear, 2, 2));
  luxel::builtin::addInwardBox(rooms, Vec3(kWallFar, 0, 0), Vec3(4, 2, 2));
  luxel::Mesh light{.name = "light", .material = 1};
  // Just under room A's ceiling, facing down.
  luxel::builtin::addQuad(light, Vec3(0.7f, 1.98f, 0.7f), Vec3(1.3f, 1.98f, 0.7f), Vec3(1.3f, 1.98f, 1.3f),
                          Vec3(0.7f, 1.98f, 1.3f));
  s.meshes = {rooms, light};
  s.cameras.push_back(luxel::Camera{.name = "default", .eye = Vec3(0.1f, 1, 1), .target = Vec3(4, 1, 1), .up = Vec3(0, 1, 0), .fovY = 90.0f});
  return s;
}

class GlThinWall : public ::testing::TestWithParam<std::string> {};

TEST_P(GlThinWall, LightStaysInItsRoom) {
  std::string why;
  if (!luxel::test::glContextOr(why)) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  const luxel::Scene scene = twoRooms();
  luxel::DiscretiseOptions d;
  d.elementBudget = 3000;
  luxel::SurfaceSet surfaces = luxel::discretise(scene, d);
  SolveOptions o;
  o.backend = "gl";
  o.settings.set("hemicube-visibility", GetParam());
  o.settings.set("unshot", 1e-4);
  o.settings.set("ambient", false);  // the ambient term spreads unshot light everywhere by design
  const luxel::Solution s = luxel::solve(scene, surfaces, o);
  float lit = 0.0f, leaked = 0.0f;
  size_t leaking = 0, inB = 0;
  for (size_t e = 0; e < surfaces.elements.size(); ++e) {
    const float b = s.radiosity[e].g;
    if (surfaces.elements[e].centroid.x < 0.5f * (kWallNear + kWallFar)) {
      lit = std::max(lit, b);
    } else {
      ++inB;
      leaked = std::max(leaked, b);
      leaking += b > 0.0f ? 1 : 0;
    }
  }
  std::printf("%s hemicubes: brightest in the lit room %.3f, in the other %.3g (%zu of its %zu elements lit)\n",
              luxel::test::visibilityName(GetParam()).c_str(), lit, leaked, leaking, inB);
  ASSERT_GT(inB, 100u);
  EXPECT_GT(lit, 1.0f);
  if (GetParam() == "item") {
    EXPECT_EQ(leaked, 0.0f) << "light through a 2 cm wall";
  }
  // Depth hemicubes (seed 003) allow up to 7% of the distance for a surface's slope, and do let
  // light through walls this thin: the measurement is printed, not asserted (docs/algorithms.md).
}

INSTANTIATE_TEST_SUITE_P(GlVisibility, GlThinWall,
                         ::testing::Values("item",
                                           "distance"),
                         [](const auto& info) { return luxel::test::visibilityName(info.param); });

}  // namespace
