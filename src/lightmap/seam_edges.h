// Seam candidates for the lightmap baker (lightmap_bake.cpp): which face edges lie on one another
// in 3D. Shared edges and T-junctions (a long edge against several short ones) both count.
#pragma once

#include <cstdint>
#include <vector>

#include "luxel/surface.h"

namespace luxel::lightmap {

struct SeamEdge {
  uint32_t face = 0;  // edges of one face are never paired
  Vec3 a{0.0f}, b{0.0f};
};

// Edges `first` < `second` (indices into the input) overlap: both ends of `second` lie within eps
// of `first`'s line, and they share the stretch [s0, s1] of `first`, in distances from its end a
// (0 <= s0, s1 <= |b - a|, s1 - s0 > eps). `first` itself is longer than eps.
struct EdgeOverlap {
  uint32_t first = 0, second = 0;
  float s0 = 0.0f, s1 = 0.0f;
};

// The test for one ordered pair (i < j), in the arithmetic the baker has always used.
bool edgesOverlap(const SeamEdge& e0, const SeamEdge& e1, float eps, float* s0, float* s1);

// Every overlapping pair of edges of different faces, sorted by (first, second): exactly the pairs
// that testing all n^2/2 pairs finds, in roughly linear time (Sibenik's 224,000 edges: 0.2 s on 2
// cores). Candidates come from grids of cells whose side doubles from level to level: an edge lies
// in the cells its segment, grown by 2 eps, passes through at the level of its own size (capped
// near the median size, so long edges lie in many small cells), and looks in the cells it passes
// through at its level and every coarser one; pairs that are not parallel within 2 eps are
// dropped before the exact test. Two overlapping edges share a point within eps of both, so they
// always meet in a cell: near-equal vertices cannot be split by rounding, as hashed endpoints can.
std::vector<EdgeOverlap> overlappingEdges(const std::vector<SeamEdge>& edges, float eps);

}  // namespace luxel::lightmap
