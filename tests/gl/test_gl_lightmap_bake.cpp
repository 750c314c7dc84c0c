// Lightmap-texel shooting on the GPU (seed 003): `bakeLightmaps` with the GL backend runs the
// GPU-resident progressive solver on the texels, with depth or ID hemicubes, and must agree with
// the CPU bake of the same atlas. Skips, saying why, without an OpenGL 4.5 context.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "gl/gl_parity.h"
#include "gl/gl_test_context.h"
#include "luxel/import.h"
#include "luxel/lightmap.h"
#include "luxel/solve.h"

namespace {

using luxel::SolveOptions;

// Relative RMS difference of two bakes over the texels both solved (luminance).
double pageNrmse(const luxel::LightmapBake& a, const luxel::LightmapBake& b) {
  double diff = 0.0, ref = 0.0;
  for (size_t p = 0; p < a.pages.size(); ++p)
    for (size_t i = 0; i < a.pages[p].size(); ++i) {
      if (a.state[p][i] != luxel::LightmapBake::Solved || b.state[p][i] != luxel::LightmapBake::Solved) continue;
      auto lum = [](luxel::Rgb c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
      const double x = lum(a.pages[p][i]), y = lum(b.pages[p][i]);
      diff += (x - y) * (x - y);
      ref += y * y;
    }
  return ref > 0.0 ? std::sqrt(diff / ref) : 1.0;
}

class GlTexelShooting : public ::testing::TestWithParam<std::string> {};

TEST_P(GlTexelShooting, CornellBakeAgreesWithTheCpuBake) {
  std::string why;
  if (!luxel::test::glContextOr(why)) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  const luxel::Scene scene = luxel::loadScene("cornell");
  luxel::AtlasOptions ao;
  ao.texelsPerMetre = 16.0f / 0.55f;  // 16 texels per wall side
  ao.pageSize = 256;
  const luxel::LightmapAtlas atlas = luxel::buildLightmapAtlas(scene, ao);
  luxel::LightmapBakeOptions cpu;
  cpu.solve.settings.set("unshot", 1e-4);
  luxel::LightmapBakeOptions gpu = cpu;
  gpu.solve.backend = "gl";
  gpu.solve.settings.set("hemicube-visibility", GetParam());
  const luxel::LightmapBake a = luxel::bakeLightmaps(scene, atlas, gpu);
  const luxel::LightmapBake b = luxel::bakeLightmaps(scene, atlas, cpu);
  EXPECT_EQ(a.solution.stats.backend, "gl");
  EXPECT_GT(a.solution.stats.hemicubes, 0u);
  EXPECT_EQ(a.texels, b.texels);
  const double rms = pageNrmse(a, b);
  std::printf("GL texel shooting (%s) vs CPU bake: %zu texels, NRMSE %.4f, %llu shots, %.2f s\n",
              GetParam() == "item" ? "item" : "distance", a.texels, rms,
              (unsigned long long)a.solution.stats.shots, a.solution.stats.secondsTotal);
  // Measured on llvmpipe (1,649 texels, 64 pixels, 3 x 3 per patch, 6 x 6 for the light's first
  // shot): item 0.0136, depth 0.0128.
  EXPECT_LT(rms, 0.025);
  EXPECT_GT(rms, 0.0);
}

INSTANTIATE_TEST_SUITE_P(GlVisibility, GlTexelShooting,
                         ::testing::Values("item",
                                           "distance"),
                         [](const auto& info) { return luxel::test::visibilityName(info.param); });

}  // namespace
