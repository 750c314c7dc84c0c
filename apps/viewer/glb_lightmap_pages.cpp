#include "glb_lightmap_pages.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace luxel::viewer {

namespace {

struct Footprint {
  Vec3 lo{std::numeric_limits<float>::max()}, hi{-std::numeric_limits<float>::max()};
  double area = 0.0;

  void add(Vec3 a, Vec3 b, Vec3 c) {
    for (const Vec3& p : {a, b, c}) lo = glm::min(lo, p), hi = glm::max(hi, p);
    area += 0.5 * double(glm::length(glm::cross(b - a, c - a)));
  }
  bool matches(const Footprint& o, float lengthTolerance) const {
    return glm::all(glm::lessThanEqual(glm::abs(lo - o.lo), Vec3(lengthTolerance))) &&
           glm::all(glm::lessThanEqual(glm::abs(hi - o.hi), Vec3(lengthTolerance))) &&
           std::abs(area - o.area) <= 1e-4 * std::max(area, o.area);
  }
};

}  // namespace

GlbLightmapPages glbLightmapPages(const BakedGlb& glb, const Scene& scene) {
  GlbLightmapPages out;
  out.meshPage.assign(scene.meshes.size(), -1);
  std::vector<Footprint> primitives(glb.primitives.size());
  Vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (size_t i = 0; i < glb.primitives.size(); ++i) {
    const BakedGlb::Primitive& p = glb.primitives[i];
    for (size_t t = 0; t + 2 < p.indices.size(); t += 3)
      primitives[i].add(p.positions[p.indices[t]], p.positions[p.indices[t + 1]],
                        p.positions[p.indices[t + 2]]);
    lo = glm::min(lo, primitives[i].lo), hi = glm::max(hi, primitives[i].hi);
  }
  // Float positions written and read again: equal to rounding, far below any two meshes' gap.
  const float tolerance = 1e-5f * std::max(1.0f, glm::length(hi - lo));
  auto pageOf = [&](size_t primitive) {
    const int material = glb.primitives[primitive].material;
    return material >= 0 && size_t(material) < glb.materials.size()
               ? glb.materials[size_t(material)].lightmap
               : -1;
  };
  std::vector<uint8_t> taken(glb.primitives.size(), 0);
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    if (mesh.lightmapUvs.empty()) continue;
    Footprint f;
    for (const Face& face : mesh.faces) {
      f.add(mesh.positions[face.v[0]], mesh.positions[face.v[1]], mesh.positions[face.v[2]]);
      if (!face.isTriangle())
        f.add(mesh.positions[face.v[0]], mesh.positions[face.v[2]], mesh.positions[face.v[3]]);
    }
    for (size_t i = 0; i < primitives.size(); ++i)
      if (!taken[i] && pageOf(i) >= 0 && f.matches(primitives[i], tolerance)) {
        taken[i] = 1;
        out.meshPage[m] = pageOf(i);
        break;
      }
  }
  // One page size for all: the atlas has one.
  for (int page : out.meshPage) {
    if (page < 0 || size_t(page) >= glb.images.size()) continue;
    const BakedGlb::Image& image = glb.images[size_t(page)];
    const int side = image.width == image.height ? image.width : -1;
    if (out.pageSize == 0) out.pageSize = side;
    if (side != out.pageSize) out.pageSize = -1;
  }
  out.pageSize = std::max(out.pageSize, 0);
  return out;
}

}  // namespace luxel::viewer
