// Rendering from baked lightmaps (luxel::renderLightmapped, `luxel render --mode lightmap`): the
// built-in Cornell box (light radiance (17, 12, 4); reflectances as builtin cornell) baked at
// about 32 texels per wall side looks like the element solution rendered in radiosity mode.
#include <gtest/gtest.h>

#include "cli/cli_runner.h"
#include "luxel/error.h"
#include "luxel/lightmap.h"
#include "luxel/render.h"
#include "luxel/solve.h"
#include "scene/builtin/builtin_scenes.h"

namespace {

double meanLuminance(const luxel::Image& img, int x0, int y0, int x1, int y1) {
  double sum = 0.0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const luxel::Rgb c = img.at(x, y);
      sum += 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    }
  return sum / double((x1 - x0) * (y1 - y0));
}

TEST(LightmapRender, CornellLooksLikeTheElementSolution) {
  const luxel::Scene scene = luxel::builtin::cornellBox();
  luxel::AtlasOptions ao;
  ao.texelsPerMetre = 32.0f / 0.5592f;
  ao.pageSize = 512;
  const luxel::LightmapAtlas atlas = luxel::buildLightmapAtlas(scene, ao);
  const luxel::LightmapBake bake = luxel::bakeLightmaps(scene, atlas);

  luxel::RenderOptions ro;
  ro.camera = scene.cameras.front();
  ro.width = ro.height = 64;
  ro.samplesPerPixel = 4;
  ro.mode = luxel::RenderOptions::Mode::Radiosity;
  const luxel::Image lit = luxel::renderLightmapped(scene, atlas, bake, ro);

  luxel::DiscretiseOptions d;
  d.elementSize = 0.5592f / 32.0f;  // matched resolution
  luxel::SurfaceSet surfaces = luxel::discretise(scene, d);
  const luxel::Solution solution = luxel::solve(scene, surfaces, luxel::SolveOptions{});
  const luxel::Image ref = luxel::render(scene, surfaces, solution, ro);

  const double whole = meanLuminance(lit, 0, 0, 64, 64), wholeRef = meanLuminance(ref, 0, 0, 64, 64);
  EXPECT_NEAR(whole, wholeRef, 0.03 * wholeRef);
  // Regions: the back wall's middle band, and the floor in front of the blocks.
  for (auto [x0, y0, x1, y1] : {std::array{24, 14, 40, 22}, std::array{20, 56, 44, 62}}) {
    const double a = meanLuminance(lit, x0, y0, x1, y1), b = meanLuminance(ref, x0, y0, x1, y1);
    EXPECT_NEAR(a, b, 0.05 * b) << "region " << x0 << "," << y0;
  }
  // The light itself (image centre (32, 9)) shows its radiance (17, 12, 4), luminance 12.5, plus a
  // little reflected light.
  EXPECT_NEAR(meanLuminance(lit, 31, 8, 33, 10), 0.2126 * 17 + 0.7152 * 12 + 0.0722 * 4, 0.5);
  // Coverage for auto exposure: the light's pixel shows a surface with every sample.
  ASSERT_EQ(lit.coverage.size(), lit.pixels.size());
  EXPECT_EQ(lit.coverage[9 * 64 + 32], 1.0f);
}

TEST(LightmapRender, RejectsAForeignAtlas) {
  const luxel::Scene scene = luxel::builtin::cornellBox();
  luxel::LightmapAtlas atlas;
  luxel::LightmapBake bake;
  luxel::RenderOptions ro;
  ro.camera = scene.cameras.front();
  EXPECT_THROW(luxel::renderLightmapped(scene, atlas, bake, ro), luxel::Error);
}

TEST(LightmapRender, CliModeLightmapWritesTheImage) {
  const fs::path dir = scratchDir();
  CliRun r = luxel(dir, {"render", "cornell", "-o", "c.exr", "--mode", "lightmap", "--size", "32x32", "--elements", "3000"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("(lightmap)"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir / "c.exr"));
}

}  // namespace
