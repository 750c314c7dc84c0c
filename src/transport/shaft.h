// Shaft culling: Haines and Wallace, "Shaft Culling for Efficient Ray-Cast Radiosity",
// Eurographics Workshop on Rendering 1991. The convex hull of two patches holds every segment
// between them; when no other face reaches into it, the pair is wholly visible, proved rather
// than sampled. (A handful of test rays can miss a small occluder and bias every element of the
// pair; the shaft cannot.)
#pragma once

#include <array>
#include <cstdint>
#include <functional>

#include <glm/glm.hpp>

#include "luxel/surface.h"

namespace luxel {

class RayTracer;

// A shaft with more candidate faces than this is left to its rays: scenes of many small faces (a
// wall cut into a thousand quads) put hundreds in every shaft's bounds, and past a few dozen the
// test costs more than the rays it spares.
inline constexpr int kMaxShaftCandidates = 48;

class Shaft {
 public:
  // The hull of the corners of `a` and `b`. `tolerance` is how far a face may reach into the
  // hull and still count as outside: faces that touch the shaft along an edge or lie in its
  // boundary plane (the walls of a room) block no ray that starts a ray offset off a surface.
  Shaft(const Polygon& a, const Polygon& b, float tolerance);

  // False when the hull is degenerate (flat): nothing can be proved about it.
  bool valid() const { return planeCount_ > 0; }
  Vec3 boundsMin() const { return lo_; }
  Vec3 boundsMax() const { return hi_; }
  // False only when `poly` certainly stays outside the shaft (conservative: may say true for a
  // polygon that misses it narrowly, never false for one that enters it).
  bool mayIntersect(const Polygon& poly) const;

 private:
  // Fixed capacity, no heap: a solve builds tens of thousands of shafts. At most 2 polygon planes
  // and 2 x 4 x 4 edge-corner planes; 8 corners.
  std::array<glm::vec4, 34> planes_;  // outward normal, offset: inside where dot(n, x) + w <= 0
  int planeCount_ = 0;
  std::array<Vec3, 8> points_;
  int pointCount_ = 0;
  Vec3 lo_{0.0f}, hi_{0.0f};
  float tolerance_ = 0.0f;
};

// Whether no face but `skipA` and `skipB` reaches into `shaft`: the candidates are the faces
// `faces` (a ray tracer over them) finds near the shaft's bounds, each one's polygon from
// `polygonOf`. False for a degenerate shaft, and past kMaxShaftCandidates candidates.
bool shaftIsClear(const Shaft& shaft, const RayTracer& faces, const std::function<Polygon(uint32_t)>& polygonOf,
                  uint32_t skipA, uint32_t skipB);

}  // namespace luxel
