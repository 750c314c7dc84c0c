// The CPU backend's form factor under partial occlusion against a closed form
// (half_shadow_scene.h): visibility rays weighted by their point-to-point kernel reproduce it; the
// unweighted share of rays that arrive (Wallace et al. 1989's estimator, which luxel used before)
// would not.
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>

#include "analytic/half_shadow_scene.h"
#include "luxel/solve.h"

namespace luxel {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(VisibilityWeighting, TheClosedFormShowsTheUnweightedShareIsBiased) {
  const double seen = test::halfShadowFactor(true), all = test::halfShadowFactor(false);
  const double nearArea = (1.0 - test::kHalfShadowEmitterX0) / (test::kHalfShadowEmitterX1 - test::kHalfShadowEmitterX0);
  std::printf("factor %.5f of %.5f unoccluded (%.1f%%); visible area %.1f%%\n", seen, all, 100 * seen / all, 100 * nearArea);
  EXPECT_NEAR(seen / all, 0.87, 0.01);
  EXPECT_NEAR(nearArea, 0.43, 0.01);
}

class CpuVisibility : public ::testing::TestWithParam<std::string> {};

TEST_P(CpuVisibility, PartlyOccludedFactorMatchesTheClosedForm) {
  const Scene scene = test::halfShadowScene();
  SurfaceSet surfaces = test::halfShadowSurfaces(scene);
  ASSERT_EQ(surfaces.elements.size(), 3u);
  const size_t receiver = test::halfShadowReceiver(surfaces);
  ASSERT_LT(receiver, surfaces.elements.size());

  SolveOptions o;
  o.method = GetParam();
  o.settings.set("emitter-rays-per-pair", 256);
  const Solution s = solve(scene, surfaces, o);
  const double factor = s.directIrradiance[receiver].g / kPi;  // exitance pi Le, Le = 1
  const double expected = test::halfShadowFactor(true);
  // What Wallace's share tends to: the unoccluded factor times the visible share of the area.
  const double nearArea = (1.0 - test::kHalfShadowEmitterX0) / (test::kHalfShadowEmitterX1 - test::kHalfShadowEmitterX0);
  const double unweighted = test::halfShadowFactor(false) * nearArea;
  std::printf("factor %.5f, closed form %.5f (unweighted share: %.5f)\n", factor, expected, unweighted);
  EXPECT_NEAR(factor, expected, 0.03 * expected);
  ASSERT_GT(std::abs(unweighted - expected), 10 * 0.03 * expected);  // the test tells the two apart
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, CpuVisibility,
                         ::testing::Values("progressive", "gather"),
                         [](const auto& info) {
                           return info.param == "progressive" ? "Progressive" : "Gather";
                         });

}  // namespace
}  // namespace luxel
