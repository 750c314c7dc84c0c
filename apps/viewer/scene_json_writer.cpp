#include "scene_json_writer.h"

#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "io/atomic_file.h"
#include "luxel/error.h"

namespace luxel::viewer {
namespace {

using Json = nlohmann::ordered_json;

Json vec(const Vec3& v) { return Json::array({v.x, v.y, v.z}); }
float degrees(float radians) { return radians * 180.0f / 3.14159265358979f; }

Json lightJson(const Light& l) {
  Json j;
  switch (l.type) {
    case Light::Type::Point: j["type"] = "point"; break;
    case Light::Type::Spot: j["type"] = "spot"; break;
    case Light::Type::Directional: j["type"] = "directional"; break;
    case Light::Type::Sky: j["type"] = "sky"; break;
    case Light::Type::CieOvercastSky: j["type"] = "cie-overcast"; break;
  }
  if (!l.name.empty()) j["name"] = l.name;
  j["color"] = vec(l.color);
  j["intensity"] = l.intensity;
  if (l.type == Light::Type::Point || l.type == Light::Type::Spot) j["position"] = vec(l.position);
  if (l.type == Light::Type::Spot || l.type == Light::Type::Directional) j["direction"] = vec(l.direction);
  if (l.type == Light::Type::Spot) {
    j["innerConeAngle"] = degrees(l.innerConeAngle);
    j["outerConeAngle"] = degrees(l.outerConeAngle);
  }
  if (l.type == Light::Type::Directional) j["angularRadius"] = degrees(l.angularRadius);
  return j;
}

}  // namespace

std::string sceneJson(const Scene& edited, const Scene& loaded, const std::string& baseSpec, const Camera& camera) {
  Json doc;
  doc["name"] = edited.name;
  doc["base"] = baseSpec;

  Json objects = Json::object();
  for (size_t o = 0; o < edited.objects.size() && o < loaded.objects.size(); ++o) {
    const Object& e = edited.objects[o];
    const bool moved = e.transform != loaded.objects[o].transform;
    if (!moved && e.dynamic == loaded.objects[o].dynamic) continue;
    size_t sharing = 0;
    for (const Object& other : edited.objects) sharing += other.name == e.name;
    if (sharing > 1)
      throw Error(fmt::format("cannot save the scene: object '{}' was edited and {} objects share its name, which a "
                              "scene file cannot tell apart",
                              e.name, sharing));
    Json spec;
    spec["dynamic"] = e.dynamic;
    if (moved) {
      Json rows = Json::array();
      for (int r = 0; r < 4; ++r) rows.push_back(Json::array({e.transform[0][r], e.transform[1][r], e.transform[2][r], e.transform[3][r]}));
      spec["transform"] = rows;
    }
    objects[e.name] = spec;
  }
  if (!objects.empty()) doc["objects"] = objects;

  Json materials = Json::object();
  for (size_t m = 0; m < edited.materials.size() && m < loaded.materials.size(); ++m) {
    const Material& e = edited.materials[m];
    if (e.reflectance == loaded.materials[m].reflectance && e.emission == loaded.materials[m].emission) continue;
    materials[e.name] = Json{{"reflectance", vec(e.reflectance)}, {"emission", vec(e.emission)}};
  }
  if (!materials.empty()) doc["materials"] = materials;

  doc["replaceLights"] = true;
  Json lights = Json::array();
  for (const Light& l : edited.lights) lights.push_back(lightJson(l));
  doc["lights"] = lights;

  Json cam;
  cam["name"] = "viewer";
  cam["eye"] = vec(camera.eye);
  cam["target"] = vec(camera.target);
  cam["up"] = vec(camera.up);
  cam["fov"] = camera.fovY;
  doc["cameras"] = Json::array({cam});
  return doc.dump(2) + "\n";
}

void writeSceneJson(const std::filesystem::path& path, const Scene& edited, const Scene& loaded,
                    const std::string& baseSpec, const Camera& camera) {
  writeTextAtomically(path, sceneJson(edited, loaded, baseSpec, camera));
}

}  // namespace luxel::viewer
