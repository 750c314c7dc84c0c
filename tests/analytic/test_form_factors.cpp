// Form factors against closed forms (Howell, "A Catalog of Radiation Heat Transfer Configuration
// Factors", 3rd ed.: cases B-11 parallel discs... C-11 parallel rectangles, C-14 perpendicular rectangles).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "transport/form_factor.h"

namespace luxel {
namespace {

constexpr double kPi = std::numbers::pi;

Polygon quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d) { return Polygon{{a, b, c, d}, 4}; }

// Closed form for directly opposed parallel rectangles a x b at distance c (Howell C-11).
double parallelRectangles(double a, double b, double c) {
  double x = a / c, y = b / c;
  double x1 = std::sqrt(1 + x * x), y1 = std::sqrt(1 + y * y);
  return 2.0 / (kPi * x * y) *
         (std::log(std::sqrt((1 + x * x) * (1 + y * y) / (1 + x * x + y * y))) +
          x * y1 * std::atan(x / y1) + y * x1 * std::atan(y / x1) - x * std::atan(x) - y * std::atan(y));
}

TEST(FormFactor, ParallelOpposedUnitSquaresAtDistanceOne) {
  // Receiver z = 0 facing +z; source z = 1 facing -z.
  Polygon receiver = quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  Polygon source = quad({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1});
  double f = polygonToPolygonFormFactor(receiver, source, 48);
  EXPECT_NEAR(parallelRectangles(1, 1, 1), 0.19982, 5e-5);  // the closed form itself
  EXPECT_NEAR(f, 0.1998, 1e-4);
}

TEST(FormFactor, PerpendicularUnitSquaresSharingAnEdge) {
  // Floor [0,1]^2 at y = 0 facing +y; wall at z = 0 facing +z, sharing the edge along x.
  Polygon floor = quad({0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0});
  Polygon wall = quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  double f = polygonToPolygonFormFactor(floor, wall, 256);
  EXPECT_NEAR(f, 0.2000, 2e-4);  // exact: 0.20004 (Howell C-14 with unit sides)
}

TEST(FormFactor, PointToCoaxialDisc) {
  // A differential area facing a coaxial parallel disc of radius R at height h: R^2 / (R^2 + h^2).
  // The disc is a 256-gon, whose form factor is the inscribed polygon's; compare with tolerance.
  for (double h : {0.1, 0.5, 1.0, 3.0}) {
    const double r = 1.0;
    double f = 0.0;
    const int n = 256;
    for (int i = 0; i < n; ++i) {
      double a0 = 2 * kPi * i / n, a1 = 2 * kPi * (i + 1) / n;
      // Fan triangles (centre, rim i+1, rim i) face -z, towards the receiver at the origin.
      Polygon tri{{Vec3(0, 0, h), Vec3(r * std::cos(a1), r * std::sin(a1), h),
                   Vec3(r * std::cos(a0), r * std::sin(a0), h), Vec3(r * std::cos(a0), r * std::sin(a0), h)},
                  3};
      f += pointToPolygonFormFactor(Vec3(0), Vec3(0, 0, 1), tri, Sides::Front, Sides::Front);
    }
    double polygonArea = 0.5 * n * std::sin(2 * kPi / n);  // inscribed polygon / pi r^2
    double expected = r * r / (r * r + h * h);
    EXPECT_NEAR(f, expected, expected * (1.0 - polygonArea / kPi) + 1e-5) << "h = " << h;
  }
}

TEST(FormFactor, CoaxialDiscsAreaToArea) {
  // Parallel coaxial discs of radii r1, r2 at distance h (Howell B-13):
  // F12 = (X - sqrt(X^2 - 4 (R2/R1)^2)) / 2, X = 1 + (1 + R2^2) / R1^2, Ri = ri / h.
  const double r1 = 1.0, r2 = 1.0, h = 1.0;
  double R1 = r1 / h, R2 = r2 / h, X = 1 + (1 + R2 * R2) / (R1 * R1);
  double expected = 0.5 * (X - std::sqrt(X * X - 4 * (R2 / R1) * (R2 / R1)));
  // Receiver disc as 128 fan triangles at z = 0 facing +z; source disc at z = h facing -z.
  const int n = 128;
  double weighted = 0.0, area = 0.0;
  for (int i = 0; i < n; ++i) {
    double a0 = 2 * kPi * i / n, a1 = 2 * kPi * (i + 1) / n;
    Polygon recv{{Vec3(0), Vec3(r1 * std::cos(a0), r1 * std::sin(a0), 0), Vec3(r1 * std::cos(a1), r1 * std::sin(a1), 0),
                  Vec3(r1 * std::cos(a1), r1 * std::sin(a1), 0)}, 3};
    double fi = 0.0;
    for (int j = 0; j < n; ++j) {
      double b0 = 2 * kPi * j / n, b1 = 2 * kPi * (j + 1) / n;
      Polygon src{{Vec3(0, 0, h), Vec3(r2 * std::cos(b1), r2 * std::sin(b1), h),
                   Vec3(r2 * std::cos(b0), r2 * std::sin(b0), h), Vec3(r2 * std::cos(b0), r2 * std::sin(b0), h)}, 3};
      fi += polygonToPolygonFormFactor(recv, src, 8);
    }
    weighted += recv.area() * fi;
    area += recv.area();
  }
  EXPECT_NEAR(weighted / area, expected, 2e-3 * expected);
}

TEST(FormFactor, UnitCubeRowSumsToOne) {
  // The five faces of a unit cube seen from the sixth sum to 1.
  Polygon bottom = quad({0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0});  // faces +y
  Polygon others[5] = {
      quad({0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}),  // top, faces -y
      quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}),  // z = 0, faces +z
      quad({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}),  // z = 1, faces -z
      quad({0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}),  // x = 0, faces +x
      quad({1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}),  // x = 1, faces -x
  };
  double sum = 0.0;
  for (const Polygon& p : others) sum += polygonToPolygonFormFactor(bottom, p, 64);
  EXPECT_NEAR(sum, 1.0, 0.005);
  EXPECT_NEAR(sum, 1.0, 1e-4);  // the point factors are exact; only float rounding remains
}

TEST(FormFactor, Reciprocity) {
  // A_i F_ij = A_j F_ji for two unequal, skewed rectangles.
  Polygon a = quad({0, 0, 0}, {2, 0, 0}, {2, 0, 1}, {0, 0, 1});                     // faces -y
  Polygon b = quad({0.5f, -1, -0.3f}, {0.5f, -2, 0.8f}, {1.2f, -2, 0.8f}, {1.2f, -1, -0.3f});
  // orient b towards a if needed
  if (glm::dot(b.normal(), a.centroid() - b.centroid()) < 0) std::swap(b.v[1], b.v[3]);
  if (glm::dot(a.normal(), b.centroid() - a.centroid()) < 0) std::swap(a.v[1], a.v[3]);
  double fab = polygonToPolygonFormFactor(a, b, 96), fba = polygonToPolygonFormFactor(b, a, 96);
  ASSERT_GT(fab, 0.01);
  EXPECT_NEAR(a.area() * fab, b.area() * fba, 1e-3 * a.area() * fab);
}

TEST(FormFactor, SourceCrossingTheReceiverPlaneIsClipped) {
  // A wall standing on the receiver's plane, half of it below: only the upper half counts.
  Polygon upper = quad({-1, 0, 1}, {1, 0, 1}, {1, 1, 1}, {-1, 1, 1});
  Polygon both = quad({-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1});
  // Receiver at the origin with normal +y; the wall is at z = 1 facing -z (orientation irrelevant for two-sided).
  float fu = pointToPolygonFormFactor(Vec3(0), Vec3(0, 1, 0), upper, Sides::Front, Sides::Both);
  float fb = pointToPolygonFormFactor(Vec3(0), Vec3(0, 1, 0), both, Sides::Front, Sides::Both);
  EXPECT_GT(fu, 0.01f);
  EXPECT_NEAR(fb, fu, 1e-6f);
  // Gathering from both hemispheres sees the lower half too, by symmetry equally much.
  float f2 = pointToPolygonFormFactor(Vec3(0), Vec3(0, 1, 0), both, Sides::Both, Sides::Both);
  EXPECT_NEAR(f2, 2 * fu, 1e-6f);
}

TEST(FormFactor, OneSidedSourceSeenFromBehindGivesNothing) {
  Polygon facingAway = quad({0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1});  // normal +z, receiver at z=0
  EXPECT_EQ(pointToPolygonFormFactor(Vec3(0.5f, 0.5f, 0), Vec3(0, 0, 1), facingAway, Sides::Front, Sides::Front), 0.0f);
  EXPECT_GT(pointToPolygonFormFactor(Vec3(0.5f, 0.5f, 0), Vec3(0, 0, 1), facingAway, Sides::Front, Sides::Both), 0.1f);
}

TEST(FormFactor, SolidAngleOfCubeFaceFromCentreIsFourPiOverSix) {
  Polygon face = quad({-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1});
  EXPECT_NEAR(polygonSolidAngle(Vec3(0), face), 4 * kPi / 6, 1e-5);
}

// The four-lane moments agree with the one-point functions lane by lane, on random points seeing
// random quads and triangles; lanes the plane cuts, or behind the source, are left undone.
TEST(FormFactor, FourLaneMomentsMatchTheOnePointFunctions) {
  uint32_t state = 7u;
  auto uniform = [&] { return float((state = state * 1664525u + 1013904223u) >> 8) / float(1u << 24); };
  auto point = [&] { return Vec3(uniform(), uniform(), uniform()) * 2.0f - 1.0f; };
  int computed = 0, left = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const Vec3 a = point(), b = point(), c = point();
    // A planar convex quad: a parallelogram on a, b, c; or their triangle.
    const Polygon poly = trial % 2 ? Polygon{{a, b, c, c}, 3} : Polygon{{a, b, b + c - a, c}, 4};
    const Vec3 polyNormal = poly.normal();
    Vec3 p[4], n[4], v[4];
    float omega[4];
    for (int i = 0; i < 4; ++i) p[i] = point() * 2.0f, n[i] = glm::normalize(point());
    const int done = polygonMoments4(p, n, poly, polyNormal, v, omega);
    for (int i = 0; i < 4; ++i) {
      bool above = glm::dot(polyNormal, p[i] - poly.v[0]) > 0.0f;
      for (int k = 0; k < poly.count; ++k) above &= glm::dot(n[i], poly.v[k] - p[i]) >= 0.0f;
      ASSERT_EQ(bool(done >> i & 1), above) << "trial " << trial << " lane " << i;
      if (!above) {
        ++left;
        continue;
      }
      ++computed;
      const Vec3 exact = polygonIrradianceVector(p[i], n[i], poly, polyNormal);
      const float exactOmega = polygonSolidAngle(p[i], poly);
      EXPECT_LT(glm::length(v[i] - exact), 1e-5f * std::max(1.0f, glm::length(exact))) << trial;
      EXPECT_NEAR(omega[i], exactOmega, 1e-5f * std::max(1.0f, exactOmega)) << trial;
    }
  }
  EXPECT_GT(computed, 200);
  EXPECT_GT(left, 200);
}

}  // namespace
}  // namespace luxel
