// Scanned models at a prescribed face count, for seed 002's room (face_cluster_room.cpp): a model
// is welded into one indexed triangle mesh, cut by 1-to-4 midpoint subdivision until it has more
// faces than asked for, then simplified to the count by quadric error metrics (Garland and
// Heckbert, "Surface Simplification Using Quadric Error Metrics", SIGGRAPH 1997, the method seed
// 002 used for its ladder of 160K to 1.5M faces), through meshoptimizer's meshopt_simplify.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "luxel/scene.h"

namespace luxel::builtin {

struct TriangleMesh {
  std::vector<Vec3> positions;
  std::vector<std::array<uint32_t, 3>> triangles;  // counter-clockwise seen from the front
};

// Every face of every mesh of `scene` as triangles (a quad as two), with corners at bit-identical
// positions welded into one vertex: importers split vertices at uv and normal seams, and
// subdivision and simplification need the surface's own connectivity. Triangles that welding
// makes degenerate (two corners the same vertex) are dropped.
TriangleMesh weldedTriangles(const Scene& scene);

// 1-to-4 subdivision at the edges' midpoints: each triangle becomes its three corner triangles
// and the middle one; a midpoint is shared by both triangles of its edge, so a closed mesh stays
// closed. The shape does not change (every new vertex lies on an old face).
void subdivideMidpoints(TriangleMesh& mesh);

// `mesh` simplified to at most `triangles` triangles (edge collapses ordered by quadric error, no
// error limit: the count alone decides), unused vertices dropped. A mesh that has no more than
// `triangles` already comes back as it is.
TriangleMesh simplifyTo(const TriangleMesh& mesh, size_t triangles);

// `mesh` subdivided until it has at least `triangles` triangles, then simplified to them: the
// same surface at any face count, finer or coarser than the scan.
TriangleMesh withTriangleCount(TriangleMesh mesh, size_t triangles);

}  // namespace luxel::builtin
