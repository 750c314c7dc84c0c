// Test geometry: a closed ball whose radius wobbles, for the face-cluster tests.
#pragma once

#include <numbers>
#include <random>

#include "luxel/scene.h"

namespace luxel::test {

// A closed sphere whose radius wobbles (a crumpled ball: convex and concave parts), outward.
inline Scene crumpledBall(int rings, int segments, float wobble, uint32_t seed) {
  Scene scene;
  scene.name = "crumpled";
  scene.materials.push_back(Material{});
  Mesh mesh;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-wobble, wobble);
  mesh.positions.push_back(Vec3(0, 1 + u(rng), 0));
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const float theta = std::numbers::pi_v<float> * float(r) / float(rings);
      const float phi = 2.0f * std::numbers::pi_v<float> * float(s) / float(segments);
      const float radius = 1.0f + u(rng);
      mesh.positions.push_back(radius * Vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
    }
  mesh.positions.push_back(Vec3(0, -1 + u(rng), 0));
  const uint32_t bottom = uint32_t(mesh.positions.size() - 1);
  auto ring = [&](int r, int s) { return uint32_t(1 + (r - 1) * segments + (s % segments)); };
  auto tri = [&](uint32_t a, uint32_t b, uint32_t c) { mesh.faces.push_back(Face{{a, b, c, c}}); };
  for (int s = 0; s < segments; ++s) {
    tri(0, ring(1, s + 1), ring(1, s));
    tri(bottom, ring(rings - 1, s), ring(rings - 1, s + 1));
    for (int r = 1; r < rings - 1; ++r) {
      tri(ring(r, s), ring(r, s + 1), ring(r + 1, s + 1));
      tri(ring(r, s), ring(r + 1, s + 1), ring(r + 1, s));
    }
  }
  scene.meshes.push_back(std::move(mesh));
  return scene;
}

}  // namespace luxel::test
