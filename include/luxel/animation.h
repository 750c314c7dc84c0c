// Animation: objects and lights that move with time, and lights whose colour and intensity change
// (seed 001's rotating box, a sun crossing the sky). A motion is a spin or a path of keyframes,
// applied on top of the thing's rest pose (where the scene put it when it was loaded), so the pose
// at any time is computed from the rest pose and never from the last frame's: many frames do not
// accumulate rounding, and the functions below give the same answer on a scene whose objects a
// Session has since moved.
//
// Every motion is a similarity (rotation, translation, uniform positive scale), the only moves
// Scene::placeObject accepts.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace luxel {

struct Scene;
struct Light;

// A turn about the line through `pivot` along `axis` (world space), at a constant rate,
// counter-clockwise looking down the axis towards the pivot (right-handed): angle = rate * t.
struct Spin {
  glm::vec3 axis{0.0f, 1.0f, 0.0f};  // unit length
  glm::vec3 pivot{0.0f};
  double degreesPerSecond = 0.0;
};

// One pose of a path, relative to the rest pose: `rotate` and `scale` act about the thing's origin
// (where its rest transform puts its local origin; a light's position), along world axes, then
// `translate` moves it (world units).
struct Keyframe {
  double time = 0.0;  // seconds
  glm::vec3 translate{0.0f};
  glm::quat rotate{1.0f, 0.0f, 0.0f, 0.0f};  // unit
  float scale = 1.0f;                        // uniform, positive
  // Lights only: the colour and intensity at this key; absent, the light's own (rest) values.
  std::optional<glm::vec3> color;
  std::optional<float> intensity;
};

struct Motion {
  std::optional<Spin> spin;         // a spin, or else
  std::vector<Keyframe> keyframes;  // a path: at least one key, times strictly increasing
  // Keyframes: before the first key and after the last, hold the end pose (false) or repeat the
  // path with period last - first time (true).
  bool loop = false;

  // The world-space move from the rest pose at time `t`, for a thing whose origin at rest is
  // `origin`. Between keys, translation and scale are linear in time and the rotation is a
  // spherical linear interpolation (the shorter way round: keys less than 180 degrees apart turn
  // as written).
  glm::mat4 moveAt(double t, const glm::vec3& origin) const;
};

struct ObjectAnimation {
  uint32_t object = 0;   // index into Scene::objects; the object must be dynamic
  glm::mat4 rest{1.0f};  // the object's transform (object to world) at rest
  Motion motion;
};

struct LightAnimation {
  uint32_t light = 0;  // index into Scene::lights
  // The light at rest. Position and direction move with the motion; colour and intensity follow
  // the keyframes' when they give them.
  glm::vec3 restPosition{0.0f};
  glm::vec3 restDirection{0.0f, -1.0f, 0.0f};
  glm::vec3 restColor{1.0f};
  float restIntensity = 1.0f;
  Motion motion;
};

struct Animation {
  std::vector<ObjectAnimation> objects;  // at most one per object
  std::vector<LightAnimation> lights;    // at most one per light
  bool empty() const { return objects.empty() && lights.empty(); }
};

// The world transform of object `object` at time `t` seconds: its animation's, or its current
// transform when it has none. Throws Error when there is no such object.
glm::mat4 objectTransformAt(const Scene& scene, uint32_t object, double t);
// Light `light` at time `t`: its animation's position, direction, colour and intensity (colour
// and intensity linear in time between keys), the rest of it (type, name, cone, ...) as the scene
// has it. Throws Error when there is no such light.
Light lightAt(const Scene& scene, uint32_t light, double t);
// Every light of the scene at time `t` (for Session::setLights).
std::vector<Light> lightsAt(const Scene& scene, double t);
// The animated objects and their transforms at time `t` (for Session::placeObjects).
std::vector<std::pair<uint32_t, glm::mat4>> animatedPlacements(const Scene& scene, double t);
// Whether anything in the scene is animated.
bool hasAnimation(const Scene& scene);

}  // namespace luxel
