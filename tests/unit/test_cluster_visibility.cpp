// Seed 002's multiresolution visibility (cluster/cluster_visibility.h; notes 002 section 6.4, T8):
// a ray outside a cluster's box passes whole, a closed cluster is opaque, a flat cluster's opacity
// is the share of its box that its faces cover, the estimate converges to exact ray casting as the
// stop threshold shrinks and is exact at 0, and the hierarchical solver with it agrees with its
// exact rays.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cluster/cluster_visibility.h"
#include "cluster/face_cluster_tree.h"
#include "crumpled_ball.h"
#include "luxel/import.h"
#include "luxel/solve.h"
#include "scene/builtin/builtin_scenes.h"
#include "trace/ray_tracer.h"

namespace luxel {
namespace {

SurfaceSet elementsOf(const Scene& scene, float elementSize = 1e6f) {
  DiscretiseOptions d;
  d.elementSize = elementSize;
  d.orientByLight = false;
  return discretise(scene, d);
}

Vec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<float> g(0.0f, 1.0f);
  return glm::normalize(Vec3(g(rng), g(rng), g(rng)));
}

// Exact occlusion of each segment by the elements, from Embree.
std::vector<float> exactPassed(const SurfaceSet& set,
                               const std::vector<std::pair<Vec3, Vec3>>& segments) {
  std::vector<Polygon> polygons;
  for (const Element& e : set.elements) polygons.push_back(e.polygon);
  const RayTracer tracer(polygons);
  std::vector<RTCRay> rays;
  for (const auto& [a, b] : segments) rays.push_back(makeRay(a, b - a, 0.0f, 1.0f));
  tracer.occluded(rays);
  std::vector<float> passed;
  for (const RTCRay& r : rays) passed.push_back(isOccluded(r) ? 0.0f : 1.0f);
  return passed;
}

// Segments between two spheres of radius 3 round the origin: most of them cross the unit ball.
std::vector<std::pair<Vec3, Vec3>> segmentsAcross(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<std::pair<Vec3, Vec3>> segments;
  for (int i = 0; i < n; ++i) {
    const Vec3 a = 3.0f * randomUnit(rng);
    const Vec3 b = -3.0f * glm::normalize(a + 0.6f * randomUnit(rng));
    segments.push_back({a, b});
  }
  return segments;
}

TEST(ClusterVisibility, ARayOutsideEveryBoxPassesWhole) {
  const SurfaceSet set = elementsOf(test::crumpledBall(16, 32, 0.2f, 3));
  const FaceClusterTree tree = buildFaceClusterTree(set);
  const ClusterVisibility vis(tree, set, 1e-5f);
  std::mt19937 rng(5);
  for (int i = 0; i < 200; ++i) {
    // Segments in the plane x = 2, beyond the ball (radius at most 1.2) and its box.
    const Vec3 a(2.0f, 4.0f * randomUnit(rng).y, 4.0f * randomUnit(rng).z);
    const Vec3 b(2.0f, 4.0f * randomUnit(rng).y, 4.0f * randomUnit(rng).z);
    for (float stop : {0.0f, 0.1f, 1e6f})
      EXPECT_EQ(vis.transmittance(a, b - a, 0.0f, 1.0f, stop), 1.0f);
  }
}

// A closed cube's cluster covers its box from every direction: opacity 1, to rounding.
TEST(ClusterVisibility, AClosedCubeIsOpaqueFromEveryDirection) {
  Scene scene;
  scene.materials.push_back(Material{});
  Mesh cube;
  for (int i = 0; i < 8; ++i)
    cube.positions.push_back(
        Vec3(i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : -1.0f));
  // Outward, counter-clockwise seen from outside.
  for (const auto& f : {std::array<uint32_t, 4>{0, 2, 3, 1},
                        {4, 5, 7, 6},
                        {0, 1, 5, 4},
                        {2, 6, 7, 3},
                        {0, 4, 6, 2},
                        {1, 3, 7, 5}})
    cube.faces.push_back(Face{f});
  scene.meshes.push_back(std::move(cube));
  const SurfaceSet set = elementsOf(scene, 0.25f);
  const FaceClusterTree tree = buildFaceClusterTree(set);
  ASSERT_FALSE(tree.isLeaf(tree.root));
  ASSERT_TRUE(tree.joined(tree.root).connected);
  const ClusterVisibility vis(tree, set, 1e-5f);
  std::mt19937 rng(11);
  for (int i = 0; i < 200; ++i) EXPECT_NEAR(vis.opacity(tree.root, randomUnit(rng)), 1.0f, 1e-3f);
}

// A flat cluster with holes (a comb: a strip with teeth, all joined): its opacity is the covered
// share of its box, so over rays spread evenly across the box the estimate's mean is the exact one.
TEST(ClusterVisibility, AFlatClustersOpacityIsTheShareOfItsBoxItCovers) {
  Scene scene;
  scene.materials.push_back(Material{});
  Mesh comb;
  // The spine: y in [0, 0.25], x in [0, 4]; teeth: x in [k, k + 0.5], y in [0.25, 1].
  auto quad = [&](float x0, float y0, float x1, float y1) {
    const uint32_t b = uint32_t(comb.positions.size());
    comb.positions.insert(comb.positions.end(),
                          {Vec3(x0, y0, 0), Vec3(x1, y0, 0), Vec3(x1, y1, 0), Vec3(x0, y1, 0)});
    comb.faces.push_back(Face{{b, b + 1, b + 2, b + 3}});
  };
  for (int k = 0; k < 4; ++k) {
    quad(float(k), 0.0f, float(k) + 0.5f, 0.25f);
    quad(float(k) + 0.5f, 0.0f, float(k) + 1.0f, 0.25f);
    quad(float(k), 0.25f, float(k) + 0.5f, 1.0f);
  }
  scene.meshes.push_back(std::move(comb));
  const SurfaceSet set = elementsOf(scene);
  const FaceClusterTree tree = buildFaceClusterTree(set);
  ASSERT_TRUE(tree.joined(tree.root).connected) << "the comb's faces share edges";
  const ClusterVisibility vis(tree, set, 1e-5f);
  // Covered: the spine 4 x 0.25 and four teeth 0.5 x 0.75, 2.5 of the box's 4 x 1.
  const float covered = 2.5f / 4.0f;
  EXPECT_NEAR(vis.opacity(tree.root, Vec3(0, 0, 1)), covered, 1e-4f);
  EXPECT_NEAR(vis.opacity(tree.root, glm::normalize(Vec3(0.3f, -0.2f, 1))), covered, 1e-4f);

  // Rays from far above to far below, evenly over the box, at a slant.
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const Vec3 slant = glm::normalize(Vec3(0.2f, 0.1f, 1.0f));
  std::vector<std::pair<Vec3, Vec3>> segments;
  double estimated = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const Vec3 onPlane(4.0f * u(rng), u(rng), 0.0f);
    segments.push_back({onPlane + 50.0f * slant, onPlane - 50.0f * slant});
    const auto& [a, b] = segments.back();
    estimated += vis.transmittance(a, b - a, 0.0f, 1.0f, 1e6f);
  }
  const std::vector<float> exact = exactPassed(set, segments);
  double exactMean = 0.0;
  for (float v : exact) exactMean += v;
  // Binomial noise of the exact mean over n rays: sqrt(p (1 - p) / n) = 0.0035.
  EXPECT_NEAR(estimated / n, 1.0 - covered, 1e-4);
  EXPECT_NEAR(exactMean / n, 1.0 - covered, 4.0 * 0.0035);
}

// T8: against exact ray casting on random segments across a unit ball, the mean error shrinks as
// the stop threshold does, and at 0 the walk reaches every face it needs: the exact verdict.
// (Above a stop of about the ball's radius the clusters stood for are halves of the ball or all of
// it, whose error depends on how their boxes sit more than on their size: not monotone there.)
TEST(ClusterVisibility, ConvergesToExactRayCastingAsTheStopShrinks) {
  const SurfaceSet set = elementsOf(test::crumpledBall(24, 48, 0.25f, 7));
  const FaceClusterTree tree = buildFaceClusterTree(set);
  const ClusterVisibility vis(tree, set, 1e-5f);
  const auto segments = segmentsAcross(4000, 23);
  const std::vector<float> exact = exactPassed(set, segments);
  double lastError = 1e9;
  for (float stop : {2.0f, 1.0f, 0.5f, 0.25f, 0.125f, 0.0f}) {
    double error = 0.0;
    int differ = 0;
    for (size_t i = 0; i < segments.size(); ++i) {
      const auto& [a, b] = segments[i];
      const float t = vis.transmittance(a, b - a, 0.0f, 1.0f, stop);
      ASSERT_GE(t, 0.0f);
      ASSERT_LE(t, 1.0f);
      error += std::abs(t - exact[i]);
      differ += std::abs(t - exact[i]) > 0.5f;
    }
    error /= double(segments.size());
    EXPECT_LE(error, lastError) << "stop " << stop;
    if (stop == 2.0f) EXPECT_GT(error, 0.01) << "a coarse stop approximates";
    if (stop == 0.0f) EXPECT_LE(differ, 2) << "grazing rays aside, exact";
    lastError = error;
  }
}

// The solver with multiresolution visibility: exact at stop 0 (the same light as Embree's rays,
// but for rays that graze an edge), and near it at the default.
TEST(ClusterVisibility, TheHierarchicalSolverAgreesWithItsExactRays) {
  const Scene scene = builtinScene("cornell-low");
  auto solveWith = [&](const char* visibility, double stop) {
    SurfaceSet surfaces = discretise(scene, DiscretiseOptions{});
    SolveOptions o;
    o.method = "hierarchical";
    o.settings.set("cache", false)
        .set("visibility", std::string(visibility))
        .set("visibility-stop", stop);
    return solve(scene, surfaces, o);
  };
  const Solution rays = solveWith("rays", 1.0);
  auto nrmse = [&](const Solution& s) {
    double num = 0.0, den = 0.0;
    for (size_t e = 0; e < rays.irradiance.size(); ++e) {
      const Rgb d = s.irradiance[e] - rays.irradiance[e];
      num += glm::dot(d, d), den += glm::dot(rays.irradiance[e], rays.irradiance[e]);
    }
    return std::sqrt(num / den);
  };
  const Solution exact = solveWith("clusters", 0.0);
  EXPECT_LT(nrmse(exact), 1e-3);
  const Solution coarse = solveWith("clusters", 1.0);
  EXPECT_LT(nrmse(coarse), 0.02);
  const Solution coarser = solveWith("clusters", 16.0);
  EXPECT_GT(nrmse(coarser), nrmse(exact));
}

}  // namespace
}  // namespace luxel
