// Animation (luxel/animation.h): spins turn about their axis at their rate, keyframed paths
// interpolate linearly and by slerp, hold or loop at their ends, lights move and change colour,
// and the poses come from the rest pose whatever the scene's objects have since done.
//
// Expected values are worked by hand from the definitions (a rotation about an axis through a
// point, the linear and spherical interpolations); the tolerances are float rounding.
#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "luxel/animation.h"
#include "luxel/error.h"
#include "luxel/import.h"
#include "luxel/scene.h"
#include "error_message.h"

namespace luxel {
namespace {

using test::errorOf;

constexpr float kPi = 3.14159265358979f;

glm::vec3 apply(const glm::mat4& m, const glm::vec3& p) {
  return glm::vec3(m * glm::vec4(p, 1.0f));
}

void expectNear(const glm::vec3& got, const glm::vec3& want, float tol = 1e-5f) {
  EXPECT_NEAR(got.x, want.x, tol) << "x";
  EXPECT_NEAR(got.y, want.y, tol) << "y";
  EXPECT_NEAR(got.z, want.z, tol) << "z";
}

// Rodrigues' formula: `p` turned by `degrees` about the line through `pivot` along unit `axis`.
glm::vec3 turned(const glm::vec3& p, const glm::vec3& pivot, const glm::vec3& axis, float degrees) {
  const float a = degrees * kPi / 180.0f;
  const glm::vec3 v = p - pivot;
  return pivot + v * std::cos(a) + glm::cross(axis, v) * std::sin(a) +
         axis * glm::dot(axis, v) * (1.0f - std::cos(a));
}

// A one-quad scene whose only object is dynamic, at rest at `origin`, moving by `motion`.
Scene movingQuad(const glm::vec3& origin, const Motion& motion) {
  Scene s;
  s.name = "moving";
  s.materials.push_back(Material{.name = "grey"});
  s.objects.push_back(Object{
      .name = "quad", .transform = glm::translate(glm::mat4(1.0f), origin), .dynamic = true});
  Mesh m{.name = "quad", .object = 0};
  m.positions = {origin, origin + glm::vec3(1, 0, 0), origin + glm::vec3(1, 1, 0),
                 origin + glm::vec3(0, 1, 0)};
  m.faces = {Face{{0, 1, 2, 3}}};
  s.meshes.push_back(m);
  s.animation.objects.push_back(
      ObjectAnimation{.object = 0, .rest = s.objects[0].transform, .motion = motion});
  return s;
}

Keyframe key(double time, glm::vec3 translate = glm::vec3(0.0f),
             glm::quat rotate = glm::quat(1, 0, 0, 0), float scale = 1.0f) {
  return Keyframe{.time = time, .translate = translate, .rotate = rotate, .scale = scale};
}

glm::quat aboutY(float degrees) {
  return glm::angleAxis(degrees * kPi / 180.0f, glm::vec3(0, 1, 0));
}

TEST(Animation, SpinTurnsAboutItsAxisAtItsRate) {
  const glm::vec3 axis = glm::normalize(glm::vec3(1, 1, 0)), pivot(0.5f, -1.0f, 2.0f);
  Scene s = movingQuad(glm::vec3(3, 0, 0),
                       {.spin = Spin{.axis = axis, .pivot = pivot, .degreesPerSecond = 30.0}});
  s.validate();
  const glm::mat4 rest = s.objects[0].transform;
  // At t = 0 the object is at rest, exactly (a still first frame touches nothing).
  EXPECT_EQ(objectTransformAt(s, 0, 0.0), rest);
  for (double t : {0.5, 1.5, 4.0, -2.0}) {
    const glm::mat4 move = objectTransformAt(s, 0, t) * glm::inverse(rest);
    // Points on the axis stay where they are.
    for (float along : {0.0f, 1.0f, -3.0f})
      expectNear(apply(move, pivot + along * axis), pivot + along * axis);
    // Points off it turn by rate * t degrees.
    for (glm::vec3 p : {glm::vec3(3, 0, 0), glm::vec3(0, 0, 0), glm::vec3(1, 2, 3)})
      expectNear(apply(move, p), turned(p, pivot, axis, float(30.0 * t)), 2e-5f);
  }
  // A whole turn (12 s at 30 degrees a second) comes back to rest.
  const glm::mat4 turn = objectTransformAt(s, 0, 12.0);
  for (int c = 0; c < 4; ++c) expectNear(glm::vec3(turn[c]), glm::vec3(rest[c]));
}

TEST(Animation, KeyframesInterpolateTranslationScaleAndRotationAboutTheOrigin) {
  // Rest origin o = (1, 1, 1). Keys: at rest at t = 0; at t = 2, moved by (2, 0, 0), scaled 3 and
  // turned 90 degrees about z. Half way, t = 1: moved by (1, 0, 0), scaled 2, turned 45 degrees.
  const glm::vec3 o(1, 1, 1);
  Scene s = movingQuad(
      o, {.keyframes = {key(0.0), key(2.0, glm::vec3(2, 0, 0),
                                      glm::angleAxis(kPi / 2, glm::vec3(0, 0, 1)), 3.0f)}});
  s.validate();
  const glm::mat4 rest = s.objects[0].transform;
  const glm::mat4 move = objectTransformAt(s, 0, 1.0) * glm::inverse(rest);
  // The origin is only translated; (2, 1, 1), one unit along x from it, goes to o + (1, 0, 0) +
  // 2 (cos 45, sin 45, 0).
  expectNear(apply(move, o), o + glm::vec3(1, 0, 0));
  const float r = std::sqrt(2.0f);
  expectNear(apply(move, glm::vec3(2, 1, 1)), o + glm::vec3(1 + r, r, 0));
  // A quarter of the way: a quarter of each.
  const glm::mat4 quarter = objectTransformAt(s, 0, 0.5) * glm::inverse(rest);
  const float a = 22.5f * kPi / 180.0f;
  expectNear(apply(quarter, glm::vec3(2, 1, 1)),
             o + glm::vec3(0.5f, 0, 0) + 1.5f * glm::vec3(std::cos(a), std::sin(a), 0));
}

TEST(Animation, SlerpTurnsAtAConstantRateTheShorterWay) {
  // 0 to 120 degrees about y over 4 s: 30 degrees a second, the angle linear in time.
  Scene s =
      movingQuad(glm::vec3(0), {.keyframes = {key(0.0, {}, aboutY(0)), key(4.0, {}, aboutY(120))}});
  for (double t : {1.0, 2.0, 3.0})
    expectNear(apply(objectTransformAt(s, 0, t), glm::vec3(1, 0, 0)),
               turned(glm::vec3(1, 0, 0), {}, {0, 1, 0}, float(30 * t)));
  // 0 to 270 degrees is the same orientation as -90: it turns the shorter way, through -45.
  Scene shorter =
      movingQuad(glm::vec3(0), {.keyframes = {key(0.0, {}, aboutY(0)), key(2.0, {}, aboutY(270))}});
  expectNear(apply(objectTransformAt(shorter, 0, 1.0), glm::vec3(1, 0, 0)),
             turned(glm::vec3(1, 0, 0), {}, {0, 1, 0}, -45.0f));
}

TEST(Animation, PathsHoldOrLoopAtTheirEnds) {
  // From x = 0 at t = 1 to x = 2 at t = 3.
  const Motion path{.keyframes = {key(1.0), key(3.0, glm::vec3(2, 0, 0))}};
  Scene hold = movingQuad(glm::vec3(0), path);
  auto x = [](const Scene& s, double t) { return objectTransformAt(s, 0, t)[3].x; };
  EXPECT_FLOAT_EQ(x(hold, 2.0), 1.0f);
  EXPECT_FLOAT_EQ(x(hold, 0.0), 0.0f);   // before the first key: the first
  EXPECT_FLOAT_EQ(x(hold, 10.0), 2.0f);  // after the last: the last
  Motion looped = path;
  looped.loop = true;
  Scene loop = movingQuad(glm::vec3(0), looped);
  // Period 2 s: t = 4 is t = 2, t = 0.5 is t = 2.5, t = 7 is t = 3 (the first key again).
  EXPECT_FLOAT_EQ(x(loop, 2.0), 1.0f);
  EXPECT_FLOAT_EQ(x(loop, 4.0), 1.0f);
  EXPECT_FLOAT_EQ(x(loop, 0.5), 1.5f);
  EXPECT_NEAR(x(loop, 7.0), 0.0f, 1e-6f);
  // One key: a still pose, loop or not.
  Scene one = movingQuad(glm::vec3(0), {.keyframes = {key(5.0, glm::vec3(0, 3, 0))}, .loop = true});
  EXPECT_FLOAT_EQ(objectTransformAt(one, 0, 0.0)[3].y, 3.0f);
  EXPECT_FLOAT_EQ(objectTransformAt(one, 0, 9.0)[3].y, 3.0f);
}

TEST(Animation, PosesComeFromTheRestPoseNotTheCurrentOne) {
  Scene s =
      movingQuad(glm::vec3(1, 0, 0), {.spin = Spin{.axis = {0, 1, 0}, .degreesPerSecond = 90.0}});
  const glm::mat4 atTwo = objectTransformAt(s, 0, 2.0);
  // A session moves the scene's object frame after frame; the pose at a time stays the same.
  for (double t : {0.25, 0.5, 1.0}) s.placeObject(0, objectTransformAt(s, 0, t));
  EXPECT_EQ(objectTransformAt(s, 0, 2.0), atTwo);
  const auto placements = animatedPlacements(s, 2.0);
  ASSERT_EQ(placements.size(), 1u);
  EXPECT_EQ(placements[0].first, 0u);
  EXPECT_EQ(placements[0].second, atTwo);
  EXPECT_TRUE(hasAnimation(s));
  s.animation = {};
  EXPECT_FALSE(hasAnimation(s));
  EXPECT_TRUE(animatedPlacements(s, 2.0).empty());
  EXPECT_EQ(objectTransformAt(s, 0, 2.0), s.objects[0].transform);  // not animated: where it is
}

TEST(Animation, LightsMoveTurnAndChangeColourAndIntensity) {
  Scene s = movingQuad(glm::vec3(0), {.spin = Spin{.axis = {0, 1, 0}, .degreesPerSecond = 10.0}});
  const Light spot{.type = Light::Type::Spot,
                   .name = "spot",
                   .color = Rgb(1, 0.5f, 0.25f),
                   .intensity = 10.0f,
                   .position = {2, 3, 0},
                   .direction = {1, 0, 0}};
  s.lights = {spot,
              Light{.type = Light::Type::Directional, .name = "sun", .direction = {0, -1, 0}}};
  // Over 2 s the spot's beam turns 90 degrees about the vertical, its intensity goes from 10 to
  // 30 and its colour from its own to white.
  s.animation.lights.push_back(LightAnimation{
      .light = 0,
      .restPosition = spot.position,
      .restDirection = spot.direction,
      .restColor = spot.color,
      .restIntensity = spot.intensity,
      .motion = {
          .keyframes = {
              Keyframe{.time = 0.0},
              Keyframe{.time = 2.0, .rotate = aboutY(90), .color = Rgb(1), .intensity = 30.0f}}}});
  s.validate();
  const Light half = lightAt(s, 0, 1.0);
  // Keyframe rotations act about the light's own position: it stays, its beam turns 45 degrees.
  expectNear(half.position, glm::vec3(2, 3, 0));
  expectNear(half.direction, glm::vec3(std::sqrt(0.5f), 0, -std::sqrt(0.5f)));
  EXPECT_FLOAT_EQ(half.intensity, 20.0f);
  expectNear(half.color, Rgb(1, 0.75f, 0.625f));
  EXPECT_EQ(half.name, "spot");
  EXPECT_EQ(half.outerConeAngle, spot.outerConeAngle);
  // A spin about a pivot carries the position round it.
  s.animation.lights[0].motion = {
      .spin = Spin{.axis = {0, 1, 0}, .pivot = {0, 0, 0}, .degreesPerSecond = 90.0}};
  const Light spun = lightAt(s, 0, 1.0);
  expectNear(spun.position, glm::vec3(0, 3, -2));
  expectNear(spun.direction, glm::vec3(0, 0, -1));
  EXPECT_EQ(spun.intensity, 10.0f);  // a spin keeps the light's own colour and intensity
  // Not animated: as it is.
  const std::vector<Light> all = lightsAt(s, 1.0);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[1].direction, glm::vec3(0, -1, 0));
}

TEST(Animation, ValidationNamesWhatIsWrong) {
  auto errorFor = [](auto edit) {
    Scene s = movingQuad(glm::vec3(0), {.keyframes = {key(0.0), key(1.0, glm::vec3(1, 0, 0))}});
    edit(s);
    return errorOf([&] { s.validate(); });
  };
  std::string e = errorFor([](Scene& s) { s.objects[0].dynamic = false; });
  EXPECT_NE(e.find("object 'quad'"), std::string::npos) << e;
  EXPECT_NE(e.find("not dynamic"), std::string::npos) << e;
  e = errorFor([](Scene& s) { s.animation.objects[0].motion.keyframes[1].time = 0.0; });
  EXPECT_NE(e.find("keyframe 1"), std::string::npos) << e;
  EXPECT_NE(e.find("not after"), std::string::npos) << e;
  e = errorFor([](Scene& s) { s.animation.objects[0].motion.keyframes[1].scale = -1.0f; });
  EXPECT_NE(e.find("scale -1 is not positive"), std::string::npos) << e;
  e = errorFor([](Scene& s) { s.animation.objects[0].motion.keyframes[0].translate.x = NAN; });
  EXPECT_NE(e.find("not finite"), std::string::npos) << e;
  e = errorFor([](Scene& s) { s.animation.objects[0].motion = {.spin = Spin{.axis = {0, 0, 0}}}; });
  EXPECT_NE(e.find("axis is not a unit vector"), std::string::npos) << e;
  e = errorFor([](Scene& s) { s.animation.objects[0].object = 7; });
  EXPECT_NE(e.find("object 7, which does not exist"), std::string::npos) << e;
  e = errorFor([](Scene& s) {
    s.lights.push_back(Light{.name = "lamp"});
    s.animation.lights.push_back(
        LightAnimation{.light = 0, .motion = {.keyframes = {Keyframe{.time = 0, .intensity = 1e16f}}}});
  });
  EXPECT_NE(e.find("light 'lamp': animation: keyframe 0: intensity 1e+16 times colour is over the limit"),
            std::string::npos)
      << e;
  e = errorFor([](Scene& s) { s.animation.objects.push_back(s.animation.objects[0]); });
  EXPECT_NE(e.find("has two"), std::string::npos) << e;
}

// Seed 001's four scenes: the box turns about the vertical through its centre at 30 degrees a
// second (builtin_scenes.h, docs/seed-scenes.md).
TEST(Animation, SeedScenesSpinTheirBox) {
  for (const char* name : {"cornell-large", "cornell-small", "cornell-low", "indirect-light"}) {
    SCOPED_TRACE(name);
    const Scene s = builtinScene(name);
    ASSERT_EQ(s.animation.objects.size(), 1u);
    const uint32_t box = s.animation.objects[0].object;
    EXPECT_EQ(s.objects[box].name, "box");
    EXPECT_TRUE(s.objects[box].dynamic);
    const glm::vec3 centre(s.objects[box].transform[3]);
    // Three seconds: 90 degrees.
    const glm::mat4 move = objectTransformAt(s, box, 3.0) * glm::inverse(s.objects[box].transform);
    expectNear(apply(move, centre), centre);
    expectNear(apply(move, centre + glm::vec3(0, 0.1f, 0)), centre + glm::vec3(0, 0.1f, 0));
    expectNear(apply(move, centre + glm::vec3(0.1f, 0, 0)), centre + glm::vec3(0, 0, -0.1f));
    EXPECT_TRUE(s.animation.lights.empty());
  }
  EXPECT_FALSE(hasAnimation(builtinScene("cornell")));
}

}  // namespace
}  // namespace luxel
