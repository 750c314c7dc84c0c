// Multiresolution visibility over the face-cluster hierarchy: Gobbetti, Spano and Agus,
// "Hierarchical Higher Order Face Cluster Radiosity", Eurographics 2003, section 3.3.1 (notes 002,
// section 2.5), after the volume clustering of Sillion and Drettakis 1995. A ray descends the tree
// from its root, leaving every cluster whose oriented box it misses; a cluster whose shadow on the
// receiver would be smaller than `stopSize` stops the descent and passes the ray with its opacity,
// the visible projected area of the cluster along the ray over its box's; a single face is tested
// exactly. Opacities of the clusters a ray crosses multiply as transmittances. The choices the
// paper leaves open are settled in docs/algorithms.md ("Multiresolution visibility").
#pragma once

#include <cstdint>
#include <vector>

#include "cluster/face_cluster_tree.h"

namespace luxel {

class ClusterVisibility {
 public:
  // `tree` built over `surfaces.elements` (read here, not kept). `padding` grows every box
  // against rounding (and decides when a ray's end lies in one): best below the rays' offset
  // from the surfaces they leave, so that a ray leaving a flat cluster leaves its box before its
  // first point and the walk need not descend it.
  ClusterVisibility(const FaceClusterTree& tree, const SurfaceSet& surfaces, float padding);

  // The share of light that passes along org + t dir for t in (tnear, tfar): the receiver at org,
  // the emitter at org + dir. 1 where nothing is in the way, 0 where a face is; between, where
  // only clusters whose shadow on the receiver is smaller than `stopSize` (scene units) are. With
  // `stopSize` 0 every cluster is descended to its faces: the exact verdict.
  float transmittance(Vec3 org, Vec3 dir, float tnear, float tfar, float stopSize) const;

  // The opacity joined node `node` stands for along unit direction r: the larger of its
  // front-facing projected areas along r and -r (exact for a flat cluster, whose faces face one
  // way, and for a closed convex one, whose front and back cover the same silhouette), over its
  // box's projected area, at most 1.
  float opacity(uint32_t node, Vec3 r) const;

 private:
  // What the walk reads of a joined node. The tree's own boxes and projected areas are bounds
  // made from its children's, looser at every level up (the root's box of a unit ball has a half
  // extent of 6): here they are measured again from the node's faces. What every visit reads is
  // kept apart from what only some do, so that the walk's nodes stay in cache: the box as an
  // axis-aligned one (the first, cheap test), padded.
  struct WalkNode {
    Vec3 lo, hi;
    std::array<uint32_t, 2> child;
    float diagonal;   // of the box unpadded, for the shadow's size
    uint8_t aligned;  // the oriented box is the axis-aligned one: no second test
    uint8_t connected;
  };
  // The oriented box as measured, unpadded (tighter than the axis-aligned one, for boxes not
  // along the axes), and the projected areas along its axes, D+_j and D-_j, for the opacity.
  struct NodeShape {
    OrientedBox box;
    std::array<float, 6> axisAreas;
  };
  // Node ids of the walk: a leaf's is its element's, as in the tree; joined nodes follow the
  // leaves in the walk's order.
  uint32_t walkId(uint32_t treeNode) const {
    return treeNode < leaves_ ? treeNode : uint32_t(leaves_) + slot_[treeNode - leaves_];
  }
  float opacityAt(uint32_t i, Vec3 r) const;
  const WalkNode& walkNode(uint32_t i) const { return nodes_[i - leaves_]; }
  const NodeShape& shape(uint32_t i) const { return shapes_[i - leaves_]; }

  float padding_;
  std::vector<WalkNode> nodes_;    // per joined node
  std::vector<NodeShape> shapes_;  // per joined node
  std::vector<uint32_t> slot_;     // per joined node of the tree: its place in nodes_
  uint32_t root_ = kNoCluster;     // a walk id
  std::vector<Polygon> polygons_;  // per leaf: its element's polygon
  size_t leaves_ = 0;
};

}  // namespace luxel
