// The highlight of a glossy material (Material::specular and shininess) as a BRDF: the modified
// Blinn-Phong lobe f = specular / pi * pow(max(N.H, 0), s), H the half vector, as the viewer's
// per-pixel lamps take it (Material's convention: radiance = specular / pi * pow(N.H, s) * E for
// a light of irradiance E). Seed 002 displays glossy statues by this lobe evaluated for the one
// dominant direction of the irradiance vector (its Eq. 10); a render can afford to integrate it
// over the incoming light instead, which is what that direction approximates: rays drawn from the
// lobe read the light the solution leaves where they land. Lafortune and Willems, "Using the
// Modified Phong Reflectance Model for Physically Based Rendering", 1994, for the sampling.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "luxel/scene.h"
#include "trace/hemisphere_rays.h"

namespace luxel {

class GlossyLobe {
 public:
  // `normal` and `toEye` unit; `shininess` > 0.
  GlossyLobe(Vec3 normal, Vec3 toEye, float shininess)
      : frame_(normal), toEye_(toEye), shininess_(shininess) {}

  // pow(max(N.H, 0), s) / pi for light from unit direction `toLight`: f over the specular colour.
  float value(Vec3 toLight) const {
    const Vec3 h = toLight + toEye_;
    const float len = glm::length(h);
    if (!(len > 0.0f)) return 0.0f;
    return std::pow(std::max(0.0f, glm::dot(frame_.n, h / len)), shininess_) *
           std::numbers::inv_pi_v<float>;
  }

  // A direction towards the light drawn from (u1, u2) in [0,1)^2, and f cos / pdf for it over the
  // specular colour: the half vector H from pdf (s + 2) / (2 pi) (N.H)^(s + 1), mirrored about it,
  // so pdf(l) = that / (4 V.H) and f cos / pdf = 8 (V.H) (N.l) / ((s + 2) (N.H)). Weight 0 where
  // the direction falls below the surface.
  struct Sample {
    Vec3 toLight;
    float weight;
  };
  Sample sample(float u1, float u2) const {
    const float cosH = std::pow(u1, 1.0f / (shininess_ + 2.0f));
    const Vec3 h = frame_.uniform(cosH, u2);
    const float vh = glm::dot(toEye_, h);
    const Vec3 l = 2.0f * vh * h - toEye_;
    const float nl = glm::dot(frame_.n, l);
    if (vh <= 0.0f || nl <= 0.0f || cosH <= 0.0f) return {l, 0.0f};
    return {l, 8.0f * vh * nl / ((shininess_ + 2.0f) * cosH)};
  }

 private:
  HemisphereFrame frame_;
  Vec3 toEye_;
  float shininess_;
};

}  // namespace luxel
