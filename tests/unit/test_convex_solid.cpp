// ConvexSolid (src/trace/convex_solid.h): which polygon sets bound a closed convex solid, the
// segment test against the solid inset by a depth, and the corner rule that proves every segment
// between two polygons blocked.
#include <gtest/gtest.h>

#include <vector>

#include "core/random.h"
#include "trace/convex_solid.h"
#include "transport/form_factor.h"

namespace luxel {
namespace {

Polygon quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  Polygon p;
  p.count = 4;
  p.v = {a, b, c, d};
  return p;
}

// The faces of the box [lo, hi], wound so that their normals point out of it (or into it).
std::vector<Polygon> boxFaces(Vec3 lo, Vec3 hi, bool outward = true) {
  const Vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                     {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
  std::vector<Polygon> faces = {
      quad(c[0], c[3], c[2], c[1]),  // z = lo, normal -z
      quad(c[4], c[5], c[6], c[7]),  // z = hi, +z
      quad(c[0], c[1], c[5], c[4]),  // y = lo, -y
      quad(c[3], c[7], c[6], c[2]),  // y = hi, +y
      quad(c[0], c[4], c[7], c[3]),  // x = lo, -x
      quad(c[1], c[2], c[6], c[5]),  // x = hi, +x
  };
  if (!outward)
    for (Polygon& f : faces) std::swap(f.v[1], f.v[3]);
  return faces;
}

// A square of side 2 * half in the plane y = height, centred on (x, z), facing `up` or down.
Polygon square(float x, float height, float z, float half, bool up) {
  Polygon p = quad(Vec3(x - half, height, z - half), Vec3(x - half, height, z + half), Vec3(x + half, height, z + half),
                   Vec3(x + half, height, z - half));
  if (!up) std::swap(p.v[1], p.v[3]);
  return p;
}

TEST(ConvexSolid, ABoxIsASolidAndItsNormalsPointOut) {
  const std::vector<Polygon> box = boxFaces(Vec3(-1.0f), Vec3(1.0f));
  for (const Polygon& f : box) EXPECT_GT(glm::dot(f.normal(), f.centroid()), 0.0f);
  EXPECT_TRUE(ConvexSolid::fromPolygons(box, 1e-5f).valid());
}

TEST(ConvexSolid, OpenInwardAndConcaveShapesAreNotSolids) {
  std::vector<Polygon> open = boxFaces(Vec3(-1.0f), Vec3(1.0f));
  open.pop_back();
  EXPECT_FALSE(ConvexSolid::fromPolygons(open, 1e-5f).valid()) << "a box without a side";
  EXPECT_FALSE(ConvexSolid::fromPolygons(boxFaces(Vec3(-1.0f), Vec3(1.0f), false), 1e-5f).valid()) << "a room";
  // Two boxes side by side with a gap: closed, but not convex.
  std::vector<Polygon> two = boxFaces(Vec3(-2.0f, -1.0f, -1.0f), Vec3(-1.0f, 1.0f, 1.0f));
  for (const Polygon& f : boxFaces(Vec3(1.0f, -1.0f, -1.0f), Vec3(2.0f, 1.0f, 1.0f))) two.push_back(f);
  EXPECT_FALSE(ConvexSolid::fromPolygons(two, 1e-5f).valid()) << "two boxes";
  EXPECT_FALSE(ConvexSolid::fromPolygons({}, 1e-5f).valid());
}

TEST(ConvexSolid, ASegmentMeetsTheSolidInsetByLessThanItsDepth) {
  const ConvexSolid cube = ConvexSolid::fromPolygons(boxFaces(Vec3(-1.0f), Vec3(1.0f)), 1e-5f);
  // Along x, 0.3 inside the face y = 1: 0.3 deep at most.
  const Vec3 a(-3.0f, 0.7f, 0.0f), b(3.0f, 0.7f, 0.0f);
  EXPECT_TRUE(cube.segmentMeets(a, b, 0.0f));
  EXPECT_TRUE(cube.segmentMeets(a, b, 0.29f));
  EXPECT_FALSE(cube.segmentMeets(a, b, 0.31f));
  // Stopping short of the cube, or passing beside it.
  EXPECT_FALSE(cube.segmentMeets(a, Vec3(-1.1f, 0.7f, 0.0f), 0.0f));
  EXPECT_FALSE(cube.segmentMeets(Vec3(-3.0f, 1.2f, 0.0f), Vec3(3.0f, 1.2f, 0.0f), 0.0f));
  // Parallel to a face plane, inside and outside it.
  EXPECT_TRUE(cube.segmentMeets(Vec3(0.0f, -3.0f, 0.5f), Vec3(0.0f, 3.0f, 0.5f), 0.4f));
  EXPECT_FALSE(cube.segmentMeets(Vec3(0.0f, -3.0f, 0.5f), Vec3(0.0f, 3.0f, 0.5f), 0.6f));
}

TEST(ConvexSolid, SegmentsAreClearCrossingOrUnsureWithinAMargin) {
  const ConvexSolid cube = ConvexSolid::fromPolygons(boxFaces(Vec3(-1.0f), Vec3(1.0f)), 1e-5f);
  using S = ConvexSolid::Segment;
  const float margin = 0.1f;
  EXPECT_EQ(cube.classify(Vec3(-3, 0, 0), Vec3(3, 0, 0), margin), S::Crosses);      // through the middle
  EXPECT_EQ(cube.classify(Vec3(-3, 1.2f, 0), Vec3(3, 1.2f, 0), margin), S::Clear);  // 0.2 above the top
  EXPECT_EQ(cube.classify(Vec3(-3, 1.05f, 0), Vec3(3, 1.05f, 0), margin), S::Unsure);
  EXPECT_EQ(cube.classify(Vec3(-3, 0.95f, 0), Vec3(3, 0.95f, 0), margin), S::Unsure);
  EXPECT_EQ(cube.classify(Vec3(-3, 0.85f, 0), Vec3(3, 0.85f, 0), margin), S::Crosses);
  EXPECT_EQ(cube.classify(Vec3(-3, 0, 0), Vec3(-1.05f, 0, 0), margin), S::Unsure);  // stops at a face
  EXPECT_EQ(cube.classify(Vec3(-3, 0, 0), Vec3(-1.2f, 0, 0), margin), S::Clear);
  // Wholly inside: it meets no face.
  EXPECT_EQ(cube.classify(Vec3(-0.5f, 0, 0), Vec3(0.5f, 0, 0), margin), S::Unsure);
  // From inside to far outside: it crosses a face.
  EXPECT_EQ(cube.classify(Vec3(0, 0, 0), Vec3(0, 0, 5), margin), S::Crosses);
  // Rising away from the top.
  EXPECT_EQ(cube.classify(Vec3(-3, 1.1f, 0), Vec3(0, 1.1f + 3.0f, 0), margin), S::Clear);
}

TEST(ConvexSolid, CornersDecideWhetherEverySegmentIsBlocked) {
  const ConvexSolid cube = ConvexSolid::fromPolygons(boxFaces(Vec3(-1.0f), Vec3(1.0f)), 1e-5f);
  // A floor and a ceiling square under and over the cube: the cube hides one from the other when
  // they are narrower than it, and not when they are wider.
  const Polygon floorSmall = square(0.0f, -3.0f, 0.0f, 0.5f, true), ceilingSmall = square(0.0f, 3.0f, 0.0f, 0.5f, false);
  const Polygon floorWide = square(0.0f, -3.0f, 0.0f, 1.5f, true), ceilingWide = square(0.0f, 3.0f, 0.0f, 1.5f, false);
  EXPECT_TRUE(cube.blocksEverySegment(floorSmall, ceilingSmall, 0.0f));
  EXPECT_TRUE(cube.blocksEverySegment(floorSmall, ceilingSmall, 0.4f));
  EXPECT_FALSE(cube.blocksEverySegment(floorSmall, ceilingSmall, 0.6f)) << "corner segments pass 0.5 inside";
  EXPECT_FALSE(cube.blocksEverySegment(floorWide, ceilingWide, 0.0f));
  EXPECT_FALSE(cube.blocksEverySegment(floorSmall, square(2.5f, 3.0f, 0.0f, 0.5f, false), 0.0f)) << "offset sideways";

  // The rule holds for every segment, not only the corners': random pairs of squares that the
  // corner rule calls blocked, checked with random points of both.
  Rng rng(7);
  int proved = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Polygon low = square(2.0f * rng.next() - 1.0f, -1.5f - 2.0f * rng.next(), 2.0f * rng.next() - 1.0f,
                               0.05f + 0.8f * rng.next(), true);
    const Polygon high = square(2.0f * rng.next() - 1.0f, 1.5f + 2.0f * rng.next(), 2.0f * rng.next() - 1.0f,
                                0.05f + 0.8f * rng.next(), false);
    if (!cube.blocksEverySegment(low, high, 0.05f)) continue;
    ++proved;
    for (int k = 0; k < 200; ++k) {
      const Vec3 a = polygonPoint(low, rng.next(), rng.next()), b = polygonPoint(high, rng.next(), rng.next());
      ASSERT_TRUE(cube.segmentMeets(a, b, 0.05f)) << "trial " << trial;
    }
  }
  EXPECT_GT(proved, 50);
}

TEST(ConvexSolid, APolygonBeyondAFacePlaneIsSeparated) {
  const ConvexSolid cube = ConvexSolid::fromPolygons(boxFaces(Vec3(-1.0f), Vec3(1.0f)), 1e-5f);
  EXPECT_TRUE(cube.separatedFrom(square(0.0f, -3.0f, 0.0f, 5.0f, true), 1.0f));   // 2 below, wider than the cube
  EXPECT_FALSE(cube.separatedFrom(square(0.0f, -3.0f, 0.0f, 5.0f, true), 2.5f));  // not with a 2.5 gap
  EXPECT_FALSE(cube.separatedFrom(square(0.0f, 0.0f, 0.0f, 0.5f, true), 0.0f));   // inside it
  EXPECT_FALSE(cube.separatedFrom(square(0.0f, -1.0f, 0.0f, 5.0f, true), 1e-3f)); // the floor it stands on
}

}  // namespace
}  // namespace luxel
