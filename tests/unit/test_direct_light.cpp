// Per-pixel direct light (hq mode) where the receiver's plane cuts through an emitter: the shadow
// rays must only aim at the emitter's part in front of the receiver. Found by the Cycles
// comparison: the Cornell tall block's front face got 62% of its direct light.
#include <numbers>

#include <gtest/gtest.h>

#include "render/direct_light.h"
#include "scene/builtin/builtin_scenes.h"

namespace luxel {
namespace {

TEST(DirectLight, EmitterCutByTheReceiverPlaneIsSampledInFront) {
  // A 2 x 2 emitter at y = 1 facing down (Le = 1, exitance pi), centred on x = 0, and a wall in
  // the plane x = 0 facing +x: half the emitter lies behind the wall's plane. Nothing occludes
  // the half in front.
  Scene s;
  s.name = "cut emitter";
  s.materials = {Material{.name = "lamp", .reflectance = Rgb(0.0f), .emission = Rgb(1.0f)},
                 Material{.name = "wall", .reflectance = Rgb(0.5f)}};
  Mesh lamp{.name = "lamp", .material = 0};
  builtin::addQuad(lamp, {-1, 1, -1}, {1, 1, -1}, {1, 1, 1}, {-1, 1, 1});  // normal -y
  // The wall is a slab, like the Cornell block: a back face 5 cm behind, so the emitter's part
  // behind the front face's plane is hidden from it by the slab itself.
  Mesh wall{.name = "wall", .material = 1};
  builtin::addQuad(wall, {0, -1, -1}, {0, 0.5f, -1}, {0, 0.5f, 1}, {0, -1, 1});  // normal +x
  builtin::addQuad(wall, {-0.05f, -1, -1}, {-0.05f, -1, 1}, {-0.05f, 0.5f, 1}, {-0.05f, 0.5f, -1});  // -x
  builtin::addQuad(wall, {-0.05f, 0.5f, -1}, {-0.05f, 0.5f, 1}, {0, 0.5f, 1}, {0, 0.5f, -1});  // top, +y
  s.meshes = {lamp, wall};
  SurfaceSet set = discretise(s, DiscretiseOptions{.elementBudget = 50});

  std::vector<Polygon> faces;
  for (const SurfaceFace& f : set.faces) faces.push_back(Polygon{f.corners, f.triangle ? 3 : 4});
  RayTracer tracer(faces);
  DirectLight direct(s, set);

  const Vec3 x(0.0f, 0.0f, 0.0f), n(1.0f, 0.0f, 0.0f);
  const double expected = std::numbers::pi * pointToPolygonFormFactor(x, n, faces[0], Sides::Front, Sides::Front);
  ASSERT_GT(expected, 0.1);
  Rng rng(7);
  double sum = 0.0;
  const int samples = 4000;
  std::vector<RTCRay> rays;
  std::vector<Rgb> values;
  for (int i = 0; i < samples; ++i) {
    rays.clear();
    values.clear();
    direct.sample(x, n, Sides::Front, rng, 1e-5f, rays, values);
    tracer.occluded(rays);
    for (size_t k = 0; k < rays.size(); ++k)
      if (!isOccluded(rays[k])) sum += values[k].g;
  }
  // The part in front is unoccluded, so every sample carries exactly the analytic value.
  EXPECT_NEAR(sum / samples, expected, 1e-3 * expected);
}

}  // namespace
}  // namespace luxel
