// The GL backend's form factor under partial occlusion against a closed form
// (analytic/half_shadow_scene.h), where an unweighted share of visibility samples is 51% low:
// the gathering hemicube integrates the visible part pixel by pixel, and progressive shooting
// weights each shooting hemicube's verdict by its point-to-point kernel. Skips, saying why, when
// no OpenGL 4.5 context can be made.
#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>

#include "analytic/half_shadow_scene.h"
#include "gl/gl_parity.h"
#include "gl/gl_test_context.h"
#include "luxel/solve.h"

namespace {

using luxel::SolveOptions;

double receiverFactor(const SolveOptions& o) {
  const luxel::Scene scene = luxel::test::halfShadowScene();
  luxel::SurfaceSet surfaces = luxel::test::halfShadowSurfaces(scene);
  const size_t receiver = luxel::test::halfShadowReceiver(surfaces);
  if (receiver >= surfaces.elements.size()) return -1.0;
  const luxel::Solution s = luxel::solve(scene, surfaces, o);
  return s.directIrradiance[receiver].g / std::numbers::pi;  // exitance pi Le, Le = 1
}

TEST(GlHalfShadow, GatheringHemicubesMatchTheClosedForm) {
  std::string why;
  if (!luxel::test::glContextOr(why)) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  SolveOptions o;
  o.method = "gather";
  o.backend = "gl";
  o.settings.set("hemicube-resolution", 128).set("hemicubes-per-side", 2);
  const double factor = receiverFactor(o), expected = luxel::test::halfShadowFactor(true);
  std::printf("GL gather: factor %.5f, closed form %.5f\n", factor, expected);
  EXPECT_NEAR(factor, expected, 0.01 * expected);
}

class GlHalfShadowShooting : public ::testing::TestWithParam<std::string> {};

TEST_P(GlHalfShadowShooting, KernelWeightedVisibilityMatchesTheClosedForm) {
  std::string why;
  if (!luxel::test::glContextOr(why)) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  SolveOptions o;
  o.method = "progressive";
  o.backend = "gl";
  o.settings.set("hemicube-visibility", GetParam());
  // The shadow's edge crosses the 3.5 m emitter, so the answer is only as good as the midpoint
  // rule over the shooting hemicubes' centres: at 8 x 8 that rule gives 0.4331 (5.3% low; 3 x 3
  // gives 0.4310), and the GPU gives 0.4334. An unweighted share would give 0.198.
  o.settings.set("hemicube-resolution", 64).set("hemicubes-per-side", 8);
  o.settings.set("emitter-hemicubes-per-side", 8);  // the emitter's one shot is all there is
  const double factor = receiverFactor(o), expected = luxel::test::halfShadowFactor(true);
  std::printf("GL progressive (%s): factor %.5f, closed form %.5f\n", luxel::test::visibilityName(GetParam()).c_str(),
              factor, expected);
  EXPECT_NEAR(factor, expected, 0.06 * expected);
}

INSTANTIATE_TEST_SUITE_P(GlVisibility, GlHalfShadowShooting,
                         ::testing::Values("item",
                                           "distance"),
                         [](const auto& info) { return luxel::test::visibilityName(info.param); });

}  // namespace
