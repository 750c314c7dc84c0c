// The pinhole camera of every renderer, and the checks on render options they share.
#pragma once

#include <cmath>

#include <fmt/format.h>

#include "luxel/error.h"
#include "luxel/render.h"

namespace luxel {

struct CameraFrame {
  Vec3 eye, forward, right, up;
  float tanHalfY, aspect;

  CameraFrame(const Camera& c, int width, int height) {
    eye = c.eye;
    forward = glm::normalize(c.target - c.eye);
    right = glm::normalize(glm::cross(forward, c.up));
    up = glm::cross(right, forward);
    tanHalfY = std::tan(glm::radians(c.fovY) * 0.5f);
    aspect = float(width) / float(height);
  }
  // (sx, sy) in [0,1]^2, y down.
  Vec3 direction(float sx, float sy) const {
    return glm::normalize(forward + right * ((2.0f * sx - 1.0f) * tanHalfY * aspect) +
                          up * ((1.0f - 2.0f * sy) * tanHalfY));
  }
};

}  // namespace luxel
