// A moving object's solid, when its faces close a convex polyhedron: the half-spaces of its
// faces. Cross-redistribution uses it to prove without tracing that the light between two
// polygons, or along one ray, was blocked by the object before a move and still is after it, or
// passed it by and still does, so that their factor cannot have changed (van de Hoef 2013
// redistributes only "the radiosity that passes through the modified geometry"; a pair in the
// object's umbra at both places passes none).
//
// Why the corners decide: for a convex solid K and a point x, the set of points y whose segment
// [x, y] meets K is convex (x + s (k - x), k in K, s >= 1, is closed under convex combination).
// So if every segment between a corner of polygon A and a corner of polygon B meets K, then for
// each corner b of B the whole of A lies in that convex set of b, and then, for each point a of A,
// every corner of B lies in the convex set of a, and so does B: every segment between A and B
// meets K.
#pragma once

#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/surface.h"

namespace luxel {

class ConvexSolid {
 public:
  // The solid the polygons bound, when they are the outward faces of a closed convex polyhedron
  // of at most kMaxPlanes distinct planes, to within `tolerance` (a length); otherwise an empty
  // solid (valid() is false), which proves nothing.
  static ConvexSolid fromPolygons(std::span<const Polygon> polygons, float tolerance);

  static constexpr size_t kMaxPlanes = 32;

  bool valid() const { return !planes_.empty(); }

  // Whether the segment [a, b] meets the solid with its planes moved `inset` inwards (the points
  // at least `inset` deep inside it).
  bool segmentMeets(Vec3 a, Vec3 b, float inset) const;

  // What a segment does with the solid's faces wherever the solid stands within `margin` of here
  // (every point moved by less): Clear, it misses them (it misses the solid grown by margin);
  // Crosses, it meets them (it passes deeper than margin inside, with an end outside the solid
  // grown by margin); Unsure otherwise.
  enum class Segment { Clear, Crosses, Unsure };
  Segment classify(Vec3 a, Vec3 b, float margin) const;

  // Whether every segment between the two polygons (their convex hulls) meets the solid inset by
  // `inset`: tested on the corner pairs, which suffices (see the top of the file).
  bool blocksEverySegment(const Polygon& a, const Polygon& b, float inset) const;

  // Whether the polygon lies more than `gap` outside one of the solid's planes, and so outside the
  // solid grown by `gap`.
  bool separatedFrom(const Polygon& p, float gap) const;

 private:
  std::vector<glm::vec4> planes_;  // unit outward normal n and offset d: inside is n.x <= d
};

}  // namespace luxel
