// Points on the actual surface of a face cluster, for the coupling integrals and their visibility
// rays. Gobbetti et al. 2003 put cubature nodes on the cluster's box plane; a node there may lie
// inside or behind the cluster's own faces (a bumpy statue, a wall's corner), where a ray says
// nothing about the light the surface gets. Points on the faces themselves, with their own
// normals, make the emitter integral and its visibility those of the real surface, self-shadowing
// included (docs/algorithms.md, "Face-cluster radiosity").
#pragma once

#include <cstdint>
#include <vector>

#include "cluster/face_cluster_tree.h"

namespace luxel {

struct SurfacePoint {
  Vec3 position{0.0f};
  Vec3 normal{0.0f};
  float weight = 0.0f;  // share of the cluster's area: the weights sum to 1
  uint32_t element = 0;
};

class ClusterPoints {
 public:
  ClusterPoints(const FaceClusterTree& tree, const SurfaceSet& surfaces);

  // About side^2 points on cluster `node`. One element: the midpoints of a side x side split of
  // it (for a triangle, its side^2 congruent sub-triangles' centroids; for a quad, the cells of
  // its bilinear map), weighted by their areas. More: side^2 points stratified by area along the
  // cluster's elements (contiguous and spatially coherent in the tree's order), each placed in
  // its element by a Halton pair, weighted equally.
  void points(uint32_t node, int side, std::vector<SurfacePoint>& out) const;

 private:
  const FaceClusterTree& tree_;
  const SurfaceSet& surfaces_;
  std::vector<double> cumulativeArea_;  // over tree.order, with a leading 0
};

}  // namespace luxel
