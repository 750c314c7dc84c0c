// Scenes with moving parts: dynamic objects placed by transforms (Scene::placeObject), surfaces
// that follow (SurfaceSet::placeObject), a two-level ray tracer whose instances move by a
// transform and a commit, and a session that solves the scene at its new pose as a fresh solve of
// that pose would.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "luxel/bench.h"
#include "luxel/error.h"
#include "luxel/session.h"
#include "scene/builtin/builtin_scenes.h"
#include "scene/builtin/seed_geometry.h"
#include "trace/ray_tracer.h"
#include "transport/cpu_transport.h"

namespace luxel {
namespace {

glm::mat4 turnedAbout(Vec3 centre, float degrees) {
  return glm::rotate(glm::translate(glm::mat4(1.0f), centre), glm::radians(degrees), Vec3(0, 1, 0));
}

uint32_t theBox(const Scene& scene) {
  const std::vector<uint32_t> dynamic = scene.dynamicObjects();
  EXPECT_EQ(dynamic.size(), 1u);
  return dynamic.at(0);
}

TEST(MovingObjects, MeshesFollowTheirObjectWithoutDrift) {
  Scene scene = builtin::cornellLow();
  const uint32_t box = theBox(scene);
  const Vec3 centre(scene.objects[box].transform[3]);
  std::vector<Vec3> rest;
  for (const Mesh& m : scene.meshes)
    if (m.object == box) rest.insert(rest.end(), m.positions.begin(), m.positions.end());
  ASSERT_FALSE(rest.empty());
  // A quarter turn about the box's own vertical axis: every vertex turns about its centre.
  scene.placeObject(box, turnedAbout(centre, 90.0f));
  size_t i = 0;
  for (const Mesh& m : scene.meshes) {
    if (m.object != box) continue;
    for (const Vec3& p : m.positions) {
      const Vec3 r = rest[i++] - centre, q = p - centre;
      EXPECT_NEAR(q.x, r.z, 1e-5f);
      EXPECT_NEAR(q.z, -r.x, 1e-5f);
      EXPECT_NEAR(q.y, r.y, 1e-5f);
    }
  }
  // A thousand small turns, each computed from the rest pose, end where one turn would.
  for (int k = 1; k <= 1000; ++k) scene.placeObject(box, turnedAbout(centre, 0.36f * float(k)));
  i = 0;
  for (const Mesh& m : scene.meshes)
    if (m.object == box)
      for (const Vec3& p : m.positions) EXPECT_LT(glm::length(p - rest[i++]), 2e-6f);
}

TEST(MovingObjects, OnlyDynamicObjectsMoveAndOnlyRigidly) {
  Scene scene = builtin::cornellLow();
  const uint32_t box = theBox(scene);
  const glm::mat4 at = scene.objects[box].transform;
  EXPECT_THROW(scene.placeObject(box, glm::scale(at, Vec3(-1, 1, 1))), Error);     // a mirror
  EXPECT_THROW(scene.placeObject(box, glm::scale(at, Vec3(1, 2, 1))), Error);      // a stretch
  EXPECT_THROW(scene.placeObject(uint32_t(scene.objects.size()), at), Error);      // no such object
  glm::mat4 bad = at;
  bad[3][0] = std::nanf("");
  EXPECT_THROW(scene.placeObject(box, bad), Error);
  EXPECT_NO_THROW(scene.placeObject(box, glm::scale(at, Vec3(0.5f))));             // a uniform scale
  scene.objects[box].dynamic = false;
  EXPECT_THROW(scene.placeObject(box, at), Error);
}

// Two unit squares facing +z at z = 0, the second one an instance; rays down -z. Both forms a
// moving instance can take: the two-level BVH, and the one-level BVH that small scenes rebuild.
class RayTracerInstances : public ::testing::TestWithParam<size_t> {};
INSTANTIATE_TEST_SUITE_P(MovingObjects, RayTracerInstances, ::testing::Values(size_t(0), RayTracer::kRebuiltFlatLimit),
                         [](const auto& info) { return info.param == 0 ? "TwoLevel" : "RebuiltOneLevel"; });

TEST_P(RayTracerInstances, InstancesMoveByATransform) {
  const Polygon a{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}, 4};
  const Polygon b{{Vec3(2, 0, 0), Vec3(3, 0, 0), Vec3(3, 1, 0), Vec3(2, 1, 0)}, 4};
  const Polygon polygons[] = {a, b};
  const int32_t instances[] = {-1, 0};
  RayTracer tracer(polygons, instances, GetParam());
  EXPECT_EQ(tracer.layered(), false);
  ASSERT_EQ(tracer.instanceCount(), 1u);
  auto hitAt = [&](float x, float y) {
    RTCRayHit h;
    h.ray = makeRay(Vec3(x, y, 5.0f), Vec3(0, 0, -1), 0.0f, 100.0f);
    tracer.intersect({&h, 1});
    return h;
  };
  RTCRayHit h = hitAt(2.5f, 0.25f);
  ASSERT_NE(h.hit.geomID, RTC_INVALID_GEOMETRY_ID);
  EXPECT_EQ(h.hit.primID, 1u);  // the polygon's own index, not the instance's
  EXPECT_NEAR(h.hit.u, 0.5f, 1e-5f);
  EXPECT_NEAR(h.hit.v, 0.25f, 1e-5f);
  EXPECT_EQ(hitAt(0.5f, 0.5f).hit.primID, 0u);
  // Lift the instance by 2 and slide it by 3 along x: it is found at its new place only.
  // Placed twice before a commit: the last placement counts, relative to where it was built.
  tracer.placeInstance(0, glm::translate(glm::mat4(1.0f), Vec3(1, 0, 0)));
  tracer.placeInstance(0, glm::translate(glm::mat4(1.0f), Vec3(3, 0, 2)));
  tracer.commit();
  EXPECT_EQ(tracer.layered(), GetParam() == 0);
  EXPECT_EQ(hitAt(2.5f, 0.5f).hit.geomID, RTC_INVALID_GEOMETRY_ID);
  h = hitAt(5.5f, 0.25f);
  ASSERT_NE(h.hit.geomID, RTC_INVALID_GEOMETRY_ID);
  EXPECT_EQ(h.hit.primID, 1u);
  EXPECT_NEAR(h.ray.tfar, 3.0f, 1e-5f);
  EXPECT_NEAR(h.hit.u, 0.5f, 1e-5f);
  // Occlusion and point queries see it there too.
  RTCRay r = makeRay(Vec3(5.5f, 0.5f, 5.0f), Vec3(0, 0, -1), 0.0f, 100.0f);
  tracer.occluded({&r, 1});
  EXPECT_TRUE(isOccluded(r));
  std::vector<uint32_t> near;
  tracer.forEachNear(Vec3(5.5f, 0.5f, 2.0f), 0.1f, [&](uint32_t p) { return near.push_back(p), true; });
  EXPECT_EQ(near, std::vector<uint32_t>{1u});
  near.clear();
  tracer.forEachNear(Vec3(2.5f, 0.5f, 0.0f), 0.1f, [&](uint32_t p) { return near.push_back(p), true; });
  EXPECT_TRUE(near.empty());
  // A second move, again relative to where the instance was built; the static square stays.
  tracer.placeInstance(0, glm::translate(glm::mat4(1.0f), Vec3(0, 2, 0)));
  tracer.commit();
  EXPECT_EQ(hitAt(5.5f, 0.25f).hit.geomID, RTC_INVALID_GEOMETRY_ID);
  EXPECT_EQ(hitAt(2.5f, 2.5f).hit.primID, 1u);
  EXPECT_EQ(hitAt(0.5f, 0.5f).hit.primID, 0u);
}

// Moving the box in a session and solving again gives what a fresh session of the scene with
// the box already there gives: the surfaces, the transport's instances and the analytic light
// all followed the move.
TEST(MovingObjects, SessionSolvesTheNewPoseAsAFreshSolveDoes) {
  SolveOptions o;
  o.settings.set("unshot", 1e-4);
  const Scene original = builtin::cornellLow();
  const uint32_t box = theBox(original);
  const glm::mat4 pose = turnedAbout(Vec3(original.objects[box].transform[3]), 40.0f) *
                         glm::translate(glm::mat4(1.0f), Vec3(0.05f, -0.1f, 0.0f));

  Session moved(original, DiscretiseOptions{}, {o});
  const Solution before = moved.solve();
  moved.placeObject(box, pose);
  const Solution after = moved.solve();

  Scene there = original;
  there.placeObject(box, pose);
  Session fresh(there, DiscretiseOptions{}, {o});
  const Solution expected = fresh.solve();

  ASSERT_EQ(moved.surfaces().elements.size(), fresh.surfaces().elements.size());
  for (size_t e = 0; e < fresh.surfaces().elements.size(); ++e)
    ASSERT_LT(glm::length(moved.surfaces().elements[e].centroid - fresh.surfaces().elements[e].centroid), 1e-5f) << e;
  const double rms = bench::normalisedRmsError(fresh.surfaces(), after.radiosity, expected.radiosity);
  const double change = bench::normalisedRmsError(fresh.surfaces(), before.radiosity, expected.radiosity);
  std::printf("moved box: NRMSE %.2e against a fresh solve; the move itself changed the room by %.3f\n", rms, change);
  // The two differ only by float rounding of the same geometry (and the rays it steers), far
  // below the change the move made.
  EXPECT_LT(rms, 1e-3);
  EXPECT_GT(change, 0.02);
  EXPECT_GT(after.stats.shots, before.stats.shots);  // the solver's work before the move is counted
}

TEST(MovingObjects, ABadPlacementLeavesTheSessionAsItWas) {
  Session session(builtin::cornellLow(), DiscretiseOptions{}, {});
  const uint32_t box = theBox(session.scene());
  const std::vector<Vec3> positions = session.scene().meshes.back().positions;
  const glm::mat4 at = session.scene().objects[box].transform;
  // The first placement is fine, the second mirrors: neither is made.
  EXPECT_THROW(session.placeObjects({{box, glm::translate(at, Vec3(0.01f, 0, 0))}, {box, glm::scale(at, Vec3(-1, 1, 1))}}),
               Error);
  EXPECT_EQ(session.scene().meshes.back().positions, positions);
  EXPECT_EQ(session.scene().objects[box].transform, at);
}

// Cross-redistribution recomputes only the factors the transport says a move can have changed
// (Transport::visibilityChangedByMove); the rest it keeps. So every static pair it calls unchanged
// must compute to the same number after the move, for a small turn, a shift and a large turn.
TEST(MovingObjects, FactorsCalledUnchangedByAMoveAreUnchanged) {
  Scene scene = builtin::cornellLow();
  for (Mesh& m : scene.meshes) m.elementGrids.clear();
  const uint32_t box = theBox(scene);
  SurfaceSet surfaces = discretise(scene, DiscretiseOptions{.elementBudget = 2000});
  CpuTransport transport(scene, surfaces, FormFactorOptions{});
  const size_t ne = surfaces.elements.size(), np = surfaces.patches.size();
  auto onBox = [&](uint32_t face) { return scene.meshes[surfaces.faces[face].mesh].object == box; };
  std::vector<Transport::ElementPatch> pairs;
  for (uint32_t e = 0; e < ne; ++e)
    for (uint32_t p = 0; p < np; ++p)
      if (!onBox(surfaces.elements[e].face) && !onBox(surfaces.patches[p].face)) pairs.push_back({e, p});
  std::vector<float> before(pairs.size()), after(pairs.size());
  transport.pairs(pairs, before);

  const Vec3 centre(scene.objects[box].transform[3]);
  const glm::mat4 rest = scene.objects[box].transform;
  const glm::mat4 poses[] = {turnedAbout(centre, 1.0f) * glm::translate(glm::mat4(1.0f), -centre) * rest,
                             glm::translate(glm::mat4(1.0f), Vec3(0.03f, 0.0f, -0.02f)) * rest,
                             turnedAbout(centre, 40.0f) * glm::translate(glm::mat4(1.0f), -centre) * rest};
  for (const glm::mat4& pose : poses) {
    scene.placeObject(box, pose);
    surfaces.placeObject(scene, box);
    transport.objectsMoved(std::vector<uint32_t>{box});
    std::vector<uint8_t> changed(pairs.size());
    transport.visibilityChangedByMove(pairs, changed);
    transport.pairs(pairs, after);
    std::vector<uint8_t> redone(ne, 0);
    for (uint32_t e : transport.receiversRedoneByMove()) redone[e] = 1;
    size_t called = 0, differ = 0, broken = 0;
    for (size_t i = 0; i < pairs.size(); ++i) {
      if (redone[pairs[i].element]) continue;
      called += changed[i];
      differ += after[i] != before[i];
      broken += !changed[i] && after[i] != before[i];
    }
    std::printf("%zu static pairs: %zu called changed, %zu changed\n", pairs.size(), called, differ);
    EXPECT_EQ(broken, 0u);
    EXPECT_GT(differ, 0u);                  // the move mattered
    EXPECT_LT(called, pairs.size() / 2);    // and the test culls
    before = after;
  }
}

// After a move the analytic lights' irradiance is brought up to date only where the move can
// have changed it (Transport::updateLightIrradianceAfterMove): the result must be what tracing
// every element again gives, to the bit, for a sun (rays to infinity) and a point lamp (finite).
TEST(MovingObjects, LightIrradianceFollowsAMoveWhereItCanHaveChanged) {
  // A 6 x 6 m ground under a 1 m box standing 0.5 m above it, lit by a low sun (rays to
  // infinity) and a lamp (finite rays).
  Scene scene;
  scene.materials.push_back(Material{});
  Mesh& ground = scene.meshes.emplace_back();
  builtin::addGridQuad(ground, Vec3(-3.0f, 0.0f, 3.0f), Vec3(6.0f, 0.0f, 0.0f), Vec3(0.0f, 0.0f, -6.0f), 40, 40);
  Mesh& cube = scene.meshes.emplace_back();
  builtin::addOutwardBox(cube, Vec3(0.0f, 1.0f, 0.0f), Vec3(1.0f), 0.0f, 4, 4, 4);
  builtin::makeDynamicObject(scene, cube, "box", Vec3(0.0f, 1.0f, 0.0f));
  Light sun;
  sun.type = Light::Type::Directional;
  sun.intensity = 1000.0f;
  sun.direction = glm::normalize(Vec3(0.6f, -0.5f, 0.2f));
  sun.angularRadius = 0.00465f;
  scene.lights.push_back(sun);
  Light lamp;
  lamp.type = Light::Type::Point;
  lamp.intensity = 50.0f;
  lamp.position = Vec3(-0.5f, 3.0f, 0.8f);
  scene.lights.push_back(lamp);
  const uint32_t box = theBox(scene);
  SurfaceSet surfaces = discretise(scene, DiscretiseOptions{});
  CpuTransport transport(scene, surfaces, FormFactorOptions{});
  const size_t ne = surfaces.elements.size();
  std::vector<std::vector<Rgb>> parts(scene.lights.size(), std::vector<Rgb>(ne));
  for (uint32_t i = 0; i < scene.lights.size(); ++i) transport.lightIrradiance(std::vector<uint32_t>{i}, parts[i]);

  const Vec3 centre(scene.objects[box].transform[3]);
  const glm::mat4 rest = scene.objects[box].transform;
  const glm::mat4 poses[] = {turnedAbout(centre, 1.0f) * glm::translate(glm::mat4(1.0f), -centre) * rest,
                             glm::translate(glm::mat4(1.0f), Vec3(0.5f, 0.0f, 0.3f)) * rest};
  for (const glm::mat4& pose : poses) {
    scene.placeObject(box, pose);
    surfaces.placeObject(scene, box);
    transport.objectsMoved(std::vector<uint32_t>{box});
    for (uint32_t i = 0; i < scene.lights.size(); ++i) {
      const std::vector<uint32_t> one{i};
      const std::vector<Rgb> was = parts[i];
      const size_t redone = transport.updateLightIrradianceAfterMove(one, parts[i]);
      std::vector<Rgb> fresh(ne);
      transport.lightIrradiance(one, fresh);
      size_t changed = 0;
      for (size_t e = 0; e < ne; ++e) {
        ASSERT_EQ(parts[i][e], fresh[e]) << "light " << i << ", element " << e;
        changed += fresh[e] != was[e];
      }
      std::printf("light %u: %zu of %zu elements computed again, %zu changed\n", i, redone, ne, changed);
      EXPECT_GE(redone, changed);
      EXPECT_GT(changed, 20u);     // the shadow moved
      EXPECT_LT(redone, ne / 3);  // where the shadows were and are, and the box, not the ground
    }
  }
}

}  // namespace
}  // namespace luxel
