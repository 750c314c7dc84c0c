// The spherical-harmonic moments of a patch's light at an element: see solve/incident_sh.h.
#include "solve/incident_sh.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/spherical_harmonics.h"
#include "transport/form_factor.h"
#include "transport/transport.h"

namespace luxel {

void addPatchSh(const SurfaceSet& surfaces, uint32_t e, uint32_t p, float f, Rgb b, int count, Rgb* c) {
  if (f == 0.0f) return;
  const Element& el = surfaces.elements[e];
  const Patch& patch = surfaces.patches[p];
  if (addFarPatchSh(el, patch, f, b, count, c)) return;
  // v: the irradiance vector per unit exitance, the integral of w / pi over the visible polygon;
  // v . n is the unoccluded factor.
  const Vec3 v = polygonIrradianceVector(el.centroid, el.normal, patch.polygon, patch.normal);
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
  // Radiance b / pi over the solid angle: integral of L = visible * b / pi * omega, integral of
  // L w = visible * b * v.
  const float omega = std::max(polygonSolidAngle(el.centroid, patch.polygon), std::numbers::pi_v<float> * length);
  const Rgb m0 = (visible * omega / std::numbers::pi_v<float>) * b;
  const Rgb scale = visible * b;
  c[0] += kShY0 * m0;
  if (count < kShL1Coefficients) return;
  c[1] += (kShY1 * v.y) * scale;
  c[2] += (kShY1 * v.z) * scale;
  c[3] += (kShY1 * v.x) * scale;
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
    const Vec3 pv = polygonIrradianceVector(el.centroid, el.normal, piece, patch.normal);
    const float pl = glm::length(pv);
    if (!(pl > 0.0f)) return;
    const float pieceOmega = std::max(polygonSolidAngle(el.centroid, piece), std::numbers::pi_v<float> * pl);
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

}  // namespace luxel
