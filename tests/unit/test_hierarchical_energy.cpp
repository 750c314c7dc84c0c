// The face-cluster solver keeps the light it is given. In a closed enclosure every watt emitted
// is absorbed in the end; a solver that loses light at each bounce (vectors from opposite sides
// cancelling on round clusters, point samples missing the light near a crease, a systematically
// low coupling) shows it here long before it shows in a picture. docs/algorithms.md ("Face-cluster
// radiosity", energy) has the history of these losses.
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <numbers>

#include <gtest/gtest.h>

#include "crumpled_ball.h"
#include "luxel/import.h"
#include "luxel/solve.h"
#include "scene/builtin/builtin_scenes.h"
#include "solve/radiosity_system.h"
#include "transport/form_factor.h"

namespace luxel {
namespace {

// Solved with every element its own patch (elementBudget 1: one element a face where faces are
// small), as the face-cluster solver shoots from each face.
Solution solveElementwise(const Scene& scene, size_t elementBudget, const std::string& method, const SolverSettings& settings,
                          SurfaceSet& surfaces) {
  DiscretiseOptions d;
  d.elementBudget = elementBudget;
  d.elementsPerPatchSide = 1;
  surfaces = discretise(scene, d);
  SolveOptions o;
  o.method = method;
  o.settings = settings;
  return solve(scene, surfaces, o);
}

struct Means {
  double box = 0.0, ball = 0.0;
};

// The furnace (rho 0.5, Le 1: irradiance 2 pi everywhere once converged) with a closed ball of the
// same material floating in it: a cluster whose faces look every way, lit from every side.
Means furnaceWithABall(double error) {
  Scene scene = builtin::furnace(0.5f, 1.0f);
  Scene ball = test::crumpledBall(16, 32, 0.0f, 1);
  Mesh mesh = ball.meshes[0];
  for (Vec3& p : mesh.positions) p = Vec3(0.5f) + 0.25f * p;
  mesh.material = 0;
  scene.meshes.push_back(mesh);
  SurfaceSet surfaces;
  const Solution s = solveElementwise(scene, 3000, "hierarchical", SolverSettings().set("error", error), surfaces);
  double sum[2] = {0, 0}, area[2] = {0, 0};
  for (size_t e = 0; e < surfaces.elements.size(); ++e) {
    const Element& el = surfaces.elements[e];
    const int onBall = glm::length(el.centroid - Vec3(0.5f)) < 0.3f;
    sum[onBall] += el.area * s.irradiance[e].g, area[onBall] += el.area;
  }
  const double expected = 2.0 * std::numbers::pi;
  return {sum[0] / area[0] / expected, sum[1] / area[1] / expected};
}

// Measured: box 0.957 and ball 1.011 of the closed form at the default threshold, 0.980 and 0.996
// at 1e-4: what remains on the box is a coupling about 1.5% low per bounce (the receiver's 3 x 3
// points on a convex irradiance), which the threshold controls. Before the fixes these tests came
// with, the box was at 0.73 and the ball far lower still.
TEST(HierarchicalEnergy, AFurnaceWithABallKeepsItsLight) {
  const Means coarse = furnaceWithABall(1e-3);
  EXPECT_NEAR(coarse.box, 1.0, 0.06);
  EXPECT_NEAR(coarse.ball, 1.0, 0.06);
  const Means fine = furnaceWithABall(1e-4);
  std::printf("box / closed form %.4f (1e-3), %.4f (1e-4); ball %.4f, %.4f\n", coarse.box, fine.box, coarse.ball, fine.ball);
  EXPECT_NEAR(fine.box, 1.0, 0.03);
  EXPECT_NEAR(fine.ball, 1.0, 0.03);
}

// Seed 002's room at 20k faces: closed, so at 0.1% unshot what is absorbed is what was emitted.
// Measured 99.9% at the defaults (it was 66%, then 97.0% before the statues' light was kept as
// harmonics per emitter point, then 99.6% before a cluster's light to itself below the threshold
// was kept as a link).
TEST(HierarchicalEnergy, TheClosedRoomAbsorbsWhatItEmits) {
  const Scene scene = builtinScene("room-20k");
  SurfaceSet surfaces;
  const Solution s = solveElementwise(scene, 1, "hierarchical", {}, surfaces);
  ASSERT_GT(s.stats.emittedPower, 0.0);
  std::printf("absorbed / emitted %.4f\n", s.stats.absorbedPower / s.stats.emittedPower);
  EXPECT_NEAR(s.stats.absorbedPower / s.stats.emittedPower, 1.0, 0.03);
}

// The same room against the flat progressive solver, irradiance per material (area-weighted, all
// channels). Measured: the walls and floor within 1.8%; the pedestals 7.6% high and the statues
// 6.7% low (they were 22%, 12.5% and 11.2% low before the harmonics and the self-links of
// docs/algorithms.md, "Energy"), held here so that it cannot grow unseen. The light's own
// irradiance (all of it reflected, so small and the first to show a coarse link's error) is 6.2%
// high at the default threshold (5.9% before the self-links; 4.1% and 0.2% at 3e-4 and 1e-4):
// the threshold's error, bounded at 8%.
TEST(HierarchicalEnergy, TheRoomAgreesWithProgressivePerMaterial) {
  const Scene scene = builtinScene("room-20k");
  SurfaceSet surfaces;
  const Solution p = solveElementwise(scene, 1, "progressive", SolverSettings().set("unshot", 1e-3), surfaces);
  const Solution h = solveElementwise(scene, 1, "hierarchical", {}, surfaces);
  std::map<std::string, std::array<double, 2>> perMaterial;  // progressive, hierarchical
  for (size_t e = 0; e < surfaces.elements.size(); ++e) {
    const Element& el = surfaces.elements[e];
    auto& m = perMaterial[scene.materials[el.material].name];
    m[0] += el.area * channelSum(p.irradiance[e]), m[1] += el.area * channelSum(h.irradiance[e]);
  }
  const std::map<std::string, double> tolerance = {{"white", 0.05}, {"floor", 0.05}, {"red", 0.05}, {"green", 0.05},
                                                   {"light", 0.08}, {"pedestal", 0.1}, {"statue", 0.1}};
  for (const auto& [name, m] : perMaterial) {
    std::printf("%s: hierarchical / progressive %.4f\n", name.c_str(), m[1] / m[0]);
    ASSERT_GT(m[0], 0.0) << name;
    EXPECT_NEAR(m[1] / m[0], 1.0, tolerance.at(name)) << name;
  }
}

// A ball (reflectance 0) before a large emitting wall: every face's irradiance has a closed form,
// pi times the point form factor to the wall (a convex ball does not shadow itself beyond each
// face's horizon). The ball does not wholly face the wall, so its light is harmonics of band 2,
// whose clamped cosine overshoots by up to 6.25% where a face looks straight at a narrow source
// (Ramamoorthi and Hanrahan's 1 + 1/16): the tolerance. Measured 1.038; before the harmonics took
// each emitter point unclipped by the receiver point's horizon and constant over the receiver,
// a 0.01 threshold left it 15% short.
TEST(HierarchicalEnergy, ABallBeforeAWallGetsTheClosedForm) {
  Scene scene;
  Material wall, ball;
  wall.name = "wall", wall.reflectance = Rgb(0.0f), wall.emission = Rgb(1.0f);
  ball.name = "ball", ball.reflectance = Rgb(0.0f);
  scene.materials = {wall, ball};
  // The wall: 4 x 4 m in z = 0, facing +z, as a grid of 16 x 16 quads.
  Mesh w;
  constexpr int kCells = 16;
  constexpr float kSize = 4.0f;
  for (int i = 0; i <= kCells; ++i)
    for (int j = 0; j <= kCells; ++j) w.positions.push_back(Vec3(kSize * float(i) / kCells, kSize * float(j) / kCells, 0.0f));
  for (uint32_t i = 0; i < kCells; ++i)
    for (uint32_t j = 0; j < kCells; ++j) {
      const uint32_t a = i * (kCells + 1) + j, b = a + kCells + 1;
      w.faces.push_back(Face{{a, b, b + 1, a + 1}});
    }
  scene.meshes.push_back(w);
  Polygon wallPolygon;
  wallPolygon.count = 4;
  wallPolygon.v = {Vec3(0, 0, 0), Vec3(kSize, 0, 0), Vec3(kSize, kSize, 0), Vec3(0, kSize, 0)};
  Mesh b = test::crumpledBall(16, 32, 0.0f, 1).meshes[0];
  for (Vec3& p : b.positions) p = Vec3(2.0f, 2.0f, 2.0f) + 0.5f * p;
  b.material = 1;
  scene.meshes.push_back(b);
  SurfaceSet surfaces;
  const Solution s = solveElementwise(scene, 1, "hierarchical", {}, surfaces);
  double solved = 0.0, exact = 0.0;
  for (size_t e = 0; e < surfaces.elements.size(); ++e) {
    const Element& el = surfaces.elements[e];
    if (el.material != 1) continue;
    solved += el.area * s.irradiance[e].g;
    exact += el.area * std::numbers::pi *
             pointToPolygonFormFactor(el.centroid, el.normal, wallPolygon, Vec3(0, 0, 1), Sides::Front, Sides::Front);
  }
  ASSERT_GT(exact, 0.0);
  std::printf("ball: solved / closed form %.4f\n", solved / exact);
  EXPECT_NEAR(solved / exact, 1.0, 0.0625);
}

}  // namespace
}  // namespace luxel
