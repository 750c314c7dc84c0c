#include "transport/form_factor.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#if defined(__SSE__)
#include <immintrin.h>
#endif

namespace luxel {
namespace {

constexpr float kInv2Pi = 0.5f / std::numbers::pi_v<float>;

// One edge's term of the contour integral, gamma * (n . c) / |c| with c = a x b and gamma the
// angle between a and b. This is the hottest code of the solver (per polygon edge, per
// element-patch pair). Far sources subtend small angles; there gamma = atan(t), t = |c| / (a.b),
// and gamma / |c| = (atan(t) / t) / (a.b), where atan(t) / t is a short even series in t^2: no
// square root, one division. The series is exact to float precision for t < 0.25
// (the next term is below 1e-7).
inline float edgeTerm(Vec3 a, Vec3 b, Vec3 n) {
  const Vec3 c = glm::cross(a, b);
  const float cl2 = glm::dot(c, c);
  if (cl2 <= 0.0f) return 0.0f;  // p collinear with the edge: the edge subtends no angle
  const float cosine = glm::dot(a, b);
  const float nc = glm::dot(n, c);
  if (cosine > 0.0f && cl2 < 0.0625f * cosine * cosine) {
    const float inv = 1.0f / cosine, t2 = cl2 * inv * inv;
    const float atanOverT = 1.0f + t2 * (-1.0f / 3.0f + t2 * (1.0f / 5.0f + t2 * (-1.0f / 7.0f + t2 * (1.0f / 9.0f))));
    return atanOverT * nc * inv;
  }
  const float cl = std::sqrt(cl2);
  return std::atan2(cl, cosine) * nc / cl;
}

// Lambert's contour integral over the part of `poly` above the plane through `p` with normal `n`:
// F = (1/2pi) |sum_i gamma_i n . (R_i x R_i+1) / |R_i x R_i+1||, gamma_i the angle between R_i
// and R_i+1. The formula assumes the polygon lies wholly in the upper hemisphere, so the polygon
// is clipped against the tangent plane first (Sutherland-Hodgman).
// The corners of the part of `poly` above the plane through `p` with normal `n`, relative to
// `p` (Sutherland-Hodgman); fewer than 3 when nothing of it is above.
int clipAbove(Vec3 p, Vec3 n, const Polygon& poly, Vec3 r[8]) {
  float d[4];
  bool allAbove = true, allBelow = true;
  for (int i = 0; i < poly.count; ++i) {
    d[i] = glm::dot(n, poly.v[i] - p);
    allAbove &= d[i] >= 0.0f;  // corners in the plane bound the visible part exactly
    allBelow &= d[i] <= 0.0f;
  }
  if (allBelow) return 0;
  int count = 0;
  if (allAbove) {
    for (int i = 0; i < poly.count; ++i) r[count++] = poly.v[i] - p;
    return count;
  }
  for (int i = 0; i < poly.count; ++i) {
    int j = i + 1 == poly.count ? 0 : i + 1;
    if (d[i] > 0.0f) r[count++] = poly.v[i] - p;
    if ((d[i] > 0.0f) != (d[j] > 0.0f)) {
      float t = d[i] / (d[i] - d[j]);
      r[count++] = poly.v[i] + t * (poly.v[j] - poly.v[i]) - p;
    }
  }
  return count;
}

float upperHemisphereFormFactor(Vec3 p, Vec3 n, const Polygon& poly) {
  Vec3 r[8];
  const int count = clipAbove(p, n, poly, r);
  if (count < 3) return 0.0f;
  float sum = 0.0f;
  for (int i = 0; i < count; ++i) sum += edgeTerm(r[i], r[i + 1 == count ? 0 : i + 1], n);
  return std::abs(sum) * kInv2Pi;
}

// Four lanes of float: GCC and Clang vector extensions, SSE on x86-64 and NEON on arm64, plain
// code elsewhere.
using Float4 = float __attribute__((vector_size(16)));
using Mask4 = int __attribute__((vector_size(16)));

inline Float4 splat(float x) { return Float4{x, x, x, x}; }

inline Float4 sqrt4(Float4 x) {
#if defined(__SSE__)
  return _mm_sqrt_ps(x);
#else
  Float4 r;
  for (int i = 0; i < 4; ++i) r[i] = std::sqrt(x[i]);
  return r;
#endif
}

// atan2(y, x) for y >= 0, lane by lane: Abramowitz and Stegun 4.4.49 on [0, 1] (|error| <= 2e-8
// rad before float rounding), folded by atan(1/a) = pi/2 - atan(a) and atan2(y, -x) = pi - ....
inline Float4 atan2Upper(Float4 y, Float4 x) {
  constexpr float kPi = std::numbers::pi_v<float>;
  const Float4 ax = x < 0.0f ? -x : x;
  const Mask4 steep = y > ax;
  const Float4 num = steep ? ax : y, den = steep ? y : ax;
  const Float4 a = den > 0.0f ? num / (den > 0.0f ? den : splat(1.0f)) : splat(0.0f);
  const Float4 a2 = a * a;
  Float4 g = a * (1.0f + a2 * (-0.3333314528f + a2 * (0.1999355085f + a2 * (-0.1420889944f +
                 a2 * (0.1065626393f + a2 * (-0.0752896400f + a2 * (0.0429096138f +
                 a2 * (-0.0161657367f + a2 * 0.0028662257f))))))));
  g = steep ? splat(0.5f * kPi) - g : g;
  return x < 0.0f ? splat(kPi) - g : g;
}

}  // namespace

void pointToPolygonFormFactors4(const Vec3 p[4], const Vec3 n[4], const Polygon& poly, Vec3 polyNormal,
                                float out[4]) {
  const Float4 px{p[0].x, p[1].x, p[2].x, p[3].x}, py{p[0].y, p[1].y, p[2].y, p[3].y},
      pz{p[0].z, p[1].z, p[2].z, p[3].z};
  const Float4 nx{n[0].x, n[1].x, n[2].x, n[3].x}, ny{n[0].y, n[1].y, n[2].y, n[3].y},
      nz{n[0].z, n[1].z, n[2].z, n[3].z};
  // Corner vectors R_k = v_k - p, and which side of each receiver's plane they lie on.
  Float4 rx[4], ry[4], rz[4];
  Mask4 above = Mask4{-1, -1, -1, -1}, below = Mask4{-1, -1, -1, -1};
  for (int k = 0; k < poly.count; ++k) {
    rx[k] = poly.v[k].x - px, ry[k] = poly.v[k].y - py, rz[k] = poly.v[k].z - pz;
    const Float4 d = nx * rx[k] + ny * ry[k] + nz * rz[k];
    above &= d >= 0.0f;
    below &= d <= 0.0f;
  }
  // A one-sided source radiates only into the half-space its normal points into.
  const Mask4 facing = (polyNormal.x * rx[0] + polyNormal.y * ry[0] + polyNormal.z * rz[0]) < 0.0f;

  Float4 sum = splat(0.0f);
  for (int k = 0; k < poly.count; ++k) {
    const int j = k + 1 == poly.count ? 0 : k + 1;
    const Float4 cx = ry[k] * rz[j] - rz[k] * ry[j], cy = rz[k] * rx[j] - rx[k] * rz[j],
                 cz = rx[k] * ry[j] - ry[k] * rx[j];
    const Float4 cl = sqrt4(cx * cx + cy * cy + cz * cz);
    const Float4 cosine = rx[k] * rx[j] + ry[k] * ry[j] + rz[k] * rz[j];
    const Float4 nc = nx * cx + ny * cy + nz * cz;
    const Mask4 edge = cl > 0.0f;  // p collinear with the edge: it subtends no angle
    sum += edge ? atan2Upper(cl, cosine) * nc / (edge ? cl : splat(1.0f)) : splat(0.0f);
  }
  for (int i = 0; i < 4; ++i) {
    if (!facing[i] || below[i]) out[i] = 0.0f;
    else if (above[i]) out[i] = std::abs(sum[i]) * kInv2Pi;
    else out[i] = upperHemisphereFormFactor(p[i], n[i], poly);  // the plane cuts the polygon
  }
}

int polygonMoments4(const Vec3 p[4], const Vec3 n[4], const Polygon& poly, Vec3 polyNormal, Vec3 vector[4],
                    float solidAngle[4]) {
  const Float4 px{p[0].x, p[1].x, p[2].x, p[3].x}, py{p[0].y, p[1].y, p[2].y, p[3].y},
      pz{p[0].z, p[1].z, p[2].z, p[3].z};
  const Float4 nx{n[0].x, n[1].x, n[2].x, n[3].x}, ny{n[0].y, n[1].y, n[2].y, n[3].y},
      nz{n[0].z, n[1].z, n[2].z, n[3].z};
  Float4 rx[4], ry[4], rz[4], length[4];
  Mask4 above = Mask4{-1, -1, -1, -1};
  for (int k = 0; k < poly.count; ++k) {
    rx[k] = poly.v[k].x - px, ry[k] = poly.v[k].y - py, rz[k] = poly.v[k].z - pz;
    above &= nx * rx[k] + ny * ry[k] + nz * rz[k] >= 0.0f;
    length[k] = sqrt4(rx[k] * rx[k] + ry[k] * ry[k] + rz[k] * rz[k]);
  }
  const Mask4 facing = (polyNormal.x * rx[0] + polyNormal.y * ry[0] + polyNormal.z * rz[0]) < 0.0f;
  // Arvo's contour sum, as polygonIrradianceVector.
  Float4 vx = splat(0.0f), vy = splat(0.0f), vz = splat(0.0f);
  for (int k = 0; k < poly.count; ++k) {
    const int j = k + 1 == poly.count ? 0 : k + 1;
    const Float4 cx = ry[k] * rz[j] - rz[k] * ry[j], cy = rz[k] * rx[j] - rx[k] * rz[j],
                 cz = rx[k] * ry[j] - ry[k] * rx[j];
    const Float4 cl = sqrt4(cx * cx + cy * cy + cz * cz);
    const Mask4 edge = cl > 0.0f;
    const Float4 w = edge ? atan2Upper(cl, rx[k] * rx[j] + ry[k] * ry[j] + rz[k] * rz[j]) / (edge ? cl : splat(1.0f))
                          : splat(0.0f);
    vx += w * cx, vy += w * cy, vz += w * cz;
  }
  // Van Oosterom and Strackee's triangles of a fan, as polygonSolidAngle; a convex polygon's
  // triangles turn one way, so each contributes 2 atan2(|num|, den).
  Float4 omega = splat(0.0f);
  for (int k = 1; k + 1 < poly.count; ++k) {
    const Float4 num = rx[0] * (ry[k] * rz[k + 1] - rz[k] * ry[k + 1]) + ry[0] * (rz[k] * rx[k + 1] - rx[k] * rz[k + 1]) +
                       rz[0] * (rx[k] * ry[k + 1] - ry[k] * rx[k + 1]);
    const Float4 den = length[0] * length[k] * length[k + 1] +
                       (rx[0] * rx[k] + ry[0] * ry[k] + rz[0] * rz[k]) * length[k + 1] +
                       (rx[0] * rx[k + 1] + ry[0] * ry[k + 1] + rz[0] * rz[k + 1]) * length[k] +
                       (rx[k] * rx[k + 1] + ry[k] * ry[k + 1] + rz[k] * rz[k + 1]) * length[0];
    omega += 2.0f * atan2Upper(num < 0.0f ? -num : num, den);
  }
  int done = 0;
  for (int i = 0; i < 4; ++i) {
    if (!facing[i] || !above[i]) continue;
    const Vec3 v(vx[i], vy[i], vz[i]);
    vector[i] = (glm::dot(v, n[i]) < 0.0f ? -v : v) * kInv2Pi;
    solidAngle[i] = omega[i];
    done |= 1 << i;
  }
  return done;
}

float pointToPolygonFormFactor(Vec3 p, Vec3 n, const Polygon& poly, Sides receiverSides,
                               Sides sourceSides) {
  return pointToPolygonFormFactor(p, n, poly, poly.normal(), receiverSides, sourceSides);
}

float pointToPolygonFormFactor(Vec3 p, Vec3 n, const Polygon& poly, Vec3 polyNormal,
                               Sides receiverSides, Sides sourceSides) {
  if (sourceSides == Sides::Front) {
    // A one-sided source radiates only into the half-space its normal points into.
    if (glm::dot(polyNormal, p - poly.v[0]) <= 0.0f) return 0.0f;
  }
  float f = upperHemisphereFormFactor(p, n, poly);
  if (receiverSides == Sides::Both) f += upperHemisphereFormFactor(p, -n, poly);
  return f;
}

double polygonToPolygonFormFactor(const Polygon& receiver, const Polygon& source, int k,
                                  Sides receiverSides, Sides sourceSides) {
  const Vec3 n = receiver.normal();
  double weighted = 0.0, total = 0.0;
  auto accumulate = [&](const Polygon& cell) {
    double w = cell.area();
    weighted += w * pointToPolygonFormFactor(cell.centroid(), n, source, receiverSides, sourceSides);
    total += w;
  };
  if (receiver.count == 3) {
    auto at = [&](int i, int j) {
      return receiver.v[0] + (float(i) / k) * (receiver.v[1] - receiver.v[0]) +
             (float(j) / k) * (receiver.v[2] - receiver.v[0]);
    };
    for (int j = 0; j < k; ++j)
      for (int i = 0; i + j < k; ++i) {
        accumulate(Polygon{{at(i, j), at(i + 1, j), at(i, j + 1), at(i, j + 1)}, 3});
        if (i + j + 1 < k) accumulate(Polygon{{at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), at(i, j + 1)}, 3});
      }
  } else {
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i) {
        float s0 = float(i) / k, s1 = float(i + 1) / k, t0 = float(j) / k, t1 = float(j + 1) / k;
        accumulate(Polygon{{polygonPoint(receiver, s0, t0), polygonPoint(receiver, s1, t0),
                            polygonPoint(receiver, s1, t1), polygonPoint(receiver, s0, t1)},
                           4});
      }
  }
  return total > 0.0 ? weighted / total : 0.0;
}

Vec3 polygonIrradianceVector(Vec3 p, Vec3 n, const Polygon& poly, Vec3 polyNormal) {
  if (glm::dot(polyNormal, p - poly.v[0]) <= 0.0f) return Vec3(0.0f);  // behind a one-sided source
  Vec3 r[8];
  const int count = clipAbove(p, n, poly, r);
  if (count < 3) return Vec3(0.0f);
  Vec3 sum(0.0f);
  for (int i = 0; i < count; ++i) {
    const Vec3 a = r[i], b = r[i + 1 == count ? 0 : i + 1];
    const Vec3 c = glm::cross(a, b);
    const float cl = glm::length(c);
    if (cl <= 0.0f) continue;
    sum += (std::atan2(cl, glm::dot(a, b)) / cl) * c;
  }
  // The contour's winding decides the sign: the vector points from p towards the polygon.
  if (glm::dot(sum, n) < 0.0f) sum = -sum;
  return sum * kInv2Pi;
}

PolygonMoments clippedPolygonMoments(Vec3 p, Vec3 n, const Polygon& poly, Vec3 polyNormal) {
  PolygonMoments m;
  m.vector = polygonIrradianceVector(p, n, poly, polyNormal);
  if (m.vector == Vec3(0.0f)) return m;
  Vec3 r[8];
  const int count = clipAbove(p, n, poly, r);
  // Van Oosterom and Strackee over the clipped polygon's fan, as polygonSolidAngle.
  double omega = 0.0;
  for (int i = 1; i + 1 < count; ++i) {
    const glm::dvec3 a(r[0]), b(r[i]), c(r[i + 1]);
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    const double num = glm::dot(a, glm::cross(b, c));
    const double den = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
    omega += 2.0 * std::atan2(num, den);
  }
  m.solidAngle = float(std::abs(omega));
  return m;
}

float pointPolygonDistance(Vec3 p, const Polygon& poly) {
  const Vec3 n = poly.normal();
  const float height = glm::dot(p - poly.v[0], n);
  const Vec3 q = p - height * n;  // p projected onto the polygon's plane
  bool inside = true;
  float edgeDistance = std::numeric_limits<float>::max();
  for (int i = 0; i < poly.count; ++i) {
    const Vec3& a = poly.v[i];
    const Vec3& b = poly.v[(i + 1) % poly.count];
    inside &= glm::dot(glm::cross(b - a, q - a), n) >= 0.0f;
    Vec3 ab = b - a;
    float t = std::clamp(glm::dot(p - a, ab) / std::max(glm::dot(ab, ab), 1e-30f), 0.0f, 1.0f);
    edgeDistance = std::min(edgeDistance, glm::length(p - (a + t * ab)));
  }
  return inside ? std::abs(height) : edgeDistance;
}

float areaInFront(const Polygon& poly, Vec3 p, Vec3 n) {
  Vec3 r[8];
  const int count = clipAbove(p, n, poly, r);
  Vec3 twice(0.0f);  // the fan's summed cross products: twice the vector area
  for (int i = 1; i + 1 < count; ++i) twice += glm::cross(r[i] - r[0], r[i + 1] - r[0]);
  return 0.5f * glm::length(twice);
}

float polygonSolidAngle(Vec3 p, const Polygon& poly) {
  // Van Oosterom and Strackee, "The Solid Angle of a Plane Triangle", IEEE TBME 30(2), 1983.
  double omega = 0.0;
  for (int i = 1; i + 1 < poly.count; ++i) {
    glm::dvec3 a = glm::dvec3(poly.v[0] - p), b = glm::dvec3(poly.v[i] - p),
               c = glm::dvec3(poly.v[i + 1] - p);
    double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    double num = glm::dot(a, glm::cross(b, c));
    double den = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
    omega += 2.0 * std::atan2(num, den);
  }
  return float(std::abs(omega));
}

}  // namespace luxel
