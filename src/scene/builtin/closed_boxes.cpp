// Closed enclosures with closed-form answers: the furnace and CIE 171:2006 test case 5.8.
#include <numbers>

#include "scene/builtin/builtin_scenes.h"

namespace luxel::builtin {

Scene furnace(float rho, float le) {
  Scene s;
  s.name = "furnace";
  s.materials.push_back(Material{.name = "furnace wall", .reflectance = Rgb(rho), .emission = Rgb(le)});
  Mesh box;
  box.name = "furnace box";
  addInwardBox(box, Vec3(0.0f), Vec3(1.0f));
  s.meshes.push_back(box);
  s.cameras.push_back(Camera{.name = "default",
                             .eye = Vec3(0.5f, 0.5f, 0.05f),
                             .target = Vec3(0.5f, 0.5f, 1.0f),
                             .up = Vec3(0, 1, 0),
                             .fovY = 90.0f});
  return s;
}

Scene cieCube(float rho, float flux) {
  Scene s;
  s.name = "cie-5.8";
  s.materials.push_back(Material{.name = "cube wall", .reflectance = Rgb(rho)});
  Mesh box;
  box.name = "cie cube";
  addInwardBox(box, Vec3(0.0f), Vec3(4.0f));
  s.meshes.push_back(box);
  // An isotropic point source radiates flux / (4 pi) in every direction.
  s.lights.push_back(Light{.type = Light::Type::Point,
                           .name = "isotropic source",
                           .color = Rgb(1.0f),
                           .intensity = flux / (4.0f * std::numbers::pi_v<float>),
                           .position = Vec3(2.0f)});
  s.cameras.push_back(Camera{.name = "default",
                             .eye = Vec3(2.0f, 2.0f, 0.1f),
                             .target = Vec3(2.0f, 2.0f, 4.0f),
                             .up = Vec3(0, 1, 0),
                             .fovY = 90.0f});
  return s;
}

}  // namespace luxel::builtin
