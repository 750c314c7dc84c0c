// How the CPU transport samples analytic lights per element (transport/cpu_transport.h): a sun's
// shadow edge across an element is sampled 16 times as densely, and a sky seen through an opening
// takes 4 times the samples everywhere. Checked against closed forms: the lit share of an element
// cut by a straight shadow edge, and the form factor of an element to a skylight.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "scene/builtin/builtin_scenes.h"
#include "transport/cpu_transport.h"
#include "transport/form_factor.h"

namespace luxel {
namespace {

TEST(LightRefinement, ASunsShadowEdgeAcrossElementsIsSampledFinely) {
  // A 4 x 4 m floor in 0.5 m elements under a sun straight down (a point-like disc), and a roof
  // over x < 0.1 at 1 m: the shadow's edge cuts the elements of the column x in [0, 0.5] at a
  // fifth of their width, so each is lit over 0.8 of its area.
  Scene s;
  s.name = "shadow edge";
  s.materials = {Material{.name = "grey", .reflectance = Rgb(0.5f)}};
  Mesh floor{.name = "floor", .material = 0};
  builtin::addQuad(floor, {-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2});  // normal +y
  Mesh roof{.name = "roof", .material = 0};
  builtin::addQuad(roof, {-3, 1, -3}, {-3, 1, 3}, {0.1f, 1, 3}, {0.1f, 1, -3});
  s.meshes = {floor, roof};
  s.lights.push_back(Light{.type = Light::Type::Directional, .name = "sun", .intensity = 1000.0f,
                           .direction = Vec3(0, -1, 0)});
  const SurfaceSet set = discretise(s, DiscretiseOptions{.elementSize = 0.5f, .orientByLight = false});
  CpuTransport transport(s, set, FormFactorOptions{});  // 16 samples an element
  std::vector<Rgb> e(set.elements.size());
  transport.analyticIrradiance(e);
  double squares = 0.0;
  int edge = 0;
  for (size_t i = 0; i < set.elements.size(); ++i) {
    const Element& el = set.elements[i];
    if (el.normal.y < 0.5f || el.centroid.y > 0.5f) continue;  // the floor's elements only
    const float x = el.centroid.x;
    if (x < 0.0f) {
      EXPECT_EQ(e[i].g, 0.0f) << "in the roof's shadow";
    } else if (x > 0.5f) {
      EXPECT_NEAR(e[i].g, 1000.0f, 1e-2f) << "in the sun";
    } else {
      const double relative = e[i].g / 800.0 - 1.0;
      squares += relative * relative;
      ++edge;
    }
  }
  ASSERT_EQ(edge, 8);
  // On the first pass's 4 x 4 grid, the edge lies in the first column of strata, four samples
  // each lit with probability 0.2: a standard deviation of sqrt(4 * 0.16) / 16 = 0.05 of the
  // whole, 6% of 0.8. On 16 x 16 it lies in one column of sixteen: sqrt(16 * 0.16) / 256, 0.8%.
  // 2.5% is three times that, and half the first pass's.
  EXPECT_LT(std::sqrt(squares / edge), 0.025);
}

TEST(LightRefinement, ASkyThroughAnOpeningTakesFourTimesTheSamples) {
  // A closed 2 x 2 x 2 m room whose ceiling has a 0.5 x 0.5 m opening, under a uniform sky of
  // radiance 1000: a floor element receives pi 1000 F, F its form factor to the opening.
  Scene s;
  s.name = "skylight";
  s.materials = {Material{.name = "grey", .reflectance = Rgb(0.5f)}};
  Mesh room{.name = "room", .material = 0};
  builtin::addQuad(room, {0, 0, 0}, {0, 0, 2}, {2, 0, 2}, {2, 0, 0});  // floor, +y
  builtin::addQuad(room, {0, 0, 0}, {0, 2, 0}, {0, 2, 2}, {0, 0, 2});  // x = 0, +x
  builtin::addQuad(room, {2, 0, 0}, {2, 0, 2}, {2, 2, 2}, {2, 2, 0});  // x = 2, -x
  builtin::addQuad(room, {0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0});  // z = 0, +z
  builtin::addQuad(room, {0, 0, 2}, {0, 2, 2}, {2, 2, 2}, {2, 0, 2});  // z = 2, -z
  // The ceiling (facing down) in four pieces around the opening [0.75, 1.25]^2.
  auto ceiling = [&](float x0, float z0, float x1, float z1) {
    builtin::addQuad(room, {x0, 2, z0}, {x1, 2, z0}, {x1, 2, z1}, {x0, 2, z1});
  };
  ceiling(0, 0, 2, 0.75f), ceiling(0, 1.25f, 2, 2), ceiling(0, 0.75f, 0.75f, 1.25f), ceiling(1.25f, 0.75f, 2, 1.25f);
  s.meshes = {room};
  s.lights.push_back(Light{.type = Light::Type::Sky, .name = "sky", .intensity = 1000.0f});
  const SurfaceSet set = discretise(s, DiscretiseOptions{.elementSize = 0.4f, .orientByLight = false});
  CpuTransport transport(s, set, FormFactorOptions{});
  std::vector<Rgb> e(set.elements.size());
  transport.analyticIrradiance(e);
  Polygon opening;
  opening.count = 4;
  opening.v = {Vec3(0.75f, 2, 0.75f), Vec3(1.25f, 2, 0.75f), Vec3(1.25f, 2, 1.25f), Vec3(0.75f, 2, 1.25f)};  // facing down
  double squares = 0.0, bound16 = 0.0, bound64 = 0.0, ratio = 0.0;
  int n = 0;
  for (size_t i = 0; i < set.elements.size(); ++i) {
    const Element& el = set.elements[i];
    if (el.normal.y < 0.5f) continue;  // the floor's
    const double f = polygonToPolygonFormFactor(el.polygon, opening, 16);
    ASSERT_GT(f, 0.005);
    const double expected = std::numbers::pi * 1000.0 * f;
    const double relative = e[i].g / expected - 1.0;
    squares += relative * relative, ratio += e[i].g / expected;
    // A sample reaches the sky with probability F: the binomial's relative variance (1 - F) / (N F).
    bound16 += (1.0 - f) / (16.0 * f), bound64 += (1.0 - f) / (64.0 * f);
    ++n;
  }
  ASSERT_EQ(n, 25);
  const double rms = std::sqrt(squares / n);
  // Stratified samples are never worse than independent ones; 1.3 allows for the RMS of 25
  // elements' errors, itself uncertain by about 1 / sqrt(50).
  EXPECT_LT(rms, 1.3 * std::sqrt(bound64 / n));
  EXPECT_LT(rms, std::sqrt(bound16 / n)) << "no better than 16 samples";
  EXPECT_NEAR(ratio / n, 1.0, 3.0 * rms / std::sqrt(n));  // no bias
}

}  // namespace
}  // namespace luxel
