// The GL backend's incremental solver (progressive_gl.cpp, followChanges): after a move or a
// light edit it reshoots every patch's shot light, negated from the old geometry and positive
// from the new, and must end where the same solver, solved afresh at the new state, ends: its
// hemicubes are turned by patch and sample alone, so the factors they measure are a function of
// the geometry, and a redistribution cancels what the move did not touch. On a coarse cut of
// cornell-low, so that llvmpipe takes seconds.
#include <gtest/gtest.h>

#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>

#include "gl_test_context.h"
#include "luxel/bench.h"
#include "luxel/session.h"
#include "scene/builtin/builtin_scenes.h"

namespace luxel {
namespace {

Scene coarseCornellLow() {
  Scene scene = builtin::cornellLow();
  for (Mesh& m : scene.meshes) m.elementGrids.clear();
  return scene;
}

DiscretiseOptions coarse() {
  DiscretiseOptions d;
  d.elementBudget = 400;
  return d;
}

SessionOptions gl(const char* method) {
  SessionOptions o;
  o.solve.method = method;
  o.solve.backend = "gl";
  o.solve.settings.set("unshot", 1e-6);
  o.solve.settings.set("ambient", false);
  return o;
}

glm::mat4 turned(const Scene& scene, float degrees, Vec3 shift) {
  const glm::mat4 rest = scene.objects[scene.dynamicObjects().at(0)].transform;
  return glm::translate(glm::mat4(1.0f), shift) * rest * glm::rotate(glm::mat4(1.0f), glm::radians(degrees), Vec3(0, 1, 0));
}

TEST(GlDynamic, AMoveEndsNearWhereAFreshGlSolveEnds) {
  std::string why;
  if (!test::glContextOr(why)) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  const Scene scene = coarseCornellLow();
  const uint32_t box = scene.dynamicObjects().at(0);
  const glm::mat4 pose = turned(scene, 35.0f, Vec3(0.04f, 0.06f, -0.03f));
  Session reference(scene, coarse(), gl("progressive"));  // restarts after the move
  const Solution before = reference.solve();
  reference.placeObject(box, pose);
  const Solution expected = reference.solve();

  Session dynamic(scene, coarse(), gl("incremental"));
  const Solution first = dynamic.solve();
  dynamic.placeObject(box, pose);
  const Solution after = dynamic.solve();
  const double error = bench::normalisedRmsError(dynamic.surfaces(), after.radiosity, expected.radiosity);
  const double change = bench::normalisedRmsError(dynamic.surfaces(), before.radiosity, expected.radiosity);
  Scene there = scene;
  there.placeObject(box, pose);
  Session fresh(there, coarse(), gl("incremental"));
  const double exact = bench::normalisedRmsError(dynamic.surfaces(), after.radiosity, fresh.solve().radiosity);
  std::printf("GL incremental: NRMSE %.2e against itself solved afresh, %.4f against GL progressive (other hemicube "
              "turns); the move changed the room by %.4f\n", exact, error, change);
  EXPECT_EQ(after.stats.redistributions, 1u);
  EXPECT_EQ(after.stats.method, "incremental");
  EXPECT_LT(exact, 1e-3);
  EXPECT_LT(error, 0.1 * change);

  // Back to where it started: the redistribution's own hemicubes cancel, and the first solution
  // returns up to float rounding and the stopping threshold.
  dynamic.placeObject(box, scene.objects[box].transform);
  const Solution back = dynamic.solve();
  const double returned = bench::normalisedRmsError(dynamic.surfaces(), back.radiosity, first.radiosity);
  std::printf("GL incremental: there and back, NRMSE %.2e against the first solution\n", returned);
  EXPECT_LT(returned, 1e-3);
}

TEST(GlDynamic, ALightTurnedUpEndsNearWhereAFreshGlSolveEnds) {
  std::string why;
  if (!test::glContextOr(why)) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  Scene scene = coarseCornellLow();
  const int light = scene.findMaterial("light");
  ASSERT_GE(light, 0);
  const Material m = scene.materials[size_t(light)];
  Session dynamic(scene, coarse(), gl("incremental"));
  const Solution before = dynamic.solve();
  dynamic.setMaterial(uint32_t(light), m.reflectance, 2.0f * m.emission);
  const Solution after = dynamic.solve();
  scene.materials[size_t(light)].emission = 2.0f * m.emission;
  Session fresh(scene, coarse(), gl("incremental"));
  const Solution expected = fresh.solve();
  // A doubled light doubles everything: the same hemicubes, so float rounding and the stop only.
  const double error = bench::normalisedRmsError(dynamic.surfaces(), after.radiosity, expected.radiosity);
  std::printf("GL incremental, light doubled: NRMSE %.2e against a fresh GL solve\n", error);
  EXPECT_LT(error, 1e-3);
  EXPECT_GT(bench::normalisedRmsError(dynamic.surfaces(), before.radiosity, expected.radiosity), 0.3);
  for (size_t e = 0; e < after.directIrradiance.size(); ++e)
    ASSERT_NEAR(after.directIrradiance[e].g, expected.directIrradiance[e].g, 1e-3f * (1.0f + expected.directIrradiance[e].g))
        << "direct light of element " << e;
}

}  // namespace
}  // namespace luxel
