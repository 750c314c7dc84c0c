#include "cluster/cluster_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/convex_hull.h"

namespace luxel {

std::array<Vec3, 8> OrientedBox::corners() const {
  std::array<Vec3, 8> c;
  for (int i = 0; i < 8; ++i) {
    const float sx = (i & 1) ? 1.0f : -1.0f, sy = (i & 2) ? 1.0f : -1.0f, sz = (i & 4) ? 1.0f : -1.0f;
    c[size_t(i)] = centre + sx * half.x * axis[0] + sy * half.y * axis[1] + sz * half.z * axis[2];
  }
  return c;
}

Vec2 OrientedBox::planeParameters(Vec3 p) const {
  const Vec3 d = p - centre;
  const float u = half.x > 0.0f ? 0.5f + 0.5f * glm::dot(d, axis[0]) / half.x : 0.5f;
  const float v = half.y > 0.0f ? 0.5f + 0.5f * glm::dot(d, axis[1]) / half.y : 0.5f;
  return {u, v};
}

float OrientedBox::distance(Vec3 p) const {
  const Vec3 d = p - centre;
  Vec3 outside(0.0f);
  for (int k = 0; k < 3; ++k) outside[k] = std::max(0.0f, std::abs(glm::dot(d, axis[size_t(k)])) - half[k]);
  return glm::length(outside);
}

namespace {

// Any unit vector perpendicular to unit `n`.
Vec3 perpendicular(Vec3 n) {
  const Vec3 a = std::abs(n.x) < 0.6f ? Vec3(1, 0, 0) : (std::abs(n.y) < 0.6f ? Vec3(0, 1, 0) : Vec3(0, 0, 1));
  return glm::normalize(glm::cross(n, a));
}

}  // namespace

OrientedBox fitOrientedBox(std::span<const Vec3> points, Vec3 normal) {
  OrientedBox box;
  const Vec3 z = normal;
  const Vec3 x0 = perpendicular(z), y0 = glm::cross(z, x0);
  std::vector<glm::dvec2> flat;
  flat.reserve(points.size());
  double zmin = std::numeric_limits<double>::max(), zmax = -zmin;
  for (const Vec3& p : points) {
    flat.emplace_back(glm::dot(p, x0), glm::dot(p, y0));
    const double h = glm::dot(p, z);
    zmin = std::min(zmin, h), zmax = std::max(zmax, h);
  }
  const std::vector<glm::dvec2> hull = convexHull2d(flat);
  // The best rectangle has a side along a hull edge (Freeman and Shapira): try each (hulls here
  // have a few dozen points at most, so the quadratic scan beats calipers' bookkeeping).
  double best = std::numeric_limits<double>::max();
  glm::dvec2 bestU(1, 0), lo(0), hi(0);
  const size_t n = hull.size();
  for (size_t i = 0; i < std::max<size_t>(n, 1); ++i) {
    glm::dvec2 u(1, 0);
    if (n >= 2) {
      const glm::dvec2 e = hull[(i + 1) % n] - hull[i];
      const double len = glm::length(e);
      if (len <= 0) continue;
      u = e / len;
    }
    const glm::dvec2 v(-u.y, u.x);
    glm::dvec2 a(std::numeric_limits<double>::max()), b(-std::numeric_limits<double>::max());
    for (const glm::dvec2& p : hull.empty() ? flat : hull) {
      const glm::dvec2 q(glm::dot(p, u), glm::dot(p, v));
      a = glm::min(a, q), b = glm::max(b, q);
    }
    const double area = (b.x - a.x) * (b.y - a.y);
    if (area < best) best = area, bestU = u, lo = a, hi = b;
  }
  const glm::dvec2 bestV(-bestU.y, bestU.x);
  const Vec3 ax = glm::normalize(float(bestU.x) * x0 + float(bestU.y) * y0);
  const Vec3 ay = glm::cross(z, ax);
  box.axis = {ax, ay, z};
  const glm::dvec2 mid = 0.5 * (lo + hi);
  const double zmid = 0.5 * (zmin + zmax);
  // Centre back in 3-D: the rectangle's middle in the (u, v) frame, then the plane frame.
  const double cx = mid.x * bestU.x + mid.y * bestV.x, cy = mid.x * bestU.y + mid.y * bestV.y;
  box.centre = float(cx) * x0 + float(cy) * y0 + float(zmid) * z;
  box.half = Vec3(float(0.5 * (hi.x - lo.x)), float(0.5 * (hi.y - lo.y)), float(0.5 * (zmax - zmin)));
  // Rounding in the frame change must not leave a point outside.
  const float pad = 1e-6f * (box.half.x + box.half.y + box.half.z) + 1e-12f;
  box.half += Vec3(pad);
  return box;
}

NormalCone mergeCones(const NormalCone& a, const NormalCone& b) {
  if (a.cosHalfAngle <= -1.0f || b.cosHalfAngle <= -1.0f) return {a.axis, -1.0f};
  const double ta = std::acos(std::clamp(double(a.cosHalfAngle), -1.0, 1.0));
  const double tb = std::acos(std::clamp(double(b.cosHalfAngle), -1.0, 1.0));
  const double between = std::acos(std::clamp(double(glm::dot(a.axis, b.axis)), -1.0, 1.0));
  if (between + tb <= ta) return a;  // b inside a
  if (between + ta <= tb) return b;
  const double half = 0.5 * (ta + between + tb);
  if (half >= std::numbers::pi) return {a.axis, -1.0f};
  // The new axis lies on the great circle from a to b, (half - ta) from a.
  Vec3 axis = a.axis;
  if (between > 1e-7) {
    const double t = (half - ta) / between;
    const double s = std::sin(between);
    axis = glm::normalize(float(std::sin((1 - t) * between) / s) * a.axis + float(std::sin(t * between) / s) * b.axis);
  }
  // A hair wider than exact, so that rounding never excludes a normal.
  return {axis, float(std::cos(std::min(std::numbers::pi, half + 1e-5)))};
}

bool mayFace(const NormalCone& cone, const OrientedBox& from, const OrientedBox& to) {
  if (cone.cosHalfAngle <= 0.0f) return true;  // a half angle of 90 degrees or more faces everything
  const float sinHalf = std::sqrt(std::max(0.0f, 1.0f - cone.cosHalfAngle * cone.cosHalfAngle));
  const std::array<Vec3, 8> a = from.corners(), b = to.corners();
  for (const Vec3& p : a)
    for (const Vec3& q : b) {
      const Vec3 d = q - p;
      if (glm::dot(cone.axis, d) > -sinHalf * glm::length(d)) return true;
    }
  return false;
}

bool whollyFaces(const NormalCone& cone, const OrientedBox& from, const OrientedBox& to, float slack) {
  if (cone.cosHalfAngle <= 0.0f) return false;
  const float sinHalf = std::sqrt(std::max(0.0f, 1.0f - cone.cosHalfAngle * cone.cosHalfAngle)) - slack;
  const std::array<Vec3, 8> a = from.corners(), b = to.corners();
  for (const Vec3& p : a)
    for (const Vec3& q : b) {
      const Vec3 d = q - p;
      if (glm::dot(cone.axis, d) <= sinHalf * glm::length(d)) return false;
    }
  return true;
}

float maxProjectedArea(const OrientedBox& box, const std::array<float, 6>& axisAreas, Vec3 r) {
  float sum = 0.0f;
  for (int j = 0; j < 3; ++j) {
    const float c = glm::dot(box.axis[size_t(j)], r);
    sum += c > 0.0f ? c * axisAreas[size_t(j)] : -c * axisAreas[size_t(j) + 3];
  }
  return sum;
}

double smallestEigenvalue(const std::array<double, 6>& m) {
  const double a = m[0], b = m[1], c = m[2], d = m[3], e = m[4], f = m[5];
  const double p1 = d * d + e * e + f * f;
  if (p1 <= 1e-30 * (a * a + b * b + c * c) || p1 == 0.0) return std::min({a, b, c});
  const double q = (a + b + c) / 3.0;
  const double p2 = (a - q) * (a - q) + (b - q) * (b - q) + (c - q) * (c - q) + 2.0 * p1;
  const double p = std::sqrt(p2 / 6.0);
  // B = (A - qI) / p; r = det(B) / 2.
  const double ba = (a - q) / p, bb = (b - q) / p, bc = (c - q) / p, bd = d / p, be = e / p, bf = f / p;
  const double det = ba * (bb * bc - bf * bf) - bd * (bd * bc - bf * be) + be * (bd * bf - bb * be);
  const double r = std::clamp(det / 2.0, -1.0, 1.0);
  const double phi = std::acos(r) / 3.0;
  // Eigenvalues q + 2p cos(phi + 2k pi / 3); the smallest is k = 1.
  return q + 2.0 * p * std::cos(phi + 2.0 * std::numbers::pi / 3.0);
}

}  // namespace luxel
