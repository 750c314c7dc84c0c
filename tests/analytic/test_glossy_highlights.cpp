// Glossy highlights in hq renders (render/glossy_lobe.h): the lobe's sampling integrates the lobe,
// a lamp's highlight on a black glossy floor is the closed form specular / pi * pow(N.H, s) * E,
// an emitting square's is the lobe integrated over it, and materials without a highlight render
// as before.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "luxel/import.h"
#include "luxel/render.h"
#include "luxel/solve.h"
#include "render/glossy_lobe.h"

namespace luxel {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// The lobe's integral over the hemisphere, int f cos dw over the specular colour, by a midpoint
// rule fine enough (2000 x 2000 in (cos theta, phi)) to be exact to 1e-4 for these exponents.
double lobeAlbedo(const GlossyLobe& lobe, Vec3 n) {
  const HemisphereFrame frame(n);
  const int steps = 2000;
  double sum = 0.0;
  for (int i = 0; i < steps; ++i)
    for (int j = 0; j < steps; ++j) {
      const float z = (float(i) + 0.5f) / float(steps), phi = (float(j) + 0.5f) / float(steps);
      const Vec3 l = frame.uniform(z, phi);
      sum += double(lobe.value(l)) * z;  // cos theta; dw = dz dphi 2 pi
    }
  return sum * 2.0 * std::numbers::pi / (double(steps) * double(steps));
}

TEST(GlossyLobe, SamplingIntegratesTheLobe) {
  const Vec3 n(0, 0, 1);
  for (float shininess : {1.0f, 10.0f, 100.0f})
    for (float viewAngle : {0.0f, 0.6f, 1.3f}) {
      const Vec3 toEye(std::sin(viewAngle), 0.0f, std::cos(viewAngle));
      const GlossyLobe lobe(n, toEye, shininess);
      double sum = 0.0, sum2 = 0.0;
      const int count = 400000;
      uint32_t state = 12345u;
      auto next = [&] {
        state ^= state << 13, state ^= state >> 17, state ^= state << 5;
        return float(state >> 8) / float(1u << 24);
      };
      for (int k = 0; k < count; ++k) {
        const GlossyLobe::Sample s = lobe.sample(next(), next());
        sum += s.weight, sum2 += double(s.weight) * s.weight;
      }
      const double mean = sum / count, sigma = std::sqrt((sum2 / count - mean * mean) / count);
      EXPECT_NEAR(mean, lobeAlbedo(lobe, n), 4.0 * sigma + 1e-4)
          << "shininess " << shininess << ", view " << viewAngle;
    }
}

// A black glossy floor: the quad z = 0, 40 units a side, reflectance 0, with a highlight.
Scene glossyFloor(float specular, float shininess) {
  Scene scene;
  scene.name = "glossy-floor";
  Material floor;
  floor.reflectance = Rgb(0.0f);
  floor.specular = Rgb(specular);
  floor.shininess = shininess;
  scene.materials.push_back(floor);
  Mesh mesh;
  mesh.positions = {Vec3(-20, -20, 0), Vec3(20, -20, 0), Vec3(20, 20, 0), Vec3(-20, 20, 0)};
  mesh.faces.push_back(Face{{0, 1, 2, 3}});
  mesh.material = 0;
  scene.meshes.push_back(std::move(mesh));
  scene.up = Vec3(0, 0, 1);
  return scene;
}

// One pixel, a narrow view of the point `at` from `eye`.
Rgb renderPixel(const Scene& scene, Vec3 eye, Vec3 at, int spp, int glossyRays = kDefaultGlossyRays,
                uint32_t seed = 7) {
  SurfaceSet surfaces = discretise(scene, DiscretiseOptions{});
  SolveOptions so;
  so.method = "progressive";
  const Solution solution = solve(scene, surfaces, so);
  RenderOptions ro;
  ro.width = ro.height = 1;
  ro.samplesPerPixel = spp;
  ro.glossyRays = glossyRays;
  ro.seed = seed;
  ro.camera.eye = eye;
  ro.camera.target = at;
  ro.camera.up = Vec3(0, 0, 1);
  ro.camera.fovY = 0.01f;
  return render(scene, surfaces, solution, ro).at(0, 0);
}

TEST(GlossyRender, ALampsHighlightIsTheClosedForm) {
  Scene scene = glossyFloor(0.5f, 20.0f);
  Light lamp;
  lamp.type = Light::Type::Point;
  lamp.intensity = 100.0f;
  lamp.position = Vec3(0, 0, 4);
  scene.lights.push_back(lamp);
  // Seen from (3, 0, 3) the mirror point of the lamp is where eye and lamp make equal angles.
  const Vec3 eye(3, 0, 3);
  for (const Vec3 at : {Vec3(12.0f / 7.0f, 0, 0), Vec3(1.0f, 0.5f, 0.0f)}) {
    const Vec3 toLamp = glm::normalize(lamp.position - at), toEye = glm::normalize(eye - at);
    const float r2 = glm::dot(lamp.position - at, lamp.position - at);
    const float e = lamp.intensity * toLamp.z / r2;
    const float expected = 0.5f / kPi * std::pow(glm::normalize(toLamp + toEye).z, 20.0f) * e;
    const Rgb got = renderPixel(scene, eye, at, 4);
    // A lamp's sample is exact: the rest is the pixel's footprint, a hundredth of a degree wide.
    EXPECT_NEAR(got.g, expected, 1e-3f * expected + 1e-7f) << at.x << ", " << at.y;
  }
  // No highlight asked for: the black floor is black.
  EXPECT_EQ(renderPixel(scene, eye, Vec3(12.0f / 7.0f, 0, 0), 4, 0).g, 0.0f);
}

TEST(GlossyRender, AnEmittersHighlightIsTheLobeOverIt) {
  Scene scene = glossyFloor(0.8f, 10.0f);
  // A square emitter, 1 x 1, facing down at height 3 over (-1, 0).
  Material light;
  light.reflectance = Rgb(0.0f);
  light.emission = Rgb(0.6f);  // radiance
  scene.materials.push_back(light);
  Mesh square;
  square.positions = {Vec3(-1.5f, -0.5f, 3), Vec3(-1.5f, 0.5f, 3), Vec3(-0.5f, 0.5f, 3),
                      Vec3(-0.5f, -0.5f, 3)};
  square.faces.push_back(Face{{0, 1, 2, 3}});
  square.material = 1;
  scene.meshes.push_back(std::move(square));
  const Vec3 eye(2, 0, 3), at(0.5f, 0, 0);
  const Vec3 toEye = glm::normalize(eye - at);
  // int f cos Le dw over the square, by a 400 x 400 midpoint rule over its area.
  const float le = 0.6f;
  double expected = 0.0;
  const int steps = 400;
  for (int i = 0; i < steps; ++i)
    for (int j = 0; j < steps; ++j) {
      const Vec3 y(-1.5f + (float(i) + 0.5f) / steps, -0.5f + (float(j) + 0.5f) / steps, 3.0f);
      const Vec3 d = y - at;
      const float r2 = glm::dot(d, d), r = std::sqrt(r2);
      const Vec3 l = d / r;
      const float f = 0.8f / kPi * std::pow(glm::normalize(l + toEye).z, 10.0f);
      expected +=
          double(f * le * l.z * l.z / r2) / (double(steps) * steps);  // cos at x, cos at y, dA
    }
  // 65,536 samples, a quarter of them camera samples (the pixel sees one untextured face) with four
  // lobe rays each: one image is within about 2% (measured over seeds), the mean of four within 1%.
  double got = 0.0;
  for (uint32_t seed : {1u, 2u, 3u, 4u})
    got += renderPixel(scene, eye, at, 65536, kDefaultGlossyRays, seed).g / 4.0;
  EXPECT_NEAR(got, expected, 0.03 * expected);
}

// Without glossy materials the rays are never drawn: the same image, bit for bit.
TEST(GlossyRender, DiffuseScenesRenderAsBefore) {
  Scene scene = glossyFloor(0.0f, 0.0f);
  scene.materials[0].reflectance = Rgb(0.5f);
  Light lamp;
  lamp.position = Vec3(0, 0, 4);
  scene.lights.push_back(lamp);
  const Rgb with = renderPixel(scene, Vec3(3, 0, 3), Vec3(1, 0, 0), 16, 4);
  const Rgb without = renderPixel(scene, Vec3(3, 0, 3), Vec3(1, 0, 0), 16, 0);
  EXPECT_EQ(with, without);
  EXPECT_GT(with.g, 0.0f);
}

}  // namespace
}  // namespace luxel
