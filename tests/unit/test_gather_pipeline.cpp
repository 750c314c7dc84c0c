// What an hq render's gather reads and shows (render/gather_pipeline.h), against the furnace's
// closed form: every surface emits Le = 1 and reflects rho = 0.5, so the irradiance is
// pi Le / (1 - rho) everywhere, pi of it direct and pi Le rho / (1 - rho) = pi indirect.
#include <gtest/gtest.h>

#include <numbers>
#include <vector>

#include "luxel/error.h"
#include "luxel/render.h"
#include "luxel/solve.h"
#include "render/gather_pipeline.h"
#include "scene/builtin/builtin_scenes.h"

namespace luxel {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// The furnace's surfaces cut into about `elements` elements.
SurfaceSet furnaceSurfaces(const Scene& furnace, size_t elements) {
  DiscretiseOptions d;
  d.elementBudget = elements;
  d.orientByLight = false;
  return discretise(furnace, d);
}

TEST(GatherPipeline, TheGatheredIndirectLightOfAFurnaceIsItsClosedForm) {
  const Scene scene = builtin::furnace(0.5f, 1.0f);
  SurfaceSet surfaces = furnaceSurfaces(scene, 400);
  SolveOptions o;
  o.method = "progressive";
  o.settings.set("unshot", 1e-6);
  const Solution solution = solve(scene, surfaces, o);
  std::vector<uint32_t> probes;
  for (uint32_t e = 0; e < surfaces.elements.size(); e += 37) probes.push_back(e);
  for (int bounces : {1, 3}) {
    RenderOptions options;
    options.gatherBounces = bounces;
    const std::vector<Rgb> gathered = gatheredIndirect(scene, surfaces, solution, probes, options);
    ASSERT_EQ(gathered.size(), probes.size());
    // The solution's own error at the hits (times rho), as in FinalGather's furnace tests.
    for (size_t i = 0; i < probes.size(); ++i)
      EXPECT_NEAR(gathered[i].g, kPi, 3e-3f * kPi) << "element " << probes[i] << ", " << bounces << " bounces";
  }
}

// Every wall emits, and every element sees the others whole: the direct light is pi Le,
// the emitters' exact factors summing to 1, whatever the points.
TEST(GatherPipeline, ThePixelsDirectLightInAFurnaceIsItsClosedForm) {
  const Scene scene = builtin::furnace(0.5f, 1.0f);
  const SurfaceSet surfaces = furnaceSurfaces(scene, 400);
  std::vector<uint32_t> probes;
  for (uint32_t e = 0; e < surfaces.elements.size(); e += 29) probes.push_back(e);
  const std::vector<Rgb> direct = pixelDirectLight(scene, surfaces, probes, 64, 1);
  ASSERT_EQ(direct.size(), probes.size());
  for (size_t i = 0; i < probes.size(); ++i) EXPECT_NEAR(direct[i].g, kPi, 1e-3f * kPi) << "element " << probes[i];
}

TEST(GatherPipeline, AnElementPastTheSolutionIsRefused) {
  const Scene scene = builtin::furnace(0.5f, 1.0f);
  SurfaceSet surfaces = furnaceSurfaces(scene, 24);
  const Solution solution = solve(scene, surfaces, SolveOptions{});
  const std::vector<uint32_t> probes{uint32_t(surfaces.elements.size())};
  EXPECT_THROW(gatheredIndirect(scene, surfaces, solution, probes, RenderOptions{}), Error);
  EXPECT_THROW(pixelDirectLight(scene, surfaces, probes, 16, 1), Error);
}

}  // namespace
}  // namespace luxel
