// A scene whose partly occluded form factor has a closed form, for the visibility estimators of
// every backend: a 1 cm receiver at the origin facing up (+y), a black emitter of radiance 1
// facing down at y = 1 over x in [-0.5, 3], z in [-1, 1], and between them a black sheet at
// y = 0.5 over x >= 0.5. From a receiver point at (xr, 0, zr) the sheet hides the emitter beyond
// x = 1 - xr, so the factor is Lambert's point-to-polygon factor of the emitter's near part.
//
// The near part is 43% of the emitter's area but carries 87% of its unoccluded factor: an
// estimator that weights every ray between the two alike (the unoccluded factor times the share of
// rays that arrive) comes out 51% low here.
#pragma once

#include <vector>

#include "luxel/scene.h"
#include "luxel/surface.h"
#include "scene/builtin/builtin_scenes.h"
#include "transport/form_factor.h"

namespace luxel::test {

inline constexpr float kHalfShadowReceiverHalfSize = 0.005f;
inline constexpr float kHalfShadowEmitterX0 = -0.5f, kHalfShadowEmitterX1 = 3.0f, kHalfShadowEmitterHalfZ = 1.0f;

inline Scene halfShadowScene() {
  Scene s;
  s.name = "half-shadow";
  s.materials.push_back(Material{.name = "black", .reflectance = Rgb(0.0f)});
  s.materials.push_back(Material{.name = "emitter", .reflectance = Rgb(0.0f), .emission = Rgb(1.0f)});
  const float r = kHalfShadowReceiverHalfSize, x0 = kHalfShadowEmitterX0, x1 = kHalfShadowEmitterX1,
              z = kHalfShadowEmitterHalfZ;
  Mesh black{.name = "receiver and sheet"};
  builtin::addQuad(black, {-r, 0, -r}, {-r, 0, r}, {r, 0, r}, {r, 0, -r});                   // faces +y
  builtin::addQuad(black, {0.5f, 0.5f, -10}, {10, 0.5f, -10}, {10, 0.5f, 10}, {0.5f, 0.5f, 10});  // faces -y
  black.elementGrids = {{1, 1}, {1, 1}};
  Mesh light{.name = "emitter", .material = 1};
  builtin::addQuad(light, {x0, 1, -z}, {x1, 1, -z}, {x1, 1, z}, {x0, 1, z});  // faces -y
  light.elementGrids = {{1, 1}};
  s.meshes = {black, light};
  s.cameras.push_back(Camera{.name = "default", .eye = Vec3(0, 0.2f, -1), .target = Vec3(0, 0.5f, 0), .up = Vec3(0, 1, 0), .fovY = 90.0f});
  return s;
}

// One element per face, as the scene's grids ask, and no face turned round.
inline SurfaceSet halfShadowSurfaces(const Scene& scene) {
  DiscretiseOptions d;
  d.orientByLight = false;
  return discretise(scene, d);
}

// The receiver's form factor to the emitter: the closed form at each point of an 8 x 8 grid over
// the receiver, averaged (`occluded` false: without the sheet).
inline double halfShadowFactor(bool occluded) {
  const int n = 8;
  double sum = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const float xr = kHalfShadowReceiverHalfSize * (2.0f * (float(i) + 0.5f) / n - 1.0f);
      const float zr = kHalfShadowReceiverHalfSize * (2.0f * (float(j) + 0.5f) / n - 1.0f);
      const float xEnd = occluded ? 1.0f - xr : kHalfShadowEmitterX1;
      const float z = kHalfShadowEmitterHalfZ;
      const Polygon seen{{Vec3(kHalfShadowEmitterX0, 1, -z), Vec3(xEnd, 1, -z), Vec3(xEnd, 1, z), Vec3(kHalfShadowEmitterX0, 1, z)}, 4};
      sum += pointToPolygonFormFactor(Vec3(xr, 0, zr), Vec3(0, 1, 0), seen, Sides::Front, Sides::Front);
    }
  return sum / (n * n);
}

// The element of the scene's receiver (the one at the origin).
inline size_t halfShadowReceiver(const SurfaceSet& surfaces) {
  for (size_t e = 0; e < surfaces.elements.size(); ++e)
    if (glm::length(surfaces.elements[e].centroid) < 1e-3f) return e;
  return surfaces.elements.size();
}

}  // namespace luxel::test
