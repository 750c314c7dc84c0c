#include "transport/form_factor.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace luxel {
namespace {

constexpr float kInv2Pi = 0.5f / std::numbers::pi_v<float>;

// The angle atan2(sine, cosine) for sine >= 0, without libm: the hottest call of the solver (one
// per polygon edge per element-patch pair). atan on [0, 1] is Abramowitz and Stegun 4.4.49
// (|error| <= 2e-8 rad, below float resolution); larger angles fold onto it by
// atan(1/a) = pi/2 - atan(a) and atan2(y, -x) = pi - atan2(y, x).
inline float edgeAngle(float sine, float cosine) {
  const float c = std::abs(cosine);
  const bool steep = sine > c;
  const float a = steep ? c / sine : (c > 0.0f ? sine / c : 0.0f);
  const float a2 = a * a;
  float r = a * (1.0f + a2 * (-0.3333314528f + a2 * (0.1999355085f + a2 * (-0.1420889944f +
                 a2 * (0.1065626393f + a2 * (-0.0752896400f + a2 * (0.0429096138f +
                 a2 * (-0.0161657367f + a2 * 0.0028662257f))))))));
  if (steep) r = 0.5f * std::numbers::pi_v<float> - r;
  return cosine < 0.0f ? std::numbers::pi_v<float> - r : r;
}

// Lambert's contour integral over the part of `poly` above the plane through `p` with normal `n`:
// F = (1/2pi) |sum_i gamma_i n . (R_i x R_i+1) / |R_i x R_i+1||, gamma_i the angle between R_i
// and R_i+1. The formula assumes the polygon lies wholly in the upper hemisphere, so the polygon
// is clipped against the tangent plane first (Sutherland-Hodgman).
float upperHemisphereFormFactor(Vec3 p, Vec3 n, const Polygon& poly) {
  float d[4];
  bool allAbove = true, allBelow = true;
  for (int i = 0; i < poly.count; ++i) {
    d[i] = glm::dot(n, poly.v[i] - p);
    allAbove &= d[i] > 0.0f;
    allBelow &= d[i] <= 0.0f;
  }
  if (allBelow) return 0.0f;

  Vec3 r[8];
  int count = 0;
  if (allAbove) {
    for (int i = 0; i < poly.count; ++i) r[count++] = poly.v[i] - p;
  } else {
    for (int i = 0; i < poly.count; ++i) {
      int j = (i + 1) % poly.count;
      if (d[i] > 0.0f) r[count++] = poly.v[i] - p;
      if ((d[i] > 0.0f) != (d[j] > 0.0f)) {
        float t = d[i] / (d[i] - d[j]);
        r[count++] = poly.v[i] + t * (poly.v[j] - poly.v[i]) - p;
      }
    }
    if (count < 3) return 0.0f;
  }

  float sum = 0.0f;
  for (int i = 0; i < count; ++i) {
    const Vec3& a = r[i];
    const Vec3& b = r[(i + 1) % count];
    Vec3 c = glm::cross(a, b);
    float cl = glm::length(c);
    if (cl <= 0.0f) continue;  // p collinear with the edge: the edge subtends no angle
    float gamma = edgeAngle(cl, glm::dot(a, b));
    sum += gamma * glm::dot(n, c) / cl;
  }
  return std::abs(sum) * kInv2Pi;
}

}  // namespace

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

Vec3 polygonPoint(const Polygon& poly, float s, float t) {
  if (poly.count == 3) {
    if (s + t > 1.0f) s = 1.0f - s, t = 1.0f - t;
    return poly.v[0] + s * (poly.v[1] - poly.v[0]) + t * (poly.v[2] - poly.v[0]);
  }
  return (1 - s) * (1 - t) * poly.v[0] + s * (1 - t) * poly.v[1] + s * t * poly.v[2] +
         (1 - s) * t * poly.v[3];
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
