// SeparatingPlanes (src/dynamic/separating_planes.h): the planes between a light polygon and a box
// bound the box's shadow. A receiver they call clear must see the whole light past the box, which
// is checked here segment by segment; receivers in the shadow must not be called clear; and the
// bound must be tight enough to call most of a floor clear.
#include <gtest/gtest.h>

#include <array>

#include "core/random.h"
#include "dynamic/separating_planes.h"
#include "transport/form_factor.h"

namespace luxel {
namespace {

Polygon square(float x, float height, float z, float half, bool up) {
  Polygon p;
  p.count = 4;
  p.v = {Vec3(x - half, height, z - half), Vec3(x - half, height, z + half), Vec3(x + half, height, z + half),
         Vec3(x + half, height, z - half)};
  if (!up) std::swap(p.v[1], p.v[3]);
  return p;
}

std::array<Vec3, 8> boxCorners(Vec3 lo, Vec3 hi) {
  std::array<Vec3, 8> c;
  for (int i = 0; i < 8; ++i) c[size_t(i)] = Vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
  return c;
}

// Whether the segment [a, b] meets the box [lo, hi] (slab test).
bool segmentMeetsBox(Vec3 a, Vec3 b, Vec3 lo, Vec3 hi) {
  float t0 = 0.0f, t1 = 1.0f;
  for (int i = 0; i < 3; ++i) {
    const float d = b[i] - a[i];
    if (d == 0.0f) {
      if (a[i] < lo[i] || a[i] > hi[i]) return false;
      continue;
    }
    float ta = (lo[i] - a[i]) / d, tb = (hi[i] - a[i]) / d;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta), t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

TEST(SeparatingPlanes, ReceiversCalledClearSeeTheWholeLightPastTheBox) {
  // A 0.4 m light facing down at y = 3 over a 1 x 1 x 1 box standing on a floor at y = 0; floor
  // tiles of 0.1 m from -3 to 3 m.
  const Polygon light = square(0.2f, 3.0f, -0.1f, 0.2f, false);
  const Vec3 lo(-0.5f, 0.0f, -0.5f), hi(0.5f, 1.0f, 0.5f);
  const SeparatingPlanes planes(light, Vec3(0.0f, -1e-4f, 0.0f), boxCorners(lo, hi), 1e-6f);
  EXPECT_GT(planes.size(), 0u);
  Rng rng(3);
  int clear = 0, shadowed = 0, tiles = 0;
  for (float x = -3.0f; x < 3.0f; x += 0.1f)
    for (float z = -3.0f; z < 3.0f; z += 0.1f) {
      const Polygon tile = square(x + 0.05f, 0.0f, z + 0.05f, 0.05f, true);
      ++tiles;
      // Whether some segment from the tile to the light meets the box, by 64 random segments and
      // the 16 corner pairs.
      bool meets = false;
      for (int i = 0; i < 4 && !meets; ++i)
        for (int j = 0; j < 4 && !meets; ++j) meets = segmentMeetsBox(tile.v[size_t(i)], light.v[size_t(j)], lo, hi);
      for (int k = 0; k < 64 && !meets; ++k)
        meets = segmentMeetsBox(polygonPoint(tile, rng.next(), rng.next()), polygonPoint(light, rng.next(), rng.next()), lo, hi);
      if (planes.separates(tile, Vec3(0.0f, 1e-4f, 0.0f))) {
        ++clear;
        ASSERT_FALSE(meets) << "a tile at " << x << ", " << z << " called clear has a segment through the box";
      } else {
        shadowed += meets;
      }
    }
  std::printf("%d floor tiles: %d called clear, %d not clear with a segment through the box\n", tiles, clear, shadowed);
  // The box's shadow on the floor, penumbra included, is about 1.9 x 1.9 m of the 6 x 6 m: the
  // rest is clear, and the planes find nearly all of it (the tiles neither called clear nor
  // found shadowed by the segments are the bound's slack).
  EXPECT_GT(shadowed, tiles / 20);
  EXPECT_LT(tiles - clear - shadowed, tiles / 50);
}

TEST(SeparatingPlanes, NothingIsClearWhenTheLightCutsThroughTheBox) {
  // A light through the middle of the box, wider than it: no plane has the light on one side and
  // the box on the other, so nothing can be proved.
  const Polygon light = square(0.0f, 0.5f, 0.0f, 1.0f, false);
  const SeparatingPlanes planes(light, Vec3(0.0f, -1e-4f, 0.0f), boxCorners(Vec3(-0.5f, 0.0f, -0.5f), Vec3(0.5f, 1.0f, 0.5f)), 1e-6f);
  EXPECT_EQ(planes.size(), 0u);
  EXPECT_FALSE(planes.separates(square(3.0f, -2.0f, 0.0f, 0.1f, true), Vec3(0.0f, 1e-4f, 0.0f)));
}

}  // namespace
}  // namespace luxel
