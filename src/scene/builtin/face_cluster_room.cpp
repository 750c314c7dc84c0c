// The test scene of seed 002: E. Gobbetti, L. Spanò and M. Agus, "Hierarchical Higher Order Face
// Cluster Radiosity for Global Illumination Walkthroughs of Complex Non-Diffuse Environments",
// Eurographics 2003, Sec. 4 (shared/seeds/notes/002-face-cluster-radiosity.md, sections 3 and 4):
// "a closed rectangular room (6m x 5m x 4m)" with coloured walls, "a single area light (power =
// 10925W)", "three high resolution scanned models ... and a polygonized implicit surface (the
// pedestal)", average reflectivity 0.67, in versions of 160K to 1.5M faces made by quadric-based
// simplification. The statues are not named in the paper; ours are the Stanford bunny
// (statue_mesh.h makes it any face count). What we chose is in docs/seed-scenes.md.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <glm/gtc/constants.hpp>
#include <string>
#include <vector>

#include "luxel/error.h"
#include "luxel/import.h"
#include "scene/builtin/builtin_scenes.h"
#include "scene/builtin/seed_geometry.h"
#include "scene/builtin/statue_mesh.h"

#ifndef LUXEL_BUNNY_OBJ
#error "LUXEL_BUNNY_OBJ (the unzipped Stanford bunny's path) is set by CMakeLists.txt"
#endif

namespace luxel::builtin {
namespace {

// The room, metres, y up: x in [0, 6], y in [0, 4], z in [0, 5].
constexpr float kWidth = 6.0f, kHeight = 4.0f, kDepth = 5.0f;
// Walls are grids of 25 cm quads, one element each, that meet edge to edge at the room's corners
// (24 x 16 x 20 cells), so the room is a closed mesh and its walls are not single huge faces.
constexpr float kCell = 0.25f;
// The light: a 1 x 1 m panel in a hole at the ceiling's centre, flush with it (as `cornell`'s and
// the seed Cornell boxes' lights: a panel hung below a whole ceiling would hide the ceiling above
// it, and open a slit to the outside if hung below a hole). White, of the paper's total power.
constexpr int kLightCells = 4;
constexpr float kLightPower = 10925.0f;  // W, over the hemisphere, each channel
// Pedestals: a superellipse |r/a|^p + |y/b|^p = 1 turned about the vertical (a rounded column,
// the implicit surface polygonised on its own parameter grid), sunk 1 cm into the floor so that
// its flat base is never in the floor's plane.
constexpr float kPedestalRadius = 0.45f, kPedestalHeight = 0.8f, kPedestalExponent = 8.0f;
constexpr int kPedestalSegments = 64, kPedestalRings = 48;
constexpr float kFloorSink = 0.01f;
// Statues: the bunny scaled to 1 m tall, sunk 5 mm into its pedestal's top (which sags a few mm
// towards its rounded rim) so that its feet touch it.
constexpr float kStatueHeight = 1.0f, kStatueSink = 0.005f;
struct Stand {
  float x, z, yawDegrees;
};
constexpr Stand kStands[3] = {{1.7f, 2.3f, 30.0f}, {3.0f, 2.0f, -20.0f}, {4.3f, 2.3f, 200.0f}};

// Reflectances. The paper gives only the average, 0.67 (the mean of the three channels weighted
// by area, over every face of the scene, the light's included). The red and green walls, the
// grey floor, the stone pedestals and the statues are set; the white of the ceiling, back and
// front walls is what makes the average 0.67:
//   areas (m^2): ceiling 29 and light 1, back and front walls 24 each, red and green walls 20
//   each, floor 30, three pedestals 3 x 3.20, three statues 3 x 2.44 (the bunny at 1 m tall,
//   the same to 0.1% at every face count): 164.9 in all, so sum(A rho) = 0.67 x 164.9 = 110.5.
//   Set: floor 30 x 0.58 + coloured walls 40 x 0.40 + light 0.78 + pedestals 9.60 x 0.66
//   + statues 7.32 x 0.72 = 45.8; the white's 77 m^2 take the rest, 64.7: a mean of 0.84.
// (tests/unit/test_face_cluster_room.cpp checks the average from the faces.)
const Rgb kWhite(0.85f, 0.84f, 0.83f);
const Rgb kFloor(0.62f, 0.58f, 0.54f);
const Rgb kRed(0.75f, 0.27f, 0.18f);
const Rgb kGreen(0.25f, 0.65f, 0.30f);
const Rgb kLightReflectance(0.78f);
const Rgb kPedestal(0.68f, 0.66f, 0.64f);
const Rgb kStatue(0.76f, 0.72f, 0.68f);
const Rgb kGlossSpecular(0.2f);
constexpr float kGlossExponent = 10.0f;

// The bunny from shared/scenes, welded, standing on y = 0 and centred on the y axis, 1 m tall.
// Read once per process: every ladder level starts from it.
TriangleMesh loadBunny() {
  const std::filesystem::path path = LUXEL_BUNNY_OBJ;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error(fmt::format(
        "seed 002's room needs the Stanford bunny at {}, unzipped there from stanford-bunny.zip "
        "when CMake configures with -DLUXEL_SCENES_DIR=<the folder of the shared scenes>",
        path.string()));
  TriangleMesh m = weldedTriangles(importMeshFile(path));
  Vec3 lo(INFINITY), hi(-INFINITY);
  for (Vec3 p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const float scale = kStatueHeight / (hi.y - lo.y);
  const Vec3 foot(0.5f * (lo.x + hi.x), lo.y, 0.5f * (lo.z + hi.z));
  for (Vec3& p : m.positions) p = scale * (p - foot);
  return m;
}

const TriangleMesh& bunny() {
  static const TriangleMesh mesh = loadBunny();
  return mesh;
}

// The pedestal standing on the floor at (x, z): rings at equal arc length along the superellipse
// profile from the bottom pole to the top pole, quads between rings, triangle fans at the poles,
// every face outward.
void addPedestal(Mesh& m, float x, float z) {
  const float a = kPedestalRadius, b = 0.5f * kPedestalHeight, e = 2.0f / kPedestalExponent;
  const float halfPi = glm::half_pi<float>();
  // The profile (r, y) for theta in [-pi/2, pi/2]: r = a cos^e, y = b sin^e (signed).
  auto profile = [&](float theta) {
    const float c = std::cos(theta), s = std::sin(theta);
    return Vec2(a * std::pow(std::max(c, 0.0f), e), b * std::copysign(std::pow(std::abs(s), e), s));
  };
  constexpr int kSamples = 4096;
  std::vector<Vec2> dense(kSamples + 1);
  std::vector<float> length(kSamples + 1, 0.0f);
  for (int i = 0; i <= kSamples; ++i) {
    dense[i] = profile(-halfPi + glm::pi<float>() * float(i) / float(kSamples));
    if (i > 0) length[i] = length[i - 1] + glm::length(dense[i] - dense[i - 1]);
  }
  const Vec3 centre(x, b - kFloorSink, z);
  const auto bottom = uint32_t(m.positions.size());
  m.positions.push_back(centre + Vec3(0, dense.front().y, 0));
  for (int k = 1, i = 0; k < kPedestalRings; ++k) {
    const float want = length.back() * float(k) / float(kPedestalRings);
    while (length[i + 1] < want) ++i;
    const float t = (want - length[i]) / (length[i + 1] - length[i]);
    const Vec2 p = glm::mix(dense[i], dense[i + 1], t);
    for (int j = 0; j < kPedestalSegments; ++j) {
      const float phi = glm::two_pi<float>() * float(j) / float(kPedestalSegments);
      m.positions.push_back(centre + Vec3(p.x * std::cos(phi), p.y, p.x * std::sin(phi)));
    }
  }
  const auto top = uint32_t(m.positions.size());
  m.positions.push_back(centre + Vec3(0, dense.back().y, 0));
  auto at = [&](int k, int j) {
    return bottom + 1 + uint32_t((k - 1) * kPedestalSegments + j % kPedestalSegments);
  };
  // Along a ring phi runs from +x towards +z, so up x (towards +z) points out at +x.
  for (int j = 0; j < kPedestalSegments; ++j) {
    m.faces.push_back(Face{{bottom, at(1, j), at(1, j + 1), at(1, j + 1)}});
    for (int k = 1; k + 1 < kPedestalRings; ++k)
      m.faces.push_back(Face{{at(k, j), at(k + 1, j), at(k + 1, j + 1), at(k, j + 1)}});
    const int last = kPedestalRings - 1;
    m.faces.push_back(Face{{top, at(last, j + 1), at(last, j), at(last, j)}});
  }
}

// `statue` turned by `yawDegrees` about the vertical and set with its foot at `foot`.
void addStatue(Mesh& m, const TriangleMesh& statue, Vec3 foot, float yawDegrees) {
  const float angle = glm::radians(yawDegrees), c = std::cos(angle), s = std::sin(angle);
  const auto base = uint32_t(m.positions.size());
  for (Vec3 p : statue.positions)
    m.positions.push_back(foot + Vec3(c * p.x + s * p.z, p.y, -s * p.x + c * p.z));
  for (const auto& [a, b, t] : statue.triangles)
    m.faces.push_back(Face{{base + a, base + b, base + t, base + t}});
}

std::string roomName(size_t faces) {
  for (const RoomRung& r : kRoomLadder)
    if (r.faces == faces) return r.name;
  return fmt::format("room-{}", faces);
}

}  // namespace

Scene faceClusterRoom(size_t faces) {
  Scene s;
  s.name = roomName(faces);
  enum : uint32_t { kWhiteMat, kFloorMat, kRedMat, kGreenMat, kLightMat, kPedestalMat, kStatueMat };
  const float lightArea = float(kLightCells * kLightCells) * kCell * kCell;
  s.materials = {
      Material{.name = "white", .reflectance = kWhite},
      Material{.name = "floor", .reflectance = kFloor},
      Material{.name = "red", .reflectance = kRed},
      Material{.name = "green", .reflectance = kGreen},
      // A Lambertian panel of power P and area A has radiance P / (pi A).
      Material{.name = "light",
               .reflectance = kLightReflectance,
               .emission = Rgb(kLightPower / (glm::pi<float>() * lightArea))},
      // The paper's glossy models and pedestals, Phong exponent 10, for display (the transport is
      // diffuse, as there); the paper gives no specular colour, and 0.2 keeps reflectance plus
      // specular under 1 on both.
      Material{.name = "pedestal", .reflectance = kPedestal, .specular = kGlossSpecular, .shininess = kGlossExponent},
      Material{.name = "statue", .reflectance = kStatue, .specular = kGlossSpecular, .shininess = kGlossExponent},
  };
  const Vec3 X(kWidth, 0, 0), Y(0, kHeight, 0), Z(0, 0, kDepth);
  const int nx = int(std::lround(kWidth / kCell)), ny = int(std::lround(kHeight / kCell)),
            nz = int(std::lround(kDepth / kCell));
  const int lx = (nx - kLightCells) / 2, lz = (nz - kLightCells) / 2;
  auto inLight = [=](int i, int j) {
    return i >= lx && i < lx + kLightCells && j >= lz && j < lz + kLightCells;
  };
  auto wall = [&](const char* name, uint32_t material, Vec3 origin, Vec3 u, Vec3 v, int nu, int nv,
                  bool lightHole = false) {
    Mesh m;
    m.name = name;
    m.material = material;
    addCellGrid(m, origin, u, v, nu, nv,
                lightHole ? std::function<bool(int, int)>(inLight) : nullptr);
    s.meshes.push_back(std::move(m));
  };
  // Inward faces (u x v points into the room); x = 0 is on the default camera's left.
  wall("floor", kFloorMat, Vec3(0), Z, X, nz, nx);
  wall("ceiling", kWhiteMat, Y, X, Z, nx, nz, true);
  wall("back wall", kWhiteMat, Vec3(0), X, Y, nx, ny);
  wall("front wall", kWhiteMat, Z, Y, X, ny, nx);
  wall("left wall", kRedMat, Vec3(0), Y, Z, ny, nz);
  wall("right wall", kGreenMat, X, Z, Y, nz, ny);

  // The ceiling's missing cells, in the ceiling's plane, facing down.
  Mesh light;
  light.name = "light";
  light.material = kLightMat;
  const float side = float(kLightCells) * kCell;
  addCellGrid(light, Vec3(float(lx) * kCell, kHeight, float(lz) * kCell), Vec3(side, 0, 0),
              Vec3(0, 0, side), kLightCells, kLightCells);
  s.meshes.push_back(std::move(light));

  for (int i = 0; i < 3; ++i) {
    Mesh pedestal;
    pedestal.name = fmt::format("pedestal {}", i + 1);
    pedestal.material = kPedestalMat;
    addPedestal(pedestal, kStands[i].x, kStands[i].z);
    s.meshes.push_back(std::move(pedestal));
  }

  // The statues take what the room and pedestals leave of the face count (Scene::faceCount: a
  // quad is one face, one leaf of the face-cluster hierarchy), shared equally; all three are the
  // same simplified mesh.
  const size_t fixed = s.faceCount();
  constexpr size_t kMinStatue = 1000;
  if (faces < fixed + 3 * kMinStatue)
    throw Error(fmt::format("{}: the room and pedestals alone have {} faces; ask for at least {}",
                            s.name, fixed, fixed + 3 * kMinStatue));
  const TriangleMesh statue = withTriangleCount(bunny(), (faces - fixed) / 3);
  const float pedestalTop = kPedestalHeight - kFloorSink;
  for (int i = 0; i < 3; ++i) {
    Mesh m;
    m.name = fmt::format("statue {}", i + 1);
    m.material = kStatueMat;
    addStatue(m, statue, Vec3(kStands[i].x, pedestalTop - kStatueSink, kStands[i].z),
              kStands[i].yawDegrees);
    s.meshes.push_back(std::move(m));
  }

  // Inside, against the front wall at eye height, looking down at the statues: the red and
  // green walls at the edges of the picture.
  s.cameras.push_back(Camera{.name = "default",
                             .eye = Vec3(0.5f * kWidth, 1.9f, kDepth - 0.05f),
                             .target = Vec3(0.5f * kWidth, 1.1f, 2.0f),
                             .up = Vec3(0, 1, 0),
                             .fovY = 70.0f});
  return s;
}

}  // namespace luxel::builtin
