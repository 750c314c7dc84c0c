// The emitting surfaces as the polygons that direct light samples (transport/emitting_polygons.h):
// pieces of one lamp that tile a convex polygon become it, and nothing else is joined.
#include <gtest/gtest.h>

#include "scene/builtin/builtin_scenes.h"
#include "scene/builtin/seed_geometry.h"
#include "solve/emitter_direct.h"
#include "transport/emitting_polygons.h"
#include "transport/form_factor.h"

namespace luxel {
namespace {

// Each mesh is a lamp of its own material (emission `Le` times its index + 1 where `distinct`),
// over a grey floor; one element a face.
SurfaceSet lampsOverAFloor(const std::vector<Mesh>& lamps, bool distinct = false, float elementSize = 100.0f) {
  Scene scene;
  scene.name = "lamps";
  scene.materials.push_back(Material{.name = "grey", .reflectance = Rgb(0.5f)});
  Mesh floor{.name = "floor", .material = 0};
  builtin::addQuad(floor, {-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2});
  scene.meshes.push_back(floor);
  for (size_t k = 0; k < lamps.size(); ++k) {
    const float le = distinct ? float(k + 1) : 1.0f;
    scene.materials.push_back(Material{.name = "lamp" + std::to_string(k), .reflectance = Rgb(0.0f), .emission = Rgb(le)});
    Mesh m = lamps[k];
    m.material = uint32_t(scene.materials.size() - 1);
    scene.meshes.push_back(m);
  }
  return discretise(scene, DiscretiseOptions{.elementSize = elementSize, .orientByLight = false});
}

// A grid of nu x nv cells of 0.25 m facing down at height 1, from (x0, z0).
Mesh cells(int nu, int nv, float x0 = -0.5f, float z0 = -0.5f, const std::function<bool(int, int)>& skip = {}) {
  Mesh m{.name = "cells"};
  builtin::addCellGrid(m, {x0, 1, z0}, {0.25f * float(nu), 0, 0}, {0, 0, 0.25f * float(nv)}, nu, nv, skip);
  return m;
}

float totalArea(const std::vector<EmittingPolygon>& polygons) {
  float a = 0.0f;
  for (const EmittingPolygon& p : polygons) a += p.polygon.area();
  return a;
}

TEST(EmittingPolygons, APanelOfCellsIsOneQuad) {
  const std::vector<EmittingPolygon> p = emittingPolygons(lampsOverAFloor({cells(4, 4)}));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].polygon.count, 4);
  EXPECT_NEAR(p[0].polygon.area(), 1.0f, 1e-6f);
  EXPECT_GT(glm::dot(p[0].polygon.normal(), Vec3(0, -1, 0)), 0.9999f) << "the winding keeps the cells' side";
  EXPECT_GT(glm::dot(p[0].normal, Vec3(0, -1, 0)), 0.9999f);
  EXPECT_NEAR(p[0].exitance.g, std::numbers::pi_v<float>, 1e-5f);
  for (const Vec3& v : p[0].polygon.v) EXPECT_NEAR(std::abs(v.x) + std::abs(v.z), 1.0f, 1e-6f) << "a corner of the panel";
  // A rectangle of 2 x 3 cells too.
  const std::vector<EmittingPolygon> r = emittingPolygons(lampsOverAFloor({cells(2, 3)}));
  ASSERT_EQ(r.size(), 1u);
  EXPECT_NEAR(r[0].polygon.area(), 6 * 0.0625f, 1e-6f);
}

TEST(EmittingPolygons, AQuadSplitIntoTrianglesIsTheQuad) {
  Mesh lamp{.name = "lamp"};
  lamp.positions = {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}};  // normal -y
  lamp.faces = {Face{{0, 1, 2, 2}}, Face{{0, 2, 3, 3}}};
  const std::vector<EmittingPolygon> p = emittingPolygons(lampsOverAFloor({lamp}));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].polygon.count, 4);
  EXPECT_NEAR(p[0].polygon.area(), 1.0f, 1e-6f);
  EXPECT_GT(glm::dot(p[0].polygon.normal(), Vec3(0, -1, 0)), 0.9999f);
}

TEST(EmittingPolygons, PiecesThatAreNotOneConvexLampStayApart) {
  // An L of three cells: its hull is four cells' area.
  const auto l = emittingPolygons(lampsOverAFloor({cells(2, 2, -0.5f, -0.5f, [](int i, int j) { return i == 1 && j == 1; })}));
  EXPECT_EQ(l.size(), 3u);
  // Two panels a cell apart.
  EXPECT_EQ(emittingPolygons(lampsOverAFloor({cells(1, 1, 0.0f, 0.0f), cells(1, 1, 0.0f, 0.5f)})).size(), 2u);
  // Two cells side by side with different exitance.
  EXPECT_EQ(emittingPolygons(lampsOverAFloor({cells(1, 1, 0.0f, 0.0f), cells(1, 1, 0.25f, 0.0f)}, true)).size(), 2u);
  // The same, with one exitance: one lamp of two materials is still one lamp.
  EXPECT_EQ(emittingPolygons(lampsOverAFloor({cells(1, 1, 0.0f, 0.0f), cells(1, 1, 0.25f, 0.0f)})).size(), 1u);
  // Folded: two cells sharing an edge, at a right angle.
  Mesh folded{.name = "folded"};
  builtin::addQuad(folded, {0.25f, 1, 0}, {0.25f, 1, 0.25f}, {0.25f, 0.75f, 0.25f}, {0.25f, 0.75f, 0});
  EXPECT_EQ(emittingPolygons(lampsOverAFloor({cells(1, 1, 0.0f, 0.0f), folded})).size(), 2u);
  // Facing opposite ways: a cell and its neighbour turned over.
  Mesh turned{.name = "turned"};
  builtin::addQuad(turned, {0.25f, 1, 0}, {0.25f, 1, 0.25f}, {0.5f, 1, 0.25f}, {0.5f, 1, 0});  // facing up
  EXPECT_EQ(emittingPolygons(lampsOverAFloor({cells(1, 1, 0.0f, 0.0f), turned})).size(), 2u);
  // One quad twice: the pieces overlap.
  const auto d = emittingPolygons(lampsOverAFloor({cells(1, 1, 0.0f, 0.0f), cells(1, 1, 0.0f, 0.0f)}));
  EXPECT_EQ(d.size(), 2u);
  EXPECT_NEAR(totalArea(d), 2 * 0.0625f, 1e-6f);
}

TEST(EmittingPolygons, APanelOfCellsLightsTheFloorAsOneQuadDoes) {
  // Where nothing is in the way every element's first rays agree, so the 16 cells, joined, cost
  // 16 rays an element, not 256, and give the light of one quad lamp of the panel's shape.
  auto direct = [](const SurfaceSet& set) {
    std::vector<Polygon> faces;
    for (const SurfaceFace& f : set.faces) faces.push_back(Polygon{f.corners, f.triangle ? 3 : 4});
    const RayTracer tracer(faces);
    return emitterDirectLight(set, tracer, 0, 7);
  };
  Mesh quad{.name = "quad"};
  builtin::addQuad(quad, {-0.5f, 1, -0.5f}, {0.5f, 1, -0.5f}, {0.5f, 1, 0.5f}, {-0.5f, 1, 0.5f});  // normal -y
  const SurfaceSet gridSet = lampsOverAFloor({cells(4, 4)}, false, 0.5f), quadSet = lampsOverAFloor({quad}, false, 0.5f);
  const EmitterDirectLight grid = direct(gridSet), one = direct(quadSet);
  std::vector<Rgb> gridFloor, oneFloor;
  for (size_t e = 0; e < gridSet.elements.size(); ++e)
    if (gridSet.elements[e].material == 0) gridFloor.push_back(grid.irradiance[e]);
  for (size_t e = 0; e < quadSet.elements.size(); ++e)
    if (quadSet.elements[e].material == 0) oneFloor.push_back(one.irradiance[e]);
  ASSERT_EQ(gridFloor.size(), 64u);
  ASSERT_EQ(oneFloor.size(), 64u);
  for (size_t k = 0; k < gridFloor.size(); ++k) EXPECT_NEAR(gridFloor[k].g / oneFloor[k].g, 1.0, 1e-4) << k;
  EXPECT_EQ(grid.rays, 64u * 16u);
  EXPECT_EQ(one.rays, 64u * 16u);
}

}  // namespace
}  // namespace luxel
