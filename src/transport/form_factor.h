// Analytic form factors: the exact differential-area-to-polygon form factor (Lambert 1760, in the
// contour-integral form of Baum, Rushmeier and Winget, "Improving Radiosity Solutions Through the
// Use of Analytically Determined Form-Factors", SIGGRAPH 1989), with the polygon clipped to the
// receiver's hemisphere so that it stays exact when the source crosses the receiver's plane.
#pragma once

#include <span>

#include "luxel/surface.h"

namespace luxel {

// Which sides of a surface take part in an exchange.
enum class Sides { Front, Both };

// Form factor from a differential area at `p` with unit normal `n` to the polygon `poly`
// (unoccluded). With Sides::Both the receiver gathers from both hemispheres (|cos|).
// `sourceSides` == Front means the polygon radiates only from its front face.
float pointToPolygonFormFactor(Vec3 p, Vec3 n, const Polygon& poly, Sides receiverSides,
                               Sides sourceSides);
// The same with the polygon's unit normal supplied, for callers that have it at hand.
float pointToPolygonFormFactor(Vec3 p, Vec3 n, const Polygon& poly, Vec3 polyNormal,
                               Sides receiverSides, Sides sourceSides);

// Four point factors at once, one per receiver point p[i] with unit normal n[i], towards the same
// one-sided polygon (unit normal polyNormal), front-facing receivers: the numbers of
// pointToPolygonFormFactor(p[i], n[i], poly, polyNormal, Front, Front) to float rounding. Four
// SIMD lanes where the polygon lies wholly above or below each receiver's plane; lanes whose
// plane cuts the polygon are clipped one by one.
void pointToPolygonFormFactors4(const Vec3 p[4], const Vec3 n[4], const Polygon& poly, Vec3 polyNormal,
                                float out[4]);

// The irradiance vector per unit exitance of the one-sided polygon (unit normal polyNormal) at
// `p`, the polygon clipped to the half-space in front of the plane through `p` with normal `n`:
// (1/2pi) sum_i gamma_i (R_i x R_i+1) / |R_i x R_i+1|, pointing from p towards the polygon. Its
// dot product with n is pointToPolygonFormFactor(p, n, poly, polyNormal, Front, Front); with another
// normal m whose half-space holds the clipped polygon, m . vector is the factor for m (Arvo,
// "The Irradiance Jacobian for Partially Occluded Polyhedral Sources", SIGGRAPH 1994).
Vec3 polygonIrradianceVector(Vec3 p, Vec3 n, const Polygon& poly, Vec3 polyNormal);

// The moments of the part of the one-sided polygon (unit normal polyNormal) in front of the plane
// through `p` with normal `n`, seen from `p`: its irradiance vector (polygonIrradianceVector) and
// its solid angle (Van Oosterom and Strackee's triangles, over the clipped polygon). Both zero for
// a polygon seen from behind or wholly behind the plane.
struct PolygonMoments {
  Vec3 vector{0.0f};
  float solidAngle = 0.0f;
};
PolygonMoments clippedPolygonMoments(Vec3 p, Vec3 n, const Polygon& poly, Vec3 polyNormal);

// polygonIrradianceVector and polygonSolidAngle at four points at once, for lanes where the
// polygon lies wholly in front of the point's plane (n[i]) and of its own (polyNormal): the
// numbers of those functions to float rounding (atan2 by a polynomial within 2e-8 rad). Returns
// a bit per lane that was computed; the others (the plane cuts the polygon, a point behind it)
// are left for the one-point functions.
int polygonMoments4(const Vec3 p[4], const Vec3 n[4], const Polygon& poly, Vec3 polyNormal, Vec3 vector[4],
                    float solidAngle[4]);

// Area-to-area form factor F(receiver -> source), the point form factor integrated over the
// receiver with a regular k x k (quads) or k^2 (triangles) midpoint rule.
double polygonToPolygonFormFactor(const Polygon& receiver, const Polygon& source, int k,
                                  Sides receiverSides = Sides::Front,
                                  Sides sourceSides = Sides::Front);

// Solid angle of a polygon seen from `p` (Van Oosterom and Strackee 1983, per fan triangle).
float polygonSolidAngle(Vec3 p, const Polygon& poly);

// The area of the part of `poly` above the plane through `p` with normal `n`.
float areaInFront(const Polygon& poly, Vec3 p, Vec3 n);

// Euclidean distance from `p` to the (filled) planar convex polygon.
float pointPolygonDistance(Vec3 p, const Polygon& poly);

// A point on the polygon from (s,t) in [0,1)^2: bilinear on quads, folded barycentric on triangles.
// Inline: every visibility ray calls it twice.
inline Vec3 polygonPoint(const Polygon& poly, float s, float t) {
  if (poly.count == 3) {
    if (s + t > 1.0f) s = 1.0f - s, t = 1.0f - t;
    return poly.v[0] + s * (poly.v[1] - poly.v[0]) + t * (poly.v[2] - poly.v[0]);
  }
  return (1 - s) * (1 - t) * poly.v[0] + s * (1 - t) * poly.v[1] + s * t * poly.v[2] +
         (1 - s) * t * poly.v[3];
}

// A point uniform by area on the polygon from three uniform numbers: a triangle of the fan
// (0, i, i + 1) chosen by area, then a uniform point of it. (polygonPoint's bilinear map is
// uniform only on parallelograms.)
inline Vec3 uniformPolygonPoint(const Polygon& poly, float pick, float a, float b) {
  const Vec3 o = poly.v[0];
  int t = 1;
  if (poly.count == 4) {
    const float first = glm::length(glm::cross(poly.v[1] - o, poly.v[2] - o));
    const float second = glm::length(glm::cross(poly.v[2] - o, poly.v[3] - o));
    t = pick * (first + second) < first ? 1 : 2;
  }
  if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
  return o + a * (poly.v[size_t(t)] - o) + b * (poly.v[size_t(t) + 1] - o);
}

// A uniformly distributed point on the part of `poly` strictly above the plane through `p` with
// normal `n`, by rejection from (s,t) pairs drawn with `next()`; false when none of `tries`
// lands there (a sliver). A shadow ray towards the part behind the plane would always count as
// blocked and darken a receiver whose plane cuts through an emitter.
template <typename Next>
bool pointInFront(const Polygon& poly, Vec3 p, Vec3 n, Next&& next, Vec3& out, int tries = 16) {
  for (int i = 0; i < tries; ++i) {
    float s = next(), t = next();
    Vec3 y = polygonPoint(poly, s, t);
    if (glm::dot(y - p, n) > 0.0f) {
      out = y;
      return true;
    }
  }
  return false;
}

}  // namespace luxel
