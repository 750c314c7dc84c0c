// Lattices of gathered points where a vertex gather's interpolation misses the light's shape
// (render/gather_refinement.h), on a sill: a floor lit only by a 5 cm step beside it (one bounce of
// a sun off the step), whose light falls to a twentieth within 10 cm of the crease. The corners at
// the crease see the step fill half their sky and the far ones see nothing, so a straight line
// between them overstates the floor's mean about tenfold.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "luxel/render.h"
#include "luxel/solve.h"
#include "render/corner_values.h"
#include "render/direct_light.h"
#include "render/final_gather.h"
#include "render/gather_refinement.h"
#include "scene/builtin/builtin_scenes.h"
#include "trace/element_polygons.h"

namespace luxel {
namespace {

// A 2 x 1 m floor (y = 0, facing +y) with a 5 cm step along its edge x = 0 (facing +x), under a
// sun from +x that lights the step's face; the gather reads no solution (its corners are 0), so
// the floor's gathered light is the step's one bounce alone.
struct Sill {
  Sill() {
    scene.name = "sill";
    scene.materials = {Material{.name = "floor", .reflectance = Rgb(0.5f)},
                       Material{.name = "step", .reflectance = Rgb(0.8f)}};
    Mesh floor{.name = "floor", .material = 0};
    builtin::addQuad(floor, {0, 0, 0}, {0, 0, 1}, {2, 0, 1}, {2, 0, 0});  // +y
    Mesh step{.name = "step", .material = 1};
    builtin::addQuad(step, {0, 0, 0}, {0, 0.05f, 0}, {0, 0.05f, 1}, {0, 0, 1});  // +x
    scene.meshes = {floor, step};
    Light sun;
    sun.type = Light::Type::Directional;
    sun.name = "sun";
    sun.direction = glm::normalize(Vec3(-1.0f, -0.5f, 0.0f));
    sun.intensity = 1000.0f;
    sun.angularRadius = 0.0f;
    scene.lights = {sun};
    surfaces = discretise(scene, DiscretiseOptions{.elementBudget = 16});
    polygons = elementPolygonsTwinsApart(surfaces);
    tracer.emplace(polygons);
    direct.emplace(scene, surfaces, &surfaces);
    corners.assign(surfaces.elements.size() * 4, Rgb(0.0f));
    gather.emplace(surfaces, *tracer, *direct, corners, /*gatherNearHits=*/false);
  }
  bool onFloor(uint32_t e) const { return surfaces.elements[e].normal.y > 0.99f; }

  Scene scene;
  SurfaceSet surfaces;
  std::vector<Polygon> polygons;
  std::optional<RayTracer> tracer;
  std::optional<DirectLight> direct;
  std::vector<Rgb> corners;
  std::optional<FinalGather> gather;
};

// Where point f (0 to 1) of edge c of a 3- or 4-cornered element lies in its hit parameters.
Vec2 onEdge(int count, int c, float f) {
  if (count == 4) {
    const std::array<Vec2, 4> at = {Vec2(f, 0.0f), Vec2(1.0f, f), Vec2(1.0f - f, 1.0f), Vec2(0.0f, 1.0f - f)};
    return at[size_t(c)];
  }
  const std::array<Vec2, 3> at = {Vec2(f, 0.0f), Vec2(1.0f - f, f), Vec2(0.0f, 1.0f - f)};
  return at[size_t(c)];
}

// The floor's mean gathered light, as the corners interpolate it and as the lattices do, against
// gathers at 16 x 16 points over each floor element (the same rays a vertex takes): the lattices
// must take away most of the interpolation's error. Measured: corners 4.0 times the points'
// mean, lattices 1.13 times.
TEST(GatherRefinement, LatticesTakeTheCreaseOutOfTheInterpolation) {
  const Sill sill;
  const SurfaceSet& surfaces = sill.surfaces;
  VertexGather vertices(surfaces, *sill.gather, 1024, 3);
  const GatherRefinement refinement(surfaces, vertices, {});
  EXPECT_GT(refinement.refinedElements(), 0u);
  EXPECT_GT(refinement.pointsTraced(), 0u);
  double cornersMean = 0.0, latticeMean = 0.0, pointsMean = 0.0, area = 0.0;
  uint32_t index = uint32_t(vertices.vertexCount());
  for (uint32_t e = 0; e < surfaces.elements.size(); ++e) {
    if (!sill.onFloor(e)) continue;
    const Element& el = surfaces.elements[e];
    const Rgb* c = vertices.corners(e);
    double corners = 0.0;
    for (int k = 0; k < el.polygon.count; ++k) corners += c[k].g / float(el.polygon.count);
    double points = 0.0;
    constexpr int kSide = 16;
    for (int j = 0; j < kSide; ++j)
      for (int i = 0; i < kSide; ++i) {
        const auto w = cornerWeights(el.polygon.count, (float(i) + 0.5f) / kSide, (float(j) + 0.5f) / kSide);
        if (el.polygon.count == 3 && (float(i) + float(j) + 1.0f) / kSide > 1.0f) continue;
        Vec3 p(0.0f);
        for (int k = 0; k < el.polygon.count; ++k) p += w[size_t(k)] * el.polygon.v[size_t(k)];
        points += vertices.gatherAt(p, el.normal, el.centroid, 32, ++index + 100000).irradiance.g;
      }
    ASSERT_EQ(el.polygon.count, 4) << "the floor's elements are quads";
    points /= kSide * kSide;
    cornersMean += el.area * corners;
    latticeMean += el.area * refinement.mean(e).g;
    pointsMean += el.area * points;
    area += el.area;
  }
  ASSERT_GT(area, 1.9);
  cornersMean /= area, latticeMean /= area, pointsMean /= area;
  // One bounce off a 5 cm strip of radiosity rho E cos: a few percent of it on a 2 m floor.
  ASSERT_GT(pointsMean, 0.0);

  EXPECT_GT(cornersMean, 3.0 * pointsMean);
  EXPECT_LT(std::abs(latticeMean - pointsMean), 0.15 * std::abs(cornersMean - pointsMean))
      << "corners " << cornersMean << ", lattices " << latticeMean << ", points " << pointsMean;
}

// No cracks: along every edge two floor elements share, each side's irradiance is the same at
// every point, refined or not (the lattices follow the coarser side's points there). Half the
// crease is seen by few pixels, so that a refined and an unrefined element meet there too, where
// the light changes fastest.
TEST(GatherRefinement, NeighboursAgreeAlongTheirSharedEdges) {
  const Sill sill;
  const SurfaceSet& surfaces = sill.surfaces;
  VertexGather vertices(surfaces, *sill.gather, 256, 5);
  std::vector<float> pixels(surfaces.elements.size());
  for (uint32_t e = 0; e < pixels.size(); ++e) pixels[e] = surfaces.elements[e].centroid.z < 0.5f ? 15.0f : 1e6f;
  const GatherRefinement refinement(surfaces, vertices, pixels, pixels);
  int levels[kMaxRefineLevels + 1] = {};
  for (uint32_t e = 0; e < surfaces.elements.size(); ++e)
    if (sill.onFloor(e)) ++levels[refinement.level(e)];
  EXPECT_GT(levels[0], 0) << "elements far from the step keep their corners";
  EXPECT_GT(levels[kMaxRefineLevels], 0) << "elements at the step refine to the deepest lattice";
  size_t edges = 0, mixed = 0, atCrease = 0;
  for (uint32_t a = 0; a < surfaces.elements.size(); ++a)
    for (uint32_t b = a + 1; b < surfaces.elements.size(); ++b) {
      if (!sill.onFloor(a) || !sill.onFloor(b)) continue;
      const Polygon &pa = surfaces.elements[a].polygon, &pb = surfaces.elements[b].polygon;
      for (int ca = 0; ca < pa.count; ++ca)
        for (int cb = 0; cb < pb.count; ++cb) {
          const Vec3 a0 = pa.v[size_t(ca)], a1 = pa.v[size_t((ca + 1) % pa.count)];
          const Vec3 b0 = pb.v[size_t(cb)], b1 = pb.v[size_t((cb + 1) % pb.count)];
          const bool reversed = a0 == b1 && a1 == b0;
          if (!reversed && !(a0 == b0 && a1 == b1)) continue;
          ++edges;
          mixed += refinement.level(a) != refinement.level(b);
          atCrease += refinement.level(a) != refinement.level(b) && std::min(a0.x, a1.x) == 0.0f;
          for (int k = 0; k <= 16; ++k) {
            const float f = float(k) / 16.0f;
            const Vec2 ua = onEdge(pa.count, ca, f), ub = onEdge(pb.count, cb, reversed ? 1.0f - f : f);
            const Rgb va = refinement.irradianceAt(a, ua.x, ua.y), vb = refinement.irradianceAt(b, ub.x, ub.y);
            ASSERT_NEAR(va.g, vb.g, 1e-5f * std::max(1.0f, std::abs(va.g)))
                << "elements " << a << " (level " << refinement.level(a) << ") and " << b << " (level "
                << refinement.level(b) << "), point " << f << " of their edge";
          }
        }
    }

  EXPECT_GT(edges, 4u);
  EXPECT_GT(atCrease, 0u) << "a refined and a coarser element meet at the step";
}

// An element that is not refined shows its corners' interpolation, to the bit, and a refined one
// its corners' values at its corners.
TEST(GatherRefinement, CornersStayWhereTheyWere) {
  const Sill sill;
  const SurfaceSet& surfaces = sill.surfaces;
  VertexGather vertices(surfaces, *sill.gather, 256, 5);
  const GatherRefinement refinement(surfaces, vertices, {});
  for (uint32_t e = 0; e < surfaces.elements.size(); ++e) {
    const int count = surfaces.elements[e].polygon.count;
    const Rgb* c = vertices.corners(e);
    for (int k = 0; k < count; ++k) {
      const Vec2 uv = onEdge(count, k, 0.0f);
      EXPECT_EQ(refinement.irradianceAt(e, uv.x, uv.y), c[k]) << "element " << e << " corner " << k;
    }
    if (refinement.level(e) > 0) continue;
    for (float u : {0.1f, 0.37f, 0.8f})
      for (float v : {0.05f, 0.5f})
        EXPECT_EQ(refinement.irradianceAt(e, u, v), interpolateCorners(c, count, u, v)) << "element " << e;
  }
}

// A picture's pixels bound the lattice: an element covering fewer than 16 pixels (4 cells of 4)
// is not refined, whatever its light.
TEST(GatherRefinement, FewPixelsKeepTheCorners) {
  const Sill sill;
  const SurfaceSet& surfaces = sill.surfaces;
  VertexGather vertices(surfaces, *sill.gather, 256, 5);
  const std::vector<float> few(surfaces.elements.size(), 15.0f), many(surfaces.elements.size(), 1e6f);
  const GatherRefinement coarse(surfaces, vertices, few, few), fine(surfaces, vertices, many, many);
  EXPECT_EQ(coarse.refinedElements(), 0u);
  EXPECT_GT(fine.refinedElements(), 0u);
}

}  // namespace
}  // namespace luxel
