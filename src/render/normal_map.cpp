#include "render/normal_map.h"

#include <cmath>

namespace luxel {
namespace {

// Below this sine of the angle between a face's two uv edges, its uvs span no usable area.
constexpr float kMinUvSine = 1e-6f;

bool finite(Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

TangentFrame faceTangentFrame(const Mesh& mesh, uint32_t face, Vec3 n) {
  TangentFrame frame;
  if (mesh.uvs.empty() || face >= mesh.faces.size()) return frame;
  const Face& f = mesh.faces[face];
  // Two edges from a common start: a triangle's sides, or a quad's diagonals, whose uv differences
  // give dp/du and dp/dv exactly when the quad is planar with affine uvs (a parallelogram's
  // diagonals span it) and average the two triangles otherwise.
  const bool tri = f.isTriangle();
  const Vec3 e1 = mesh.positions[f.v[tri ? 1 : 2]] - mesh.positions[f.v[0]];
  const Vec3 e2 = mesh.positions[f.v[tri ? 2 : 3]] - mesh.positions[f.v[tri ? 0 : 1]];
  const Vec2 d1 = mesh.uvs[f.v[tri ? 1 : 2]] - mesh.uvs[f.v[0]];
  const Vec2 d2 = mesh.uvs[f.v[tri ? 2 : 3]] - mesh.uvs[f.v[tri ? 0 : 1]];
  // e = dp/du * d.x + dp/dv * d.y for both edges: a 2x2 system in the uv differences.
  const float det = d1.x * d2.y - d2.x * d1.y;
  if (!(std::abs(det) > kMinUvSine * glm::length(d1) * glm::length(d2))) return frame;  // also NaN
  const Vec3 dpdu = (e1 * d2.y - e2 * d1.y) / det;
  const Vec3 dpdv = (e2 * d1.x - e1 * d2.x) / det;
  const Vec3 t = dpdu - n * glm::dot(n, dpdu);  // Gram-Schmidt against the normal
  const float len = glm::length(t);
  if (!(len > 0.0f) || !finite(t)) return frame;
  frame.t = t / len;
  const Vec3 b = glm::cross(n, frame.t);
  frame.b = glm::dot(b, dpdv) < 0.0f ? -b : b;  // mirrored uvs: a left-handed frame
  frame.n = n;
  frame.valid = true;
  return frame;
}

Vec3 tangentSpaceNormal(Rgb texel, float scale) {
  const Vec3 v = (2.0f * texel - 1.0f) * Vec3(scale, scale, 1.0f);
  const float len = glm::length(v);
  return len > 0.0f ? v / len : Vec3(0.0f, 0.0f, 1.0f);
}

Vec3 shadingNormal(const Scene& scene, uint32_t meshIndex, uint32_t face, Vec2 uv,
                   Vec3 geometricNormal) {
  const Mesh& mesh = scene.meshes[meshIndex];
  const Material& m = scene.materials[mesh.material];
  if (m.normalTexture < 0 || mesh.uvs.empty() || face >= mesh.faces.size()) return geometricNormal;
  // Which side: the winding's normal (unnormalised: only its sign against ours matters).
  const Face& f = mesh.faces[face];
  const bool tri = f.isTriangle();
  const Vec3 winding =
      glm::cross(mesh.positions[f.v[tri ? 1 : 2]] - mesh.positions[f.v[0]],
                 mesh.positions[f.v[tri ? 2 : 3]] - mesh.positions[f.v[tri ? 0 : 1]]);
  // The back of a two-sided face is the front seen from behind: the front's normal, reversed.
  const float side = m.twoSided && glm::dot(winding, geometricNormal) < 0.0f ? -1.0f : 1.0f;
  const TangentFrame frame = faceTangentFrame(mesh, face, side * geometricNormal);
  if (!frame.valid) return geometricNormal;
  const Vec3 ts =
      tangentSpaceNormal(scene.textures[size_t(m.normalTexture)].sample(uv), m.normalScale);
  const Vec3 n = frame.t * ts.x + frame.b * ts.y + frame.n * ts.z;
  const float len = glm::length(n);
  return len > 0.0f ? side * (n / len) : geometricNormal;
}

}  // namespace luxel
