// Applying affine transforms to meshes, lights and cameras (see transform.h).
#include "scene/import/transform.h"

#include <utility>

namespace luxel {
namespace {

Vec3 point(const glm::mat4& m, Vec3 p) { return Vec3(m * glm::vec4(p, 1.0f)); }

// Directions turn with the linear part and keep unit length; a degenerate transform (zero scale)
// leaves them as they were rather than producing NaN.
Vec3 direction(const glm::mat4& m, Vec3 d) {
  Vec3 t = glm::mat3(m) * d;
  float len = glm::length(t);
  return len > 0.0f ? t / len : d;
}

}  // namespace

void transformMesh(Mesh& mesh, const glm::mat4& m) {
  for (Vec3& p : mesh.positions) p = point(m, p);
  if (glm::determinant(glm::mat3(m)) < 0.0f) {
    for (Face& f : mesh.faces) {
      // (a,b,c,d) -> (a,d,c,b) for quads, (a,b,c,c) -> (a,c,b,b) for triangles.
      if (f.isTriangle()) {
        std::swap(f.v[1], f.v[2]);
        f.v[3] = f.v[2];
      } else {
        std::swap(f.v[1], f.v[3]);
      }
    }
    // s ran from corner 0 to corner 1 and t from corner 0 to corner 3: with those corners
    // swapped, so are the grid's counts along them (a triangle's {n, n} is unchanged).
    for (auto& grid : mesh.elementGrids) std::swap(grid[0], grid[1]);
  }
}

void transformLight(Light& light, const glm::mat4& m) {
  light.position = point(m, light.position);
  light.direction = direction(m, light.direction);
}

void transformCamera(Camera& camera, const glm::mat4& m) {
  camera.eye = point(m, camera.eye);
  camera.target = point(m, camera.target);
  camera.up = direction(m, camera.up);
}

}  // namespace luxel
