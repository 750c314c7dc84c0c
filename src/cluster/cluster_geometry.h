// Geometry a face cluster answers queries with (Willmott's bounds as Gobbetti, Spano and Agus,
// "Hierarchical Higher Order Face Cluster Radiosity", Eurographics 2003, section 3.1, use them):
// an oriented box whose z axis follows the area-averaged normal and whose x and y axes minimise
// its volume (rotating calipers over the 2-D hull, Freeman and Shapira 1975), lower and upper
// bounds on the projected area in a direction, and a cone bounding the face normals.
#pragma once

#include <array>
#include <span>

#include "luxel/scene.h"

namespace luxel {

struct OrientedBox {
  Vec3 centre{0.0f};
  std::array<Vec3, 3> axis{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};  // orthonormal; axis[2] the normal
  Vec3 half{0.0f};                                                          // half extents along the axes

  std::array<Vec3, 8> corners() const;
  // Parameters of `p` on the box's horizontal plane: (0,0) to (1,1) over the box.
  Vec2 planeParameters(Vec3 p) const;
  // Distance from `p` to the box; 0 inside.
  float distance(Vec3 p) const;
};

// The smallest-volume box with z along `normal` (unit) that holds `points`: the 2-D hull of the
// points projected on the plane, each hull edge tried as the rectangle's side.
OrientedBox fitOrientedBox(std::span<const Vec3> points, Vec3 normal);

// Every unit normal n of a cluster satisfies dot(n, axis) >= cosHalfAngle.
struct NormalCone {
  Vec3 axis{0.0f, 0.0f, 1.0f};
  float cosHalfAngle = 1.0f;  // -1: any direction
};
NormalCone mergeCones(const NormalCone& a, const NormalCone& b);

// Whether a cluster whose normals lie in `cone` and whose faces lie in `from` may have a face
// that sees any point of `to` from its front. False only when provably not: every direction from
// a point of `from` to a point of `to` is at least 90 degrees plus the cone's half angle away from
// the cone's axis. The directions form the Minkowski difference of the boxes, a convex polytope
// whose vertices are corner differences, and the allowed set is a convex cone: checking the 64
// corner differences is exact.
bool mayFace(const NormalCone& cone, const OrientedBox& from, const OrientedBox& to);

// Whether every face of a cluster (normals in `cone`, faces in `from`) has every point of `to`
// strictly in front of it: n . d > 0 for every normal n and every direction d from `from` to
// `to`, i.e. every d within 90 degrees minus the half angle of the axis (the same corner argument
// as mayFace). Light from such a `to` adds to a cluster's vector irradiance without any face
// seeing it from behind, so the sum of vectors stays exact when each face takes its dot product.
// `slack` (a sine) lets `to` reach that far below the faces' horizons: light from there arrives at
// grazing angles and weighs little, while without it every pair of boxes that meet at a corner
// of a room would fail.
bool whollyFaces(const NormalCone& cone, const OrientedBox& from, const OrientedBox& to, float slack = 0.0f);

// Bounds on a cluster's front-facing projected area sum_k A_k max(0, n_k . r) in direction r (not
// necessarily unit; both are homogeneous of degree 1 in r): the lower bound from the vector area
// sum_k A_k n_k, the upper from the samples D+_j, D-_j of the projected area along the box's six
// axis directions (Willmott; Gobbetti et al. 2003, section 3.1).
inline float minProjectedArea(Vec3 vectorArea, Vec3 r) { return std::max(0.0f, glm::dot(vectorArea, r)); }
float maxProjectedArea(const OrientedBox& box, const std::array<float, 6>& axisAreas, Vec3 r);

// The smallest eigenvalue of a symmetric 3x3 matrix (xx, yy, zz, xy, xz, yz), by the
// trigonometric closed form (Smith 1961).
double smallestEigenvalue(const std::array<double, 6>& m);

}  // namespace luxel
