// The viewer's camera: a position and a heading (yaw and pitch about the scene's up), for walking
// (WASD and mouse look) and for orbiting a pivot, convertible to and from luxel::Camera so that the
// viewer and `luxel render` see through the same pinhole.
#pragma once

#include <glm/glm.hpp>

#include "luxel/scene.h"

namespace luxel::viewer {

class ViewCamera {
 public:
  // Looks as `camera` does, in a scene whose zenith is `sceneUp`; walking speed and clip planes
  // scale with `sceneExtent` (the bounding box's diagonal).
  ViewCamera(const Camera& camera, Vec3 sceneUp, float sceneExtent);

  Camera toCamera() const;  // eye, a target one unit ahead, the scene's up, the field of view
  Vec3 position() const { return position_; }
  Vec3 forward() const;
  Vec3 right() const;
  Vec3 up() const { return up_; }
  float fovY() const { return fovY_; }
  float yaw() const { return yaw_; }
  float pitch() const { return pitch_; }
  float walkSpeed() const { return 0.2f * extent_; }  // scene units per second

  // Moves by `amount` scene units along the camera's right, the scene's up and the camera's
  // forward projected on the ground (walking does not climb when looking up).
  void walk(Vec3 rightUpForward);
  // Turns the heading (radians); pitch stays within 89 degrees of the horizon.
  void look(float yawRadians, float pitchRadians);
  // Turns about `pivot` at a fixed distance, keeping the pivot in the centre of the view.
  void orbit(Vec3 pivot, float yawRadians, float pitchRadians);
  // Moves towards `pivot` by a factor of the distance (0.5: half-way; negative: away).
  void dolly(Vec3 pivot, float factor);

  glm::mat4 view() const;
  // OpenGL clip space with reversed depth in [0, 1] (the near plane at 1, infinity at 0:
  // glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE), a GL_GREATER test), the near plane from the
  // scene's extent and where the camera stands relative to `sceneCentre`.
  glm::mat4 projection(float aspect, Vec3 sceneCentre) const;
  float nearPlane(Vec3 sceneCentre) const;
  float farPlane(Vec3 sceneCentre) const;

 private:
  void setForward(Vec3 forward);

  Vec3 position_{0.0f};
  Vec3 up_{0.0f, 1.0f, 0.0f};
  Vec3 east_{1.0f, 0.0f, 0.0f}, north_{0.0f, 0.0f, -1.0f};  // the horizontal frame yaw is measured in
  float yaw_ = 0.0f, pitch_ = 0.0f;
  float fovY_ = 45.0f;
  float extent_ = 1.0f;
};

}  // namespace luxel::viewer
