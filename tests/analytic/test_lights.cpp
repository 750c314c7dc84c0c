// Analytic lights (src/transport/light_sampling.cpp) against closed forms, both point-wise through
// sampleLight and averaged over elements through solve().
//
// Scene values used: a floor quad 100 m x 100 m (x, z in [-50, 50], y = 0, facing +y,
// reflectance 0, so nothing is inter-reflected and the irradiance is the light's alone), cut into
// 1 m x 1 m elements (elementSize 1, 10 elements per patch side), and one light each:
// - point: intensity I = 100 W/sr at height h = 10 m above (0.5, 0.5), the centre of element
//   [0,1] x [0,1];
// - spot: the same, pointing straight down, inner cone 20 deg, outer cone 30 deg;
// - directional: irradiance E = 1000 W/m^2 normal to the beam, 60 deg from the zenith; also with
//   an angular radius of 0.5 deg;
// - uniform sky of radiance L = 1000; CIE overcast sky of zenith radiance Lz = 1000;
// - a vertical 2 m x 2 m wall (reflectance 0) under the uniform sky, alone and on a 10 m floor;
// - a 2 m x 2 m occluder (reflectance 0) at y = 5 under the point light.
#include <cmath>
#include <functional>
#include <numbers>

#include <gtest/gtest.h>

#include "luxel/solve.h"
#include "scene/builtin/builtin_scenes.h"
#include "core/random.h"
#include "transport/form_factor.h"
#include "transport/light_sampling.h"

namespace luxel {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr float kI = 100.0f, kH = 10.0f;
const Vec3 kLightPos(0.5f, kH, 0.5f);
const Vec3 kUp(0.0f, 1.0f, 0.0f);

Scene floorScene() {
  Scene s;
  s.name = "floor";
  s.materials.push_back(Material{.name = "black", .reflectance = Rgb(0.0f)});
  Mesh floor;
  floor.name = "floor";
  // (b - a) x (d - a) = (0,0,100) x (100,0,0) = +y.
  builtin::addQuad(floor, Vec3(-50, 0, -50), Vec3(-50, 0, 50), Vec3(50, 0, 50), Vec3(50, 0, -50));
  s.meshes.push_back(floor);
  return s;
}

Light pointLight() {
  return Light{.type = Light::Type::Point, .name = "bulb", .intensity = kI, .position = kLightPos};
}

Light spotLight() {
  Light l = pointLight();
  l.type = Light::Type::Spot;
  l.direction = Vec3(0, -1, 0);
  l.innerConeAngle = float(20.0 * kPi / 180.0);
  l.outerConeAngle = float(30.0 * kPi / 180.0);
  return l;
}

struct Solved {
  SurfaceSet set;
  Solution sol;
};

Solved solveScene(const Scene& scene, int lightSamples = 16) {
  DiscretiseOptions d;
  d.elementSize = 1.0f;
  d.elementsPerPatchSide = 10;
  Solved s{discretise(scene, d), {}};
  SolveOptions o;
  o.settings.set("light-samples", lightSamples);
  s.sol = solve(scene, s.set, o);
  return s;
}

// The floor element (mesh 0) containing (x, z).
size_t floorElementAt(const SurfaceSet& set, float x, float z) {
  for (size_t e = 0; e < set.elements.size(); ++e) {
    const Element& el = set.elements[e];
    if (set.faces[el.face].mesh != 0) continue;
    Vec3 lo(1e30f), hi(-1e30f);
    for (int i = 0; i < el.polygon.count; ++i) lo = glm::min(lo, el.polygon.v[i]), hi = glm::max(hi, el.polygon.v[i]);
    if (x > lo.x && x < hi.x && z > lo.z && z < hi.z) return e;
  }
  ADD_FAILURE() << "no floor element at (" << x << ", " << z << ")";
  return 0;
}

// The mean of f(x, z) over an axis-aligned floor element, by a 100 x 100 midpoint rule.
double elementMean(const Element& el, const std::function<double(double, double)>& f) {
  Vec3 lo(1e30f), hi(-1e30f);
  for (int i = 0; i < el.polygon.count; ++i) lo = glm::min(lo, el.polygon.v[i]), hi = glm::max(hi, el.polygon.v[i]);
  const int n = 100;
  double sum = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      sum += f(lo.x + (hi.x - lo.x) * (i + 0.5) / n, lo.z + (hi.z - lo.z) * (j + 0.5) / n);
  return sum / (n * n);
}

// Point light: E = I cos(theta) / d^2 = I h / (h^2 + r^2)^(3/2), r the horizontal offset.
double pointIrradiance(double x, double z) {
  const double dx = x - kLightPos.x, dz = z - kLightPos.z;
  return kI * kH / std::pow(kH * kH + dx * dx + dz * dz, 1.5);
}

// Spot light: the point light's E times t^2, t = clamp((cos a - cos outer) / (cos inner - cos outer))
// with a the angle from the axis (glTF KHR_lights_punctual's recommended falloff).
double spotIrradiance(double x, double z) {
  const double dx = x - kLightPos.x, dz = z - kLightPos.z;
  const double cosA = kH / std::sqrt(kH * kH + dx * dx + dz * dz);
  const double cosIn = std::cos(20.0 * kPi / 180.0), cosOut = std::cos(30.0 * kPi / 180.0);
  const double t = std::clamp((cosA - cosOut) / (cosIn - cosOut), 0.0, 1.0);
  return pointIrradiance(x, z) * t * t;
}

TEST(PointLight, SampleIsExactInverseSquareCosine) {
  const Light l = pointLight();
  for (float x : {0.0f, 3.0f, 10.0f, 25.0f}) {
    Vec3 p(kLightPos.x + x, 0.0f, kLightPos.z);
    LightSample s = sampleLight(l, p, kUp, Sides::Front, kUp, 0.3f, 0.7f);
    const double want = kI * kH / std::pow(double(kH) * kH + double(x) * x, 1.5);
    EXPECT_NEAR(s.irradiance.g, want, 1e-5 * want) << "x = " << x;
    // The shadow ray runs towards the light and stops just short of it (1e-4 of the way).
    const float d = glm::length(kLightPos - p);
    EXPECT_NEAR(glm::length(p + s.direction * s.tfar - kLightPos), 0.0f, 2e-4f * d);
    EXPECT_NEAR(glm::dot(glm::normalize(s.direction), (kLightPos - p) / d), 1.0f, 1e-6f);
  }
  EXPECT_NEAR(sampleLight(l, Vec3(0.5f, 0, 0.5f), kUp, Sides::Front, kUp, 0, 0).irradiance.r, kI / (kH * kH), 1e-6);
  // A receiver facing away gets nothing one-sided, and the same |cos| two-sided.
  EXPECT_EQ(sampleLight(l, Vec3(3, 0, 0), -kUp, Sides::Front, kUp, 0, 0).irradiance.g, 0.0f);
  EXPECT_NEAR(sampleLight(l, Vec3(3, 0, 0), -kUp, Sides::Both, kUp, 0, 0).irradiance.g,
              sampleLight(l, Vec3(3, 0, 0), kUp, Sides::Front, kUp, 0, 0).irradiance.g, 1e-6);
}

TEST(PointLight, SolvedElementIrradianceMatchesClosedForm) {
  Scene scene = floorScene();
  scene.lights.push_back(pointLight());
  Solved s = solveScene(scene);
  // Directly below: I / h^2 = 1 W/m^2 (the element mean is 0.25% lower: E ~ E0 (1 - 1.5 r^2/h^2)).
  size_t below = floorElementAt(s.set, 0.5f, 0.5f);
  EXPECT_NEAR(s.sol.irradiance[below].g, kI / (kH * kH), 0.01 * kI / (kH * kH));
  EXPECT_NEAR(s.sol.irradiance[below].g, elementMean(s.set.elements[below], pointIrradiance), 0.005);
  // At horizontal offsets x: I h / (h^2 + x^2)^(3/2): 0.3536 at x = 10, 0.0894 at x = 20.
  for (float x : {5.0f, 10.0f, 20.0f, 40.0f}) {
    size_t e = floorElementAt(s.set, 0.5f + x, 0.5f);
    const double point = kI * kH / std::pow(double(kH) * kH + double(x) * x, 1.5);
    const double mean = elementMean(s.set.elements[e], pointIrradiance);
    EXPECT_NEAR(s.sol.irradiance[e].g, point, 0.01 * point) << "x = " << x;
    // 16 jittered samples per element: 0.34% off the exact element mean at x = 5, where the
    // gradient across the element is steepest.
    EXPECT_NEAR(s.sol.irradiance[e].g, mean, 0.01 * mean) << "x = " << x;
    EXPECT_EQ(s.sol.irradiance[e].r, s.sol.irradiance[e].g);  // white light
    EXPECT_EQ(s.sol.radiosity[e], Rgb(0.0f));                 // black floor
  }
  // Everything is direct.
  for (size_t e = 0; e < s.set.elements.size(); ++e)
    ASSERT_NEAR(s.sol.directIrradiance[e].g, s.sol.irradiance[e].g, 1e-6f * s.sol.irradiance[e].g + 1e-12f);
}

TEST(SpotLight, FullInsideInnerConeZeroOutsideOuterQuadraticBetween) {
  const Light l = spotLight();
  auto at = [&](double angleDeg) {
    const double r = kH * std::tan(angleDeg * kPi / 180.0);
    Vec3 p(kLightPos.x + float(r), 0.0f, kLightPos.z);
    return double(sampleLight(l, p, kUp, Sides::Front, kUp, 0.5f, 0.5f).irradiance.g);
  };
  const double cosIn = std::cos(20.0 * kPi / 180.0), cosOut = std::cos(30.0 * kPi / 180.0);
  for (double a : {0.0, 10.0, 19.5}) {  // inside the inner cone: the point light's I cos^3(a) / h^2
    const double want = kI * std::pow(std::cos(a * kPi / 180.0), 3) / (kH * kH);
    EXPECT_NEAR(at(a), want, 1e-5 * want) << a << " deg";
  }
  for (double a : {30.5, 45.0, 80.0}) EXPECT_EQ(at(a), 0.0) << a << " deg";
  for (double a : {22.0, 25.0, 28.0}) {
    const double c = std::cos(a * kPi / 180.0), t = (c - cosOut) / (cosIn - cosOut);
    const double want = kI * c * c * c / (kH * kH) * t * t;
    EXPECT_NEAR(at(a), want, 1e-4 * want) << a << " deg";
  }
  // 25 deg: t = (0.90631 - 0.86603) / (0.93969 - 0.86603) = 0.5468, falloff t^2 = 0.299.
  EXPECT_NEAR(at(25.0) / (kI * std::pow(std::cos(25.0 * kPi / 180.0), 3) / (kH * kH)), 0.299, 0.001);

  // Solved element means: inside (r < 10 tan 20 = 3.64 m), outside (r > 10 tan 30 = 5.77 m), and
  // elements straddling the falloff zone.
  Scene scene = floorScene();
  scene.lights.push_back(l);
  Solved s = solveScene(scene, 64);
  for (float x : {0.0f, 1.0f, 2.0f}) {
    size_t e = floorElementAt(s.set, 0.5f + x, 0.5f);
    const double want = elementMean(s.set.elements[e], pointIrradiance);
    EXPECT_NEAR(s.sol.irradiance[e].g, want, 0.01 * want) << "inside, x = " << x;
  }
  for (float x : {7.0f, 8.0f, 20.0f}) {  // element x offsets from 6.5 m: beyond 5.77 m
    size_t e = floorElementAt(s.set, 0.5f + x, 0.5f);
    EXPECT_EQ(s.sol.irradiance[e].g, 0.0f) << "outside, x = " << x;
  }
  for (float x : {4.0f, 5.0f}) {
    size_t e = floorElementAt(s.set, 0.5f + x, 0.5f);
    const double want = elementMean(s.set.elements[e], spotIrradiance);
    EXPECT_GT(want, 0.0);
    EXPECT_NEAR(s.sol.irradiance[e].g, want, 0.02 * want) << "falloff zone, x = " << x;
  }
}

// Directional light E = 1000 from 60 deg off the zenith: E cos 60 = 500 on the floor.
Light sun(float angularRadiusDeg) {
  const double z = 60.0 * kPi / 180.0;
  return Light{.type = Light::Type::Directional,
               .name = "sun",
               .intensity = 1000.0f,
               .direction = Vec3(float(std::sin(z)), float(-std::cos(z)), 0.0f),
               .angularRadius = float(angularRadiusDeg * kPi / 180.0)};
}

TEST(DirectionalLight, SixtyDegreesFromZenithGivesHalf) {
  for (float radius : {0.0f, 0.5f}) {
    Scene scene = floorScene();
    scene.lights.push_back(sun(radius));
    Solved s = solveScene(scene);
    double sum = 0.0;
    for (size_t e = 0; e < s.set.elements.size(); ++e) {
      ASSERT_NEAR(s.sol.irradiance[e].g, 500.0, 5.0) << "element " << e << ", radius " << radius;
      sum += s.sol.irradiance[e].g;
    }
    // A disc of angular radius a: the mean cosine over the cone is cos 60 (1 + cos a) / 2, which is
    // 500 (1 - 1.9e-5) for a = 0.5 deg.
    EXPECT_NEAR(sum / double(s.set.elements.size()), 500.0, 0.01 * 500.0) << "radius " << radius;
  }
  // Point-wise, a zero-radius sun is exact.
  LightSample ls = sampleLight(sun(0.0f), Vec3(0), kUp, Sides::Front, kUp, 0.4f, 0.6f);
  EXPECT_NEAR(ls.irradiance.g, 500.0f, 1e-3f);
  EXPECT_TRUE(std::isinf(ls.tfar));
}

TEST(SkyLight, UniformSkyGivesPiLOnTheHorizontal) {
  Scene scene = floorScene();
  scene.lights.push_back(Light{.type = Light::Type::Sky, .name = "sky", .intensity = 1000.0f});
  Solved s = solveScene(scene);
  const double want = kPi * 1000.0;
  for (size_t e = 0; e < s.set.elements.size(); ++e)
    ASSERT_NEAR(s.sol.irradiance[e].g, want, 0.02 * want) << "element " << e;
}

// CIE standard overcast sky (Moon and Spencer 1942): L(theta) = Lz (1 + 2 cos theta) / 3. On the
// horizontal, E = int L cos dw = 2 pi Lz / 3 int_0^1 (1 + 2 mu) mu dmu = 2 pi Lz / 3 (1/2 + 2/3)
// = 7 pi Lz / 9.
TEST(SkyLight, CieOvercastSkyGivesSevenPiLzOverNine) {
  Scene scene = floorScene();
  scene.lights.push_back(Light{.type = Light::Type::CieOvercastSky, .name = "overcast", .intensity = 1000.0f});
  Solved s = solveScene(scene);
  const double want = 7.0 * kPi * 1000.0 / 9.0;
  double sum = 0.0;
  for (size_t e = 0; e < s.set.elements.size(); ++e) {
    ASSERT_NEAR(s.sol.irradiance[e].g, want, 0.05 * want) << "element " << e;
    sum += s.sol.irradiance[e].g;
  }
  EXPECT_NEAR(sum / double(s.set.elements.size()), want, 0.02 * want);
  // Point-wise radiance: Lz at the zenith, Lz / 3 at the horizon, nothing below.
  const Light& sky = scene.lights[0];
  EXPECT_NEAR(skyRadiance(sky, kUp, kUp).g, 1000.0f, 1e-2f);
  EXPECT_NEAR(skyRadiance(sky, glm::normalize(Vec3(1, 1e-6f, 0)), kUp).g, 1000.0f / 3.0f, 0.1f);
  EXPECT_EQ(skyRadiance(sky, glm::normalize(Vec3(1, -0.1f, 0)), kUp).g, 0.0f);
}

// A vertical wall sees the sky in the upper half of its hemisphere only; the uniform sky's
// radiance L over that quarter sphere, cosine-weighted, gives pi L / 2. The wall is 2 m x 2 m
// (reflectance 0), alone, and then standing on a black 10 m x 10 m floor; 0.25 m elements and 256
// sky samples per element.
TEST(SkyLight, VerticalWallGetsHalfTheHorizontalIrradiance) {
  Mesh wall;
  wall.name = "wall";
  // x = 0, y in [0, 2], z in [-1, 1], facing +x: (0,2,0) x (0,0,2) = +x.
  builtin::addQuad(wall, Vec3(0, 0, -1), Vec3(0, 2, -1), Vec3(0, 2, 1), Vec3(0, 0, 1));
  Mesh floor;
  floor.name = "floor";
  builtin::addQuad(floor, Vec3(-5, 0, -5), Vec3(-5, 0, 5), Vec3(5, 0, 5), Vec3(5, 0, -5));
  Scene alone;
  alone.name = "wall";
  alone.materials.push_back(Material{.name = "black", .reflectance = Rgb(0.0f)});
  alone.meshes.push_back(wall);
  alone.lights.push_back(Light{.type = Light::Type::Sky, .name = "sky", .intensity = 1000.0f});
  Scene onFloor = alone;
  onFloor.meshes.push_back(floor);

  const double want = kPi * 1000.0 / 2.0;
  for (const Scene* scene : {&alone, &onFloor}) {
    DiscretiseOptions d;
    d.elementSize = 0.25f;
    SurfaceSet set = discretise(*scene, d);
    SolveOptions o;
    o.settings.set("light-samples", 256);
    Solution sol = solve(*scene, set, o);
    double sum = 0.0, area = 0.0;
    for (size_t e = 0; e < set.elements.size(); ++e) {
      if (set.faces[set.elements[e].face].mesh != 0) continue;
      EXPECT_NEAR(set.elements[e].normal.x, 1.0f, 1e-6f);
      sum += set.elements[e].area * sol.irradiance[e].g;
      area += set.elements[e].area;
    }
    EXPECT_NEAR(area, 4.0, 1e-4);
    // With the floor the wall gets the same: the floor only hides sky below the horizon, which
    // is dark anyway.
    EXPECT_NEAR(sum / area, want, 0.03 * want) << (scene == &alone ? "alone" : "on the floor");
  }
}

TEST(Shadows, OccluderDarkensTheFloorBelowItOnly) {
  Scene open = floorScene();
  open.lights.push_back(pointLight());
  Scene shaded = open;
  Mesh occluder;
  occluder.name = "occluder";
  // x, z in [-0.5, 1.5] at y = 5 facing +y (towards the light): its shadow is x, z in [-1.5, 2.5].
  builtin::addQuad(occluder, Vec3(-0.5f, 5, -0.5f), Vec3(-0.5f, 5, 1.5f), Vec3(1.5f, 5, 1.5f), Vec3(1.5f, 5, -0.5f));
  shaded.meshes.push_back(occluder);
  Solved a = solveScene(open), b = solveScene(shaded);
  const size_t below = floorElementAt(b.set, 0.5f, 0.5f);
  ASSERT_EQ(below, floorElementAt(a.set, 0.5f, 0.5f));
  EXPECT_GT(a.sol.irradiance[below].g, 0.9f);
  EXPECT_LT(b.sol.irradiance[below].g, 0.05f * a.sol.irradiance[below].g);
  // Every floor element wholly inside the umbra, x, z in [-1.5, 2.5], is dark: cells [-1, 2]^2.
  for (float x : {-1.0f, 0.0f, 1.0f})
    for (float z : {-1.0f, 0.0f, 1.0f}) {
      size_t e = floorElementAt(b.set, x + 0.01f, z + 0.01f);
      EXPECT_LT(b.sol.irradiance[e].g, 0.05f * a.sol.irradiance[e].g) << x << ", " << z;
    }
  // A cell half in the shadow, [2, 3] x [0, 1], gets about half.
  const size_t half = floorElementAt(b.set, 2.5f, 0.5f);
  EXPECT_NEAR(b.sol.irradiance[half].g / a.sol.irradiance[half].g, 0.5f, 0.1f);
  // Far from the shadow nothing changes.
  for (float x : {5.0f, 10.0f, -20.0f}) {
    size_t e = floorElementAt(b.set, 0.5f + x, 0.5f);
    const float want = a.sol.irradiance[e].g;
    EXPECT_NEAR(b.sol.irradiance[e].g, want, 1e-4f * want) << "x = " << x;
  }
}

}  // namespace
}  // namespace luxel

namespace luxel {
namespace {

// lightMayReachFront may only skip elements whose samples would all be dark, and a prepared light
// samples the same numbers as the light itself.
TEST(LightSkipping, SkippedElementsWouldHaveDrawnOnlyDarkSamples) {
  Rng rng(7);
  auto unit = [&] {
    return glm::normalize(Vec3(rng.next() - 0.5f, rng.next() - 0.5f, rng.next() - 0.5f) + Vec3(1e-3f));
  };
  std::vector<Light> lights;
  for (int i = 0; i < 40; ++i) {
    Light sun{.type = Light::Type::Directional, .intensity = 1000.0f};
    sun.direction = unit(), sun.angularRadius = i % 2 ? 0.0f : 0.02f * float(i);
    lights.push_back(sun);
    Light lamp{.type = i % 3 ? Light::Type::Point : Light::Type::Spot, .intensity = 100.0f};
    lamp.position = 2.0f * unit(), lamp.direction = unit();
    lamp.innerConeAngle = 0.3f, lamp.outerConeAngle = 0.6f;
    lights.push_back(lamp);
  }
  size_t skipped = 0, kept = 0;
  for (int trial = 0; trial < 400; ++trial) {
    // A small quad about a random point, facing a random way (its corners in its plane).
    const Vec3 c = unit(), n = unit();
    Vec3 t = glm::normalize(glm::cross(n, std::abs(n.x) < 0.9f ? Vec3(1, 0, 0) : Vec3(0, 1, 0)));
    const Vec3 b = glm::cross(n, t);
    t *= 0.3f;
    Polygon quad;
    quad.count = 4;
    quad.v = {c - t - 0.3f * b, c + t - 0.3f * b, c + t + 0.3f * b, c - t + 0.3f * b};
    for (const Light& light : lights) {
      const PreparedLight prepared = prepareLight(light);
      const bool may = lightMayReachFront(light, quad, n);
      (may ? kept : skipped) += 1;
      for (int k = 0; k < 64; ++k) {
        const float s = rng.next(), u = rng.next(), u1 = rng.next(), u2 = rng.next();
        const Vec3 x = polygonPoint(quad, s, u);
        const LightSample a = sampleLight(light, x, n, Sides::Front, kUp, u1, u2);
        const LightSample p = sampleLight(prepared, x, n, Sides::Front, kUp, u1, u2);
        ASSERT_EQ(a.irradiance, p.irradiance);
        ASSERT_EQ(a.direction, p.direction);
        if (!may) ASSERT_FALSE(a.valid()) << "a skipped element would have been lit";
      }
    }
  }
  // Both cases occur: a light behind the plane about half the time.
  EXPECT_GT(skipped, kept / 4);
  EXPECT_GT(kept, skipped / 4);
}

}  // namespace
}  // namespace luxel
