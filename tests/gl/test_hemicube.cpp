// The OpenGL hemicube (src/gl/): delta form factors against their closed-form sum, and rendered
// item-buffer hemicubes against the exact point-to-polygon form factor. Needs an OpenGL 4.5 core
// context (Mesa's llvmpipe is enough); without one, the GL tests skip and say why.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numeric>

#include "gl/gl_test_context.h"
#include "gl/hemicube.h"
#include "luxel/error.h"
#include "transport/form_factor.h"

namespace {

using luxel::Polygon;
using luxel::Vec3;

// The six inward walls of the box [-1, 1]^3 (counter-clockwise seen from inside).
std::vector<Polygon> insideOfCube() {
  auto quad = [](Vec3 a, Vec3 b, Vec3 c, Vec3 d) { return Polygon{{a, b, c, d}, 4}; };
  const float l = -1.0f, h = 1.0f;
  return {quad({l, l, l}, {l, l, h}, {h, l, h}, {h, l, l}),   // floor, +y
          quad({l, h, l}, {h, h, l}, {h, h, h}, {l, h, h}),   // ceiling, -y
          quad({l, l, l}, {h, l, l}, {h, h, l}, {l, h, l}),   // z = -1, +z
          quad({l, l, h}, {l, h, h}, {h, h, h}, {h, l, h}),   // z = +1, -z
          quad({l, l, l}, {l, h, l}, {l, h, h}, {l, l, h}),   // x = -1, +x
          quad({h, l, l}, {h, l, h}, {h, h, h}, {h, h, l})};  // x = +1, -x
}

TEST(DeltaFormFactors, RawSumIsNearOneAndTablesSumToOne) {
  for (int res : {16, 64, 256}) {
    luxel::gl::DeltaFormFactors d(res);
    // The midpoint rule's error shrinks with the square of the pixel size.
    EXPECT_NEAR(d.rawSum, 1.0, 2.0 / (res * res)) << res;
    double sum = std::accumulate(d.top.begin(), d.top.end(), 0.0) +
                 4.0 * std::accumulate(d.side.begin(), d.side.end(), 0.0);
    EXPECT_NEAR(sum, 1.0, 1e-5) << res;
    // The centre of the top face weighs most, the horizon least.
    EXPECT_GT(d.top[size_t(res / 2) * res + res / 2], d.top[0]);
    EXPECT_GT(d.side[size_t(res / 2 - 1) * res + res / 2], d.side[size_t(res / 2)]);
  }
  EXPECT_THROW(luxel::gl::DeltaFormFactors(15), luxel::Error);
  EXPECT_THROW(luxel::gl::DeltaFormFactors(0), luxel::Error);
}

TEST(GlHemicube, EnclosingBoxSumsToOneAndMatchesExactFactors) {
  std::string why;
  auto context = luxel::test::glContextOr(why);
  if (!context) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  const std::vector<Polygon> walls = insideOfCube();
  luxel::gl::ItemHemicube hemicube(walls, 3.5f, {.resolution = 64});
  struct Receiver {
    Vec3 p, n;
  };
  // The last receiver sits 1 mm off the floor and 2 mm from a wall, which then fills almost half
  // its hemisphere: the near plane (1e-4 of the extent, 0.35 mm) must clip none of it (seed 000's
  // and 003's near-plane artefact).
  for (const Receiver& r : {Receiver{{0, 0, 0}, {0, 1, 0}}, Receiver{{0.2f, -0.3f, 0.1f}, glm::normalize(Vec3(0.3f, 1, -0.2f))},
                            Receiver{{0.5f, -0.99f, -0.4f}, {0, 1, 0}}, Receiver{{-0.998f, -0.999f, 0.0f}, {0, 1, 0}}}) {
    const std::vector<float> f = hemicube.formFactors(r.p, r.n);
    ASSERT_EQ(f.size(), walls.size());
    EXPECT_NEAR(std::accumulate(f.begin(), f.end(), 0.0), 1.0, 0.005);  // the 0.5%
    for (size_t w = 0; w < walls.size(); ++w) {
      const float exact = luxel::pointToPolygonFormFactor(r.p, r.n, walls[w], luxel::Sides::Front, luxel::Sides::Front);
      EXPECT_NEAR(f[w], exact, 0.004 + 0.01 * exact) << "wall " << w << " from (" << r.p.x << "," << r.p.y << "," << r.p.z << ")";
    }
  }
}

TEST(GlHemicube, AnOccluderTakesItsShareFromWhatItHides) {
  std::string why;
  auto context = luxel::test::glContextOr(why);
  if (!context) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  std::vector<Polygon> scene = insideOfCube();
  // A plate facing down, 0.5 above the receiver, hiding the middle of the ceiling.
  scene.push_back(Polygon{{Vec3(-0.25f, 0.5f, -0.25f), Vec3(0.25f, 0.5f, -0.25f), Vec3(0.25f, 0.5f, 0.25f),
                           Vec3(-0.25f, 0.5f, 0.25f)}, 4});
  ASSERT_LT(scene[6].normal().y, 0.0f);
  luxel::gl::ItemHemicube hemicube(scene, 3.5f, {.resolution = 128});
  const Vec3 p(0, 0, 0), n(0, 1, 0);
  const std::vector<float> f = hemicube.formFactors(p, n);
  const float plate = luxel::pointToPolygonFormFactor(p, n, scene[6], luxel::Sides::Front, luxel::Sides::Front);
  const float ceiling = luxel::pointToPolygonFormFactor(p, n, scene[1], luxel::Sides::Front, luxel::Sides::Front);
  EXPECT_NEAR(f[6], plate, 0.01f * plate + 0.002f);
  EXPECT_NEAR(f[1], ceiling - plate, 0.01f * ceiling + 0.002f);  // the plate hides exactly its own solid angle
  EXPECT_NEAR(std::accumulate(f.begin(), f.end(), 0.0), 1.0, 0.005);
}

TEST(GlHemicube, ComputeIntegrationEqualsReadBack) {
  std::string why;
  auto context = luxel::test::glContextOr(why);
  if (!context) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  std::vector<Polygon> scene = insideOfCube();
  scene.push_back(Polygon{{Vec3(-0.25f, 0.5f, -0.25f), Vec3(0.25f, 0.5f, -0.25f), Vec3(0.25f, 0.5f, 0.25f),
                           Vec3(-0.25f, 0.5f, 0.25f)}, 4});
  for (int res : {64, 256}) {
    double maxDifference = 0.0;
    luxel::gl::ItemHemicube compute(scene, 3.5f, {.resolution = res});
    luxel::gl::ItemHemicube readBack(scene, 3.5f, {.resolution = res, .integration = luxel::gl::HemicubeIntegration::ReadBack});
    ASSERT_EQ(compute.integration(), luxel::gl::HemicubeIntegration::Compute);
    struct Receiver {
      Vec3 p, n;
    };
    for (const Receiver& r : {Receiver{{0, 0, 0}, {0, 1, 0}}, Receiver{{0.2f, -0.3f, 0.1f}, glm::normalize(Vec3(0.3f, 1, -0.2f))},
                              Receiver{{0.5f, -0.99f, -0.4f}, {0, 1, 0}}, Receiver{{-0.9f, 0.1f, 0.3f}, {1, 0, 0}}}) {
      const std::vector<float> a = compute.formFactors(r.p, r.n), b = readBack.formFactors(r.p, r.n);
      ASSERT_EQ(a.size(), b.size());
      double sa = 0, sb = 0;
      for (size_t w = 0; w < a.size(); ++w) {
        EXPECT_NEAR(a[w], b[w], 1e-5) << "item " << w << " at " << res << " pixels";
        maxDifference = std::max(maxDifference, double(std::abs(a[w] - b[w])));
        sa += a[w], sb += b[w];
      }
      EXPECT_NEAR(sa, sb, 1e-5) << res;
      EXPECT_NEAR(sa, 1.0, 0.005) << res;
    }
    RecordProperty("max_difference_" + std::to_string(res), std::to_string(maxDifference));
    std::printf("compute vs read-back at %d pixels: largest difference %.3g\n", res, maxDifference);
    // The span overload checks its size.
    std::vector<float> wrong(3);
    EXPECT_THROW(compute.formFactors(Vec3(0), Vec3(0, 1, 0), wrong), luxel::Error);
  }
}

}  // namespace
