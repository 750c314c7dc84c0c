// Quads with prescribed element grids, for the seed papers' test scenes (docs/seed-scenes.md).
#include "scene/builtin/seed_geometry.h"

#include <array>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace luxel::builtin {
namespace {

std::array<uint16_t, 2> grid(int nu, int nv) { return {uint16_t(nu), uint16_t(nv)}; }

}  // namespace

void addGridQuad(Mesh& mesh, Vec3 origin, Vec3 u, Vec3 v, int nu, int nv) {
  auto base = uint32_t(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), {origin, origin + u, origin + u + v, origin + v});
  mesh.uvs.insert(mesh.uvs.end(), {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)});
  mesh.faces.push_back(Face{{base, base + 1, base + 2, base + 3}});
  mesh.elementGrids.push_back(grid(nu, nv));
}

void addCellGrid(Mesh& mesh, Vec3 origin, Vec3 u, Vec3 v, int nu, int nv,
                 const std::function<bool(int i, int j)>& skip) {
  auto base = uint32_t(mesh.positions.size());
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      const float s = float(i) / float(nu), t = float(j) / float(nv);
      mesh.positions.push_back(origin + s * u + t * v);
      mesh.uvs.emplace_back(s, t);
    }
  auto at = [&](int i, int j) { return base + uint32_t(j * (nu + 1) + i); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      if (skip && skip(i, j)) continue;
      mesh.faces.push_back(Face{{at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}});
      mesh.elementGrids.push_back(grid(1, 1));
    }
}

void addOutwardBox(Mesh& mesh, Vec3 centre, Vec3 size, float yawDegrees, int nx, int ny, int nz) {
  const float a = glm::radians(yawDegrees), c = std::cos(a), s = std::sin(a);
  // Turning about +y: x goes towards -z for a positive angle (right-handed).
  auto turn = [&](Vec3 p) { return Vec3(c * p.x + s * p.z, p.y, -s * p.x + c * p.z); };
  const Vec3 h = 0.5f * size, ex(size.x, 0, 0), ey(0, size.y, 0), ez(0, 0, size.z);
  auto face = [&](Vec3 corner, Vec3 u, Vec3 v, int nu, int nv) {
    addGridQuad(mesh, centre + turn(corner), turn(u), turn(v), nu, nv);
  };
  // Each (u, v) pair is ordered so that u x v points out of the box.
  face({h.x, -h.y, -h.z}, ey, ez, ny, nz);   // +x
  face({-h.x, -h.y, -h.z}, ez, ey, nz, ny);  // -x
  face({-h.x, h.y, -h.z}, ez, ex, nz, nx);   // +y (top)
  face({-h.x, -h.y, -h.z}, ex, ez, nx, nz);  // -y (bottom)
  face({-h.x, -h.y, h.z}, ex, ey, nx, ny);   // +z
  face({-h.x, -h.y, -h.z}, ey, ex, ny, nx);  // -z
}

void makeDynamicObject(Scene& scene, Mesh& mesh, const std::string& name, Vec3 centre) {
  mesh.object = uint32_t(scene.objects.size());
  scene.objects.push_back(Object{.name = name, .transform = glm::translate(glm::mat4(1.0f), centre), .dynamic = true});
}

void spinAboutVertical(Scene& scene, uint32_t object, double degreesPerSecond) {
  const glm::mat4& rest = scene.objects[object].transform;
  scene.animation.objects.push_back(ObjectAnimation{
      .object = object,
      .rest = rest,
      .motion = {.spin = Spin{.axis = Vec3(0, 1, 0), .pivot = Vec3(rest[3]), .degreesPerSecond = degreesPerSecond}}});
}

}  // namespace luxel::builtin
