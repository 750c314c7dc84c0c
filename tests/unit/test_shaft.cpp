// Shaft culling (src/transport/shaft.cpp): the hull of two patches proves a pair clear only when
// nothing reaches into it, and says so for walls that merely touch it.
#include <gtest/gtest.h>

#include "transport/shaft.h"

namespace {

using luxel::Polygon;
using luxel::Shaft;
using luxel::Vec3;

// A unit square at height y, facing down (ccw seen from below) or up.
Polygon square(float y, bool down, float x0 = 0.0f, float size = 1.0f) {
  Polygon p;
  p.count = 4;
  const float x1 = x0 + size;
  if (down)
    p.v = {Vec3(x0, y, 0), Vec3(x0, y, size), Vec3(x1, y, size), Vec3(x1, y, 0)};
  else
    p.v = {Vec3(x0, y, 0), Vec3(x1, y, 0), Vec3(x1, y, size), Vec3(x0, y, size)};
  return p;
}

Polygon quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d) { return Polygon{{a, b, c, d}, 4}; }

TEST(Shaft, BlockerBetweenFacingSquaresIntersects) {
  const Shaft shaft(square(0.0f, false), square(1.0f, true), 1e-5f);
  ASSERT_TRUE(shaft.valid());
  EXPECT_TRUE(shaft.mayIntersect(square(0.5f, false, 0.4f, 0.2f)));   // small plate in the middle
  EXPECT_TRUE(shaft.mayIntersect(square(0.5f, false, -0.5f, 0.6f)));  // pokes in from the side
  EXPECT_FALSE(shaft.mayIntersect(square(0.5f, false, 1.2f, 0.5f)));  // beside the shaft
  EXPECT_FALSE(shaft.mayIntersect(square(1.5f, false)));              // above the top square
}

TEST(Shaft, WallsTouchingTheShaftDoNotCount) {
  // Floor and ceiling of a unit room: the four walls lie in the hull's side planes.
  const Shaft shaft(square(0.0f, false), square(1.0f, true), 1e-5f);
  EXPECT_FALSE(shaft.mayIntersect(quad(Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(0, 1, 1), Vec3(0, 0, 1))));
  EXPECT_FALSE(shaft.mayIntersect(quad(Vec3(1, 0, 0), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(1, 1, 0))));
  EXPECT_FALSE(shaft.mayIntersect(quad(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0))));
  // A wall just inside the room's side does count.
  EXPECT_TRUE(shaft.mayIntersect(quad(Vec3(0.01f, 0.2f, 0), Vec3(0.01f, 0.8f, 0), Vec3(0.01f, 0.8f, 1),
                                      Vec3(0.01f, 0.2f, 1))));
}

TEST(Shaft, SlantedPairUsesEdgeToCornerPlanes) {
  // Floor square and a wall square meeting at an edge: the hull is a wedge; a plate across the
  // diagonal intersects, one behind the hypotenuse does not.
  const Polygon floor = square(0.0f, false);
  const Polygon wall = quad(Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 1), Vec3(0, 1, 0));
  const Shaft shaft(floor, wall, 1e-5f);
  ASSERT_TRUE(shaft.valid());
  EXPECT_TRUE(shaft.mayIntersect(square(0.2f, false, 0.1f, 0.2f)));
  EXPECT_FALSE(shaft.mayIntersect(quad(Vec3(0.9f, 0.9f, 0), Vec3(1.5f, 0.9f, 0), Vec3(1.5f, 0.9f, 1),
                                       Vec3(0.9f, 0.9f, 1))));
}

TEST(Shaft, CoplanarPatchesProveNothing) {
  const Shaft shaft(square(0.0f, false), square(0.0f, false, 2.0f), 1e-5f);
  EXPECT_FALSE(shaft.valid());
  EXPECT_TRUE(shaft.mayIntersect(square(5.0f, false)));
}

}  // namespace
