// The face-cluster solver keeps the light it is given. In a closed enclosure every watt emitted
// is absorbed in the end; a solver that loses light at each bounce (vectors from opposite sides
// cancelling on round clusters, point samples missing the light near a crease, a systematically
// low coupling) shows it here long before it shows in a picture. docs/algorithms.md ("Face-cluster
// radiosity", energy) has the history of these losses.
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>

#include "crumpled_ball.h"
#include "luxel/import.h"
#include "luxel/solve.h"
#include "scene/builtin/builtin_scenes.h"

namespace luxel {
namespace {

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
  DiscretiseOptions d;
  d.elementBudget = 3000;
  d.elementsPerPatchSide = 1;
  SurfaceSet surfaces = discretise(scene, d);
  SolveOptions o;
  o.method = "hierarchical";
  o.settings.set("error", error);
  const Solution s = solve(scene, surfaces, o);
  double sum[2] = {0, 0}, area[2] = {0, 0};
  for (size_t e = 0; e < surfaces.elements.size(); ++e) {
    const Element& el = surfaces.elements[e];
    const int onBall = glm::length(el.centroid - Vec3(0.5f)) < 0.3f;
    sum[onBall] += el.area * s.irradiance[e].g, area[onBall] += el.area;
  }
  const double expected = 2.0 * std::numbers::pi;
  return {sum[0] / area[0] / expected, sum[1] / area[1] / expected};
}

// Measured: box 0.950 and ball 0.929 of the closed form at the default threshold, 0.978 and 0.976
// at 1e-4: what remains is a coupling about 1.5% low per bounce (the receiver's 3 x 3 points on a
// convex irradiance), which the threshold controls. Before the fixes these tests came with, the
// box was at 0.73 and the ball far lower still.
TEST(HierarchicalEnergy, AFurnaceWithABallKeepsItsLight) {
  const Means coarse = furnaceWithABall(1e-3);
  EXPECT_NEAR(coarse.box, 1.0, 0.08);
  EXPECT_NEAR(coarse.ball, 1.0, 0.08);
  const Means fine = furnaceWithABall(1e-4);
  std::printf("box / closed form %.4f (1e-3), %.4f (1e-4); ball %.4f, %.4f\n", coarse.box, fine.box, coarse.ball, fine.ball);
  EXPECT_NEAR(fine.box, 1.0, 0.03);
  EXPECT_NEAR(fine.ball, 1.0, 0.03);
}

// Seed 002's room at 20k faces: closed, so at 0.1% unshot what is absorbed is what was emitted.
// Measured 97.0% at the defaults (it was 66%); the statues' interreflected light is the largest
// part of what is missing (docs/performance.md).
TEST(HierarchicalEnergy, TheClosedRoomAbsorbsWhatItEmits) {
  const Scene scene = builtinScene("room-20k");
  DiscretiseOptions d;
  d.elementBudget = 1;
  d.elementsPerPatchSide = 1;
  SurfaceSet surfaces = discretise(scene, d);
  SolveOptions o;
  o.method = "hierarchical";
  const Solution s = solve(scene, surfaces, o);
  ASSERT_GT(s.stats.emittedPower, 0.0);
  std::printf("absorbed / emitted %.4f\n", s.stats.absorbedPower / s.stats.emittedPower);
  EXPECT_NEAR(s.stats.absorbedPower / s.stats.emittedPower, 1.0, 0.06);
}

}  // namespace
}  // namespace luxel
