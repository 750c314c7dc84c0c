#include "glb_lightmap_pages.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace luxel::viewer {

namespace {

struct Footprint {
  Vec3 lo{std::numeric_limits<float>::max()}, hi{-std::numeric_limits<float>::max()};
  double area = 0.0;
  Vec2 uvLo{std::numeric_limits<float>::max()}, uvHi{-std::numeric_limits<float>::max()};

  void add(Vec3 a, Vec3 b, Vec3 c) {
    for (const Vec3& p : {a, b, c}) lo = glm::min(lo, p), hi = glm::max(hi, p);
    area += 0.5 * double(glm::length(glm::cross(b - a, c - a)));
  }
  void addUv(Vec2 uv) { uvLo = glm::min(uvLo, uv), uvHi = glm::max(uvHi, uv); }

  bool matches(const Footprint& o, float lengthTolerance) const {
    auto near = [](auto a, auto b, float tolerance) {
      return glm::all(glm::lessThanEqual(glm::abs(a - b), decltype(a)(tolerance)));
    };
    // Assimp reads glTF's UVs with v flipped (v' = 1 - v); either way round, the bounds agree.
    constexpr float kUvTolerance = 1e-5f;
    const bool uvs = (near(uvLo, o.uvLo, kUvTolerance) && near(uvHi, o.uvHi, kUvTolerance)) ||
                     (near(uvLo, Vec2(o.uvLo.x, 1.0f - o.uvHi.y), kUvTolerance) &&
                      near(uvHi, Vec2(o.uvHi.x, 1.0f - o.uvLo.y), kUvTolerance));
    return uvs && near(lo, o.lo, lengthTolerance) && near(hi, o.hi, lengthTolerance) &&
           std::abs(area - o.area) <= 1e-4 * std::max(area, o.area);
  }
};

}  // namespace

GlbLightmapPages glbLightmapPages(const BakedGlb& glb, const Scene& scene) {
  GlbLightmapPages out;
  out.meshPage.assign(scene.meshes.size(), -1);
  auto pageOf = [&](size_t primitive) {
    const int material = glb.primitives[primitive].material;
    return material >= 0 && size_t(material) < glb.materials.size()
               ? glb.materials[size_t(material)].lightmap
               : -1;
  };
  std::vector<Footprint> primitives(glb.primitives.size());
  Vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (size_t i = 0; i < glb.primitives.size(); ++i) {
    const BakedGlb::Primitive& p = glb.primitives[i];
    for (size_t t = 0; t + 2 < p.indices.size(); t += 3)
      primitives[i].add(p.positions[p.indices[t]], p.positions[p.indices[t + 1]],
                        p.positions[p.indices[t + 2]]);
    for (const Vec2& uv : p.uv1) primitives[i].addUv(uv);
    lo = glm::min(lo, primitives[i].lo), hi = glm::max(hi, primitives[i].hi);
  }
  // Float positions written and read again: equal to rounding, far below any two meshes' gap.
  const float tolerance = 1e-5f * std::max(1.0f, glm::length(hi - lo));
  std::vector<uint8_t> taken(glb.primitives.size(), 0);
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    if (mesh.lightmapUvs.empty()) continue;
    ++out.meshesWithUvs;
    Footprint f;
    for (const Face& face : mesh.faces) {
      f.add(mesh.positions[face.v[0]], mesh.positions[face.v[1]], mesh.positions[face.v[2]]);
      if (!face.isTriangle())
        f.add(mesh.positions[face.v[0]], mesh.positions[face.v[2]], mesh.positions[face.v[3]]);
    }
    for (const Vec2& uv : mesh.lightmapUvs) f.addUv(uv);
    for (size_t i = 0; i < primitives.size(); ++i)
      if (!taken[i] && pageOf(i) >= 0 && f.matches(primitives[i], tolerance)) {
        taken[i] = 1;
        out.meshPage[m] = pageOf(i);
        ++out.matched;
        break;
      }
  }
  if (out.matched == 0) {
    out.whyNot = fmt::format(
        "none of the scene's {} meshes with lightmap uvs matches a lightmapped mesh of the glb",
        out.meshesWithUvs);
    return out;
  }
  // One page size for all: the atlas has one.
  int side = 0;
  for (int page : out.meshPage) {
    if (page < 0 || size_t(page) >= glb.images.size()) continue;
    const BakedGlb::Image& image = glb.images[size_t(page)];
    if (image.width != image.height || (side != 0 && image.width != side)) {
      out.whyNot =
          fmt::format("its lightmap pages are not all square and of one size ({}x{} beside {}^2)",
                      image.width, image.height, side);
      return out;
    }
    side = image.width;
  }
  if (side <= 0) {
    out.whyNot = "its lightmap pages have no size";
    return out;
  }
  out.pageSize = side;
  return out;
}

}  // namespace luxel::viewer
