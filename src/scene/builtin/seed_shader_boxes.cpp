// The test models of seed 000: "Programmable Shader Analysis and Development for Global
// Illumination Radiosity Rendering" (shared/seeds/notes/000-shader-radiosity.md, sections 4.2 and
// 5): a closed box "similar to the Cornell box", 200 units across, uniformly tessellated with
// factors 20, 10, 5 and 4 (1200, 4800, 19200 and 30000 triangles: six k x k grids of quads,
// k = 200 / factor), and Plate C.10's box-tess20 with a sphere, a torus above it and an HDR light
// of (100.4, 96.8, 90.0). Patches are vertices in the thesis; here every grid quad is one face,
// one element and one patch. Emitter and colours are not described; ours are in
// docs/seed-scenes.md.
#include <array>
#include <cmath>
#include <string>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include "luxel/error.h"
#include "scene/builtin/builtin_scenes.h"
#include "scene/builtin/seed_geometry.h"

namespace luxel::builtin {
namespace {

// 200 units across in the thesis; metres here, so a 2 m box centred on the origin.
constexpr float kHalf = 1.0f;
// Plate C.10's HDR light, "almost 100 times brighter than white"; every box uses it.
const Rgb kLightRadiance(100.4f, 96.8f, 90.0f);
// The light panel is the ceiling's central fifth in each direction (0.4 x 0.4 m): whole cells of
// every grid, since k = 10, 20, 40, 50 are all multiples of 5.
constexpr int kLightFraction = 5;

Scene shaderBoxScene(const std::string& name, int k) {
  Scene s;
  s.name = name;
  enum : uint32_t { kWhite, kRed, kGreen, kLight };
  s.materials = {
      Material{.name = "white", .reflectance = Rgb(0.725f, 0.71f, 0.68f)},
      Material{.name = "red", .reflectance = Rgb(0.63f, 0.065f, 0.05f)},
      Material{.name = "green", .reflectance = Rgb(0.14f, 0.45f, 0.091f)},
      Material{.name = "light", .reflectance = Rgb(0.78f), .emission = kLightRadiance},
  };
  const float a = kHalf, e = 2.0f * kHalf;
  const Vec3 X(e, 0, 0), Y(0, e, 0), Z(0, 0, e), lo(-a);
  const int l0 = 2 * k / kLightFraction, l1 = 3 * k / kLightFraction;
  auto inLight = [=](int i, int j) { return i >= l0 && i < l1 && j >= l0 && j < l1; };
  auto wall = [&](const char* wallName, uint32_t material, Vec3 origin, Vec3 u, Vec3 v,
                  bool lightHole = false) {
    Mesh m;
    m.name = wallName;
    m.material = material;
    addCellGrid(m, origin, u, v, k, k,
                lightHole ? std::function<bool(int, int)>(inLight) : nullptr);
    s.meshes.push_back(std::move(m));
  };
  // Inward faces (u x v points into the box); x = -1 is on the camera's left.
  wall("floor", kWhite, lo, Z, X);
  wall("ceiling", kWhite, Vec3(-a, a, -a), X, Z, true);
  wall("back wall", kWhite, lo, X, Y);
  wall("front wall", kWhite, Vec3(-a, -a, a), Y, X);
  wall("left wall", kRed, lo, Y, Z);
  wall("right wall", kGreen, Vec3(a, -a, -a), Z, Y);

  // The ceiling's missing cells, in the ceiling's plane, emitting downwards.
  Mesh light;
  light.name = "light";
  light.material = kLight;
  const float f0 = float(l0) / float(k), fl = float(l1 - l0) / float(k);
  addCellGrid(light, Vec3(-a, a, -a) + f0 * X + f0 * Z, fl * X, fl * Z, l1 - l0, l1 - l0);
  s.meshes.push_back(std::move(light));

  // The thesis's camera is 600 units along +z and sees in through the front wall (culled there);
  // luxel renders back faces black, so ours stands inside, against the front wall.
  s.cameras.push_back(Camera{.name = "default",
                             .eye = Vec3(0, 0, a - 0.03f),
                             .target = Vec3(0, 0, -a),
                             .up = Vec3(0, 1, 0),
                             .fovY = 75.0f});
  return s;
}

// Appends a triangle or quad, reversing its winding when its normal points towards `inside`.
void addOutward(Mesh& m, std::array<uint32_t, 4> v, Vec3 inside) {
  const auto& p = m.positions;
  Vec3 n = v[3] == v[2] ? glm::cross(p[v[1]] - p[v[0]], p[v[2]] - p[v[0]])
                        : glm::cross(p[v[2]] - p[v[0]], p[v[3]] - p[v[1]]);
  Vec3 centroid = 0.25f * (p[v[0]] + p[v[1]] + p[v[2]] + p[v[3]]);
  if (glm::dot(n, centroid - inside) < 0.0f)
    v = v[3] == v[2] ? std::array<uint32_t, 4>{v[0], v[2], v[1], v[1]}
                     : std::array<uint32_t, 4>{v[0], v[3], v[2], v[1]};
  m.faces.push_back(Face{v});
  m.elementGrids.push_back({1, 1});
}

// A UV sphere: triangle fans at the poles, quads between the rings; one element per face.
void addSphere(Mesh& m, Vec3 centre, float r, int segments, int rings) {
  const float pi = glm::pi<float>();
  const auto top = uint32_t(m.positions.size());
  m.positions.push_back(centre + Vec3(0, r, 0));
  for (int i = 1; i < rings; ++i) {
    const float theta = pi * float(i) / float(rings);
    for (int j = 0; j < segments; ++j) {
      const float phi = 2.0f * pi * float(j) / float(segments);
      m.positions.push_back(centre + r * Vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                              std::sin(theta) * std::sin(phi)));
    }
  }
  const auto bottom = uint32_t(m.positions.size());
  m.positions.push_back(centre - Vec3(0, r, 0));
  auto ring = [&](int i, int j) { return top + 1 + uint32_t((i - 1) * segments + j % segments); };
  for (int j = 0; j < segments; ++j) {
    addOutward(m, {top, ring(1, j + 1), ring(1, j), ring(1, j)}, centre);
    for (int i = 1; i + 1 < rings; ++i)
      addOutward(m, {ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j)}, centre);
    addOutward(m, {bottom, ring(rings - 1, j), ring(rings - 1, j + 1), ring(rings - 1, j + 1)},
               centre);
  }
}

// A torus about the vertical axis through `centre`: `major` radius to the tube's centre line,
// `minor` the tube's; one element per quad.
void addTorus(Mesh& m, Vec3 centre, float major, float minor, int segments, int sides) {
  const float pi = glm::pi<float>();
  const auto base = uint32_t(m.positions.size());
  for (int j = 0; j < segments; ++j) {
    const float phi = 2.0f * pi * float(j) / float(segments);
    for (int i = 0; i < sides; ++i) {
      const float theta = 2.0f * pi * float(i) / float(sides);
      const float rho = major + minor * std::cos(theta);
      m.positions.push_back(
          centre + Vec3(rho * std::cos(phi), minor * std::sin(theta), rho * std::sin(phi)));
    }
  }
  auto at = [&](int j, int i) { return base + uint32_t((j % segments) * sides + i % sides); };
  for (int j = 0; j < segments; ++j) {
    // The tube's centre line beside this ring of quads is the inside to face away from.
    const float phi = 2.0f * pi * (float(j) + 0.5f) / float(segments);
    const Vec3 core = centre + major * Vec3(std::cos(phi), 0, std::sin(phi));
    for (int i = 0; i < sides; ++i)
      addOutward(m, {at(j, i), at(j + 1, i), at(j + 1, i + 1), at(j, i + 1)}, core);
  }
}

}  // namespace

Scene shaderBox(int k) {
  if (k < kLightFraction || k % kLightFraction != 0)
    throw Error(
        fmt::format("shader box: {} cells a side is not a multiple of {}", k, kLightFraction));
  // Named after the thesis's vertex counts (Test 1), which our meshes do not share.
  const char* name = k == 10   ? "shader-box-774"
                     : k == 20 ? "shader-box-2734"
                     : k == 40 ? "shader-box-10254"
                     : k == 50 ? "shader-box-15814"
                               : nullptr;
  return shaderBoxScene(name ? std::string(name) : fmt::format("shader-box-k{}", k), k);
}

Scene shaderSphereTorus() {
  Scene s = shaderBoxScene("shader-sphere-torus", 10);  // box-tess20
  // The sphere stands 2 cm off the floor (a point contact helps nobody), a little behind the
  // box's centre so that the camera sees it whole, and shadows the floor; the torus floats above
  // it, under the light, and shadows the sphere. Both white, as the box's walls.
  const float sphereRadius = 0.3f;
  const Vec3 sphereCentre(0, -kHalf + 0.02f + sphereRadius, -0.3f);
  Mesh sphere;
  sphere.name = "sphere";
  sphere.material = 0;
  addSphere(sphere, sphereCentre, sphereRadius, 24, 12);
  Mesh torus;
  torus.name = "torus";
  torus.material = 0;
  addTorus(torus, sphereCentre + Vec3(0, sphereRadius + 0.3f, 0), 0.25f, 0.07f, 32, 12);
  s.meshes.push_back(std::move(sphere));
  s.meshes.push_back(std::move(torus));
  // Looking down at them, so that the sphere's shadow on the floor is in the picture.
  Camera& camera = s.cameras.front();
  camera.eye = Vec3(0, 0.25f, kHalf - 0.03f);
  camera.target = Vec3(0, -0.3f, -0.6f);
  camera.fovY = 65.0f;
  return s;
}

}  // namespace luxel::builtin
