// Test scene and check for directional bakes: a closed glowing box (a furnace), whose incident
// light at every texel is a uniform hemisphere about its normal, with known SH.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include "core/spherical_harmonics.h"
#include "luxel/lightmap.h"
#include "luxel/scene.h"

namespace luxel::test {

inline void addQuad(Scene& s, Vec3 a, Vec3 b, Vec3 c, Vec3 d, uint32_t material) {
  Mesh m;
  m.name = "quad" + std::to_string(s.meshes.size());
  m.positions = {a, b, c, d};
  m.faces = {Face{{0, 1, 2, 3}}};
  m.material = material;
  s.meshes.push_back(m);
}

// A closed 1 m box, every inward wall emitting evenly and reflecting half: the radiance inside is
// the same everywhere and in every direction.
inline Scene furnace() {
  Scene s;
  s.name = "furnace";
  Material glow;
  glow.name = "glow";
  glow.reflectance = Rgb(0.5f);
  glow.emission = Rgb(1.0f);
  s.materials.push_back(glow);
  const Vec3 p[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  // Inward-facing quads (counter-clockwise seen from inside).
  addQuad(s, p[0], p[1], p[2], p[3], 0);  // z = 0, normal +z
  addQuad(s, p[4], p[7], p[6], p[5], 0);  // z = 1, normal -z
  addQuad(s, p[0], p[3], p[7], p[4], 0);  // x = 0, normal +x
  addQuad(s, p[1], p[5], p[6], p[2], 0);  // x = 1, normal -x
  addQuad(s, p[0], p[4], p[5], p[1], 0);  // y = 0, normal +y
  addQuad(s, p[3], p[2], p[6], p[7], 0);  // y = 1, normal -y
  return s;
}

// Each texel's bands 0 and 1 against the uniform hemisphere's (c0 = 2 H Y00, band 1 = H n Y1),
// relative to the texel's irradiance H (red): the worst band 0, the worst and mean band 1.
struct FurnaceErrors {
  double worst0 = 0.0, worst1 = 0.0, mean1 = 0.0;
};
inline FurnaceErrors furnaceErrors(const BakedLightmaps& b) {
  FurnaceErrors r;
  const auto& set = b.bake.surfaces.surfaces;
  for (size_t e = 0; e < set.elements.size(); ++e) {
    const auto& t = b.bake.surfaces.texels[e];
    const size_t i = size_t(t.y) * size_t(b.bake.pageSize) + t.x;
    Rgb c[4];
    for (int k = 0; k < 4; ++k) c[k] = b.bake.sh[size_t(k)][t.page][i];
    const float h = b.bake.pages[t.page][i].r;
    r.worst0 = std::max(r.worst0, double(std::abs(c[0].r - 2.0f * h * kShY0) / (2.0f * h * kShY0)));
    const double off = glm::length(shBand1Vector(c[1].r, c[2].r, c[3].r) - h * set.elements[e].normal) / h;
    r.worst1 = std::max(r.worst1, off);
    r.mean1 += off / double(set.elements.size());
  }
  return r;
}

}  // namespace luxel::test
