// GPU-resident progressive refinement (gl/progressive_gl.h) against the CPU backend and closed
// forms, on llvmpipe: ID hemicubes (seed 001) and depth hemicubes (seed 003). Skips, saying why,
// when no OpenGL 4.5 context can be made.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "gl/gl_parity.h"
#include "gl/gl_test_context.h"
#include "luxel/bench.h"
#include "luxel/error.h"
#include "luxel/solve.h"
#include "scene/builtin/builtin_scenes.h"

namespace {

using luxel::SolveOptions;

SolveOptions glProgressive(const std::string& visibility) {
  SolveOptions o;
  o.method = "progressive";
  o.backend = "gl";
  o.settings.set("hemicube-visibility", visibility);
  o.settings.set("unshot", 1e-4);
  return o;
}

class GlProgressive : public ::testing::TestWithParam<std::string> {};

TEST_P(GlProgressive, FurnaceReachesTheClosedForm) {
  std::string why;
  auto context = luxel::test::glContextOr(why);
  if (!context) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  context.reset();  // solve() makes its own
  const float rho = 0.5f, le = 1.0f;
  luxel::Scene scene = luxel::builtin::furnace(rho, le);
  luxel::DiscretiseOptions d;
  d.elementBudget = 600;
  luxel::SurfaceSet surfaces = luxel::discretise(scene, d);
  SolveOptions o = glProgressive(GetParam());
  o.settings.set("ambient", false);  // the closed form from shooting alone
  o.settings.set("unshot", 1e-5);
  luxel::Solution s = luxel::solve(scene, surfaces, o);
  EXPECT_EQ(s.stats.backend, "gl");
  // 3 x 3 per shooting patch, 6 x 6 for each emitting patch's first shot: here every patch emits.
  EXPECT_EQ(s.stats.hemicubes, 9 * s.stats.shots + 27 * surfaces.patches.size());
  // B = pi Le / (1 - rho) everywhere.
  const float expected = 3.14159265f * le / (1.0f - rho);
  for (size_t e = 0; e < surfaces.elements.size(); ++e)
    ASSERT_NEAR(s.radiosity[e].g, expected, 0.005f * expected) << "element " << e;
  EXPECT_LE(s.stats.unshotFraction, 1e-5);
}

TEST_P(GlProgressive, CornellBoxAgreesWithTheCpuBackend) {
  std::string why;
  auto context = luxel::test::glContextOr(why);
  if (!context) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  context.reset();
  const luxel::test::CornellReference& ref = luxel::test::cornellReference(1500);
  const luxel::Solution& cpu = ref.cpu;
  luxel::SurfaceSet surfaces = ref.surfaces;
  const auto t0 = std::chrono::steady_clock::now();
  SolveOptions o = glProgressive(GetParam());
  o.settings.set("ambient", false);  // so that where no light arrives the answer is exactly dark
  luxel::Solution gpu = luxel::solve(ref.scene, surfaces, o);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double rms = luxel::bench::normalisedRmsError(surfaces, gpu.radiosity, cpu.radiosity);
  const double directRms = luxel::bench::normalisedRmsError(surfaces, gpu.directIrradiance, cpu.directIrradiance);
  RecordProperty("nrmse", std::to_string(rms));
  std::printf("GL progressive (%s) vs CPU: NRMSE %.4f (direct %.4f), %llu shots, %llu hemicubes, %.2f s\n",
              GetParam() == "item" ? "item" : "distance", rms, directRms,
              (unsigned long long)gpu.stats.shots, (unsigned long long)gpu.stats.hemicubes, seconds);
  // Measured on llvmpipe (64 pixels, 3 x 3 hemicubes per patch, 6 x 6 for the light's first
  // shot): item 0.0104 (direct 0.0116), depth 0.0090 (0.0102). Issue 4 aims for 2%.
  EXPECT_LT(rms, 0.02) << "GL vs CPU element radiosities";
  EXPECT_GT(rms, 0.0);
  EXPECT_LT(directRms, 0.025);
  EXPECT_LE(gpu.stats.unshotFraction, 1e-4);

  // Light leaking at contacts: the floor under the blocks, which no light reaches on the CPU
  // (11 elements), stays dark. Measured: ids 1.2e-4 of the mean floor irradiance at most, depth
  // 0.7% (its allowance reaches through the blocks' walls at their base).
  double floorMean = 0.0, floorCount = 0.0, darkMax = 0.0;
  size_t dark = 0;
  for (size_t e = 0; e < surfaces.elements.size(); ++e) {
    if (surfaces.elements[e].face != surfaces.elements[0].face) continue;  // the floor
    floorMean += cpu.irradiance[e].g, floorCount += 1.0;
    if (cpu.irradiance[e].g == 0.0f) ++dark, darkMax = std::max(darkMax, double(gpu.irradiance[e].g));
  }
  floorMean /= floorCount;
  std::printf("under the blocks: %zu dark elements, GL irradiance at most %.2g of the floor's mean\n", dark,
              darkMax / floorMean);
  EXPECT_GE(dark, 5u);
  EXPECT_LT(darkMax, (GetParam() == "item" ? 1e-3 : 2e-2) * floorMean);
}

// Seed 001's dynamic shooter subdivision: the light's first shot from 6 x 6 hemicubes instead of
// 3 x 3 resolves the penumbrae better (measured: direct NRMSE 0.0153 -> 0.0116, for 27 more
// hemicubes than 2,601).
TEST(GlEmitterSubdivision, SharpensTheDirectLight) {
  std::string why;
  auto context = luxel::test::glContextOr(why);
  if (!context) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  context.reset();
  const luxel::test::CornellReference& ref = luxel::test::cornellReference(1500);
  const luxel::Solution& cpu = ref.cpu;
  luxel::SurfaceSet surfaces = ref.surfaces;
  const luxel::Scene& scene = ref.scene;
  SolveOptions o = glProgressive("item");
  o.settings.set("emitter-hemicubes-per-side", 0);
  luxel::SurfaceSet plainSurfaces = surfaces;
  const luxel::Solution plain = luxel::solve(scene, plainSurfaces, o);
  o.settings.set("emitter-hemicubes-per-side", 6);
  const luxel::Solution subdivided = luxel::solve(scene, surfaces, o);
  const double before = luxel::bench::normalisedRmsError(surfaces, plain.directIrradiance, cpu.directIrradiance);
  const double after = luxel::bench::normalisedRmsError(surfaces, subdivided.directIrradiance, cpu.directIrradiance);
  std::printf("direct light vs CPU: %.4f with 3 x 3 hemicubes on the light, %.4f with 6 x 6 (%llu and %llu hemicubes)\n",
              before, after, (unsigned long long)plain.stats.hemicubes, (unsigned long long)subdivided.stats.hemicubes);
  EXPECT_LT(after, 0.85 * before);
  EXPECT_GT(subdivided.stats.hemicubes, plain.stats.hemicubes);
  EXPECT_LT(subdivided.stats.hemicubes, plain.stats.hemicubes + 100);  // only the light's first shot
}

// The two ways a hemicube's triangles reach their layers (a geometry shader, or the vertex shader
// with ARB_shader_viewport_layer_array; GPUs take the second) rasterise the same triangles into
// the same pixels: the same solve to the bit. Where the driver lacks the extension, asking for it
// is an error that names it.
TEST(GlHemicubeLayering, VertexShaderLayersDrawWhatTheGeometryShaderDraws) {
  std::string why;
  auto context = luxel::test::glContextOr(why);
  if (!context) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  context.reset();
  const luxel::Scene scene = luxel::builtin::cornellBox();
  luxel::DiscretiseOptions d;
  d.elementBudget = 600;
  const luxel::SurfaceSet surfaces = luxel::discretise(scene, d);
  auto solveWith = [&](const char* layering) {
    SolveOptions o = glProgressive("item");
    o.settings.set("hemicube-layering", layering).set("shooters-per-pass", 8);
    luxel::SurfaceSet s = surfaces;
    return luxel::solve(scene, s, o);
  };
  const luxel::Solution geometry = solveWith("geometry");
  luxel::Solution vertex;
  try {
    vertex = solveWith("vertex");
  } catch (const luxel::Error& e) {
    EXPECT_NE(std::string(e.what()).find("GL_ARB_shader_viewport_layer_array"), std::string::npos) << e.what();
    GTEST_SKIP() << "this OpenGL has no vertex-shader layers: " << e.what();
  }
  ASSERT_GT(geometry.stats.shots, 0u);
  EXPECT_EQ(vertex.stats.shots, geometry.stats.shots);
  size_t differ = 0;
  for (size_t e = 0; e < surfaces.elements.size(); ++e) differ += vertex.radiosity[e] != geometry.radiosity[e] ? 1 : 0;
  EXPECT_EQ(differ, 0u) << "of " << surfaces.elements.size() << " elements";
}

INSTANTIATE_TEST_SUITE_P(GlVisibility, GlProgressive,
                         ::testing::Values("item",
                                           "distance"),
                         [](const auto& info) { return luxel::test::visibilityName(info.param); });

}  // namespace
