// texelSurfaces (lightmap.h): every covered texel of an atlas as an element, blocks of texels as
// patches, so that the ordinary solvers run on texels.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <tuple>

#include <fmt/format.h>

#include "lightmap/atlas_internal.h"
#include "lightmap/texel_geometry.h"
#include "luxel/error.h"
#include "mesh/orient_faces.h"

namespace luxel {
namespace lightmap {

double area2(const std::vector<glm::dvec2>& p) {
  double a = 0.0;
  for (size_t i = 0; i < p.size(); ++i) {
    const glm::dvec2& u = p[i];
    const glm::dvec2& v = p[(i + 1) % p.size()];
    a += u.x * v.y - v.x * u.y;
  }
  return 0.5 * a;
}

std::vector<glm::dvec2> clipConvex(std::vector<glm::dvec2> poly, const std::vector<glm::dvec2>& clip) {
  // Sutherland-Hodgman against a counter-clockwise convex polygon.
  for (size_t e = 0; e < clip.size() && !poly.empty(); ++e) {
    const glm::dvec2 a = clip[e], d = clip[(e + 1) % clip.size()] - a;
    auto side = [&](glm::dvec2 q) { return d.x * (q.y - a.y) - d.y * (q.x - a.x); };
    std::vector<glm::dvec2> out;
    for (size_t i = 0; i < poly.size(); ++i) {
      const glm::dvec2 p = poly[i], q = poly[(i + 1) % poly.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0.0) out.push_back(p);
      if ((sp >= 0.0) != (sq >= 0.0)) out.push_back(p + (q - p) * (sp / (sp - sq)));
    }
    poly = std::move(out);
  }
  return poly;
}

FaceMap::FaceMap(const SurfaceFace& f, const std::array<Vec2, 4>& texel) {
  n = f.triangle ? 3 : 4;
  for (int i = 0; i < 4; ++i) t[i] = texel[size_t(i)], w[i] = f.corners[size_t(i)], uv[i] = f.uvs[size_t(i)];
  std::vector<glm::dvec2> poly(t, t + n);
  texelArea = area2(poly);
  if (texelArea < 0.0) std::reverse(poly.begin(), poly.end());
  texelArea = std::abs(texelArea);
  convex = true;
  for (int i = 0; i < n; ++i) {
    glm::dvec2 a = poly[size_t(i)], b = poly[size_t((i + 1) % n)], c = poly[size_t((i + 2) % n)];
    if ((b.x - a.x) * (c.y - b.y) - (b.y - a.y) * (c.x - b.x) < 0.0) convex = false;
  }
  clip = poly;
}

// Barycentrics of q in texel triangle (0, k, k+1), k = 1 or 2.
static glm::dvec3 bary(const glm::dvec2* t, int k, glm::dvec2 q) {
  glm::dvec2 a = t[0], b = t[k], c = t[k + 1];
  double d = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
  if (d == 0.0) return glm::dvec3(-1e30);
  double l1 = ((q.x - a.x) * (c.y - a.y) - (c.x - a.x) * (q.y - a.y)) / d;
  double l2 = ((b.x - a.x) * (q.y - a.y) - (q.x - a.x) * (b.y - a.y)) / d;
  return {1.0 - l1 - l2, l1, l2};
}

int FaceMap::triangleOf(glm::dvec2 q, glm::dvec3* b) const {
  glm::dvec3 b0 = bary(t, 1, q);
  if (n == 3) {
    *b = b0;
    return 1;
  }
  glm::dvec3 b1 = bary(t, 2, q);
  const double m0 = std::min({b0.x, b0.y, b0.z}), m1 = std::min({b1.x, b1.y, b1.z});
  if (m0 >= m1) {
    *b = b0;
    return 1;
  }
  *b = b1;
  return 2;
}

Vec3 FaceMap::world(glm::dvec2 q) const {
  glm::dvec3 b;
  int k = triangleOf(q, &b);
  return Vec3(b.x * glm::dvec3(w[0]) + b.y * glm::dvec3(w[k]) + b.z * glm::dvec3(w[k + 1]));
}

Vec2 FaceMap::uvAt(glm::dvec2 q) const {
  glm::dvec3 b;
  int k = triangleOf(q, &b);
  return Vec2(b.x * glm::dvec2(uv[0]) + b.y * glm::dvec2(uv[k]) + b.z * glm::dvec2(uv[k + 1]));
}

glm::dvec2 FaceMap::texelOf(Vec3 p) const {
  // Barycentrics in world space, in whichever of the (one or two) triangles fits best.
  glm::dvec2 best(0.0);
  double bestMin = -1e30;
  for (int k = 1; k + 1 < n; ++k) {
    glm::dvec3 a(w[0]), b(w[k]), c(w[k + 1]), q(p);
    glm::dvec3 v0 = b - a, v1 = c - a, v2 = q - a;
    double d00 = glm::dot(v0, v0), d01 = glm::dot(v0, v1), d11 = glm::dot(v1, v1);
    double d20 = glm::dot(v2, v0), d21 = glm::dot(v2, v1), den = d00 * d11 - d01 * d01;
    if (den <= 0.0) continue;
    double l1 = (d11 * d20 - d01 * d21) / den, l2 = (d00 * d21 - d01 * d20) / den, l0 = 1.0 - l1 - l2;
    double m = std::min({l0, l1, l2});
    if (m > bestMin) bestMin = m, best = l0 * t[0] + l1 * t[k] + l2 * t[k + 1];
  }
  return best;
}

glm::dvec2 FaceMap::clampInside(glm::dvec2 q) const {
  bool inside = true;
  for (size_t e = 0; e < clip.size(); ++e) {
    glm::dvec2 a = clip[e], d = clip[(e + 1) % clip.size()] - a;
    if (d.x * (q.y - a.y) - d.y * (q.x - a.x) < 0.0) inside = false;
  }
  if (inside) return q;
  glm::dvec2 best = clip[0];
  double bd = 1e300;
  for (size_t e = 0; e < clip.size(); ++e) {
    glm::dvec2 a = clip[e], d = clip[(e + 1) % clip.size()] - a;
    double l = glm::dot(d, d), s = l > 0.0 ? std::clamp(glm::dot(q - a, d) / l, 0.0, 1.0) : 0.0;
    glm::dvec2 c = a + s * d;
    if (glm::dot(q - c, q - c) < bd) bd = glm::dot(q - c, q - c), best = c;
  }
  // Nudged a hair towards the face's middle, so that it maps inside.
  glm::dvec2 mid(0.0);
  for (auto& v : clip) mid += v;
  mid /= double(clip.size());
  return best + 1e-4 * (mid - best);
}

std::vector<glm::dvec2> FaceMap::clipSquare(double x0, double y0, double size, glm::dvec2 inside) const {
  std::vector<glm::dvec2> sq = {{x0, y0}, {x0 + size, y0}, {x0 + size, y0 + size}, {x0, y0 + size}};
  if (convex) return clipConvex(sq, clip);
  // A quad that is not convex in texel space: the triangle that holds `inside`.
  glm::dvec3 b;
  int k = triangleOf(inside, &b);
  std::vector<glm::dvec2> tri = {t[0], t[k], t[k + 1]};
  if (area2(tri) < 0.0) std::reverse(tri.begin(), tri.end());
  return clipConvex(sq, tri);
}

// World polygon (<= 4 corners, counter-clockwise about `normal`) and exact world area of a
// texel-space polygon on the face.
std::pair<Polygon, float> FaceMap::worldPolygon(std::vector<glm::dvec2> p, Vec3 normal) const {
  double area = 0.0;
  std::vector<Vec3> wp;
  for (auto& q : p) wp.push_back(world(q));
  for (size_t i = 1; i + 1 < wp.size(); ++i)
    area += 0.5 * glm::length(glm::cross(glm::dvec3(wp[i] - wp[0]), glm::dvec3(wp[i + 1] - wp[0])));
  // Cut down to 4 corners, dropping the corner whose removal loses the least area each time.
  while (p.size() > 4) {
    size_t drop = 0;
    double least = 1e300;
    for (size_t i = 0; i < p.size(); ++i) {
      glm::dvec2 a = p[(i + p.size() - 1) % p.size()], b = p[i], c = p[(i + 1) % p.size()];
      double loss = std::abs((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
      if (loss < least) least = loss, drop = i;
    }
    p.erase(p.begin() + long(drop));
    wp.erase(wp.begin() + long(drop));
  }
  Polygon poly;
  poly.count = int(std::min<size_t>(wp.size(), 4));
  for (int i = 0; i < poly.count; ++i) poly.v[size_t(i)] = wp[size_t(i)];
  if (poly.count >= 3 && glm::dot(poly.normal(), normal) < 0.0f) std::reverse(poly.v.begin(), poly.v.begin() + poly.count);
  return {poly, float(area)};
}

}  // namespace lightmap

namespace {
constexpr float kPi = std::numbers::pi_v<float>;
}

TexelSurfaces texelSurfaces(const Scene& scene, const LightmapAtlas& atlas, int perPatch, bool orientByLight) {
  using namespace lightmap;
  if (perPatch < 1 || perPatch > 64) throw Error("texel surfaces: texels per patch side must be in 1..64");
  if (atlas.faces.size() != scene.meshes.size()) throw Error("texel surfaces: the atlas is for another scene");
  TexelSurfaces ts;
  SurfaceSet& set = ts.surfaces;
  Vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const Mesh& mesh : scene.meshes)
    for (const Vec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  set.sceneExtent = glm::length(hi - lo);

  for (uint32_t mi = 0; mi < scene.meshes.size(); ++mi) {
    const Mesh& mesh = scene.meshes[mi];
    if (atlas.faces[mi].size() != mesh.faces.size()) throw Error("texel surfaces: the atlas is for another scene");
    for (uint32_t fi = 0; fi < mesh.faces.size(); ++fi) {
      const Face& face = mesh.faces[fi];
      SurfaceFace f;
      f.mesh = mi, f.meshFace = fi, f.material = mesh.material, f.triangle = face.isTriangle();
      for (int i = 0; i < 4; ++i) {
        f.corners[size_t(i)] = mesh.positions[face.v[size_t(i)]];
        f.uvs[size_t(i)] = mesh.uvs.empty() ? Vec2(0.0f) : mesh.uvs[face.v[size_t(i)]];
      }
      Polygon poly{f.corners, f.triangle ? 3 : 4};
      const auto& uv = atlas.faces[mi][fi];
      std::vector<glm::dvec2> tp;
      for (int i = 0; i < poly.count; ++i) tp.push_back(uv.texel[size_t(i)]);
      if (!poly.hasArea() || !(std::abs(area2(tp)) > 1e-12)) {
        ++ts.skippedFaces;
        continue;
      }
      // A quad off its plane is cut along 0-2 into two triangles, as discretise does, so that
      // texels lie on the triangles the ray tracer sees (Embree would cut it along 1-3).
      bool planar = f.triangle;
      if (!planar) {
        const auto& c = f.corners;
        Vec3 n = glm::cross(c[1] - c[0], c[2] - c[0]);
        float len = glm::length(n);
        float edge = std::max({glm::length(c[1] - c[0]), glm::length(c[2] - c[1]), glm::length(c[3] - c[2]),
                               glm::length(c[0] - c[3])});
        planar = len > 0.0f && std::abs(glm::dot(n / len, c[3] - c[0])) <= 1e-5f * edge;
      }
      auto add = [&](SurfaceFace g, std::array<Vec2, 4> t) {
        Polygon q{g.corners, g.triangle ? 3 : 4};
        if (!q.hasArea()) return;
        g.normal = q.normal();
        set.faces.push_back(g);
        ts.faceTexels.push_back(t);
        ts.faceChart.push_back(uv.chart);
        ts.facePage.push_back(uv.page);
      };
      if (planar) {
        add(f, uv.texel);
      } else {
        ++set.splitQuads;
        SurfaceFace a = f, b = f;
        a.triangle = b.triangle = true;
        a.corners = {f.corners[0], f.corners[1], f.corners[2], f.corners[2]};
        a.uvs = {f.uvs[0], f.uvs[1], f.uvs[2], f.uvs[2]};
        b.corners = {f.corners[0], f.corners[2], f.corners[3], f.corners[3]};
        b.uvs = {f.uvs[0], f.uvs[2], f.uvs[3], f.uvs[3]};
        const auto& t = uv.texel;
        add(a, {t[0], t[1], t[2], t[2]});
        add(b, {t[0], t[2], t[3], t[3]});
      }
    }
  }
  if (set.faces.empty()) {
    scene.validate();  // coordinates past the limit overflow every area: say that, not its symptom
    throw Error(fmt::format("scene '{}': no face has a positive area", scene.name));
  }
  if (orientByLight) {
    set.flippedFaces = orientFacesByLight(scene, set.faces, set.sceneExtent);
    for (size_t i = 0; i < set.faces.size(); ++i)
      if (set.faces[i].flipped) {
        auto& t = ts.faceTexels[i];
        std::swap(t[1], t[set.faces[i].triangle ? 2 : 3]);
        if (set.faces[i].triangle) t[3] = t[2];
      }
  }

  // Texel ownership, page by page: element index or -1.
  const int size = atlas.pageSize;
  std::vector<std::vector<int32_t>> owner(size_t(atlas.pageCount), std::vector<int32_t>());
  std::vector<FaceMap> maps;
  maps.reserve(set.faces.size());
  for (size_t i = 0; i < set.faces.size(); ++i) maps.emplace_back(set.faces[i], ts.faceTexels[i]);
  std::vector<uint8_t> conservative(set.faces.size(), 0);
  struct Claim {
    uint32_t face;
    glm::dvec2 sample;
  };
  std::vector<Claim> claims;
  std::vector<TexelSurfaces::Texel> claimTexels;
  auto claim = [&](uint32_t fi, int x, int y, glm::dvec2 sample) {
    auto& o = owner[ts.facePage[fi]];
    if (o.empty()) o.assign(size_t(size) * size_t(size), -1);
    int32_t& slot = o[size_t(y) * size_t(size) + size_t(x)];
    if (slot >= 0) {
      // Two faces hold the texel's centre (conservative faces take only free texels).
      if (!conservative[fi]) ts.contested.push_back({ts.facePage[fi], uint32_t(x), uint32_t(y)});
      return;
    }
    slot = int32_t(claims.size());
    claims.push_back({fi, sample});
    claimTexels.push_back({ts.facePage[fi], uint32_t(x), uint32_t(y)});
  };
  for (uint32_t fi = 0; fi < set.faces.size(); ++fi) {
    const auto& uv = atlas.faces[set.faces[fi].mesh][set.faces[fi].meshFace];
    conservative[fi] = uv.conservative;
    if (uv.conservative) continue;
    const auto& t = ts.faceTexels[fi];  // the atlas's triangles (turned round when the face was)
    auto f = [&](int x, int y) { claim(fi, x, y, glm::dvec2(x + 0.5, y + 0.5)); };
    rasteriseTriangle(t[0], t[1], t[2], size, f);
    if (!set.faces[fi].triangle) rasteriseTriangle(t[0], t[2], t[3], size, f);
  }
  for (uint32_t fi = 0; fi < set.faces.size(); ++fi) {
    if (!conservative[fi]) continue;
    const FaceMap& m = maps[fi];
    double x0 = 1e30, y0 = 1e30, x1 = -1e30, y1 = -1e30;
    for (auto& v : m.clip) x0 = std::min(x0, v.x), y0 = std::min(y0, v.y), x1 = std::max(x1, v.x), y1 = std::max(y1, v.y);
    for (int y = std::max(0, int(std::floor(y0))); y <= std::min(size - 1, int(std::floor(y1))); ++y)
      for (int x = std::max(0, int(std::floor(x0))); x <= std::min(size - 1, int(std::floor(x1))); ++x) {
        glm::dvec2 c(x + 0.5, y + 0.5);
        if (std::abs(area2(m.clipSquare(x, y, 1.0, c))) <= 0.0) continue;
        claim(fi, x, y, m.clampInside(c));
      }
  }

  // Elements, then patches (blocks of texels of one face on one page).
  set.elements.resize(claims.size());
  ts.texels = claimTexels;
  std::map<std::tuple<uint32_t, int, int, uint32_t>, uint32_t> patchOf;
  double areaSum = 0.0;
  for (size_t ei = 0; ei < claims.size(); ++ei) {
    const uint32_t fi = claims[ei].face;
    const FaceMap& m = maps[fi];
    const SurfaceFace& f = set.faces[fi];
    const Material& mat = scene.materials[f.material];
    const auto& tx = claimTexels[ei];
    Element& e = set.elements[ei];
    auto clipped = m.clipSquare(tx.x, tx.y, 1.0, claims[ei].sample);
    if (clipped.size() < 3) {  // a conservative texel touching the face at a point: the texel square itself
      clipped = {{tx.x, tx.y}, {tx.x + 1.0, tx.y}, {tx.x + 1.0, tx.y + 1.0}, {tx.x, tx.y + 1.0}};
    }
    auto [poly, area] = m.worldPolygon(clipped, f.normal);
    e.polygon = poly;
    e.centroid = m.world(claims[ei].sample);
    e.normal = f.normal;
    e.area = std::max(area, 1e-12f * set.sceneExtent * set.sceneExtent);
    areaSum += e.area;
    e.face = fi;
    e.material = f.material;
    e.reflectance = mat.reflectance;
    e.exitance = kPi * mat.emission;
    if (mat.reflectanceTexture >= 0 || mat.emissionTexture >= 0) {
      Rgb rt(0.0f), et(0.0f);
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
          Vec2 uv = m.uvAt(glm::dvec2(tx.x + 0.25 + 0.5 * i, tx.y + 0.25 + 0.5 * j));
          if (mat.reflectanceTexture >= 0) rt += scene.textures[size_t(mat.reflectanceTexture)].sample(uv);
          if (mat.emissionTexture >= 0) et += scene.textures[size_t(mat.emissionTexture)].sample(uv);
        }
      if (mat.reflectanceTexture >= 0) e.reflectance *= rt * 0.25f;
      if (mat.emissionTexture >= 0) e.exitance *= et * 0.25f;
    }
    const int bx = int(tx.x) / perPatch, by = int(tx.y) / perPatch;
    auto key = std::make_tuple(tx.page, bx, by, fi);
    auto [it, added] = patchOf.try_emplace(key, uint32_t(set.patches.size()));
    if (added) {
      Patch p;
      auto block = m.clipSquare(bx * perPatch, by * perPatch, perPatch, claims[ei].sample);
      if (block.size() < 3) block = clipped;
      auto [ppoly, parea] = m.worldPolygon(block, f.normal);
      p.polygon = ppoly;
      p.centroid = ppoly.centroid();
      p.normal = f.normal;
      p.area = parea;
      p.face = fi;
      set.patches.push_back(std::move(p));
    }
    e.patch = it->second;
    set.patches[it->second].elements.push_back(uint32_t(ei));
  }
  set.elementSize = claims.empty() ? 0.0f : float(std::sqrt(areaSum / double(claims.size())));
  return ts;
}

}  // namespace luxel
