#include "view_camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace luxel::viewer {
namespace {

constexpr float kMaxPitch = glm::radians(89.0f);

}  // namespace

ViewCamera::ViewCamera(const Camera& camera, Vec3 sceneUp, float sceneExtent)
    : position_(camera.eye), fovY_(camera.fovY), extent_(sceneExtent > 0.0f ? sceneExtent : 1.0f) {
  up_ = glm::length(sceneUp) > 0.0f ? glm::normalize(sceneUp) : Vec3(0.0f, 1.0f, 0.0f);
  // Any horizontal axis will do as the zero of yaw; the one least parallel to up is stable.
  const Vec3 a = std::abs(up_.x) < 0.9f ? Vec3(1.0f, 0.0f, 0.0f) : Vec3(0.0f, 0.0f, 1.0f);
  east_ = glm::normalize(a - up_ * glm::dot(a, up_));
  north_ = glm::cross(up_, east_);
  Vec3 f = camera.target - camera.eye;
  setForward(glm::length(f) > 0.0f ? f : -north_);
}

void ViewCamera::setForward(Vec3 f) {
  f = glm::normalize(f);
  pitch_ = std::clamp(std::asin(std::clamp(glm::dot(f, up_), -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
  const Vec3 h = f - up_ * glm::dot(f, up_);
  yaw_ = glm::length(h) > 1e-6f ? std::atan2(glm::dot(h, north_), glm::dot(h, east_)) : yaw_;
}

Vec3 ViewCamera::forward() const {
  const Vec3 h = east_ * std::cos(yaw_) + north_ * std::sin(yaw_);
  return h * std::cos(pitch_) + up_ * std::sin(pitch_);
}

Vec3 ViewCamera::right() const { return glm::normalize(glm::cross(forward(), up_)); }

Camera ViewCamera::toCamera() const {
  Camera c;
  c.name = "viewer";
  c.eye = position_;
  c.target = position_ + forward();
  c.up = up_;
  c.fovY = fovY_;
  return c;
}

void ViewCamera::walk(Vec3 m) {
  const Vec3 f = forward();
  Vec3 ground = f - up_ * glm::dot(f, up_);
  ground = glm::length(ground) > 1e-6f ? glm::normalize(ground) : glm::cross(up_, right());
  position_ += right() * m.x + up_ * m.y + ground * m.z;
}

void ViewCamera::look(float dyaw, float dpitch) {
  yaw_ = std::remainder(yaw_ + dyaw, 2.0f * glm::pi<float>());
  pitch_ = std::clamp(pitch_ + dpitch, -kMaxPitch, kMaxPitch);
}

void ViewCamera::orbit(Vec3 pivot, float dyaw, float dpitch) {
  const float distance = glm::length(pivot - position_);
  setForward(distance > 0.0f ? pivot - position_ : forward());
  look(dyaw, dpitch);
  position_ = pivot - forward() * distance;
}

void ViewCamera::dolly(Vec3 pivot, float factor) {
  const Vec3 to = pivot - position_;
  if (factor >= 1.0f || glm::length(to) <= 1e-6f * extent_) return;  // never onto or past the pivot
  position_ += to * factor;
}

glm::mat4 ViewCamera::view() const { return glm::lookAt(position_, position_ + forward(), up_); }

float ViewCamera::farPlane(Vec3 centre) const { return glm::length(centre - position_) + extent_; }
// 1e-4 of the far plane keeps a 24-bit depth buffer's precision near what the eye sees, and never
// less than 1e-5 of the scene, so a camera at a wall still sees it.
float ViewCamera::nearPlane(Vec3 centre) const { return std::max(1e-4f * farPlane(centre), 1e-5f * extent_); }

glm::mat4 ViewCamera::projection(float aspect, Vec3 centre) const {
  // Reversed depth (near at 1, infinity at 0, glClipControl's zero-to-one range) in a float depth
  // buffer: precision stays relative at every distance, and shadow volumes' far caps at infinity
  // are inside the frustum (z-fail needs them). With the usual mapping, a lamp 0.1 mm below a
  // ceiling seen from a metre away fought the ceiling for its pixels.
  const float f = 1.0f / std::tan(0.5f * glm::radians(fovY_));
  glm::mat4 p(0.0f);
  p[0][0] = f / aspect;
  p[1][1] = f;
  p[2][3] = -1.0f;               // clip w = -z_eye
  p[3][2] = nearPlane(centre);   // clip z = near: depth = near / -z_eye
  return p;
}

}  // namespace luxel::viewer
