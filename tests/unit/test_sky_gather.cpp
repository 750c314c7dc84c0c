// A sky taken by the vertex gather (VertexGather's skiesOf) instead of per pixel: through an
// opening its light is the opening's form factor times pi L, and under the open sky a floor
// renders at rho L exactly, neither lost nor counted twice beside the pixels' own direct light.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "luxel/render.h"
#include "luxel/solve.h"
#include "render/direct_light.h"
#include "render/final_gather.h"
#include "scene/builtin/builtin_scenes.h"
#include "trace/element_polygons.h"
#include "trace/thin_glass.h"
#include "transport/form_factor.h"
#include "transport/light_sampling.h"

namespace luxel {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

Light uniformSky(float luminance) {
  Light sky;
  sky.type = Light::Type::Sky;
  sky.name = "sky";
  sky.intensity = luminance;
  return sky;
}

// A closed 2 x 1 x 2 box (black inside: no bounce reaches the gather) with a 0.5 m square hole in
// the middle of its ceiling, under a uniform sky. From the middle of the floor the sky is the hole;
// glazed (thin glass, trace/thin_glass.h), the hole passes the sky filtered by the glass.
void expectSkyThroughTheHole(const Rgb* glass) {
  Scene scene;
  scene.name = "skylight";
  scene.materials = {Material{.name = "black", .reflectance = Rgb(0.0f)}};
  Mesh box{.name = "box", .material = 0};
  builtin::addQuad(box, {-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1});  // floor, +y
  // The ceiling round the hole (|x|, |z| < 0.25), facing down.
  builtin::addQuad(box, {-1, 1, -1}, {1, 1, -1}, {1, 1, -0.25f}, {-1, 1, -0.25f});
  builtin::addQuad(box, {-1, 1, 0.25f}, {1, 1, 0.25f}, {1, 1, 1}, {-1, 1, 1});
  builtin::addQuad(box, {-1, 1, -0.25f}, {-0.25f, 1, -0.25f}, {-0.25f, 1, 0.25f}, {-1, 1, 0.25f});
  builtin::addQuad(box, {0.25f, 1, -0.25f}, {1, 1, -0.25f}, {1, 1, 0.25f}, {0.25f, 1, 0.25f});
  // The walls, facing in.
  builtin::addQuad(box, {-1, 0, -1}, {1, 0, -1}, {1, 1, -1}, {-1, 1, -1});
  builtin::addQuad(box, {-1, 0, 1}, {-1, 1, 1}, {1, 1, 1}, {1, 0, 1});
  builtin::addQuad(box, {-1, 0, -1}, {-1, 1, -1}, {-1, 1, 1}, {-1, 0, 1});
  builtin::addQuad(box, {1, 0, -1}, {1, 0, 1}, {1, 1, 1}, {1, 1, -1});
  scene.meshes = {box};
  if (glass) {
    scene.materials.push_back(Material{.name = "glass", .reflectance = Rgb(0.0f), .transmittance = *glass});
    Mesh pane{.name = "pane", .material = 1};
    builtin::addQuad(pane, {-0.25f, 1, -0.25f}, {0.25f, 1, -0.25f}, {0.25f, 1, 0.25f}, {-0.25f, 1, 0.25f});
    scene.meshes.push_back(pane);
  }
  scene.lights = {uniformSky(1000.0f)};
  const SurfaceSet surfaces = discretise(scene, DiscretiseOptions{.elementBudget = 64});
  const std::vector<Polygon> polygons = elementPolygonsTwinsApart(surfaces);
  RayTracer tracer(polygons);
  tracer.setGlass(std::make_shared<ThinGlass>(ThinGlass::overElements(scene, surfaces)));
  const DirectLight direct(scene, surfaces, &surfaces);
  const std::vector<Rgb> corners(surfaces.elements.size() * 4, Rgb(0.0f));
  const FinalGather gather(surfaces, tracer, direct, corners, /*gatherNearHits=*/false);
  const VertexGather withSky(surfaces, gather, 256, 3, {}, nullptr, &scene);
  const VertexGather without(surfaces, gather, 256, 3);

  const Vec3 x(0.0f, 0.0f, 0.0f), n(0.0f, 1.0f, 0.0f), towards(0.01f, 0.0f, 0.01f);
  const Polygon hole{{Vec3(-0.25f, 1, -0.25f), Vec3(0.25f, 1, -0.25f), Vec3(0.25f, 1, 0.25f), Vec3(-0.25f, 1, 0.25f)}, 4};
  const float f = pointToPolygonFormFactor(x, n, hole, Sides::Front, Sides::Both);
  const float radiance = skyRadiance(scene.lights[0], n, scene.up).g;
  const int side = 64;  // 4,096 rays
  const Rgb got = withSky.gatherAt(x, n, towards, side, 1u << 20).irradiance;
  const Rgb passed = glass ? *glass : Rgb(1.0f);
  // Each ray escapes through the hole with probability f (the rays are cosine-distributed):
  // binomial noise, less for the strata.
  const float sigma = kPi * radiance * std::sqrt(f * (1.0f - f) / float(side * side));
  ASSERT_GT(f, 0.05f);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(got[c], kPi * radiance * f * passed[c], 4.0f * sigma * passed[c]) << "form factor " << f << " channel " << c;
  EXPECT_EQ(without.gatherAt(x, n, towards, side, 1u << 20).irradiance.g, 0.0f);
}

TEST(SkyGather, ThroughAnOpeningTheSkyIsTheOpeningsFormFactor) { expectSkyThroughTheHole(nullptr); }

TEST(SkyGather, ThroughGlassTheSkyIsFilteredByIt) {
  const Rgb glass(0.5f, 0.25f, 1.0f);
  expectSkyThroughTheHole(&glass);
}

// A floor (reflectance 0.5) under a uniform sky of luminance L and nothing else: each point's
// irradiance is pi L, so every pixel that sees the floor is 0.5 L, whether the sky is traced per
// pixel (a per-pixel gather) or gathered at the vertices (the default); the sky behind is L.
TEST(SkyGather, AnOpenFloorRendersAtItsClosedForm) {
  Scene scene;
  scene.name = "open floor";
  scene.materials = {Material{.name = "floor", .reflectance = Rgb(0.5f)}};
  Mesh floor{.name = "floor", .material = 0};
  builtin::addQuad(floor, {-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5});
  scene.meshes = {floor};
  scene.lights = {uniformSky(1000.0f)};
  scene.cameras = {Camera{.name = "down", .eye = {0, 3, 3}, .target = {0, 0, 0}}};
  SurfaceSet surfaces = discretise(scene, DiscretiseOptions{.elementBudget = 50});
  const Solution solution = solve(scene, surfaces, SolveOptions{});
  for (RenderOptions::Indirect indirect : {RenderOptions::Indirect::VertexGather, RenderOptions::Indirect::PixelGather}) {
    RenderOptions ro;
    ro.camera = scene.cameras[0];
    ro.width = ro.height = 24;
    ro.samplesPerPixel = 4;
    ro.indirect = indirect;
    const Image image = render(scene, surfaces, solution, ro);
    size_t floorPixels = 0;
    for (size_t i = 0; i < image.pixels.size(); ++i) {
      if (image.coverage[i] < 1.0f) continue;
      ++floorPixels;
      ASSERT_NEAR(image.pixels[i].g, 500.0f, 0.5f) << "indirect mode " << int(indirect) << ", pixel " << i;
    }
    EXPECT_GT(floorPixels, 200u);
  }
}

}  // namespace
}  // namespace luxel
