// Normal maps in `luxel render --mode hq` against the closed form. A lone 4 x 4 m floor facing +y
// (reflectance 0.5, one-sided, nothing else: no indirect light) with a constant normal map that
// tilts its normal by alpha = 30 degrees about the u axis, towards -z (its +v):
//   n_p = (0, cos alpha, -sin alpha).
// The pixel at the floor's centre (0, 0, 0) then has radiance rho / pi * E with E the direct
// irradiance at the perturbed normal, max(0, n_p . l) times the light's intensity (/ r^2 for a
// point light), and none from light below the floor's own plane. Point lights and a sun of zero
// angular radius have no sampling noise; what is left is the pixel's footprint: a 0.2 degree view
// of 9 x 9 pixels from 2 m sees 0.78 mm per pixel, and the point light's radiance changes by 1.5
// of itself per metre there, so the mean of 16 jittered positions (0.07 pixel standard deviation
// per axis) moves the pixel by about 1e-4 of its value (measured: 0.9e-4 and 1.2e-4; the sun,
// uniform over the floor, 3e-7). The tolerance, 1e-3, is ten times that.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include "luxel/render.h"
#include "luxel/solve.h"
#include "luxel/surface.h"
#include "render/direct_light.h"
#include "trace/ray_tracer.h"
#include "transport/form_factor.h"

namespace luxel {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr float kRho = 0.5f;
const float kAlpha = glm::radians(30.0f);

// The floor: u along +x, v along -z, so t = +x, b = -z, n = +y. Its normal map is one texel
// encoding (0, sin alpha, cos alpha), which is n_p in the world.
Scene floorScene(const Light& light) {
  Scene s;
  s.name = "floor";
  Mesh m;
  m.name = "floor";
  m.positions = {{-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, {-2, 0, -2}};
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.faces = {Face{{0, 1, 2, 3}}};
  s.meshes = {m};
  Material mat;
  mat.name = "floor";
  mat.reflectance = Rgb(kRho);
  mat.normalTexture = 0;
  s.materials = {mat};
  const Vec3 tangentNormal(0.0f, std::sin(kAlpha), std::cos(kAlpha));
  s.textures = {
      Texture{.path = "tilt", .width = 1, .height = 1, .texels = {0.5f * tangentNormal + 0.5f}}};
  s.lights = {light};
  s.validate();
  return s;
}

const Vec3 kTilted(0.0f, std::cos(kAlpha), -std::sin(kAlpha));

struct Solved {
  Scene scene;
  SurfaceSet surfaces;
  Solution solution;
};

Solved solveFloor(const Light& light) {
  Solved f{floorScene(light), {}, {}};
  // Kept as modelled: a sun below the floor would otherwise turn it round (orientByLight).
  f.surfaces = discretise(f.scene, DiscretiseOptions{.elementBudget = 64, .orientByLight = false});
  EXPECT_EQ(f.surfaces.flippedFaces, 0u);
  SolveOptions so;
  so.method = "progressive";
  f.solution = solve(f.scene, f.surfaces, so);
  return f;
}

Image renderCentre(const Scene& scene, const Solved& f, RenderOptions::Mode mode) {
  RenderOptions ro;
  ro.mode = mode;
  ro.camera = Camera{.eye = {0, 2, 0}, .target = {0, 0, 0}, .up = {0, 0, -1}, .fovY = 0.2f};
  ro.width = ro.height = 9;
  ro.samplesPerPixel = 16;
  return render(scene, f.surfaces, f.solution, ro);
}

// The centre pixel in hq mode with the material's normal map at `scale`, or with none (scale < 0).
float centre(const Solved& f, float scale) {
  Scene s = f.scene;
  if (scale < 0.0f)
    s.materials[0].normalTexture = -1;
  else
    s.materials[0].normalScale = scale;
  const Rgb c = renderCentre(s, f, RenderOptions::Mode::HighQuality).at(4, 4);
  EXPECT_EQ(c.r, c.g);  // grey light on a grey floor
  return c.g;
}

bool sameBits(const Image& a, const Image& b) {
  return a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Rgb)) == 0;
}

TEST(NormalMapRender, PointLightOnATiltedFloorMatchesTheClosedForm) {
  // Intensity 10 at (0, 1, -1): l = (0, 1, -1) / sqrt 2, r^2 = 2. n . l = cos 45 degrees, and
  // n_p . l = cos 15 degrees (the normal leans 30 degrees towards the light).
  const Vec3 pos(0.0f, 1.0f, -1.0f);
  const Solved f = solveFloor(
      Light{.type = Light::Type::Point, .name = "bulb", .intensity = 10.0f, .position = pos});
  const Vec3 l = glm::normalize(pos);
  const float flat = kRho / kPi * 10.0f * l.y / 2.0f;
  const float tilted = kRho / kPi * 10.0f * glm::dot(kTilted, l) / 2.0f;
  ASSERT_NEAR(glm::dot(kTilted, l), std::cos(glm::radians(15.0f)), 1e-6f);
  EXPECT_NEAR(centre(f, 1.0f), tilted, 1e-3f * tilted);
  EXPECT_NEAR(centre(f, 0.0f), flat, 1e-3f * flat);  // scale 0: the unperturbed floor
  EXPECT_NEAR(centre(f, -1.0f), flat, 1e-3f * flat);

  // Radiosity mode ignores normal maps, bit for bit.
  Scene without = f.scene;
  without.materials[0].normalTexture = -1;
  EXPECT_TRUE(sameBits(renderCentre(f.scene, f, RenderOptions::Mode::Radiosity),
                       renderCentre(without, f, RenderOptions::Mode::Radiosity)));
}

// A sun (irradiance 3 facing it, no disc) from three directions l in the yz plane.
TEST(NormalMapRender, SunCosineIsTakenAtThePerturbedNormalAndClampedAndTheFloorStillShadows) {
  auto sun = [](float elevationDeg, float towardsZ) {
    const float e = glm::radians(elevationDeg);
    const Vec3 l(0.0f, std::sin(e), towardsZ * std::cos(e));
    return std::pair{
        Light{.type = Light::Type::Directional, .name = "sun", .intensity = 3.0f, .direction = -l},
        l};
  };
  {
    // 40 degrees up towards -z: n . l = sin 40, n_p . l = sin 70.
    const auto [light, l] = sun(40.0f, -1.0f);
    const Solved f = solveFloor(light);
    const float tilted = kRho / kPi * 3.0f * std::sin(glm::radians(70.0f));
    const float flat = kRho / kPi * 3.0f * std::sin(glm::radians(40.0f));
    EXPECT_NEAR(centre(f, 1.0f), tilted, 1e-3f * tilted);
    EXPECT_NEAR(centre(f, 0.0f), flat, 1e-3f * flat);
  }
  {
    // 10 degrees up towards +z: above the floor, but behind the perturbed normal
    // (n_p . l = sin(10 - 30) < 0): clamped to no light.
    const auto [light, l] = sun(10.0f, 1.0f);
    ASSERT_LT(glm::dot(kTilted, l), 0.0f);
    const Solved f = solveFloor(light);
    const float flat = kRho / kPi * 3.0f * std::sin(glm::radians(10.0f));
    EXPECT_EQ(centre(f, 1.0f), 0.0f);
    EXPECT_NEAR(centre(f, 0.0f), flat, 1e-3f * flat);
  }
  {
    // 10 degrees below the floor's plane, from -z: in front of the perturbed normal
    // (n_p . l = sin 20 > 0) but behind the surface itself, which blocks it.
    const auto [light, l] = sun(-10.0f, -1.0f);
    ASSERT_GT(glm::dot(kTilted, l), 0.3f);
    const Solved f = solveFloor(light);
    EXPECT_EQ(centre(f, 1.0f), 0.0f);
  }
}

// An emitting square above the receiver, wholly above its plane and unoccluded: every sample of
// DirectLight carries exactly exitance times the form factor at the normal it is given, so the
// shading normal, not the geometric one, must set the receiver's cosine.
TEST(NormalMapRender, EmitterFormFactorUsesTheShadingNormal) {
  Scene s;
  s.name = "lamp";
  s.materials = {Material{.name = "lamp", .reflectance = Rgb(0.0f), .emission = Rgb(1.0f)}};
  Mesh lamp{.name = "lamp", .material = 0};
  lamp.positions = {
      {-0.2f, 1, -1.2f}, {0.2f, 1, -1.2f}, {0.2f, 1, -0.8f}, {-0.2f, 1, -0.8f}};  // faces -y
  lamp.faces = {Face{{0, 1, 2, 3}}};
  s.meshes = {lamp};
  const SurfaceSet set = discretise(s, DiscretiseOptions{.elementBudget = 4});
  std::vector<Polygon> faces;
  for (const SurfaceFace& face : set.faces)
    faces.push_back(Polygon{face.corners, face.triangle ? 3 : 4});
  RayTracer tracer(faces);
  const DirectLight direct(s, set);

  const Vec3 x(0.0f), n(0.0f, 1.0f, 0.0f);
  const double tilted =
      kPi * pointToPolygonFormFactor(x, kTilted, faces[0], Sides::Front, Sides::Front);
  const double flat = kPi * pointToPolygonFormFactor(x, n, faces[0], Sides::Front, Sides::Front);
  ASSERT_GT(tilted, 1.2 * flat);  // the lamp is 45 degrees towards -z: the tilt faces it
  Rng rng(11);
  double sum = 0.0;
  const int samples = 200;
  std::vector<RTCRay> rays;
  std::vector<Rgb> values;
  for (int i = 0; i < samples; ++i) {
    rays.clear();
    values.clear();
    sum += direct.sample(x, n, kTilted, Sides::Front, rng, 1e-5f, rays, values).g;
    tracer.occluded(rays);
    for (size_t k = 0; k < rays.size(); ++k)
      if (!isOccluded(rays[k])) sum += values[k].g;
  }
  EXPECT_NEAR(sum / samples, tilted, 1e-5 * tilted);
}

}  // namespace
}  // namespace luxel
