// How an hq render spends its samples per pixel: a pixel whose corners all see one untextured face
// takes spp / 4 camera samples with 4 light points each; every other pixel (an edge, a texture, a
// scene with hard-shadowed lights) spp camera samples with one light point each.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "luxel/render.h"
#include "luxel/solve.h"
#include "scene/builtin/builtin_scenes.h"

namespace luxel {
namespace {

struct Solved {
  Scene scene;
  SurfaceSet surfaces;
  Solution solution;
};

Solved solvedCornellBox() {
  Solved s{builtin::cornellBox(), {}, {}};
  DiscretiseOptions d;
  d.elementBudget = 600;
  s.surfaces = discretise(s.scene, d);
  SolveOptions o;
  o.method = "progressive";
  s.solution = solve(s.scene, s.surfaces, o);
  return s;
}

// The box from twice as far back, so its outline shows against the background.
RenderOptions outsideView(const Scene& scene, int spp) {
  RenderOptions ro;
  ro.camera = scene.cameras[0];
  ro.camera.eye.z *= 3.0f;
  ro.width = ro.height = 48;
  ro.samplesPerPixel = spp;
  ro.indirect = RenderOptions::Indirect::Interpolated;
  return ro;
}

// A pixel's coverage is the share of its camera samples that hit a surface: on the outline it
// takes sixteenths (every camera sample taken), inside the box whole ones.
TEST(RenderSamples, EdgePixelsTakeEveryCameraSample) {
  const Solved s = solvedCornellBox();
  const Image image = render(s.scene, s.surfaces, s.solution, outsideView(s.scene, 16));
  std::set<int> sixteenths;
  int covered = 0;
  for (float c : image.coverage) {
    const int k = int(std::lround(c * 16.0f));
    ASSERT_NEAR(c * 16.0f, float(k), 1e-4f);
    if (k > 0 && k < 16) sixteenths.insert(k);
    covered += k == 16;
  }
  EXPECT_GT(covered, 150);
  // Partly covered pixels take counts that are not multiples of 4: each of their samples counted.
  int odd = 0;
  for (int k : sixteenths) odd += k % 4 != 0;
  EXPECT_GE(odd, 4) << "edge pixels should have all 16 camera samples";
}

// Fewer camera samples inside faces change nothing but noise: the same view at 16 samples (split
// 4 x 4 inside faces) and at 15 (never split, 15 is not a multiple of 4) agree on the mean of the
// covered pixels away from the lamp to within their noise (measured: 0.03% apart).
TEST(RenderSamples, SplitSamplesAgreeWithUnsplitOnes) {
  const Solved s = solvedCornellBox();
  RenderOptions ro = outsideView(s.scene, 16);
  ro.camera = s.scene.cameras[0];
  const Image split = render(s.scene, s.surfaces, s.solution, ro);
  ro.samplesPerPixel = 15;
  const Image whole = render(s.scene, s.surfaces, s.solution, ro);
  double a = 0.0, b = 0.0;
  for (size_t i = 0; i < split.pixels.size(); ++i) {
    // The lamp's pixels, a hundred times brighter than the rest: its outline's share is noise here.
    if (std::max(split.pixels[i].g, whole.pixels[i].g) > 0.5f) continue;
    a += split.pixels[i].g, b += whole.pixels[i].g;
  }
  EXPECT_NEAR(a / b, 1.0, 0.005);
}

}  // namespace
}  // namespace luxel
