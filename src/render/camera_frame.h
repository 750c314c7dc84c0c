// The pinhole camera of every renderer, and the checks on render options they share.
#pragma once

#include <cmath>

#include <fmt/format.h>

#include "luxel/error.h"
#include "luxel/render.h"

namespace luxel {

constexpr int kMaxImageSide = 32768;

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

inline void validateRenderOptions(const RenderOptions& o) {
  if (o.width < 1 || o.height < 1 || o.width > kMaxImageSide || o.height > kMaxImageSide)
    throw Error(fmt::format("image size {}x{} must be between 1 and {} a side", o.width, o.height, kMaxImageSide));
  if (o.samplesPerPixel < 1 || o.samplesPerPixel > 65536)
    throw Error(fmt::format("samples per pixel {} must be between 1 and 65536", o.samplesPerPixel));
  const Camera& c = o.camera;
  if (!(c.fovY > 0.0f && c.fovY < 180.0f))
    throw Error(fmt::format("camera '{}': field of view {} must be in (0, 180) degrees", c.name, c.fovY));
  Vec3 f = c.target - c.eye;
  if (!(glm::length(f) > 0.0f) || !(glm::length(glm::cross(f, c.up)) > 0.0f))
    throw Error(fmt::format("camera '{}': eye, target and up must span a frame", c.name));
}

}  // namespace luxel
