// The spherical-harmonic moments of a patch's light at an element: see solve/incident_sh.h.
#include "solve/incident_sh.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/spherical_harmonics.h"
#include "transport/form_factor.h"
#include "transport/transport.h"

namespace luxel {

namespace {

// Bands 0 and 1 of a polygon's light at a point: v, its irradiance vector per unit exitance
// (length |v|), omega its solid angle, `visible` the share of it the point's element sees.
// Radiance b / pi over the solid angle: integral of L = visible * b / pi * omega, integral of
// L w = visible * b * v. Returns band 0's integral.
Rgb addVisibleMoments(Vec3 v, float length, float omega, float visible, Rgb b, int count, Rgb* c) {
  omega = std::max(omega, std::numbers::pi_v<float> * length);
  const Rgb m0 = (visible * omega / std::numbers::pi_v<float>) * b;
  const Rgb scale = visible * b;
  c[0] += kShY0 * m0;
  if (count < kShL1Coefficients) return m0;
  c[1] += (kShY1 * v.y) * scale;
  c[2] += (kShY1 * v.z) * scale;
  c[3] += (kShY1 * v.x) * scale;
  return m0;
}

// The near pairs of one shooter and a chunk of elements (indices first + at[j]), four at a time
// through polygonMoments4; the lanes it leaves, and centroids that see none of the polygon, one
// by one through addPatchSh.
void addNearPairsL1(const SurfaceSet& surfaces, uint32_t shooter, const float* f, Rgb b, size_t first,
                    const uint8_t* at, size_t count, Rgb* out) {
  const Patch& patch = surfaces.patches[shooter];
  for (size_t j = 0; j < count; j += 4) {
    const size_t lanes = std::min<size_t>(4, count - j);
    Vec3 p[4], n[4], v[4];
    float omega[4];
    for (size_t i = 0; i < 4; ++i) {
      const Element& el = surfaces.elements[first + at[j + std::min(i, lanes - 1)]];
      p[i] = el.centroid, n[i] = el.normal;
    }
    const int done = polygonMoments4(p, n, patch.polygon, patch.normal, v, omega);
    for (size_t i = 0; i < lanes; ++i) {
      const size_t e = first + at[j + i];
      Rgb* c = out + e * kShL1Coefficients;
      const float unoccluded = glm::dot(v[i], n[i]), length = glm::length(v[i]);
      if ((done >> i & 1) && unoccluded > 1e-7f && length > 0.0f)
        addVisibleMoments(v[i], length, omega[i], f[at[j + i]] / unoccluded, b, kShL1Coefficients, c);
      else
        addPatchSh(surfaces, uint32_t(e), shooter, f[at[j + i]], b, kShL1Coefficients, c);
    }
  }
}

}  // namespace

void addPatchSh(const SurfaceSet& surfaces, uint32_t e, uint32_t p, float f, Rgb b, int count, Rgb* c) {
  if (f == 0.0f) return;
  const Element& el = surfaces.elements[e];
  const Patch& patch = surfaces.patches[p];
  if (addFarPatchSh(el, patch, f, b, count, c)) return;
  // v: the irradiance vector per unit exitance, the integral of w / pi over the part of the
  // polygon in front of the element; v . n is the unoccluded factor.
  const PolygonMoments moments = clippedPolygonMoments(el.centroid, el.normal, patch.polygon, patch.normal);
  const Vec3 v = moments.vector;
  const float unoccluded = glm::dot(v, el.normal);
  const float length = glm::length(v);
  if (!(unoccluded > 1e-7f) || !(length > 0.0f)) {
    // The centroid sees none of the polygon where the element's quadrature saw some (an element
    // touching the patch's plane): one direction, centroid to centroid.
    const Vec3 d = patch.centroid - el.centroid;
    const float r = glm::length(d);
    if (!(r > 0.0f)) return;
    const Vec3 w = d / r;
    shAddDirection(c, count, w, (f / std::max(glm::dot(el.normal, w), kShMinimumCosine)) * b);
    return;
  }
  const float visible = f / unoccluded;
  const Rgb m0 = addVisibleMoments(v, length, moments.solidAngle, visible, b, count, c);
  if (count < kShCoefficients) return;
  // Band 2: the polygon cut into k x k pieces, each one direction (its irradiance vector's) with
  // its solid angle; k grows as the patch comes closer, where one direction would misplace the
  // light of a neighbouring wall.
  const float across = std::sqrt(patch.area) / std::max(glm::length(patch.centroid - el.centroid), 1e-30f);
  const int k = across < 2.0f ? std::max(1, int(std::ceil(4.0f * across))) : 8;  // NaN: 8
  if (k == 1) {
    const auto y = shBasis(v / length);
    for (int i = 4; i < kShCoefficients; ++i) c[i] += y[size_t(i)] * m0;
    return;
  }
  const Polygon& poly = patch.polygon;
  auto addPiece = [&](const Polygon& piece) {
    const PolygonMoments pm = clippedPolygonMoments(el.centroid, el.normal, piece, patch.normal);
    const Vec3 pv = pm.vector;
    const float pl = glm::length(pv);
    if (!(pl > 0.0f)) return;
    const float pieceOmega = std::max(pm.solidAngle, std::numbers::pi_v<float> * pl);
    const auto y = shBasis(pv / pl);
    const Rgb w = (visible * pieceOmega / std::numbers::pi_v<float>) * b;
    for (int i = 4; i < kShCoefficients; ++i) c[i] += y[size_t(i)] * w;
  };
  const float step = 1.0f / float(k);
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      if (poly.count == 4) {
        const float s0 = float(i) * step, t0 = float(j) * step;
        addPiece(Polygon{{polygonPoint(poly, s0, t0), polygonPoint(poly, s0 + step, t0),
                          polygonPoint(poly, s0 + step, t0 + step), polygonPoint(poly, s0, t0 + step)},
                         4});
      } else if (i + j < k) {
        // Barycentric sub-triangles: (i, j) upright, and the inverted one beside it when it fits.
        auto at = [&](int along1, int along2) {
          return poly.v[0] + (float(along1) * step) * (poly.v[1] - poly.v[0]) + (float(along2) * step) * (poly.v[2] - poly.v[0]);
        };
        addPiece(Polygon{{at(i, j), at(i + 1, j), at(i, j + 1), at(i, j + 1)}, 3});
        if (i + j + 1 < k) addPiece(Polygon{{at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), at(i, j + 1)}, 3});
      }
    }
}

ElementFrames::ElementFrames(const SurfaceSet& surfaces) {
  const size_t n = surfaces.elements.size();
  for (auto* v : {&cx, &cy, &cz, &nx, &ny, &nz}) v->resize(n);
  for (size_t e = 0; e < n; ++e) {
    const Element& el = surfaces.elements[e];
    cx[e] = el.centroid.x, cy[e] = el.centroid.y, cz[e] = el.centroid.z;
    nx[e] = el.normal.x, ny[e] = el.normal.y, nz[e] = el.normal.z;
  }
}

void addShooterBlockL1(const SurfaceSet& surfaces, const ElementFrames& frames, std::span<const uint32_t> shooters,
                       std::span<const float* const> columns, std::span<const Rgb> exitance, size_t begin, size_t end,
                       Rgb* out) {
  // Elements a chunk at a time, so that the sums stay in L1 cache: the integral of the radiance
  // (band 0) and of the radiance times the direction (band 1), per channel.
  constexpr size_t kChunk = 64;
  constexpr float kFarField2 = kShFarField * kShFarField;  // addFarPatchSh's test
  float sum[3][kChunk], sumW[3][3][kChunk];
  uint8_t nearPair[kChunk];
  for (size_t first = begin; first < end; first += kChunk) {
    const size_t n = std::min(kChunk, end - first);
    std::fill(&sum[0][0], &sum[0][0] + 3 * kChunk, 0.0f);
    std::fill(&sumW[0][0][0], &sumW[0][0][0] + 9 * kChunk, 0.0f);
    const float *cx = &frames.cx[first], *cy = &frames.cy[first], *cz = &frames.cz[first];
    const float *nx = &frames.nx[first], *ny = &frames.ny[first], *nz = &frames.nz[first];
    for (size_t k = 0; k < shooters.size(); ++k) {
      const Patch& patch = surfaces.patches[shooters[k]];
      const float px = patch.centroid.x, py = patch.centroid.y, pz = patch.centroid.z, area = patch.area;
      const float br = exitance[k].r, bg = exitance[k].g, bb = exitance[k].b;
      const float* f = &columns[k][first];
      uint8_t anyNear = 0;
      for (size_t i = 0; i < n; ++i) {
        const float dx = px - cx[i], dy = py - cy[i], dz = pz - cz[i];
        const float r2 = dx * dx + dy * dy + dz * dz;
        const bool far = area < kFarField2 * r2;  // NaN: near
        // Computed for every pair and selected after, without branches (nothing here can trap).
        const float inv = 1.0f / std::sqrt(std::max(r2, 1e-30f));
        const float wx = dx * inv, wy = dy * inv, wz = dz * inv;
        const float q = f[i] / std::max(nx[i] * wx + ny[i] * wy + nz[i] * wz, kShMinimumCosine);
        const float weight = far ? q : 0.0f;
        const float wr = weight * br, wg = weight * bg, wb = weight * bb;
        sum[0][i] += wr, sum[1][i] += wg, sum[2][i] += wb;
        sumW[0][0][i] += wr * wx, sumW[0][1][i] += wr * wy, sumW[0][2][i] += wr * wz;
        sumW[1][0][i] += wg * wx, sumW[1][1][i] += wg * wy, sumW[1][2][i] += wg * wz;
        sumW[2][0][i] += wb * wx, sumW[2][1][i] += wb * wy, sumW[2][2][i] += wb * wz;
        nearPair[i] = uint8_t(!far) & uint8_t(f[i] != 0.0f);
        anyNear |= nearPair[i];
      }
      if (anyNear) {
        uint8_t at[kChunk];
        size_t nearCount = 0;
        for (size_t i = 0; i < n; ++i)
          if (nearPair[i]) at[nearCount++] = uint8_t(i);
        addNearPairsL1(surfaces, shooters[k], f, exitance[k], first, at, nearCount, out);
      }
    }
    for (size_t i = 0; i < n; ++i) {
      Rgb* c = out + (first + i) * kShL1Coefficients;
      const Rgb s(sum[0][i], sum[1][i], sum[2][i]);
      const Rgb sx(sumW[0][0][i], sumW[1][0][i], sumW[2][0][i]);
      const Rgb sy(sumW[0][1][i], sumW[1][1][i], sumW[2][1][i]);
      const Rgb sz(sumW[0][2][i], sumW[1][2][i], sumW[2][2][i]);
      c[0] += kShY0 * s, c[1] += kShY1 * sy, c[2] += kShY1 * sz, c[3] += kShY1 * sx;
    }
  }
}

}  // namespace luxel
