// Texel-space geometry of one face for the lightmap baker (texel_elements.cpp, lightmap_bake.cpp):
// the affine maps between a face's texel-space triangles and the world.
#pragma once

#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/surface.h"

namespace luxel::lightmap {

// The signed area of a polygon (counter-clockwise positive).
double area2(const std::vector<glm::dvec2>& polygon);
// Sutherland-Hodgman clip of `polygon` by the counter-clockwise convex polygon `clip`.
std::vector<glm::dvec2> clipConvex(std::vector<glm::dvec2> polygon, const std::vector<glm::dvec2>& clip);

struct FaceMap {
  FaceMap(const SurfaceFace& face, const std::array<Vec2, 4>& texel);
  int n = 3;
  glm::dvec2 t[4];
  Vec3 w[4];
  Vec2 uv[4];
  double texelArea = 0.0;
  bool convex = true;
  std::vector<glm::dvec2> clip;  // the face in texel space, counter-clockwise

  // The triangle (0, k, k+1) that best holds q, its barycentrics in *b; returns k.
  int triangleOf(glm::dvec2 q, glm::dvec3* b) const;
  Vec3 world(glm::dvec2 texel) const;
  Vec2 uvAt(glm::dvec2 texel) const;   // the face's material UV
  glm::dvec2 texelOf(Vec3 p) const;    // inverse of world() for points on the face
  glm::dvec2 clampInside(glm::dvec2 texel) const;
  // The square [x0, x0+size] x [y0, y0+size] clipped to the face (to the triangle holding
  // `inside` when the face is a quad that is not convex in texel space).
  std::vector<glm::dvec2> clipSquare(double x0, double y0, double size, glm::dvec2 inside) const;
  std::pair<Polygon, float> worldPolygon(std::vector<glm::dvec2> texelPolygon, Vec3 normal) const;
};

}  // namespace luxel::lightmap
