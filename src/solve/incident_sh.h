// Where interreflected light comes from, for directional lightmaps (issue 17, seed 004 section 4):
// the spherical-harmonic projection (core/spherical_harmonics.h) of the radiance a patch sends an
// element, from the form factor a solver already has.
#pragma once

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "core/spherical_harmonics.h"
#include "luxel/surface.h"
#include "transport/transport.h"

namespace luxel {

// Adds to c (count = 4 or 9 coefficients) the incident radiance that patch `p` of exitance `b`
// brings element `e` through the form factor `f` (visibility included). Bands 0 and 1 are the
// exact moments of the patch's polygon as seen from the element's centroid (its solid angle, Van
// Oosterom and Strackee, and its irradiance vector, Arvo 1994), scaled by the visible share
// f / (unoccluded factor); band 2 from pieces of the polygon, each taken as one direction, more of
// them the nearer the patch.
// Where the element's plane cuts the polygon, both moments are of the part in front of it (a
// light in the ceiling that reaches over a wall's plane lights it from the front part only).
void addPatchSh(const SurfaceSet& surfaces, uint32_t e, uint32_t p, float f, Rgb b, int count, Rgb* c);

// A patch under a fifth of its distance across: one direction, its solid angle A cos / r^2 to a
// few parts in a thousand, so f b / cos(theta) is the integral of L. For L2 (count 9) band 2 goes
// along the same direction, as addPatchSh takes such a patch's band 2 (one piece: it cuts a patch
// into pieces only from a quarter of its distance across). Returns false (and adds nothing) for a
// nearer patch, which addPatchSh then takes. Inline: a pass over every element and shooter calls
// it tens of millions of times.
inline constexpr float kShFarField = 0.2f;  // a far patch's side, at most, over its distance
inline bool addFarPatchSh(const Element& el, const Patch& patch, float f, Rgb b, int count, Rgb* c) {
  const Vec3 toPatch = patch.centroid - el.centroid;
  const float r2 = glm::dot(toPatch, toPatch);
  if (!(patch.area < kShFarField * kShFarField * r2)) return false;
  const Vec3 w = toPatch / std::sqrt(r2);
  const Rgb weight = (f / std::max(glm::dot(el.normal, w), kShMinimumCosine)) * b;
  c[0] += kShY0 * weight;
  c[1] += (kShY1 * w.y) * weight;
  c[2] += (kShY1 * w.z) * weight;
  c[3] += (kShY1 * w.x) * weight;
  if (count > kShL1Coefficients) {
    const auto y = shBasis(w);
    for (int i = kShL1Coefficients; i < kShCoefficients; ++i) c[i] += y[size_t(i)] * weight;
  }
  return true;
}

// Element centroids and normals as separate arrays, for addShooterBlockL1's loops over elements.
struct ElementFrames {
  std::vector<float> cx, cy, cz, nx, ny, nz;
  explicit ElementFrames(const SurfaceSet& surfaces);
};

// L1 (count 4) for the elements [begin, end) from a block of shooting patches: shooter k of
// `shooters` has exitance exitance[k] and form factors columns[k][e]. Far pairs (addFarPatchSh's
// test and formula) are summed in one branch-free pass across elements, which the compiler
// vectorises; near pairs go to addPatchSh. Adds to out[e * 4 + i].
void addShooterBlockL1(const SurfaceSet& surfaces, const ElementFrames& frames, std::span<const uint32_t> shooters,
                       std::span<const float* const> columns, std::span<const Rgb> exitance, size_t begin, size_t end,
                       Rgb* out);

}  // namespace luxel
