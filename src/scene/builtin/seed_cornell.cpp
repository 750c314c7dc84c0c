// The Cornell box test scenes of seed 001: M. van de Hoef, "Real-Time Dynamic Radiosity for High
// Quality Global Illumination", Utrecht 2013, Sec. 5.1
// (shared/seeds/notes/001-dynamic-radiosity.md, section 5). "The classic Cornell box ... built to
// resemble" Meyer et al.'s antiradiance scene, with a relatively large ceiling light (or a small,
// more intense one) and a large rotating box in the centre. The thesis gives only element counts;
// what we chose is in docs/seed-scenes.md.
#include "scene/builtin/builtin_scenes.h"
#include "scene/builtin/seed_geometry.h"

namespace luxel::builtin {
namespace {

// A cube room about the size of the measured Cornell box.
constexpr float kRoom = 0.55f;
// The box: as wide as the Cornell tall block (0.165 m), 21/9 times as high so that its elements
// are square at 9 x 9 x 21; it floats at the room's centre, so it can turn any way without
// touching a wall, turned 20 degrees about the vertical for a less symmetric first pose.
constexpr float kBoxWidth = 0.165f;
constexpr float kBoxHeight = kBoxWidth * 21.0f / 9.0f;
constexpr float kBoxYaw = 20.0f;
// The large light is 12 x 14 elements of the 41 x 41 wall grid: 0.161 x 0.188 m.
constexpr float kLargeLightX = kRoom * 12.0f / 41.0f;
constexpr float kLargeLightZ = kRoom * 14.0f / 41.0f;
// Half the measured box's radiance: the light's share of the walls' area is twice the measured
// box's, so the room is about as bright as `cornell`.
const Rgb kLargeLightRadiance(8.5f, 6.0f, 2.0f);
// The small light is a third of the large one's width and length, nine times as intense: the
// same power.
constexpr float kSmallLightScale = 1.0f / 3.0f;

struct CornellGrids {
  int wall;            // each of the six walls: wall x wall elements
  int lightX, lightZ;  // light elements along x and z
  int boxSide, boxHeight;
};

Scene seedCornell(const char* name, const CornellGrids& g, float lightScale) {
  Scene s;
  s.name = name;
  enum : uint32_t { kWhite, kRed, kGreen, kLight, kBox };
  const Rgb white(0.725f, 0.71f, 0.68f);
  s.materials = {
      Material{.name = "white", .reflectance = white},
      Material{.name = "red", .reflectance = Rgb(0.63f, 0.065f, 0.05f)},
      Material{.name = "green", .reflectance = Rgb(0.14f, 0.45f, 0.091f)},
      Material{.name = "light",
               .reflectance = Rgb(0.78f),
               .emission = kLargeLightRadiance / (lightScale * lightScale)},
      Material{.name = "box", .reflectance = white},
  };
  auto wall = [&](const char* wallName, uint32_t material, Vec3 origin, Vec3 u, Vec3 v) {
    Mesh m;
    m.name = wallName;
    m.material = material;
    addGridQuad(m, origin, u, v, g.wall, g.wall);
    s.meshes.push_back(std::move(m));
  };
  const float L = kRoom;
  const Vec3 X(L, 0, 0), Y(0, L, 0), Z(0, 0, L);
  // Inward faces (u x v points into the room); x = 0 is on the camera's left.
  wall("floor", kWhite, Vec3(0), Z, X);

  // The ceiling has a hole for the light, and the light fills it, in the ceiling's plane (as in
  // `cornell`). A panel hung under a whole ceiling would hide part of the ceiling's patches, and
  // what those patches shoot at the hidden part would hit the light's back and be lost. The
  // ceiling is four quads round the hole that keep its wall x wall elements: front and back
  // strips across the whole width, wall columns each and together wall - lightZ rows, and a left
  // and a right piece beside the hole, lightZ rows each and together wall columns; so the
  // ceiling has wall (wall - lightZ) + lightZ wall = wall^2 elements, as a whole face would.
  // Every quad is written from the same corner coordinates, so shared edges coincide exactly.
  const float lx = kLargeLightX * lightScale, lz = kLargeLightZ * lightScale;
  const float x0 = 0.5f * (L - lx), x1 = x0 + lx, z0 = 0.5f * (L - lz), z1 = z0 + lz;
  // The rectangle [xa, xb] x [za, zb] of the ceiling's plane, nu x nv elements; x cross z = -y,
  // so it faces down, into the room.
  auto ceilingQuad = [&](Mesh& m, float xa, float xb, float za, float zb, int nu, int nv) {
    auto base = uint32_t(m.positions.size());
    m.positions.insert(m.positions.end(),
                       {Vec3(xa, L, za), Vec3(xb, L, za), Vec3(xb, L, zb), Vec3(xa, L, zb)});
    m.uvs.insert(m.uvs.end(), {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)});
    m.faces.push_back(Face{{base, base + 1, base + 2, base + 3}});
    m.elementGrids.push_back({uint16_t(nu), uint16_t(nv)});
  };
  const int n = g.wall, front = (n - g.lightZ) / 2, back = n - g.lightZ - front, left = n / 2,
            right = n - left;
  Mesh ceiling;
  ceiling.name = "ceiling";
  ceiling.material = kWhite;
  ceilingQuad(ceiling, 0, L, 0, z0, n, front);
  ceilingQuad(ceiling, 0, L, z1, L, n, back);
  ceilingQuad(ceiling, 0, x0, z0, z1, left, g.lightZ);
  ceilingQuad(ceiling, x1, L, z0, z1, right, g.lightZ);
  s.meshes.push_back(std::move(ceiling));

  wall("back wall", kWhite, Vec3(0), X, Y);
  wall("front wall", kWhite, Z, Y, X);
  wall("left wall", kRed, Vec3(0), Y, Z);
  wall("right wall", kGreen, X, Z, Y);

  // The light fills the ceiling's hole, from the same corners, facing down.
  Mesh light;
  light.name = "light";
  light.material = kLight;
  ceilingQuad(light, x0, x1, z0, z1, g.lightX, g.lightZ);
  s.meshes.push_back(std::move(light));

  Mesh box;
  box.name = "box";
  box.material = kBox;
  addOutwardBox(box, Vec3(0.5f * L), Vec3(kBoxWidth, kBoxHeight, kBoxWidth), kBoxYaw, g.boxSide,
                g.boxHeight, g.boxSide);
  s.meshes.push_back(std::move(box));
  makeDynamicObject(s, s.meshes.back(), "box", Vec3(0.5f * L));
  spinAboutVertical(s, s.meshes.back().object, kSeedBoxDegreesPerSecond);

  // The room is closed, so the camera stands inside it, high in the front left corner, looking
  // down across the box (seen from the front wall's centre, the box would fill the picture).
  s.cameras.push_back(Camera{.name = "default",
                             .eye = Vec3(0.03f, 0.52f, 0.53f),
                             .target = Vec3(0.4f, 0.1f, 0.1f),
                             .up = Vec3(0, 1, 0),
                             .fovY = 72.0f});
  return s;
}

}  // namespace

// 6 x 41^2 + 12 x 14 = 10,254 static elements; box 2 x 9^2 + 4 x 9 x 21 = 918.
Scene cornellLarge() {
  return seedCornell("cornell-large",
                     {.wall = 41, .lightX = 12, .lightZ = 14, .boxSide = 9, .boxHeight = 21}, 1.0f);
}

// As cornell-large with a light a third the size, 9 times the radiance; the light keeps its
// 12 x 14 elements, so the counts are cornell-large's.
Scene cornellSmall() {
  return seedCornell("cornell-small",
                     {.wall = 41, .lightX = 12, .lightZ = 14, .boxSide = 9, .boxHeight = 21},
                     kSmallLightScale);
}

// cornell-large's geometry, coarser: 6 x 21^2 + 8 x 11 = 2,734 static; box 2 x 5^2 + 4 x 5 x 11
// = 270.
Scene cornellLow() {
  return seedCornell("cornell-low",
                     {.wall = 21, .lightX = 8, .lightZ = 11, .boxSide = 5, .boxHeight = 11}, 1.0f);
}

}  // namespace luxel::builtin
