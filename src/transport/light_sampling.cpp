#include "transport/light_sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace luxel {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr float kInfinity = std::numeric_limits<float>::infinity();

// An orthonormal basis around unit `n` (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017).
void basis(Vec3 n, Vec3& t, Vec3& b) {
  float sign = std::copysign(1.0f, n.z);
  float a = -1.0f / (sign + n.z);
  float c = n.x * n.y * a;
  t = Vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = Vec3(c, sign + n.y * n.y * a, -n.y);
}

float receiverCosine(Vec3 n, Vec3 w, Sides sides) {
  float c = glm::dot(n, w);
  return sides == Sides::Both ? std::abs(c) : std::max(c, 0.0f);
}

}  // namespace

bool isSkyLight(const Light& light) {
  return light.type == Light::Type::Sky || light.type == Light::Type::CieOvercastSky;
}

bool isDistantLight(const Light& light) {
  return light.type == Light::Type::Directional || light.type == Light::Type::Sky ||
         light.type == Light::Type::CieOvercastSky;
}

Rgb skyRadiance(const Light& light, Vec3 w, Vec3 up) {
  float cosZenith = glm::dot(w, up);
  if (cosZenith <= 0.0f) return Rgb(0.0f);
  if (light.type == Light::Type::CieOvercastSky)  // Moon and Spencer 1942, CIE standard overcast sky
    return light.power() * ((1.0f + 2.0f * cosZenith) / 3.0f);
  return light.power();
}

bool lightMayReachFront(const Light& light, const Polygon& polygon, Vec3 n) {
  switch (light.type) {
    case Light::Type::Point:
    case Light::Type::Spot:
      // A sample point is a convex combination of the corners, so its cosine's sign is theirs.
      for (int i = 0; i < polygon.count; ++i)
        if (glm::dot(n, light.position - polygon.v[size_t(i)]) >= 0.0f) return true;
      return false;
    case Light::Type::Directional:
      // The disc's directions are within angularRadius of the axis: all behind the plane when
      // the axis is further than that below it (with a margin for the samples' rounding).
      if (!(light.angularRadius < 0.5f * kPi)) return true;  // a disc wider than a hemisphere
      return glm::dot(n, -glm::normalize(light.direction)) > -std::sin(light.angularRadius) - 1e-5f;
    case Light::Type::Sky:
    case Light::Type::CieOvercastSky:
      return true;
  }
  return true;
}

PreparedLight prepareLight(const Light& light) {
  PreparedLight p;
  p.light = &light;
  p.power = light.power();
  if (light.type == Light::Type::Spot) {
    p.cosOuter = std::cos(light.outerConeAngle), p.cosInner = std::cos(light.innerConeAngle);
    p.axis = glm::normalize(light.direction);
  } else if (light.type == Light::Type::Directional) {
    p.axis = -glm::normalize(light.direction);
    basis(p.axis, p.t, p.b);
    p.cosMax = std::cos(light.angularRadius);
  }
  return p;
}

LightSample sampleLight(const Light& light, Vec3 x, Vec3 n, Sides sides, Vec3 up, float u1, float u2) {
  return sampleLight(prepareLight(light), x, n, sides, up, u1, u2);
}

LightSample sampleLight(const PreparedLight& prepared, Vec3 x, Vec3 n, Sides sides, Vec3 up, float u1, float u2) {
  const Light& light = *prepared.light;
  LightSample s;
  switch (light.type) {
    case Light::Type::Point:
    case Light::Type::Spot: {
      Vec3 d = light.position - x;
      float r2 = glm::dot(d, d);
      if (r2 <= 0.0f) return s;
      Vec3 w = d / std::sqrt(r2);
      float falloff = 1.0f;
      if (light.type == Light::Type::Spot) {
        // glTF KHR_lights_punctual's recommended falloff: quadratic in the cosine between the cones.
        const float cosOuter = prepared.cosOuter, cosInner = prepared.cosInner;
        float cosAngle = glm::dot(-w, prepared.axis);
        float t = std::clamp((cosAngle - cosOuter) / std::max(cosInner - cosOuter, 1e-6f), 0.0f, 1.0f);
        falloff = t * t;
      }
      s.irradiance = prepared.power * (falloff * receiverCosine(n, w, sides) / r2);
      s.direction = d;
      s.tfar = 1.0f - 1e-4f;
      return s;
    }
    case Light::Type::Directional: {
      // Uniform direction in the cone of the sun's disc.
      const Vec3 axis = prepared.axis, t = prepared.t, b = prepared.b;
      const float cosMax = prepared.cosMax;
      float cosTheta = 1.0f - u1 * (1.0f - cosMax);
      float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
      float phi = 2.0f * kPi * u2;
      Vec3 w = glm::normalize(axis * cosTheta + (t * std::cos(phi) + b * std::sin(phi)) * sinTheta);
      s.irradiance = prepared.power * receiverCosine(n, w, sides);
      s.direction = w;
      s.tfar = kInfinity;
      return s;
    }
    case Light::Type::Sky:
    case Light::Type::CieOvercastSky: {
      // Cosine-weighted direction: irradiance = pi * L(w) per sample. Two-sided receivers pick a
      // hemisphere at random and double the weight.
      float weight = kPi;
      Vec3 side = n;
      if (sides == Sides::Both) {
        if (u1 < 0.5f) {
          u1 *= 2.0f;
        } else {
          u1 = 2.0f * u1 - 1.0f;
          side = -n;
        }
        weight *= 2.0f;
      }
      Vec3 t, b;
      basis(side, t, b);
      float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
      Vec3 w = glm::normalize(t * (r * std::cos(phi)) + b * (r * std::sin(phi)) +
                              side * std::sqrt(std::max(0.0f, 1.0f - u1)));
      s.irradiance = skyRadiance(light, w, up) * weight;
      s.direction = w;
      s.tfar = kInfinity;
      return s;
    }
  }
  return s;
}

}  // namespace luxel
