#include "luxel/scene.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "luxel/error.h"

namespace luxel {
namespace {

bool finite(Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool inRange(Vec3 v) { return finite(v) && glm::all(glm::lessThanEqual(glm::abs(v), Vec3(kMaxCoordinate))); }

}  // namespace

size_t Scene::faceCount() const {
  size_t n = 0;
  for (const Mesh& m : meshes) n += m.faces.size();
  return n;
}

size_t Scene::triangleCount() const {
  size_t n = 0;
  for (const Mesh& m : meshes)
    for (const Face& f : m.faces) n += f.isTriangle() ? 1 : 2;
  return n;
}

const Camera* Scene::findCamera(const std::string& cameraName) const {
  for (const Camera& c : cameras)
    if (c.name == cameraName) return &c;
  return nullptr;
}

int Scene::findMaterial(const std::string& materialName) const {
  for (size_t i = 0; i < materials.size(); ++i)
    if (materials[i].name == materialName) return int(i);
  return -1;
}

bool Scene::hasLight() const {
  for (const Light& l : lights)
    if (l.intensity > 0.0f && (l.color.r > 0.0f || l.color.g > 0.0f || l.color.b > 0.0f)) return true;
  for (const Mesh& m : meshes)
    if (!m.faces.empty() && m.material < materials.size() && materials[m.material].isEmissive()) return true;
  return false;
}

void Scene::validate() const {
  if (faceCount() == 0) throw Error(fmt::format("scene '{}': contains no faces", name));
  validateMaterials();
  for (const Mesh& mesh : meshes) {
    if (mesh.material >= materials.size())
      throw Error(fmt::format("scene '{}': mesh '{}': material index {} out of range ({} materials)",
                              name, mesh.name, mesh.material, materials.size()));
    if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size())
      throw Error(fmt::format("scene '{}': mesh '{}': {} uvs for {} positions", name, mesh.name,
                              mesh.uvs.size(), mesh.positions.size()));
    if (!mesh.lightmapUvs.empty() && mesh.lightmapUvs.size() != mesh.positions.size())
      throw Error(fmt::format("scene '{}': mesh '{}': {} lightmap uvs for {} positions", name,
                              mesh.name, mesh.lightmapUvs.size(), mesh.positions.size()));
    for (size_t i = 0; i < mesh.lightmapUvs.size(); ++i)
      if (!std::isfinite(mesh.lightmapUvs[i].x) || !std::isfinite(mesh.lightmapUvs[i].y))
        throw Error(fmt::format("scene '{}': mesh '{}': lightmap uv {} is not finite", name,
                                mesh.name, i));
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      if (!finite(mesh.positions[i]))
        throw Error(fmt::format("scene '{}': mesh '{}': vertex {} is not finite", name, mesh.name, i));
      if (!inRange(mesh.positions[i]))
        throw Error(fmt::format("scene '{}': mesh '{}': vertex {} at ({:g}, {:g}, {:g}) is beyond {:g} scene units "
                                "from the origin, where areas overflow in float",
                                name, mesh.name, i, mesh.positions[i].x, mesh.positions[i].y, mesh.positions[i].z,
                                kMaxCoordinate));
    }
    for (size_t f = 0; f < mesh.faces.size(); ++f)
      for (uint32_t v : mesh.faces[f].v)
        if (v >= mesh.positions.size())
          throw Error(fmt::format("scene '{}': mesh '{}': face {} references vertex {} of {}", name,
                                  mesh.name, f, v, mesh.positions.size()));
    if (!mesh.elementGrids.empty() && mesh.elementGrids.size() != mesh.faces.size())
      throw Error(fmt::format("scene '{}': mesh '{}': {} element grids for {} faces", name,
                              mesh.name, mesh.elementGrids.size(), mesh.faces.size()));
    for (size_t f = 0; f < mesh.elementGrids.size(); ++f) {
      const auto [nu, nv] = mesh.elementGrids[f];
      // {0, 0} is automatic; a grid needs both counts, and a triangle the same count on both.
      if ((nu == 0) != (nv == 0) || (mesh.faces[f].isTriangle() && nu != nv))
        throw Error(fmt::format("scene '{}': mesh '{}': face {}: element grid {} x {} is invalid{}",
                                name, mesh.name, f, nu, nv,
                                mesh.faces[f].isTriangle() ? " for a triangle (needs n x n)" : ""));
    }
  }
  validateLights();
  for (const Camera& c : cameras)
    if (!inRange(c.eye) || !inRange(c.target) || !finite(c.up))
      throw Error(fmt::format("scene '{}': camera '{}': eye, target or up is not finite or beyond {:g} scene units "
                              "from the origin", name, c.name, kMaxCoordinate));
  if (glm::length(up) < 1e-12f || !finite(up))
    throw Error(fmt::format("scene '{}': up vector is zero or not finite", name));
  for (const Mesh& mesh : meshes)
    if (mesh.object != kNoObject && mesh.object >= objects.size())
      throw Error(fmt::format("scene '{}': mesh '{}': object index {} out of range ({} objects)", name, mesh.name,
                              mesh.object, objects.size()));
  validateAnimation();
}


void Scene::validateMaterials() const {
  for (const Material& m : materials) {
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(m.reflectance[c]) || m.reflectance[c] < 0.0f || m.reflectance[c] > 1.0f)
        throw Error(fmt::format("scene '{}': material '{}': reflectance {} is outside [0,1]", name,
                                m.name, m.reflectance[c]));
      if (!std::isfinite(m.emission[c]) || m.emission[c] < 0.0f)
        throw Error(fmt::format("scene '{}': material '{}': emission {} is negative or not finite",
                                name, m.name, m.emission[c]));
      if (m.emission[c] > kMaxRadiance)
        throw Error(fmt::format("scene '{}': material '{}': emission {:g} is over the limit of {:g} (a million "
                                "times the sun's radiance; the light would overflow in float)",
                                name, m.name, m.emission[c], kMaxRadiance));
      if (!std::isfinite(m.specular[c]) || m.specular[c] < 0.0f || m.specular[c] > 1.0f)
        throw Error(fmt::format("scene '{}': material '{}': specular {} is outside [0,1]", name,
                                m.name, m.specular[c]));
    }
    if (!std::isfinite(m.shininess) || m.shininess < 0.0f || m.shininess > kMaxShininess)
      throw Error(fmt::format("scene '{}': material '{}': shininess {} is outside [0, {:g}]", name,
                              m.name, m.shininess, kMaxShininess));
    if (!std::isfinite(m.normalScale))
      throw Error(fmt::format("scene '{}': material '{}': normal scale {} is not finite", name, m.name,
                              m.normalScale));
    for (int t : {m.reflectanceTexture, m.emissionTexture, m.normalTexture})
      if (t >= int(textures.size()))
        throw Error(fmt::format("scene '{}': material '{}': texture index {} out of range", name,
                                m.name, t));
  }
}

void Scene::validateLights() const {
  for (const Light& l : lights) {
    if (!finite(l.color) || !std::isfinite(l.intensity) || l.intensity < 0.0f ||
        l.color.r < 0.0f || l.color.g < 0.0f || l.color.b < 0.0f)
      throw Error(fmt::format("scene '{}': light '{}': colour or intensity is negative or not finite",
                              name, l.name));
    if (!finite(l.position) || !finite(l.direction))
      throw Error(fmt::format("scene '{}': light '{}': position or direction is not finite", name,
                              l.name));
    if (!inRange(l.position))
      throw Error(fmt::format("scene '{}': light '{}': position is beyond {:g} scene units from the origin", name,
                              l.name, kMaxCoordinate));
    if (l.intensity * std::max({l.color.r, l.color.g, l.color.b}) > kMaxRadiance)
      throw Error(fmt::format("scene '{}': light '{}': intensity {:g} times colour is over the limit of {:g} "
                              "(the light would overflow in float)",
                              name, l.name, l.intensity, kMaxRadiance));
    bool directed = l.type == Light::Type::Spot || l.type == Light::Type::Directional;
    if (directed && glm::length(l.direction) < 1e-12f)
      throw Error(fmt::format("scene '{}': light '{}': direction is zero", name, l.name));
  }
}

}  // namespace luxel
