// The original Cornell box, from the Cornell Program of Computer Graphics measured data:
// https://www.graphics.cornell.edu/online/box/data.html (vertex data in millimetres).
#include "scene/builtin/builtin_scenes.h"

namespace luxel::builtin {
namespace {

constexpr float kMillimetre = 0.001f;

Vec3 mm(float x, float y, float z) { return Vec3(x, y, z) * kMillimetre; }

Mesh quadsMesh(const char* name, uint32_t material) {
  Mesh m;
  m.name = name;
  m.material = material;
  return m;
}

}  // namespace

Scene cornellBox() {
  Scene s;
  s.name = "cornell";
  enum : uint32_t { kWhite, kRed, kGreen, kLight };
  s.materials = {
      Material{.name = "white", .reflectance = Rgb(0.725f, 0.71f, 0.68f)},
      Material{.name = "red", .reflectance = Rgb(0.63f, 0.065f, 0.05f)},
      Material{.name = "green", .reflectance = Rgb(0.14f, 0.45f, 0.091f)},
      Material{.name = "light", .reflectance = Rgb(0.78f), .emission = Rgb(17.0f, 12.0f, 4.0f)},
  };

  Mesh floor = quadsMesh("floor", kWhite);
  addQuad(floor, mm(552.8f, 0, 0), mm(0, 0, 0), mm(0, 0, 559.2f), mm(549.6f, 0, 559.2f));

  // The measured ceiling has a hole for the light (x 213..343, z 227..332): four quads around it.
  Mesh ceiling = quadsMesh("ceiling", kWhite);
  const float y = 548.8f;
  addQuad(ceiling, mm(556, y, 0), mm(556, y, 227), mm(0, y, 227), mm(0, y, 0));
  addQuad(ceiling, mm(556, y, 332), mm(556, y, 559.2f), mm(0, y, 559.2f), mm(0, y, 332));
  addQuad(ceiling, mm(556, y, 227), mm(556, y, 332), mm(343, y, 332), mm(343, y, 227));
  addQuad(ceiling, mm(213, y, 227), mm(213, y, 332), mm(0, y, 332), mm(0, y, 227));

  Mesh light = quadsMesh("light", kLight);
  addQuad(light, mm(343, y, 227), mm(343, y, 332), mm(213, y, 332), mm(213, y, 227));

  Mesh back = quadsMesh("back wall", kWhite);
  addQuad(back, mm(549.6f, 0, 559.2f), mm(0, 0, 559.2f), mm(0, y, 559.2f), mm(556, y, 559.2f));

  Mesh right = quadsMesh("right wall", kGreen);
  addQuad(right, mm(0, 0, 559.2f), mm(0, 0, 0), mm(0, y, 0), mm(0, y, 559.2f));

  Mesh left = quadsMesh("left wall", kRed);
  addQuad(left, mm(552.8f, 0, 0), mm(549.6f, 0, 559.2f), mm(556, y, 559.2f), mm(556, y, 0));

  Mesh shortBlock = quadsMesh("short block", kWhite);
  addQuad(shortBlock, mm(130, 165, 65), mm(82, 165, 225), mm(240, 165, 272), mm(290, 165, 114));
  addQuad(shortBlock, mm(290, 0, 114), mm(290, 165, 114), mm(240, 165, 272), mm(240, 0, 272));
  addQuad(shortBlock, mm(130, 0, 65), mm(130, 165, 65), mm(290, 165, 114), mm(290, 0, 114));
  addQuad(shortBlock, mm(82, 0, 225), mm(82, 165, 225), mm(130, 165, 65), mm(130, 0, 65));
  addQuad(shortBlock, mm(240, 0, 272), mm(240, 165, 272), mm(82, 165, 225), mm(82, 0, 225));

  Mesh tallBlock = quadsMesh("tall block", kWhite);
  addQuad(tallBlock, mm(423, 330, 247), mm(265, 330, 296), mm(314, 330, 456), mm(472, 330, 406));
  addQuad(tallBlock, mm(423, 0, 247), mm(423, 330, 247), mm(472, 330, 406), mm(472, 0, 406));
  addQuad(tallBlock, mm(472, 0, 406), mm(472, 330, 406), mm(314, 330, 456), mm(314, 0, 456));
  addQuad(tallBlock, mm(314, 0, 456), mm(314, 330, 456), mm(265, 330, 296), mm(265, 0, 296));
  addQuad(tallBlock, mm(265, 0, 296), mm(265, 330, 296), mm(423, 330, 247), mm(423, 0, 247));

  s.meshes = {floor, ceiling, light, back, right, left, shortBlock, tallBlock};
  // focal length 35 mm on a 25 mm film: 2 atan(12.5 / 35) = 39.3077 degrees.
  s.cameras.push_back(Camera{.name = "default",
                             .eye = mm(278, 273, -800),
                             .target = mm(278, 273, 0),
                             .up = Vec3(0, 1, 0),
                             .fovY = 39.3077f});
  return s;
}

}  // namespace luxel::builtin
