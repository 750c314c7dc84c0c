// The ray tracer cuts quads along their 0-2 diagonal, into the triangles (0,1,2) and (0,2,3) that
// discretisation, the lightmap bake and the glTF export use; Embree's own quad cuts along 1-3. On a
// non-planar quad the two surfaces differ, and hits on the wrong one put lightmap look-ups off.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "luxel/error.h"
#include "luxel/lightmap.h"
#include "luxel/render.h"
#include "render/camera_frame.h"
#include "trace/ray_tracer.h"

namespace {

using luxel::Vec3;

// Corner 3 lifted by 0.6: (0,1,2) lies in z = 0, (0,2,3) rises to z = 0.6 (y - x) above y > x.
// Cut along 1-3 instead, the whole quad would be bent the other way.
const std::array<Vec3, 4> kCorners = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0.6f)};

float heightOnTriangles(float x, float y) { return y > x ? 0.6f * (y - x) : 0.0f; }

Vec3 pointAt(const luxel::HitTriangle& t) {
  return t.w.x * kCorners[0] + t.w.y * kCorners[size_t(t.i1)] + t.w.z * kCorners[size_t(t.i2)];
}

TEST(RayTracerQuads, NonPlanarQuadIsCutAlongZeroTwo) {
  const luxel::Polygon quad{kCorners, 4};
  const luxel::RayTracer tracer(std::span(&quad, 1));
  std::vector<std::array<float, 2>> points = {{0.3f, 0.2f}, {0.2f, 0.3f}, {0.8f, 0.1f}, {0.1f, 0.8f},
                                              {0.5f, 0.5f}, {0.9f, 0.9f}, {0.25f, 0.75f}};
  for (float d : {1e-3f, 1e-2f})  // either side of the diagonal, close to it
    for (float c : {0.2f, 0.5f, 0.8f}) points.push_back({c + d, c - d}), points.push_back({c - d, c + d});
  std::vector<RTCRayHit> hits;
  for (auto [x, y] : points) {
    RTCRayHit h;
    h.ray = luxel::makeRay(Vec3(x, y, 10.0f), Vec3(0, 0, -1), 0.0f, 100.0f);
    hits.push_back(h);
  }
  tracer.intersect(hits);
  for (size_t i = 0; i < points.size(); ++i) {
    const auto [x, y] = points[i];
    const RTCRayHit& h = hits[i];
    ASSERT_NE(h.hit.geomID, RTC_INVALID_GEOMETRY_ID) << x << "," << y;
    EXPECT_EQ(h.hit.primID, 0u);
    EXPECT_NEAR(10.0f - h.ray.tfar, heightOnTriangles(x, y), 1e-4f) << x << "," << y;
    // (u, v) run along 0->1 and 0->3: on this square footprint they are x and y.
    EXPECT_NEAR(h.hit.u, x, 1e-4f) << x << "," << y;
    EXPECT_NEAR(h.hit.v, y, 1e-4f) << x << "," << y;
    const luxel::HitTriangle t = luxel::hitTriangle(4, h.hit.u, h.hit.v);
    EXPECT_EQ(t.i1, y > x ? 2 : 1);
    const Vec3 p = pointAt(t);
    EXPECT_NEAR(p.x, x, 1e-4f);
    EXPECT_NEAR(p.y, y, 1e-4f);
    EXPECT_NEAR(p.z, heightOnTriangles(x, y), 1e-4f);
  }
}

TEST(RayTracerQuads, ObliqueHitsReconstructTheHitPoint) {
  const luxel::Polygon quad{kCorners, 4};
  const luxel::RayTracer tracer(std::span(&quad, 1));
  const Vec3 eye(0.5f, -1.2f, 2.0f);
  std::vector<RTCRayHit> hits;
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) {
      RTCRayHit h;
      const Vec3 target((float(i) + 0.5f) / 16.0f, (float(j) + 0.5f) / 16.0f, 0.0f);
      h.ray = luxel::makeRay(eye, target - eye, 0.0f, 100.0f);
      hits.push_back(h);
    }
  tracer.intersect(hits);
  int checked = 0;
  for (const RTCRayHit& h : hits) {
    if (h.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
    const Vec3 hitPoint = eye + h.ray.tfar * Vec3(h.ray.dir_x, h.ray.dir_y, h.ray.dir_z);
    const Vec3 p = pointAt(luxel::hitTriangle(4, h.hit.u, h.hit.v));
    EXPECT_NEAR(glm::length(p - hitPoint), 0.0f, 1e-4f);
    EXPECT_NEAR(p.z, heightOnTriangles(p.x, p.y), 1e-4f);
    ++checked;
  }
  EXPECT_GT(checked, 200);
}

TEST(RayTracerQuads, TrianglesKeepBarycentricParameters) {
  const std::array<luxel::Polygon, 2> polys = {
      luxel::Polygon{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 1, 0)}, 3},
      luxel::Polygon{{Vec3(2, 0, 0), Vec3(3, 0, 0), Vec3(3, 1, 0), Vec3(2, 1, 0)}, 4}};
  const luxel::RayTracer tracer(polys);
  std::array<RTCRayHit, 2> hits;
  hits[0].ray = luxel::makeRay(Vec3(0.2f, 0.3f, 1.0f), Vec3(0, 0, -1), 0.0f, 10.0f);
  hits[1].ray = luxel::makeRay(Vec3(2.7f, 0.4f, 1.0f), Vec3(0, 0, -1), 0.0f, 10.0f);
  tracer.intersect(hits);
  EXPECT_EQ(hits[0].hit.primID, 0u);
  EXPECT_NEAR(hits[0].hit.u, 0.2f, 1e-5f);
  EXPECT_NEAR(hits[0].hit.v, 0.3f, 1e-5f);
  EXPECT_EQ(hits[1].hit.primID, 1u);
  EXPECT_NEAR(hits[1].hit.u, 0.7f, 1e-5f);
  EXPECT_NEAR(hits[1].hit.v, 0.4f, 1e-5f);
}

// The lightmapped render looks the hit up on the same triangles: with a lightmap whose value is its
// own texel coordinate, every pixel's look-up maps back to a point of the (0,1,2)/(0,2,3) surface
// that lies on a ray through that pixel.
TEST(RayTracerQuads, LightmapLookUpsLieOnThePixelsRays) {
  luxel::Scene scene;
  luxel::Mesh mesh;
  mesh.positions.assign(kCorners.begin(), kCorners.end());
  mesh.faces = {luxel::Face{{0, 1, 2, 3}}};
  scene.meshes = {mesh};
  luxel::Material m;
  m.reflectance = luxel::Rgb(0.5f);
  m.twoSided = true;
  scene.materials = {m};

  constexpr int kPage = 64;
  constexpr float kLo = 8.0f, kSide = 48.0f;  // the face's texel square
  luxel::LightmapAtlas atlas;
  atlas.pageSize = kPage;
  atlas.pageCount = 1;
  luxel::LightmapAtlas::FaceUv fuv;
  fuv.texel = {luxel::Vec2(kLo, kLo), luxel::Vec2(kLo + kSide, kLo), luxel::Vec2(kLo + kSide, kLo + kSide),
               luxel::Vec2(kLo, kLo + kSide)};
  atlas.faces = {{fuv}};
  luxel::LightmapBake bake;
  bake.pageSize = kPage;
  bake.pages.assign(1, std::vector<luxel::Rgb>(size_t(kPage * kPage)));
  for (int y = 0; y < kPage; ++y)
    for (int x = 0; x < kPage; ++x) bake.pages[0][size_t(y * kPage + x)] = luxel::Rgb(float(x) + 0.5f, float(y) + 0.5f, 0.0f);

  luxel::RenderOptions ro;
  ro.camera.eye = Vec3(0.5f, -1.2f, 2.0f);
  ro.camera.target = Vec3(0.5f, 0.5f, 0.1f);
  ro.camera.up = Vec3(0, 0, 1);
  ro.camera.fovY = 50.0f;
  ro.width = ro.height = 48;
  ro.samplesPerPixel = 1;
  const luxel::Image img = luxel::renderLightmapped(scene, atlas, bake, ro);

  const luxel::CameraFrame cam(ro.camera, ro.width, ro.height);
  const float toTexel = std::numbers::pi_v<float> / 0.5f;  // radiance = 0.5 / pi * H
  int checked = 0, upper = 0;
  for (int y = 0; y < ro.height; ++y)
    for (int x = 0; x < ro.width; ++x) {
      const luxel::Rgb c = img.at(x, y);
      if (c.r <= 0.0f) continue;  // missed the quad
      const float u = (c.r * toTexel - kLo) / kSide, v = (c.g * toTexel - kLo) / kSide;
      const luxel::HitTriangle t = luxel::hitTriangle(4, u, v);
      const Vec3 d = pointAt(t) - cam.eye;
      const float depth = glm::dot(d, cam.forward);
      const float sx = (glm::dot(d, cam.right) / depth / (cam.tanHalfY * cam.aspect) + 1.0f) * 0.5f;
      const float sy = (1.0f - glm::dot(d, cam.up) / depth / cam.tanHalfY) * 0.5f;
      const float tol = 1e-4f;
      EXPECT_GE(sx, float(x) / float(ro.width) - tol) << x << "," << y;
      EXPECT_LE(sx, float(x + 1) / float(ro.width) + tol) << x << "," << y;
      EXPECT_GE(sy, float(y) / float(ro.height) - tol) << x << "," << y;
      EXPECT_LE(sy, float(y + 1) / float(ro.height) + tol) << x << "," << y;
      ++checked;
      upper += t.i1 == 2;
    }
  EXPECT_GT(checked, 300);
  EXPECT_GT(upper, 100);            // the lifted triangle is in view
  EXPECT_GT(checked - upper, 100);  // and so is the flat one
}

// The transport of a static scene keeps no copy of the faces: it reads them back from the
// tracer, corners in their own order (the BVH stores a quad's rotated by one).
TEST(RayTracerQuads, PolygonsReadBackAsTheyWentIn) {
  const std::vector<luxel::Polygon> polygons = {{kCorners, 4},
                                                {{Vec3(2, 0, 0), Vec3(3, 0, 0.5f), Vec3(2, 1, 0), Vec3(0)}, 3}};
  const luxel::RayTracer tracer(polygons);
  for (uint32_t i = 0; i < polygons.size(); ++i) {
    const luxel::Polygon back = tracer.polygonAsBuilt(i);
    ASSERT_EQ(back.count, polygons[i].count);
    for (int c = 0; c < back.count; ++c) EXPECT_EQ(back.v[size_t(c)], polygons[i].v[size_t(c)]) << i << ", " << c;
  }
  EXPECT_THROW(tracer.polygonAsBuilt(2), luxel::Error);
}

}  // namespace
