// Recovering the quads that triangulation split, so that a quad-based mesher gets back the walls,
// floors and boxes that the modeller drew as quads.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "luxel/scene.h"

namespace luxel {

// Assimp's TriangulateProcess splits a convex quad (a,b,c,d) into the consecutive triangles
// (a,b,c), (a,c,d). Each such pair whose triangles are coplanar (unit normals within
// kQuadNormalTolerance) and whose quad is strictly convex becomes one Face {a,b,c,d}; every other
// triangle becomes Face {a,b,c,c}. Winding is preserved.
std::vector<Face> recoverQuads(const std::vector<Vec3>& positions,
                               const std::vector<std::array<uint32_t, 3>>& triangles);

// |n1 - n2| for the unit normals of the two halves, about 0.06 degrees.
constexpr float kQuadNormalTolerance = 1e-3f;

}  // namespace luxel
