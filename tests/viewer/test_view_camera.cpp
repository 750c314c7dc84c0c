// The viewer's camera: it sees through the same pinhole as `luxel render` (render/camera_frame.h),
// walks on the ground, and orbits about a pivot without drifting.
#include <gtest/gtest.h>

#include <cmath>

#include "render/camera_frame.h"
#include "view_camera.h"

namespace {

using luxel::Camera;
using luxel::Vec3;
using luxel::viewer::ViewCamera;

Camera camera(Vec3 eye, Vec3 target, float fov = 45.0f) {
  Camera c;
  c.eye = eye;
  c.target = target;
  c.fovY = fov;
  return c;
}

TEST(ViewCamera, KeepsTheEyeAndTheDirectionOfTheCameraItStartsFrom) {
  for (Vec3 up : {Vec3(0, 1, 0), Vec3(0, 0, 1), glm::normalize(Vec3(1, 1, 0))}) {
    const Camera c = camera(Vec3(1, 2, 3), Vec3(-2, 0.5f, -1), 60.0f);
    const ViewCamera v(c, up, 10.0f);
    const Camera back = v.toCamera();
    EXPECT_NEAR(glm::length(back.eye - c.eye), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(glm::normalize(back.target - back.eye), glm::normalize(c.target - c.eye)), 1.0f, 1e-5f);
    EXPECT_FLOAT_EQ(back.fovY, 60.0f);
  }
}

// A point on the ray through pixel (sx, sy) of `luxel render`'s camera projects to that pixel.
TEST(ViewCamera, ProjectsAsTheRendererCastsRays) {
  const Camera c = camera(Vec3(0.3f, 1.0f, 3.5f), Vec3(0.0f, 0.9f, 0.0f), 50.0f);
  const ViewCamera v(c, Vec3(0, 1, 0), 4.0f);
  const int width = 320, height = 200;
  const luxel::CameraFrame frame(v.toCamera(), width, height);
  const glm::mat4 vp = v.projection(float(width) / float(height), Vec3(0, 1, 0)) * v.view();
  for (float sx : {0.1f, 0.5f, 0.93f})
    for (float sy : {0.05f, 0.5f, 0.8f}) {
      const Vec3 p = frame.eye + frame.direction(sx, sy) * 2.7f;
      const glm::vec4 clip = vp * glm::vec4(p, 1.0f);
      EXPECT_NEAR(clip.x / clip.w, 2.0f * sx - 1.0f, 1e-4f);
      EXPECT_NEAR(clip.y / clip.w, 1.0f - 2.0f * sy, 1e-4f);  // NDC y up, image rows down
    }
}

TEST(ViewCamera, WalksOnTheGroundWhateverThePitch) {
  ViewCamera v(camera(Vec3(0, 1, 0), Vec3(0, 3, -1)), Vec3(0, 1, 0), 10.0f);  // looking steeply up
  v.walk(Vec3(0, 0, 2));
  EXPECT_NEAR(v.position().y, 1.0f, 1e-6f);
  EXPECT_NEAR(v.position().z, -2.0f, 1e-5f);
  v.walk(Vec3(1, 0, 0));  // right of looking down -z is +x
  EXPECT_NEAR(v.position().x, 1.0f, 1e-5f);
  v.walk(Vec3(0, 0.5f, 0));
  EXPECT_NEAR(v.position().y, 1.5f, 1e-6f);
}

TEST(ViewCamera, PitchStopsShortOfTheZenith) {
  ViewCamera v(camera(Vec3(0), Vec3(0, 0, -1)), Vec3(0, 1, 0), 1.0f);
  v.look(0.0f, 10.0f);
  EXPECT_LT(v.forward().y, std::sin(glm::radians(89.01f)));
  EXPECT_GT(v.forward().y, std::sin(glm::radians(88.99f)));
  EXPECT_NEAR(glm::length(v.right()), 1.0f, 1e-5f);  // still a frame
}

TEST(ViewCamera, OrbitKeepsThePivotInTheMiddleAtTheSameDistance) {
  const Vec3 pivot(1, 0.5f, -2);
  ViewCamera v(camera(Vec3(1, 1.5f, 2), pivot), Vec3(0, 1, 0), 5.0f);
  const float distance = glm::length(pivot - v.position());
  for (int i = 0; i < 100; ++i) v.orbit(pivot, 0.2f, i % 2 ? 0.05f : -0.03f);
  EXPECT_NEAR(glm::length(pivot - v.position()), distance, 1e-4f * distance);
  EXPECT_NEAR(glm::dot(v.forward(), glm::normalize(pivot - v.position())), 1.0f, 1e-5f);
  v.dolly(pivot, 0.5f);
  EXPECT_NEAR(glm::length(pivot - v.position()), 0.5f * distance, 1e-4f * distance);
  v.dolly(pivot, 1.5f);  // never onto or past the pivot
  EXPECT_NEAR(glm::length(pivot - v.position()), 0.5f * distance, 1e-4f * distance);
}

TEST(ViewCamera, ClipPlanesHoldTheSceneFromInsideAndOutside) {
  const Vec3 centre(0, 1, 0);
  for (Vec3 eye : {Vec3(0, 1, 0.5f), Vec3(0, 1, 30)}) {
    const ViewCamera v(camera(eye, centre + Vec3(0, 0, -1)), Vec3(0, 1, 0), 3.0f);
    EXPECT_GT(v.farPlane(centre), glm::length(eye - centre) + 1.5f);  // the far side of the bounds
    EXPECT_GT(v.nearPlane(centre), 0.0f);
    EXPECT_LT(v.nearPlane(centre), 1e-3f * v.farPlane(centre));
  }
}

}  // namespace
