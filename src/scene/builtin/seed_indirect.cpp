// The "indirect light" test scene of seed 001: M. van de Hoef, "Real-Time Dynamic Radiosity for
// High Quality Global Illumination", Utrecht 2013, Sec. 5.1 (shared/seeds/notes/
// 001-dynamic-radiosity.md, section 5): "an indoor room", albedo 0.9 everywhere, lit only by
// indirect daylight entering at the right side, with a rotating box at the left side; 10,296
// static elements, 318 on the box. The thesis shows no geometry; ours is in docs/seed-scenes.md.
//
// The room's window faces away from the sun (a north window): sunlight falls on the ground and on
// a building across the street, and only their reflections come in. The room has thick walls: an
// outer shell shades the backs of the inner walls, which would otherwise receive the sun and be
// turned round by orientation repair.
#include <glm/geometric.hpp>

#include "scene/builtin/builtin_scenes.h"
#include "scene/builtin/seed_geometry.h"

namespace luxel::builtin {
namespace {

// The room inside: x across (the window wall at x = kW on the camera's right), y up, z deep.
constexpr float kW = 5.0f, kH = 2.5f, kD = 4.0f;
constexpr float kWall = 0.2f;  // wall and roof thickness
// The window in the right wall.
constexpr float kWinZ0 = 1.0f, kWinZ1 = 3.0f, kWinY0 = 0.9f, kWinY1 = 2.1f;
// Outside: the ground from the building to a facade across the street, which is as long as the
// ground and kFacadeHeight high.
constexpr float kStreet = 8.0f;
constexpr float kGroundZ0 = -4.0f, kGroundZ1 = 8.0f;
constexpr float kFacadeHeight = 6.0f;
constexpr float kAlbedo = 0.9f;  // "comparable to bright white paint", everywhere

}  // namespace

Scene indirectLight() {
  Scene s;
  s.name = "indirect-light";
  s.materials = {Material{.name = "paint", .reflectance = Rgb(kAlbedo)}};
  s.meshes.reserve(6);  // `mesh` hands out references into it
  auto mesh = [&](const char* name) -> Mesh& {
    s.meshes.push_back(Mesh{.name = name});
    return s.meshes.back();
  };
  const float t = kWall, xo = kW + t;  // the outer face of the window wall

  // Inner faces, 0.1 m elements, facing into the room: 2000 + 2000 + 1250 + 1250 + 1000 + 760.
  Mesh& room = mesh("room");
  addGridQuad(room, Vec3(0, 0, 0), Vec3(0, 0, kD), Vec3(kW, 0, 0), 40, 50);   // floor
  addGridQuad(room, Vec3(0, kH, 0), Vec3(kW, 0, 0), Vec3(0, 0, kD), 50, 40);  // ceiling
  addGridQuad(room, Vec3(0, 0, 0), Vec3(kW, 0, 0), Vec3(0, kH, 0), 50, 25);   // back wall
  addGridQuad(room, Vec3(0, 0, kD), Vec3(0, kH, 0), Vec3(kW, 0, 0), 25, 50);  // front wall
  addGridQuad(room, Vec3(0, 0, 0), Vec3(0, kH, 0), Vec3(0, 0, kD), 25, 40);   // left wall
  // The window wall, in four pieces round the opening (360 + 160 + 120 + 120).
  const Vec3 alongZ(0, 0, kD);
  addGridQuad(room, Vec3(kW, 0, 0), alongZ, Vec3(0, kWinY0, 0), 40, 9);
  addGridQuad(room, Vec3(kW, kWinY1, 0), alongZ, Vec3(0, kH - kWinY1, 0), 40, 4);
  addGridQuad(room, Vec3(kW, kWinY0, 0), Vec3(0, 0, kWinZ0), Vec3(0, kWinY1 - kWinY0, 0), 10, 12);
  addGridQuad(room, Vec3(kW, kWinY0, kWinZ1), Vec3(0, 0, kD - kWinZ1), Vec3(0, kWinY1 - kWinY0, 0),
              10, 12);

  // The window's reveals through the wall's thickness, facing into the opening (40 + 40 + 24 + 24).
  Mesh& reveals = mesh("window reveals");
  const float winW = kWinZ1 - kWinZ0, winH = kWinY1 - kWinY0;
  addGridQuad(reveals, Vec3(kW, kWinY0, kWinZ0), Vec3(0, 0, winW), Vec3(t, 0, 0), 20, 2);  // sill
  addGridQuad(reveals, Vec3(kW, kWinY1, kWinZ0), Vec3(t, 0, 0), Vec3(0, 0, winW), 2, 20);  // head
  addGridQuad(reveals, Vec3(kW, kWinY0, kWinZ0), Vec3(t, 0, 0), Vec3(0, winH, 0), 2, 12);
  addGridQuad(reveals, Vec3(kW, kWinY0, kWinZ1), Vec3(0, winH, 0), Vec3(t, 0, 0), 12, 2);

  // The outer shell, facing out, coarse (about 0.4 m): 154 + 77 + 98 + 98 + 22 + 22 + 9 + 9.
  Mesh& shell = mesh("outer walls");
  const Vec3 outX(kW + 2 * t, 0, 0), outY(0, kH + t, 0), outZ(0, 0, kD + 2 * t);
  addGridQuad(shell, Vec3(-t, kH + t, -t), outZ, outX, 11, 14);  // roof
  addGridQuad(shell, Vec3(-t, 0, -t), outZ, outY, 11, 7);        // left
  addGridQuad(shell, Vec3(-t, 0, -t), outY, outX, 7, 14);        // back
  addGridQuad(shell, Vec3(-t, 0, kD + t), outX, outY, 14, 7);    // front
  // The window wall's outer face, round the opening.
  addGridQuad(shell, Vec3(xo, 0, -t), Vec3(0, kWinY0, 0), outZ, 2, 11);
  addGridQuad(shell, Vec3(xo, kWinY1, -t), Vec3(0, kH + t - kWinY1, 0), outZ, 2, 11);
  addGridQuad(shell, Vec3(xo, kWinY0, -t), Vec3(0, winH, 0), Vec3(0, 0, kWinZ0 + t), 3, 3);
  addGridQuad(shell, Vec3(xo, kWinY0, kWinZ1), Vec3(0, winH, 0), Vec3(0, 0, kD + t - kWinZ1), 3, 3);

  // The sunlit ground (27 x 41 = 1107, about 0.3 m) and the facade across the street
  // (26 x 12 = 312, about 0.47 x 0.5 m), facing the window.
  Mesh& ground = mesh("ground");
  addGridQuad(ground, Vec3(xo, 0, kGroundZ0), Vec3(0, 0, kGroundZ1 - kGroundZ0),
              Vec3(kStreet, 0, 0), 41, 27);
  Mesh& facade = mesh("facade");
  addGridQuad(facade, Vec3(xo + kStreet, 0, kGroundZ0), Vec3(0, 0, kGroundZ1 - kGroundZ0),
              Vec3(0, kFacadeHeight, 0), 26, 12);

  // The box at the left side: 6 x 9 x 7 elements of 0.1 m (318), floating so it can turn freely.
  Mesh& box = mesh("box");
  addOutwardBox(box, Vec3(1.3f, 1.1f, 2.0f), Vec3(0.6f, 0.9f, 0.7f), 25.0f, 6, 9, 7);
  makeDynamicObject(s, box, "box", Vec3(1.3f, 1.1f, 2.0f));
  spinAboutVertical(s, box.object, kSeedBoxDegreesPerSecond);

  // The sun behind the building (towards -x, and a little towards the front), 49 degrees high:
  // it travels towards +x, so it can never shine in through a window facing +x.
  s.lights.push_back(Light{.type = Light::Type::Directional,
                           .name = "sun",
                           .color = Rgb(1.0f, 0.96f, 0.9f),
                           .intensity = 1000.0f,
                           .direction = glm::normalize(Vec3(0.55f, -0.75f, -0.35f)),
                           .angularRadius = 0.00465f});

  // From the front left corner, across the box to the window.
  s.cameras.push_back(Camera{.name = "default",
                             .eye = Vec3(0.2f, 1.7f, kD - 0.1f),
                             .target = Vec3(4.0f, 1.0f, 0.5f),
                             .up = Vec3(0, 1, 0),
                             .fovY = 70.0f});
  return s;
}

}  // namespace luxel::builtin
