// The shadow volumes' casters (seed 004 section 3.2, back-facing polygons as casters) as triangles
// with adjacency, so that a volume's sides are drawn only along its silhouette: where a caster's
// neighbour across an edge faces the light, or has none. Two back-facing neighbours' sides along
// their shared edge would be drawn with opposite windings and cancel in the stencil count, so
// leaving both out counts the same (McGuire et al., "Fast, Practical and Robust Shadows", 2003)
// and fills far less: each face extruded on its own was under 1 fps on Sibenik even on a GPU.
#pragma once

#include <cstdint>
#include <vector>

#include "luxel/surface.h"

namespace luxel::viewer {

struct CasterMesh {
  std::vector<Vec3> vertices;  // corners at exactly the same position welded into one
  // Six indices per triangle, for GL_TRIANGLES_ADJACENCY: a, n_ab, b, n_bc, c, n_ca, where n_pq is
  // the third corner of the triangle that shares edge p-q in the opposite direction. An edge with
  // no such neighbour (the mesh's border), or shared by more than two triangles, or by two wound
  // the same way, names the triangle's own third corner: that "neighbour" is the triangle turned
  // over, so the edge is always drawn, as the face on its own would draw it.
  std::vector<uint32_t> adjacency;
};

// Each face of `surfaces` as triangles (a quad as 0-1-2 and 0-2-3).
CasterMesh casterMesh(const SurfaceSet& surfaces);

}  // namespace luxel::viewer
