// The lightmap atlas (lightmap.h): generated charts on the built-in Cornell box (quads) and the
// Stanford bunny (curved, LSCM), given second UV sets, and option checks.
//
// Every check rasterises the atlas here, independently of the library: a face's polygon at texel
// centres (inclusive edges) into a per-page chart-id image, where a texel claimed by two charts
// fails; and every face's texel bounding box (a superset of the texels conservative
// rasterisation touches) into a second image, where texels of two charts closer than the gutter
// fail. A face that holds no texel centre must carry FaceUv::conservative.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <fstream>

#include <nlohmann/json.hpp>

#include "luxel/error.h"
#include "luxel/import.h"
#include "luxel/lightmap.h"
#include "error_message.h"

namespace fs = std::filesystem;
using luxel::AtlasOptions;
using luxel::Error;
using luxel::Face;
using luxel::LightmapAtlas;
using luxel::Mesh;
using luxel::Scene;
using luxel::Vec2;
using luxel::Vec3;

namespace {

using luxel::test::errorOf;

constexpr double kPi = 3.14159265358979;

double cross2(Vec2 a, Vec2 b, Vec2 c) {
  return double(b.x - a.x) * double(c.y - a.y) - double(c.x - a.x) * double(b.y - a.y);
}

// Texel centres inside triangle abc, either orientation, edges included.
template <class F>
void centres(Vec2 a, Vec2 b, Vec2 c, int size, F f) {
  double area = cross2(a, b, c);
  if (area == 0.0) return;
  if (area < 0.0) std::swap(b, c);
  int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}))));
  int x1 = std::min(size - 1, int(std::ceil(std::max({a.x, b.x, c.x}))));
  int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}))));
  int y1 = std::min(size - 1, int(std::ceil(std::max({a.y, b.y, c.y}))));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      Vec2 q(x + 0.5f, y + 0.5f);
      if (cross2(a, b, q) >= 0 && cross2(b, c, q) >= 0 && cross2(c, a, q) >= 0) f(x, y);
    }
}

struct AtlasCheck {
  size_t faces = 0;
  size_t conservative = 0;      // faces holding no texel centre
  size_t unflagged = 0;         // ... without FaceUv::conservative
  size_t overlaps = 0;          // texel centres claimed by two charts
  size_t gutterViolations = 0;  // bounding-box texels of two charts closer than the gutter
  size_t outside = 0;           // corners off their page
  size_t coveredTexels = 0;
};

AtlasCheck check(const Scene& scene, const LightmapAtlas& atlas, int gutter) {
  AtlasCheck r;
  const int n = atlas.pageSize;
  std::vector<std::vector<int64_t>> centre(size_t(atlas.pageCount)), box(size_t(atlas.pageCount));
  for (int p = 0; p < atlas.pageCount; ++p) {
    centre[size_t(p)].assign(size_t(n) * size_t(n), -1);
    box[size_t(p)].assign(size_t(n) * size_t(n), -1);
  }
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    for (size_t f = 0; f < scene.meshes[m].faces.size(); ++f) {
      const LightmapAtlas::FaceUv& uv = atlas.faces[m][f];
      ++r.faces;
      bool quad = !scene.meshes[m].faces[f].isTriangle();
      if (int(uv.page) >= atlas.pageCount) {
        ++r.outside;
        continue;
      }
      for (Vec2 t : uv.texel)
        if (!(t.x >= 0 && t.y >= 0 && t.x <= float(n) && t.y <= float(n))) ++r.outside;
      auto& img = centre[uv.page];
      size_t hits = 0;
      auto claim = [&](int x, int y) {
        int64_t& c = img[size_t(y) * size_t(n) + size_t(x)];
        if (c >= 0 && c != int64_t(uv.chart)) ++r.overlaps;
        if (c < 0) ++r.coveredTexels;
        c = uv.chart;
        ++hits;
      };
      centres(uv.texel[0], uv.texel[1], uv.texel[2], n, claim);
      if (quad) centres(uv.texel[0], uv.texel[2], uv.texel[3], n, claim);
      if (hits == 0) {
        ++r.conservative;
        if (!uv.conservative) ++r.unflagged;
      }
      Vec2 lo = glm::min(glm::min(uv.texel[0], uv.texel[1]), glm::min(uv.texel[2], uv.texel[3]));
      Vec2 hi = glm::max(glm::max(uv.texel[0], uv.texel[1]), glm::max(uv.texel[2], uv.texel[3]));
      int x0 = std::max(0, int(std::floor(lo.x))), y0 = std::max(0, int(std::floor(lo.y)));
      int x1 = std::min(n - 1, std::max(x0, int(std::ceil(hi.x)) - 1));
      int y1 = std::min(n - 1, std::max(y0, int(std::ceil(hi.y)) - 1));
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          int64_t& c = box[uv.page][size_t(y) * size_t(n) + size_t(x)];
          if (c >= 0 && c != int64_t(uv.chart)) ++r.gutterViolations;
          c = uv.chart;
        }
    }
  // Gutter: no texel of another chart within `gutter` texels (Chebyshev distance) of a chart's.
  for (const auto& img : box)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        int64_t c = img[size_t(y) * size_t(n) + size_t(x)];
        if (c < 0) continue;
        for (int dy = -gutter; dy <= gutter; ++dy)
          for (int dx = -gutter; dx <= gutter; ++dx) {
            int xx = x + dx, yy = y + dy;
            if (xx < 0 || yy < 0 || xx >= n || yy >= n) continue;
            int64_t o = img[size_t(yy) * size_t(n) + size_t(xx)];
            if (o >= 0 && o != c) ++r.gutterViolations;
          }
      }
  return r;
}

double area3(Vec3 a, Vec3 b, Vec3 c) { return 0.5 * glm::length(glm::dvec3(glm::cross(b - a, c - a))); }
double area2(Vec2 a, Vec2 b, Vec2 c) { return 0.5 * std::abs(cross2(a, b, c)); }

double faceArea(const Mesh& mesh, const Face& f) {
  const auto& p = mesh.positions;
  double a = area3(p[f.v[0]], p[f.v[1]], p[f.v[2]]);
  return f.isTriangle() ? a : a + area3(p[f.v[0]], p[f.v[2]], p[f.v[3]]);
}
double uvArea(const Face& f, const LightmapAtlas::FaceUv& uv) {
  // Shoelace over the polygon (a quad's signed area, as the parameterisation keeps orientation).
  int k = f.vertexCount();
  double s = 0;
  for (int i = 0; i < k; ++i) {
    Vec2 a = uv.texel[size_t(i)], b = uv.texel[size_t((i + 1) % k)];
    s += double(a.x) * b.y - double(b.x) * a.y;
  }
  return 0.5 * std::abs(s);
}

Mesh quadMesh(const std::string& name, float x0, float z0) {
  Mesh m;
  m.name = name;
  m.positions = {Vec3(x0, 0, z0), Vec3(x0 + 1, 0, z0), Vec3(x0 + 1, 0, z0 - 1), Vec3(x0, 0, z0 - 1),
                 Vec3(x0 + 2, 0, z0), Vec3(x0 + 2, 0, z0 - 1)};
  m.faces = {Face{{0, 1, 2, 3}}, Face{{1, 4, 5, 2}}};
  return m;
}

Scene twoMeshes() {
  Scene s;
  s.name = "given";
  s.materials.push_back(luxel::Material{.name = "white"});
  Mesh given = quadMesh("given uvs", 0, 0);
  given.lightmapUvs = {Vec2(0.0f, 0.0f), Vec2(0.5f, 0.0f), Vec2(0.5f, 0.5f), Vec2(0.0f, 0.5f),
                       Vec2(1.0f, 0.0f), Vec2(1.0f, 0.5f)};
  s.meshes.push_back(given);
  s.meshes.push_back(quadMesh("generated", 0, 5));
  return s;
}

std::string base64(const std::string& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 2]));
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? k[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? k[v & 63] : '=';
  }
  return out;
}

}  // namespace

// glTF TEXCOORD_1 becomes Mesh::lightmapUvs, with v flipped like TEXCOORD_0 (Assimp's convention
// for every set), and the atlas uses it.
TEST(LightmapAtlas, ImportsGltfTexcoord1AsLightmapUvs) {
  const float pos[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
  const float uv0[8] = {0, 0, 1, 0, 1, 1, 0, 1};
  const float uv1[8] = {0.125f, 0.25f, 0.5f, 0.25f, 0.5f, 0.75f, 0.125f, 0.75f};
  std::string buf(reinterpret_cast<const char*>(pos), sizeof pos);
  buf.append(reinterpret_cast<const char*>(idx), sizeof idx);
  buf.append(reinterpret_cast<const char*>(uv0), sizeof uv0);
  buf.append(reinterpret_cast<const char*>(uv1), sizeof uv1);
  using nlohmann::json;
  json g = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes",
       {{{"name", "panel"},
         {"primitives",
          {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 2}, {"TEXCOORD_1", 3}}},
            {"indices", 1}}}}}}},
      {"buffers",
       {{{"byteLength", buf.size()},
         {"uri", "data:application/octet-stream;base64," + base64(buf)}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
        {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 12}},
        {{"buffer", 0}, {"byteOffset", 60}, {"byteLength", 32}},
        {{"buffer", 0}, {"byteOffset", 92}, {"byteLength", 32}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"},
         {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
        {{"bufferView", 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}},
        {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 3}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}}}}};
  fs::path dir = fs::path(LUXEL_TEST_TMP) / "lightmap";
  fs::create_directories(dir);
  fs::path file = dir / "panel.gltf";
  std::ofstream(file) << g.dump();
  Scene s = luxel::importMeshFile(file);
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& m = s.meshes[0];
  ASSERT_EQ(m.lightmapUvs.size(), m.positions.size());
  ASSERT_EQ(m.uvs.size(), m.positions.size());
  for (size_t i = 0; i < m.positions.size(); ++i) {
    // Vertex i of the file sits at (x, y); its TEXCOORD_1 is (0.125 + 0.375 x, 0.25 + 0.5 y).
    Vec3 p = m.positions[i];
    EXPECT_NEAR(m.lightmapUvs[i].x, 0.125f + 0.375f * p.x, 1e-6f);
    EXPECT_NEAR(m.lightmapUvs[i].y, 1.0f - (0.25f + 0.5f * p.y), 1e-6f);
    EXPECT_NEAR(m.uvs[i].y, 1.0f - p.y, 1e-6f);
  }
  AtlasOptions o;
  o.pageSize = 64;
  LightmapAtlas atlas = luxel::buildLightmapAtlas(s, o);
  EXPECT_EQ(atlas.pageCount, 1);
  EXPECT_EQ(atlas.chartCount, 1u);
  for (size_t f = 0; f < m.faces.size(); ++f)
    for (int k = 0; k < 4; ++k)
      EXPECT_EQ(atlas.faces[0][f].texel[size_t(k)], m.lightmapUvs[m.faces[f].v[size_t(k)]] * 64.0f);
}

TEST(LightmapAtlas, CornellBoxQuadsAtAGivenDensity) {
  Scene scene = luxel::loadScene("cornell");
  AtlasOptions o;
  o.texelsPerMetre = 64.0f;  // the 0.55 m walls get about 35 texels a side
  o.pageSize = 256;
  o.gutter = 2;
  LightmapAtlas atlas = luxel::buildLightmapAtlas(scene, o);
  EXPECT_EQ(atlas.pageCount, 1);
  EXPECT_EQ(atlas.pageSize, 256);
  EXPECT_FLOAT_EQ(atlas.texelsPerMetre, 64.0f);
  ASSERT_EQ(atlas.faces.size(), scene.meshes.size());
  AtlasCheck c = check(scene, atlas, o.gutter);
  EXPECT_EQ(c.faces, scene.faceCount());
  EXPECT_EQ(c.outside, 0u);
  EXPECT_EQ(c.overlaps, 0u);
  EXPECT_EQ(c.gutterViolations, 0u);
  EXPECT_EQ(c.conservative, 0u);  // every Cornell face holds texel centres
  EXPECT_EQ(c.unflagged, 0u);
  // Flat faces keep the density: UV area / world area = density^2, within 1%.
  double worst = 0;
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    for (size_t f = 0; f < scene.meshes[m].faces.size(); ++f) {
      const Face& face = scene.meshes[m].faces[f];
      double ratio = uvArea(face, atlas.faces[m][f]) / faceArea(scene.meshes[m], face) / (64.0 * 64.0);
      worst = std::max(worst, std::abs(ratio - 1.0));
    }
  EXPECT_LT(worst, 0.01);
  std::printf("cornell: %zu faces, %zu charts, 1 page of 256^2, %zu texels covered, worst density "
              "error %.2g%%\n",
              c.faces, atlas.chartCount, c.coveredTexels, 100 * worst);
  // No two Cornell faces share a whole edge within 45 degrees (the ceiling's four quads meet in
  // T-junctions, the blocks' faces at 90 degrees): every face is a chart.
  EXPECT_EQ(atlas.chartCount, scene.faceCount());
}

TEST(LightmapAtlas, FitsOnePageWhenNoDensityIsGiven) {
  Scene scene = luxel::loadScene("cornell");
  AtlasOptions o;
  o.pageSize = 128;
  LightmapAtlas atlas = luxel::buildLightmapAtlas(scene, o);
  EXPECT_EQ(atlas.pageCount, 1);
  EXPECT_GT(atlas.texelsPerMetre, 0.0f);
  AtlasCheck c = check(scene, atlas, o.gutter);
  EXPECT_EQ(c.outside, 0u);
  EXPECT_EQ(c.overlaps, 0u);
  EXPECT_EQ(c.gutterViolations, 0u);
  EXPECT_EQ(c.unflagged, 0u);
  // The area bound: the charts cannot cover more than the page.
  double area = 0;
  for (const Mesh& m : scene.meshes)
    for (const Face& f : m.faces) area += faceArea(m, f);
  double bound = std::sqrt(128.0 * 128.0 / area);
  std::printf("cornell fit: %.1f texels per metre on 128^2 (area bound %.1f), %zu texels covered\n",
              atlas.texelsPerMetre, bound, c.coveredTexels);
  EXPECT_LE(atlas.texelsPerMetre, bound);
  EXPECT_GT(atlas.texelsPerMetre, 0.4 * bound);  // shelf packing wastes some, not most
  // A density that cannot fit on one page spills onto more pages, scaled down where a chart
  // is larger than a page.
  o.texelsPerMetre = 4.0f * atlas.texelsPerMetre;
  LightmapAtlas big = luxel::buildLightmapAtlas(scene, o);
  EXPECT_GT(big.pageCount, 1);
  AtlasCheck cb = check(scene, big, o.gutter);
  EXPECT_EQ(cb.outside, 0u);
  EXPECT_EQ(cb.overlaps, 0u);
  EXPECT_EQ(cb.gutterViolations, 0u);
}

TEST(LightmapAtlas, StanfordBunnyDistortion) {
  fs::path path = fs::path(LUXEL_TEST_SCENES) / "stanford-bunny" / "bunny.obj";
  if (!fs::exists(path))
    GTEST_SKIP() << path.string() << " is missing: unzip ../shared/scenes/*.zip there";
  Scene scene = luxel::importMeshFile(path);
  AtlasOptions o;
  o.pageSize = 2048;
  auto t0 = std::chrono::steady_clock::now();
  LightmapAtlas atlas = luxel::buildLightmapAtlas(scene, o);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(atlas.pageCount, 1);
  AtlasCheck c = check(scene, atlas, o.gutter);
  EXPECT_EQ(c.outside, 0u);
  EXPECT_EQ(c.overlaps, 0u);
  EXPECT_EQ(c.gutterViolations, 0u);
  EXPECT_EQ(c.unflagged, 0u);

  // Distortion per triangle (quads as two): area stretch against its chart's mean, and the mean
  // absolute difference of its three angles.
  struct Tri {
    double area, uv, angle;
    uint32_t chart;
  };
  std::vector<Tri> tris;
  std::vector<double> chartArea(atlas.chartCount, 0.0), chartUv(atlas.chartCount, 0.0);
  auto angles = [](auto a, auto b, auto c, double out[3]) {
    using V = decltype(a);
    V p[3] = {a, b, c};
    for (int i = 0; i < 3; ++i) {
      auto u = p[(i + 1) % 3] - p[i], v = p[(i + 2) % 3] - p[i];
      double d = double(glm::dot(u, v)) / (double(glm::length(u)) * double(glm::length(v)));
      out[i] = std::acos(std::clamp(d, -1.0, 1.0)) * 180.0 / kPi;
    }
  };
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    for (size_t f = 0; f < mesh.faces.size(); ++f) {
      const Face& face = mesh.faces[f];
      const auto& uv = atlas.faces[m][f];
      for (int t = 0; t < (face.isTriangle() ? 1 : 2); ++t) {
        int i0 = 0, i1 = t == 0 ? 1 : 2, i2 = t == 0 ? 2 : 3;
        Vec3 a = mesh.positions[face.v[size_t(i0)]], b = mesh.positions[face.v[size_t(i1)]],
             cc = mesh.positions[face.v[size_t(i2)]];
        Tri tri{area3(a, b, cc), area2(uv.texel[size_t(i0)], uv.texel[size_t(i1)], uv.texel[size_t(i2)]),
                0.0, uv.chart};
        if (tri.area <= 1e-14) continue;
        double a3[3], a2[3];
        angles(a, b, cc, a3);
        angles(uv.texel[size_t(i0)], uv.texel[size_t(i1)], uv.texel[size_t(i2)], a2);
        tri.angle = (std::abs(a3[0] - a2[0]) + std::abs(a3[1] - a2[1]) + std::abs(a3[2] - a2[2])) / 3;
        chartArea[uv.chart] += tri.area;
        chartUv[uv.chart] += tri.uv;
        tris.push_back(tri);
      }
    }
  }
  size_t within2 = 0, within125 = 0;
  double angleSum = 0;
  std::vector<double> angle;
  for (const Tri& t : tris) {
    double stretch = (t.uv / t.area) / (chartUv[t.chart] / chartArea[t.chart]);
    if (stretch >= 0.5 && stretch <= 2.0) ++within2;
    if (stretch >= 0.8 && stretch <= 1.25) ++within125;
    angleSum += t.angle;
    angle.push_back(t.angle);
  }
  std::sort(angle.begin(), angle.end());
  double frac2 = double(within2) / double(tris.size()), frac125 = double(within125) / double(tris.size());
  double meanAngle = angleSum / double(tris.size()), p95Angle = angle[angle.size() * 95 / 100];
  std::printf("bunny: %zu faces, %zu charts, %.2f s, %.1f texels per metre on 2048^2, %zu texels "
              "covered, %zu faces conservative; area stretch within 2x: %.2f%%, within 1.25x: "
              "%.2f%%; angle distortion mean %.2f deg, 95th percentile %.2f deg\n",
              c.faces, atlas.chartCount, seconds, atlas.texelsPerMetre, c.coveredTexels,
              c.conservative, 100 * frac2, 100 * frac125, meanAngle, p95Angle);
  // The bounds (docs/lightmaps.md), with margin over the measured values.
  // Measured (2048^2 page, 45-degree charts): 100% within 2x (the parameterisation cuts charts
  // until it holds), 95.6% within 1.25x, angle distortion mean 0.13 and 95th percentile 0.39 deg.
  EXPECT_GE(frac2, 0.999);
  EXPECT_GE(frac125, 0.90);
  EXPECT_LT(meanAngle, 1.0);
  EXPECT_LT(p95Angle, 2.0);
  EXPECT_LT(double(c.conservative), 0.01 * double(c.faces));
}

TEST(LightmapAtlas, UsesGivenUvsAsTheyAre) {
  Scene s = twoMeshes();
  AtlasOptions o;
  o.pageSize = 64;
  o.texelsPerMetre = 16.0f;
  LightmapAtlas atlas = luxel::buildLightmapAtlas(s, o);
  EXPECT_EQ(atlas.pageCount, 2);  // the given layout on page 0, the generated charts on page 1
  for (size_t f = 0; f < s.meshes[0].faces.size(); ++f) {
    EXPECT_EQ(atlas.faces[0][f].page, 0u);
    for (int k = 0; k < 4; ++k)
      EXPECT_EQ(atlas.faces[0][f].texel[size_t(k)],
                s.meshes[0].lightmapUvs[s.meshes[0].faces[f].v[size_t(k)]] * 64.0f);
  }
  for (const auto& uv : atlas.faces[1]) EXPECT_EQ(uv.page, 1u);
  // The two faces share an edge in UV space: one chart; the generated mesh is one flat chart.
  EXPECT_EQ(atlas.chartCount, 2u);
  AtlasCheck c = check(s, atlas, 0);
  EXPECT_EQ(c.overlaps, 0u);
  EXPECT_EQ(c.outside, 0u);
  // Ignoring them lays the mesh out afresh.
  o.useMeshUvs = false;
  EXPECT_EQ(luxel::buildLightmapAtlas(s, o).pageCount, 1);
}

// A second UV set with no area (every vertex at (0,0): a placeholder channel, or one exported
// empty) passed the checks (nothing overlaps, nothing leaves [0,1]) and baked black: no texel
// centre falls in a face of no area. The mesh is unwrapped by luxel instead, with a warning.
TEST(LightmapAtlas, GivenUvsOfNoAreaAreUnwrappedWithAWarning) {
  Scene s = twoMeshes();
  for (Vec2& uv : s.meshes[0].lightmapUvs) uv = Vec2(0.0f, 0.0f);
  AtlasOptions o;
  o.pageSize = 64;
  o.texelsPerMetre = 16.0f;
  LightmapAtlas atlas = luxel::buildLightmapAtlas(s, o);
  ASSERT_EQ(atlas.warnings.size(), 1u);
  EXPECT_NE(atlas.warnings[0].find("mesh 'given uvs'"), std::string::npos) << atlas.warnings[0];
  EXPECT_NE(atlas.warnings[0].find("unwrapped by luxel"), std::string::npos) << atlas.warnings[0];
  EXPECT_EQ(atlas.pageCount, 1);  // both meshes generated, packed together
  for (const auto& uv : atlas.faces[0]) EXPECT_FALSE(uv.conservative);  // each face holds texels
  AtlasCheck c = check(s, atlas, 0);
  EXPECT_EQ(c.overlaps, 0u);
  EXPECT_EQ(c.outside, 0u);

  // Collapsed into a line (u only): no area either.
  s = twoMeshes();
  for (Vec2& uv : s.meshes[0].lightmapUvs) uv.y = 0.25f;
  EXPECT_EQ(luxel::buildLightmapAtlas(s, o).warnings.size(), 1u);

  // Engines' unwrappers collapse hidden faces on purpose; here one face of two (half the
  // surface, not more) has no UV area: the layout is kept as given, without a warning.
  s = twoMeshes();
  s.meshes[0].lightmapUvs[4] = s.meshes[0].lightmapUvs[1];
  s.meshes[0].lightmapUvs[5] = s.meshes[0].lightmapUvs[2];
  atlas = luxel::buildLightmapAtlas(s, o);
  EXPECT_TRUE(atlas.warnings.empty());
  EXPECT_EQ(atlas.pageCount, 2);
  EXPECT_EQ(atlas.faces[0][1].texel[1], s.meshes[0].lightmapUvs[4] * 64.0f);
}

TEST(LightmapAtlas, OverlappingOrOutOfRangeGivenUvsNameTheMesh) {
  Scene s = twoMeshes();
  s.meshes[0].lightmapUvs[4] = Vec2(0.25f, 0.0f);  // the second quad folds back over the first
  s.meshes[0].lightmapUvs[5] = Vec2(0.25f, 0.5f);
  std::string msg = errorOf([&] { luxel::buildLightmapAtlas(s); });
  EXPECT_NE(msg.find("given uvs"), std::string::npos) << msg;
  EXPECT_NE(msg.find("overlap"), std::string::npos) << msg;

  s = twoMeshes();
  s.meshes[0].lightmapUvs[4] = Vec2(1.2f, 0.0f);
  msg = errorOf([&] { luxel::buildLightmapAtlas(s); });
  EXPECT_NE(msg.find("given uvs"), std::string::npos) << msg;
  EXPECT_NE(msg.find("outside [0,1]"), std::string::npos) << msg;

  // Not checked, and not used, when the options say to ignore them.
  AtlasOptions o;
  o.useMeshUvs = false;
  EXPECT_NO_THROW(luxel::buildLightmapAtlas(s, o));

  // Scene::validate: one per position, finite.
  s = twoMeshes();
  s.meshes[0].lightmapUvs.pop_back();
  msg = errorOf([&] { s.validate(); });
  EXPECT_NE(msg.find("given uvs"), std::string::npos) << msg;
  s = twoMeshes();
  s.meshes[0].lightmapUvs[0].x = NAN;
  msg = errorOf([&] { s.validate(); });
  EXPECT_NE(msg.find("not finite"), std::string::npos) << msg;
}

// Meshes whose given UVs address one page (an engine's lightmap atlas, a baked glb's pages) share
// it: one page, checked together, so that one mesh's UVs over another's are an overlap and charts
// of two meshes with no texel between them are a gutter warning naming both.
TEST(LightmapAtlas, MeshesThatShareAPageAreCheckedTogether) {
  Scene s = twoMeshes();
  s.meshes.pop_back();  // two given meshes: the second's charts above the first's
  Mesh above = quadMesh("above", 0, 5);
  above.lightmapUvs = {Vec2(0.0f, 0.75f), Vec2(0.5f, 0.75f), Vec2(0.5f, 1.0f), Vec2(0.0f, 1.0f),
                       Vec2(1.0f, 0.75f), Vec2(1.0f, 1.0f)};
  s.meshes.push_back(above);
  AtlasOptions o;
  o.pageSize = 64;
  EXPECT_EQ(luxel::buildLightmapAtlas(s, o).pageCount, 2);  // a page each, by default
  o.givenUvPages = {7, 7};
  LightmapAtlas atlas = luxel::buildLightmapAtlas(s, o);
  EXPECT_EQ(atlas.pageCount, 1);
  EXPECT_TRUE(atlas.warnings.empty());
  for (const auto& mesh : atlas.faces)
    for (const auto& uv : mesh) EXPECT_EQ(uv.page, 0u);
  EXPECT_EQ(atlas.faces[1][0].texel[0], Vec2(0.0f, 48.0f));
  EXPECT_EQ(atlas.chartCount, 2u);  // a chart a mesh, numbered across the page
  EXPECT_NE(atlas.faces[0][0].chart, atlas.faces[1][0].chart);

  // Touching at v = 0.5: no gutter between the two meshes' charts.
  for (Vec2& uv : s.meshes[1].lightmapUvs) uv.y -= 0.25f;
  atlas = luxel::buildLightmapAtlas(s, o);
  ASSERT_EQ(atlas.warnings.size(), 1u);
  EXPECT_NE(atlas.warnings[0].find("meshes 'given uvs', 'above'"), std::string::npos) << atlas.warnings[0];
  // On pages of their own the same UVs are fine.
  o.givenUvPages = {0, 1};
  EXPECT_TRUE(luxel::buildLightmapAtlas(s, o).warnings.empty());

  // Over each other on a shared page: an overlap naming both meshes, or kept for the texels view.
  for (Vec2& uv : s.meshes[1].lightmapUvs) uv.y -= 0.5f;
  EXPECT_EQ(luxel::buildLightmapAtlas(s, o).pageCount, 2);
  o.givenUvPages = {3, 3};
  const std::string msg = errorOf([&] { luxel::buildLightmapAtlas(s, o); });
  EXPECT_NE(msg.find("mesh 'given uvs' face"), std::string::npos) << msg;
  EXPECT_NE(msg.find("mesh 'above' face"), std::string::npos) << msg;
  EXPECT_NE(msg.find("shared page"), std::string::npos) << msg;
  o.keepOverlappingUvs = true;
  EXPECT_EQ(luxel::buildLightmapAtlas(s, o).pageCount, 1);

  // One number a mesh, or none.
  o.givenUvPages = {3};
  EXPECT_NE(errorOf([&] { luxel::buildLightmapAtlas(s, o); }).find("1 shared pages given for the 2 meshes"),
            std::string::npos);
}

TEST(LightmapAtlas, AbsurdOptionsAreErrors) {
  Scene s = luxel::loadScene("cornell");
  auto with = [&](auto set) {
    AtlasOptions o;
    set(o);
    return errorOf([&] { luxel::buildLightmapAtlas(s, o); });
  };
  EXPECT_NE(with([](AtlasOptions& o) { o.pageSize = 0; }).find("page size"), std::string::npos);
  EXPECT_NE(with([](AtlasOptions& o) { o.pageSize = 100000; }).find("page size"), std::string::npos);
  EXPECT_NE(with([](AtlasOptions& o) { o.texelsPerMetre = -1; }).find("texels per metre"),
            std::string::npos);
  EXPECT_NE(with([](AtlasOptions& o) { o.texelsPerMetre = NAN; }).find("texels per metre"),
            std::string::npos);
  EXPECT_NE(with([](AtlasOptions& o) { o.gutter = -1; }).find("gutter"), std::string::npos);
  EXPECT_NE(with([](AtlasOptions& o) { o.chartAngle = 0; }).find("chart angle"), std::string::npos);
}
