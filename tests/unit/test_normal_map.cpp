// Normal maps: the per-face tangent frame (render/normal_map.h) against frames worked out by hand,
// the world normal a constant map gives, and the sides of a face. Tolerances are float rounding:
// every expected value is a few exact operations on exact inputs, so 1e-6 on unit vectors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "render/normal_map.h"

namespace luxel {
namespace {

constexpr float kTol = 1e-6f;

void expectVec(Vec3 got, Vec3 want, float tol = kTol) {
  EXPECT_NEAR(got.x, want.x, tol) << "x of (" << got.x << ", " << got.y << ", " << got.z << ")";
  EXPECT_NEAR(got.y, want.y, tol) << "y of (" << got.x << ", " << got.y << ", " << got.z << ")";
  EXPECT_NEAR(got.z, want.z, tol) << "z of (" << got.x << ", " << got.y << ", " << got.z << ")";
}

// A 2 x 3 quad in the xz plane facing +y (counter-clockwise seen from above), u along +x and v
// along -z: by hand, dp/du = (2, 0, 0) and dp/dv = (0, 0, -3), so t = +x, b = -z = cross(n, t).
Mesh xzQuad(bool mirrored) {
  Mesh m;
  m.positions = {{0, 0, 0}, {2, 0, 0}, {2, 0, -3}, {0, 0, -3}};
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  if (mirrored)  // u runs along -x: dp/du = (-2, 0, 0)
    for (Vec2& uv : m.uvs) uv.x = 1.0f - uv.x;
  m.faces = {Face{{0, 1, 2, 3}}};
  return m;
}

// A texel that encodes the tangent-space direction `n` (unit).
Rgb encode(Vec3 n) { return 0.5f * n + 0.5f; }

// One quad with a 1 x 1 normal map holding `texel`.
Scene quadScene(Rgb texel, float scale, bool twoSided) {
  Scene s;
  s.meshes = {xzQuad(false)};
  Material m;
  m.name = "bumpy";
  m.twoSided = twoSided;
  m.normalTexture = 0;
  m.normalScale = scale;
  s.materials = {m};
  s.textures = {Texture{.path = "n", .width = 1, .height = 1, .texels = {texel}}};
  return s;
}

TEST(NormalMap, TangentFrameOfAQuadInTheXzPlane) {
  const TangentFrame f = faceTangentFrame(xzQuad(false), 0, Vec3(0, 1, 0));
  ASSERT_TRUE(f.valid);
  expectVec(f.t, Vec3(1, 0, 0));
  expectVec(f.b, Vec3(0, 0, -1));
  expectVec(f.n, Vec3(0, 1, 0));
  expectVec(glm::cross(f.n, f.t), f.b);  // right-handed
}

TEST(NormalMap, MirroredUvsGiveALeftHandedFrame) {
  // dp/du = -x, dp/dv = -z: t = -x, and b still along +v, -z, which is -cross(n, t).
  const TangentFrame f = faceTangentFrame(xzQuad(true), 0, Vec3(0, 1, 0));
  ASSERT_TRUE(f.valid);
  expectVec(f.t, Vec3(-1, 0, 0));
  expectVec(f.b, Vec3(0, 0, -1));
  expectVec(glm::cross(f.n, f.t), -f.b);
}

TEST(NormalMap, SkewedUvsGiveTheBitangentAsCrossOfNormalAndTangent) {
  // Triangle (0,0,0), (1,0,0), (0,1,0) facing +z with uvs (0,0), (1,1), (0,1). By hand:
  // (1,0,0) = dp/du + dp/dv and (0,1,0) = dp/dv, so dp/du = (1,-1,0) and dp/dv = (0,1,0). glTF's
  // bitangent is cross(n, t) * w (MikkTSpace), not dp/dv: (1,1,0)/sqrt 2, w = +1.
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.uvs = {{0, 0}, {1, 1}, {0, 1}};
  m.faces = {Face{{0, 1, 2, 2}}};
  const TangentFrame f = faceTangentFrame(m, 0, Vec3(0, 0, 1));
  ASSERT_TRUE(f.valid);
  const float h = std::sqrt(0.5f);
  expectVec(f.t, Vec3(h, -h, 0));
  expectVec(f.b, Vec3(h, h, 0));
}

TEST(NormalMap, DegenerateUvsGiveNoFrame) {
  Mesh m = xzQuad(false);
  m.uvs = {{0, 0}, {0.5f, 0.5f}, {1, 1}, {0.25f, 0.25f}};  // on one line
  EXPECT_FALSE(faceTangentFrame(m, 0, Vec3(0, 1, 0)).valid);
  m.uvs.assign(4, Vec2(0.3f, 0.7f));  // one point
  EXPECT_FALSE(faceTangentFrame(m, 0, Vec3(0, 1, 0)).valid);
  m.uvs.clear();
  EXPECT_FALSE(faceTangentFrame(m, 0, Vec3(0, 1, 0)).valid);
}

TEST(NormalMap, TexelDecodesWithScale) {
  expectVec(tangentSpaceNormal(encode(Vec3(0.6f, 0.0f, 0.8f)), 1.0f), Vec3(0.6f, 0.0f, 0.8f));
  // Scale 0.5: (0.3, 0, 0.8) normalised, |.| = sqrt(0.73).
  const float len = std::sqrt(0.73f);
  expectVec(tangentSpaceNormal(encode(Vec3(0.6f, 0.0f, 0.8f)), 0.5f),
            Vec3(0.3f / len, 0.0f, 0.8f / len));
  expectVec(tangentSpaceNormal(Rgb(0.5f), 1.0f), Vec3(0, 0, 1));  // encodes no direction
}

TEST(NormalMap, ConstantMapGivesTheExpectedWorldNormal) {
  // Tangent space (0.36, -0.48, 0.8) on t = +x, b = -z, n = +y: 0.36 x + 0.48 z + 0.8 y.
  const Vec3 ts(0.36f, -0.48f, 0.8f);
  const Scene s = quadScene(encode(ts), 1.0f, false);
  expectVec(shadingNormal(s, 0, 0, Vec2(0.3f, 0.6f), Vec3(0, 1, 0)), Vec3(0.36f, 0.8f, 0.48f));
  // Scale 0 leaves the surface flat, exactly.
  const Scene flat = quadScene(encode(ts), 0.0f, false);
  EXPECT_EQ(shadingNormal(flat, 0, 0, Vec2(0.3f, 0.6f), Vec3(0, 1, 0)), Vec3(0, 1, 0));
}

TEST(NormalMap, WithoutAMapOrUvsTheGeometricNormalComesBack) {
  Scene s = quadScene(encode(Vec3(0.36f, -0.48f, 0.8f)), 1.0f, false);
  s.materials[0].normalTexture = -1;
  EXPECT_EQ(shadingNormal(s, 0, 0, Vec2(0.5f), Vec3(0, 1, 0)), Vec3(0, 1, 0));
  s.materials[0].normalTexture = 0;
  s.meshes[0].uvs.clear();
  EXPECT_EQ(shadingNormal(s, 0, 0, Vec2(0.5f), Vec3(0, 1, 0)), Vec3(0, 1, 0));
}

TEST(NormalMap, BackOfATwoSidedFaceIsTheFrontReversedAndATurnedFaceGetsItsOwnFrame) {
  const Vec3 ts(0.36f, -0.48f, 0.8f);
  // Two-sided: the back (normal -y) is the front's perturbed normal reversed (glTF doubleSided).
  const Scene two = quadScene(encode(ts), 1.0f, true);
  expectVec(shadingNormal(two, 0, 0, Vec2(0.5f), Vec3(0, -1, 0)), -Vec3(0.36f, 0.8f, 0.48f));
  // One-sided, seen from -y: a face discretisation turned round. Its frame is built on -y: t = +x,
  // b = +v = -z, so 0.36 x + 0.48 z - 0.8 y.
  const Scene one = quadScene(encode(ts), 1.0f, false);
  expectVec(shadingNormal(one, 0, 0, Vec2(0.5f), Vec3(0, -1, 0)), Vec3(0.36f, -0.8f, 0.48f));
}

}  // namespace
}  // namespace luxel
