// Objects of a scene (luxel/scene.h): finding them, and moving the dynamic ones.
#include <cmath>

#include <fmt/format.h>

#include "luxel/error.h"
#include "luxel/scene.h"

namespace luxel {

int Scene::findObject(const std::string& objectName) const {
  for (size_t i = 0; i < objects.size(); ++i)
    if (objects[i].name == objectName) return int(i);
  return -1;
}

std::vector<uint32_t> Scene::dynamicObjects() const {
  std::vector<uint32_t> out;
  for (uint32_t i = 0; i < objects.size(); ++i)
    if (objects[i].dynamic) out.push_back(i);
  return out;
}

glm::mat4 similarityBetween(const glm::mat4& from, const glm::mat4& to, const std::string& what, float* scale) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(to[c][r])) throw Error(fmt::format("{}: transform is not finite", what));
  if (std::abs(glm::determinant(from)) < 1e-30f) throw Error(fmt::format("{}: its transform cannot be inverted", what));
  const glm::mat4 delta = to * glm::inverse(from);
  const glm::vec3 x(delta[0]), y(delta[1]), z(delta[2]);
  const float s = std::cbrt(glm::determinant(glm::mat3(delta)));
  const float tolerance = 1e-4f * std::max(s, 1e-30f);
  const bool similar = s > 0.0f && std::abs(glm::length(x) - s) < tolerance && std::abs(glm::length(y) - s) < tolerance &&
                       std::abs(glm::length(z) - s) < tolerance && std::abs(glm::dot(x, y)) < tolerance * s &&
                       std::abs(glm::dot(y, z)) < tolerance * s && std::abs(glm::dot(z, x)) < tolerance * s &&
                       std::abs(delta[0][3]) + std::abs(delta[1][3]) + std::abs(delta[2][3]) < 1e-6f &&
                       std::abs(delta[3][3] - 1.0f) < 1e-6f;
  if (!similar)
    throw Error(fmt::format("{}: a move must be a rotation, a translation and a uniform positive scale "
                            "(no mirror, shear or projection)",
                            what));
  if (scale) *scale = s;
  return delta;
}

void Scene::checkPlacement(uint32_t object, const glm::mat4& transform) const {
  if (object >= objects.size())
    throw Error(fmt::format("scene '{}': no object {} ({} objects)", name, object, objects.size()));
  const Object& o = objects[object];
  if (!o.dynamic) throw Error(fmt::format("scene '{}': object '{}' is not dynamic, so it cannot move", name, o.name));
  similarityBetween(o.transform, transform, fmt::format("scene '{}': object '{}'", name, o.name));
}

void Scene::placeObject(uint32_t object, const glm::mat4& transform) {
  checkPlacement(object, transform);  // before anything changes
  Object& o = objects[object];
  // The first move records every mesh's rest pose; later poses are computed from it.
  bool captured = false;
  for (const Mesh& m : meshes) captured = captured || (m.object == object && !m.restPositions.empty());
  if (!captured) {
    for (Mesh& m : meshes)
      if (m.object == object) m.restPositions = m.positions;
    o.restTransform = o.transform;
  }
  const glm::mat4 delta = transform * glm::inverse(o.restTransform);
  for (Mesh& m : meshes) {
    if (m.object != object) continue;
    for (size_t i = 0; i < m.positions.size(); ++i) m.positions[i] = Vec3(delta * glm::vec4(m.restPositions[i], 1.0f));
  }
  o.transform = transform;
}

}  // namespace luxel
