#include "transport/monte_carlo_transport.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "core/random.h"
#include "luxel/error.h"

namespace luxel {
namespace {

std::vector<Polygon> patchPolygons(const SurfaceSet& surfaces) {
  std::vector<Polygon> polygons;
  polygons.reserve(surfaces.patches.size());
  for (const Patch& p : surfaces.patches) polygons.push_back(p.polygon);
  return polygons;
}

}  // namespace

MonteCarloTransport::MonteCarloTransport(const Scene& scene, const SurfaceSet& surfaces, int raysPerElement,
                                         const FormFactorOptions& lightOptions)
    : surfaces_(surfaces),
      raysPerElement_(raysPerElement),
      patchPolygons_(patchPolygons(surfaces)),
      tracer_(patchPolygons_),
      lights_(scene, surfaces, lightOptions) {
  if (raysPerElement < 1) throw Error("Monte Carlo form factors need at least one ray per element");
  for (const SurfaceFace& f : surfaces.faces)
    if (f.twin >= 0)
      throw Error("Monte Carlo form factors: two-sided faces (material twoSided) are not supported: their two "
                  "sides coincide and a ray cannot tell which one it met");
}

MonteCarloTransport::~MonteCarloTransport() = default;

void MonteCarloTransport::rows(std::span<const uint32_t> elements, std::span<float> out) {
  const size_t np = surfaces_.patches.size();
  const float offset = rayOffsetFor(surfaces_.sceneExtent);
  const int n = raysPerElement_;
  const int k = std::max(1, int(std::sqrt(float(n))));  // k x k strata over the element, the rest unstratified
  tbb::parallel_for(size_t(0), elements.size(), [&](size_t i) {
    const Element& e = surfaces_.elements[elements[i]];
    float* row = out.data() + i * np;
    std::fill(row, row + np, 0.0f);
    Rng rng(0x5EEDu ^ (elements[i] * 0x9E3779B1u));
    const Vec3 nrm = e.normal;
    const Vec3 t = glm::normalize(std::abs(nrm.x) > 0.9f ? glm::cross(nrm, Vec3(0, 1, 0)) : glm::cross(nrm, Vec3(1, 0, 0)));
    const Vec3 b = glm::cross(nrm, t);
    std::vector<RTCRayHit> hits(static_cast<size_t>(n));
    // Positions and directions are each stratified on a k x k grid, paired by a random permutation
    // (so that neither follows the other); the rays past k x k are unstratified.
    std::vector<uint32_t> pairing(size_t(k) * size_t(k));
    std::iota(pairing.begin(), pairing.end(), 0u);
    for (size_t m = pairing.size(); m > 1; --m) std::swap(pairing[m - 1], pairing[rng.nextUint() % m]);
    for (int j = 0; j < n; ++j) {
      const bool stratum = j < k * k;
      const float su = stratum ? (float(j % k) + rng.next()) / float(k) : rng.next();
      const float sv = stratum ? (float(j / k) + rng.next()) / float(k) : rng.next();
      const Vec3 x = uniformPolygonPoint(e.polygon, rng.next(), su, sv);
      const int dj = stratum ? int(pairing[size_t(j)]) : 0;
      const float du = stratum ? (float(dj % k) + rng.next()) / float(k) : rng.next();
      const float dv = stratum ? (float(dj / k) + rng.next()) / float(k) : rng.next();
      // Cosine-distributed direction (Malley): a uniform point of the unit disc lifted to the
      // hemisphere.
      const float r = std::sqrt(du), phi = 2.0f * std::numbers::pi_v<float> * dv;
      const Vec3 d = r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(std::max(0.0f, 1.0f - r * r)) * nrm;
      RTCRayHit& h = hits[size_t(j)];
      h.ray = makeRay(x + offset * nrm, d, 0.0f, std::numeric_limits<float>::infinity());
      h.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    }
    tracer_.intersect(hits, false);
    const float share = 1.0f / float(n);
    for (const RTCRayHit& h : hits) {
      if (h.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;  // out of the scene
      const Patch& p = surfaces_.patches[h.hit.primID];
      // Only a patch's front sends light; its back absorbs the ray.
      if (h.ray.dir_x * p.normal.x + h.ray.dir_y * p.normal.y + h.ray.dir_z * p.normal.z < 0.0f) row[h.hit.primID] += share;
    }
  });
}

void MonteCarloTransport::ensureMatrix() {
  const size_t ne = surfaces_.elements.size(), np = surfaces_.patches.size();
  if (matrix_.size() == ne * np) return;
  std::vector<uint32_t> all(ne);
  std::iota(all.begin(), all.end(), 0u);
  matrix_.assign(ne * np, 0.0f);
  rows(all, matrix_);
}

void MonteCarloTransport::columns(std::span<const uint32_t> patches, std::span<float> out) {
  ensureMatrix();
  const size_t ne = surfaces_.elements.size(), np = surfaces_.patches.size();
  for (size_t c = 0; c < patches.size(); ++c)
    for (size_t e = 0; e < ne; ++e) out[c * ne + e] = matrix_[e * np + patches[c]];
}

void MonteCarloTransport::pairs(std::span<const ElementPatch> pairs, std::span<float> out) {
  ensureMatrix();
  const size_t np = surfaces_.patches.size();
  for (size_t i = 0; i < pairs.size(); ++i) out[i] = matrix_[size_t(pairs[i].element) * np + pairs[i].patch];
}

void MonteCarloTransport::objectsMoved(std::span<const uint32_t>) {
  throw Error("the Monte Carlo transport is a reference for static scenes: it cannot follow moving objects");
}

}  // namespace luxel
