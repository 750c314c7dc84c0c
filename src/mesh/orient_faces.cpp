#include "mesh/orient_faces.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <limits>
#include <numbers>

#include <tbb/parallel_for.h>

#include "core/random.h"
#include "trace/ray_tracer.h"
#include "transport/emitting_polygons.h"
#include "transport/form_factor.h"
#include "transport/light_sampling.h"

namespace luxel {
namespace {

// Emitting faces consulted, the most powerful first; sample points per face and side.
constexpr size_t kMaxEmitters = 32;
constexpr int kPointsPerFace = 4;  // pointToPolygonFormFactors4's four lanes
// The back must win clearly, so that noise never flips a face that is lit about equally on both sides.
constexpr float kFlipMargin = 1.5f;
// ... and get more than the brightest emitting face consulted would give it at this form factor,
// per sample point. A ratio alone cannot tell rounding from light where the front gets exactly
// none: a face in an emitter's plane (a ceiling round a light panel set into it) sees the emitter
// edge-on from both sides, its front gets an exact 0, and the point-to-polygon form factor, a sum
// of edge angles that cancel there, leaves its back a residue of order float epsilon. Measured:
// at most 2e-8 of the brightest radiance, summed over a face's points and emitters; it turned 82
// ceiling cells of shader-box-10254 round. The floor, 4e-5 of that radiance, is 2000 times
// higher, and far below real light: 1e-5 is a 1 m^2 panel seen face-on from 180 m. It is tied to
// the emitters' radiance, not to the light other faces get, so that neither a face next to a
// point light nor a ceiling of many coplanar cells (most of the lit faces, lit by the residue
// alone) moves it. Without emitting faces the floor is 0: analytic lights leave no such residue
// that we have seen.
constexpr float kMinFormFactor = 1e-5f;

Polygon polygonOf(const SurfaceFace& f) { return Polygon{f.corners, f.triangle ? 3 : 4}; }

}  // namespace

size_t orientFacesByLight(const Scene& scene, std::vector<SurfaceFace>& faces, float sceneExtent) {
  // The emitting faces, a lamp cut into cells or triangles joined into one polygon (as the
  // direct light samples them, transport/emitting_polygons.h): each is visited from every face.
  std::vector<EmittingPolygon> pieces;
  for (const SurfaceFace& f : faces) {
    const Material& m = scene.materials[f.material];
    if (m.isEmissive()) pieces.push_back({polygonOf(f), f.normal, m.emission * std::numbers::pi_v<float>});
  }
  std::vector<EmittingPolygon> emitters = joinLampPieces(std::move(pieces));
  // Summed over channels, the most powerful first.
  auto radianceOf = [](const EmittingPolygon& e) { return (e.exitance.r + e.exitance.g + e.exitance.b) / std::numbers::pi_v<float>; };
  std::stable_sort(emitters.begin(), emitters.end(), [&](const EmittingPolygon& a, const EmittingPolygon& b) {
    return a.polygon.area() * radianceOf(a) > b.polygon.area() * radianceOf(b);
  });
  if (emitters.size() > kMaxEmitters) emitters.resize(kMaxEmitters);
  if (emitters.empty() && scene.lights.empty()) return 0;

  std::vector<Polygon> polygons(faces.size());
  for (size_t i = 0; i < faces.size(); ++i) polygons[i] = polygonOf(faces[i]);
  RayTracer tracer(polygons);
  const float offset = rayOffsetFor(sceneExtent);
  const Vec3 up = glm::normalize(scene.up);

  float brightest = 0.0f;
  std::vector<float> radiance;  // per emitter consulted
  for (const EmittingPolygon& e : emitters) {
    radiance.push_back(radianceOf(e));
    brightest = std::max(brightest, radiance.back());
  }
  const float floorLight = kMinFormFactor * float(kPointsPerFace) * brightest;

  std::atomic<size_t> flipped{0};
  tbb::parallel_for(size_t(0), faces.size(), [&](size_t fi) {
    SurfaceFace& f = faces[fi];
    const Material& m = scene.materials[f.material];
    if (m.twoSided || m.isEmissive()) return;
    Rng rng(pcgHash(uint32_t(fi) * 2654435761u + 17u));
    std::vector<RTCRay> rays;
    std::vector<float> values;
    std::vector<float> weight(emitters.size() * kPointsPerFace);  // emitter x point
    std::vector<int> side;  // 0 front, 1 back
    std::vector<uint8_t> inFront, behind;  // per emitter: wholly on that side of the points
    std::array<Vec3, kPointsPerFace> points;
    for (int k = 0; k < kPointsPerFace; ++k)
      points[size_t(k)] = polygonPoint(polygons[fi], (float(k % 2) + rng.next()) * 0.5f, (float(k / 2) + rng.next()) * 0.5f);
    // Which side of the points' planes each emitting face lies on: most lie wholly on one, and
    // the other side's form factors are exactly 0 (half the calls, the bulk of this pass on a
    // million faces).
    inFront.assign(emitters.size(), 0), behind.assign(emitters.size(), 0);
    for (size_t e = 0; e < emitters.size(); ++e) {
      const Polygon& emitter = emitters[e].polygon;
      float lowest = std::numeric_limits<float>::max(), highest = -std::numeric_limits<float>::max();
      for (const Vec3& x : points)
        for (int v = 0; v < emitter.count; ++v) {
          const float d = glm::dot(emitter.v[size_t(v)] - x, f.normal);
          lowest = std::min(lowest, d), highest = std::max(highest, d);
        }
      inFront[e] = lowest >= 0.0f, behind[e] = highest <= 0.0f;
    }
    // No emitting face reaches the back and no analytic light can: the back gets nothing, so the
    // face keeps its side (most faces that look towards the light end here, without a ray).
    if (scene.lights.empty() && std::all_of(inFront.begin(), inFront.end(), [](uint8_t v) { return v != 0; })) return;
    for (int s = 0; s < 2; ++s) {
      const Vec3 n = s == 0 ? f.normal : -f.normal;
      const Vec3 normals[kPointsPerFace] = {n, n, n, n};
      // The emitting faces' light at each point, the four points in one call per emitter.
      for (size_t e = 0; e < emitters.size(); ++e) {
        float* w = &weight[e * kPointsPerFace];
        if (s == 0 ? behind[e] : inFront[e]) {
          std::fill(w, w + kPointsPerFace, 0.0f);
          continue;
        }
        pointToPolygonFormFactors4(points.data(), normals, emitters[e].polygon, emitters[e].normal, w);
        for (int k = 0; k < kPointsPerFace; ++k) w[k] = std::max(w[k], 0.0f) * radiance[e];
      }
      for (int k = 0; k < kPointsPerFace; ++k) {
        const Vec3 x = points[size_t(k)], xo = x + n * offset;
        // One shadow ray to one emitter, picked in proportion to what it brings: the same
        // expected light as a ray to each, for one ray a point however many lamps there are, on
        // every face of a million-face scene.
        float total = 0.0f;
        for (size_t e = 0; e < emitters.size(); ++e) total += weight[e * kPointsPerFace + size_t(k)];
        if (total > 0.0f) {
          float pick = rng.next() * total;
          size_t e = 0;
          while (e + 1 < emitters.size() && pick >= weight[e * kPointsPerFace + size_t(k)])
            pick -= weight[e * kPointsPerFace + size_t(k)], ++e;
          while (weight[e * kPointsPerFace + size_t(k)] <= 0.0f) --e;  // rounding ran past the last lit one
          Vec3 y;
          if (pointInFront(emitters[e].polygon, x, n, [&] { return rng.next(); }, y)) {
            const Vec3 yo = y + emitters[e].normal * offset;
            rays.push_back(makeRay(xo, yo - xo, 0.0f, 1.0f));
            values.push_back(total);
            side.push_back(s);
          }
        }
        for (const Light& light : scene.lights) {
          LightSample ls = sampleLight(light, x, n, Sides::Front, up, rng.next(), rng.next());
          if (!ls.valid()) continue;
          rays.push_back(makeRay(xo, ls.direction, 0.0f, ls.tfar));
          values.push_back(ls.irradiance.r + ls.irradiance.g + ls.irradiance.b);
          side.push_back(s);
        }
      }
    }
    tracer.occluded(rays);
    float light[2] = {0.0f, 0.0f};
    for (size_t i = 0; i < rays.size(); ++i)
      if (!isOccluded(rays[i])) light[side[i]] += values[i];
    if (light[1] > kFlipMargin * light[0] && light[1] > floorLight) {
      std::swap(f.corners[1], f.corners[f.triangle ? 2 : 3]);
      std::swap(f.uvs[1], f.uvs[f.triangle ? 2 : 3]);
      if (f.triangle) f.corners[3] = f.corners[2], f.uvs[3] = f.uvs[2];
      f.normal = -f.normal;
      f.flipped = true;
      ++flipped;
    }
  });
  return flipped.load();
}

}  // namespace luxel
