// Animation (luxel/animation.h): poses of spinning and keyframed objects and lights at a time.
// Rotations between keys are spherical linear interpolation (Shoemake, "Animating rotation with
// quaternion curves", SIGGRAPH 1985).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "luxel/error.h"
#include "luxel/scene.h"

namespace luxel {
namespace {

constexpr double kPi = 3.14159265358979323846;

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Where `t` falls on a path: between keys a and b (a == b at the ends), `u` of the way from a.
struct KeySpan {
  size_t a = 0, b = 0;
  float u = 0.0f;
};

KeySpan spanAt(const std::vector<Keyframe>& keys, bool loop, double t) {
  const double first = keys.front().time, last = keys.back().time;
  if (loop && last > first) {
    // fmod keeps the sign of t - first: a time before the path wraps to its end.
    t = std::fmod(t - first, last - first);
    t = first + (t < 0.0 ? t + (last - first) : t);
  }
  if (!(t > first)) return {0, 0, 0.0f};
  if (!(t < last)) return {keys.size() - 1, keys.size() - 1, 0.0f};
  const size_t b =
      size_t(std::upper_bound(keys.begin(), keys.end(), t,
                              [](double time, const Keyframe& k) { return time < k.time; }) -
             keys.begin());
  const size_t a = b - 1;
  return {a, b, float((t - keys[a].time) / (keys[b].time - keys[a].time))};
}

// Spherical linear interpolation the shorter way round (q and -q are one rotation).
glm::quat slerp(const glm::quat& q0, glm::quat q1, float u) {
  float d = glm::dot(q0, q1);
  if (d < 0.0f) q1 = -q1, d = -d;
  // Nearly the same rotation: sin(theta) is too small to divide by, and a straight line is exact
  // to float precision.
  if (d > 0.9995f) return glm::normalize(q0 + u * (q1 - q0));
  const float theta = std::acos(d);
  return (std::sin((1.0f - u) * theta) * q0 + std::sin(u * theta) * q1) / std::sin(theta);
}

glm::mat4 about(const glm::vec3& point, const glm::mat4& linear) {
  return glm::translate(glm::mat4(1.0f), point) * linear * glm::translate(glm::mat4(1.0f), -point);
}

const ObjectAnimation* findObject(const Scene& scene, uint32_t object) {
  for (const ObjectAnimation& a : scene.animation.objects)
    if (a.object == object) return &a;
  return nullptr;
}

const LightAnimation* findLight(const Scene& scene, uint32_t light) {
  for (const LightAnimation& a : scene.animation.lights)
    if (a.light == light) return &a;
  return nullptr;
}

// Throws Error, prefixed by `what`, when the motion cannot be evaluated to a similarity.
void checkMotion(const Motion& m, const std::string& what) {
  if (m.spin && !m.keyframes.empty())
    throw Error(fmt::format("{}: has both a spin and keyframes (give one)", what));
  if (!m.spin && m.keyframes.empty())
    throw Error(fmt::format("{}: has neither a spin nor keyframes", what));
  if (m.spin) {
    const Spin& s = *m.spin;
    if (!finite(s.axis) || std::abs(glm::length(s.axis) - 1.0f) > 1e-3f)
      throw Error(fmt::format("{}: spin axis is not a unit vector", what));
    if (!finite(s.pivot) ||
        glm::any(glm::greaterThan(glm::abs(s.pivot), glm::vec3(kMaxCoordinate))))
      throw Error(fmt::format("{}: spin pivot is not finite or beyond {:g} scene units", what,
                              kMaxCoordinate));
    if (!std::isfinite(s.degreesPerSecond))
      throw Error(fmt::format("{}: spin rate is not finite", what));
  }
  for (size_t i = 0; i < m.keyframes.size(); ++i) {
    const Keyframe& k = m.keyframes[i];
    const std::string key = fmt::format("{}: keyframe {}", what, i);
    if (!std::isfinite(k.time)) throw Error(fmt::format("{}: time is not finite", key));
    if (i > 0 && !(k.time > m.keyframes[i - 1].time))
      throw Error(fmt::format("{}: time {:g} is not after the previous key's ({:g})", key, k.time,
                              m.keyframes[i - 1].time));
    if (!finite(k.translate) ||
        glm::any(glm::greaterThan(glm::abs(k.translate), glm::vec3(kMaxCoordinate))))
      throw Error(fmt::format("{}: translation is not finite or beyond {:g} scene units", key,
                              kMaxCoordinate));
    const glm::vec4 q(k.rotate.x, k.rotate.y, k.rotate.z, k.rotate.w);
    if (!std::isfinite(glm::dot(q, q)) || std::abs(glm::length(q) - 1.0f) > 1e-3f)
      throw Error(fmt::format("{}: rotation is not a unit quaternion", key));
    if (!std::isfinite(k.scale) || !(k.scale > 0.0f))
      throw Error(fmt::format("{}: scale {:g} is not positive", key, k.scale));
    if (k.color && (!finite(*k.color) || glm::any(glm::lessThan(*k.color, glm::vec3(0.0f)))))
      throw Error(fmt::format("{}: colour is negative or not finite", key));
    if (k.intensity && (!std::isfinite(*k.intensity) || *k.intensity < 0.0f))
      throw Error(fmt::format("{}: intensity is negative or not finite", key));
  }
}

}  // namespace

glm::mat4 Motion::moveAt(double t, const glm::vec3& origin) const {
  if (spin) {
    // The angle reduced in double, so that a long animation keeps its float precision.
    const double degrees = std::fmod(spin->degreesPerSecond * t, 360.0);
    const glm::quat q = glm::angleAxis(float(degrees * kPi / 180.0), spin->axis);
    return about(spin->pivot, glm::mat4_cast(q));
  }
  if (keyframes.empty()) return glm::mat4(1.0f);
  const KeySpan s = spanAt(keyframes, loop, t);
  const Keyframe &a = keyframes[s.a], &b = keyframes[s.b];
  const glm::vec3 translate = glm::mix(a.translate, b.translate, s.u);
  const float scale = a.scale + (b.scale - a.scale) * s.u;
  const glm::mat4 linear = glm::mat4_cast(slerp(a.rotate, b.rotate, s.u)) *
                           glm::scale(glm::mat4(1.0f), glm::vec3(scale));
  return glm::translate(glm::mat4(1.0f), translate) * about(origin, linear);
}

glm::mat4 objectTransformAt(const Scene& scene, uint32_t object, double t) {
  if (object >= scene.objects.size())
    throw Error(fmt::format("scene '{}': no object {} ({} objects)", scene.name, object,
                            scene.objects.size()));
  const ObjectAnimation* a = findObject(scene, object);
  if (!a) return scene.objects[object].transform;
  return a->motion.moveAt(t, glm::vec3(a->rest[3])) * a->rest;
}

Light lightAt(const Scene& scene, uint32_t light, double t) {
  if (light >= scene.lights.size())
    throw Error(
        fmt::format("scene '{}': no light {} ({} lights)", scene.name, light, scene.lights.size()));
  Light out = scene.lights[light];
  const LightAnimation* a = findLight(scene, light);
  if (!a) return out;
  const glm::mat4 move = a->motion.moveAt(t, a->restPosition);
  out.position = glm::vec3(move * glm::vec4(a->restPosition, 1.0f));
  out.direction = glm::normalize(glm::mat3(move) * a->restDirection);
  out.color = a->restColor;
  out.intensity = a->restIntensity;
  if (!a->motion.keyframes.empty()) {
    const KeySpan s = spanAt(a->motion.keyframes, a->motion.loop, t);
    const Keyframe &ka = a->motion.keyframes[s.a], &kb = a->motion.keyframes[s.b];
    out.color = glm::mix(ka.color.value_or(a->restColor), kb.color.value_or(a->restColor), s.u);
    const float ia = ka.intensity.value_or(a->restIntensity),
                ib = kb.intensity.value_or(a->restIntensity);
    out.intensity = ia + (ib - ia) * s.u;
  }
  return out;
}

std::vector<Light> lightsAt(const Scene& scene, double t) {
  std::vector<Light> out;
  out.reserve(scene.lights.size());
  for (uint32_t j = 0; j < scene.lights.size(); ++j) out.push_back(lightAt(scene, j, t));
  return out;
}

std::vector<std::pair<uint32_t, glm::mat4>> animatedPlacements(const Scene& scene, double t) {
  std::vector<std::pair<uint32_t, glm::mat4>> out;
  for (const ObjectAnimation& a : scene.animation.objects)
    out.emplace_back(a.object, objectTransformAt(scene, a.object, t));
  return out;
}

bool hasAnimation(const Scene& scene) { return !scene.animation.empty(); }

void Scene::validateAnimation() const {
  std::vector<bool> seen(objects.size(), false);
  for (const ObjectAnimation& a : animation.objects) {
    if (a.object >= objects.size())
      throw Error(
          fmt::format("scene '{}': animation of object {}, which does not exist ({} objects)", name,
                      a.object, objects.size()));
    const Object& o = objects[a.object];
    const std::string what = fmt::format("scene '{}': object '{}': animation", name, o.name);
    if (!o.dynamic)
      throw Error(fmt::format("{}: the object is not dynamic, so it cannot move", what));
    if (seen[a.object]) throw Error(fmt::format("{}: the object has two", what));
    seen[a.object] = true;
    checkMotion(a.motion, what);
  }
  seen.assign(lights.size(), false);
  for (const LightAnimation& a : animation.lights) {
    if (a.light >= lights.size())
      throw Error(fmt::format("scene '{}': animation of light {}, which does not exist ({} lights)",
                              name, a.light, lights.size()));
    const std::string what =
        fmt::format("scene '{}': light '{}': animation", name, lights[a.light].name);
    if (seen[a.light]) throw Error(fmt::format("{}: the light has two", what));
    seen[a.light] = true;
    if (!finite(a.restPosition) || !finite(a.restDirection) || !finite(a.restColor) ||
        !std::isfinite(a.restIntensity))
      throw Error(fmt::format("{}: its rest pose is not finite", what));
    checkMotion(a.motion, what);
    // Colour and intensity are linear between keys, so the keys bound every value between them.
    for (size_t i = 0; i < a.motion.keyframes.size(); ++i) {
      const Keyframe& k = a.motion.keyframes[i];
      const glm::vec3 color = k.color.value_or(a.restColor);
      const float intensity = k.intensity.value_or(a.restIntensity);
      if (intensity * std::max({color.r, color.g, color.b}) > kMaxRadiance)
        throw Error(fmt::format(
            "{}: keyframe {}: intensity {:g} times colour is over the limit of {:g} (the light "
            "would overflow in float)",
            what, i, intensity, kMaxRadiance));
    }
  }
}

}  // namespace luxel
