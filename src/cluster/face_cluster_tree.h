// The face-cluster hierarchy: a binary tree over a scene's elements whose every node is a
// connected, nearly planar, compact piece of surface, after Garland, Willmott and Heckbert,
// "Hierarchical Face Clustering on Polygonal Surfaces", I3D 2001 (greedy contraction of the dual
// graph, cheapest edge first), as Gobbetti, Spano and Agus, "Hierarchical Higher Order Face
// Cluster Radiosity", Eurographics 2003, section 3.1 build and query it. Pieces that share no edge
// (separate objects, or faces that only touch) are joined above the contracted components by a
// spatial median split, so that one root holds the whole scene.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "cluster/cluster_geometry.h"
#include "luxel/surface.h"

namespace luxel {

inline constexpr uint32_t kNoCluster = std::numeric_limits<uint32_t>::max();

struct FaceCluster {
  uint32_t begin = 0, count = 0;  // its elements: FaceClusterTree::order[begin, begin + count)
  std::array<uint32_t, 2> child{kNoCluster, kNoCluster};
  uint32_t parent = kNoCluster;
  float area = 0.0f;
  Vec3 vectorArea{0.0f};                // sum A_k n_k
  OrientedBox box;                      // z along the area-averaged normal
  std::array<float, 6> axisAreas{};     // D+_j, D-_j: projected area along +-box.axis[j]
  NormalCone cone;
  Rgb reflectance{0.0f};                // area-weighted mean
  // Made by contracting dual edges none of which is concave: the surface is locally convex
  // everywhere, so no part of it sees another (its self form factor is 0).
  bool convex = true;
  bool connected = true;                // false for nodes that join pieces sharing no edge (components, satellites)

  bool leaf() const { return child[0] == kNoCluster; }
  float minProjectedArea(Vec3 r) const { return luxel::minProjectedArea(vectorArea, r); }
  float maxProjectedArea(Vec3 r) const { return luxel::maxProjectedArea(box, axisAreas, r); }
  // Upper bound on the share of the light leaving the cluster that lands on itself (Willmott):
  // 1 - |sum A_k n_k| / A for a connected surface, 0 for a convex one, 1 for separate pieces.
  float selfFormFactorBound() const;
};

// Node e < elementCount() is the leaf of element e; the joined nodes follow, each after its
// children (a pass in index order is bottom-up), the root last. Only the joined nodes are
// stored: a leaf is its element's polygon, and is made from it when asked (node), which keeps
// half the nodes, 148 bytes a face, out of memory (docs/performance.md, "Face-cluster radiosity").
struct FaceClusterTree {
  std::vector<FaceCluster> inner;    // node elementCount() + k is inner[k]
  std::vector<uint32_t> order;       // element indices, each cluster's a contiguous run
  std::vector<uint32_t> leafParent;  // per element: its leaf's parent (kNoCluster for a lone root)
  std::vector<uint32_t> leafAt;      // per element: its place in order (its leaf's begin)
  uint32_t root = kNoCluster;
  uint32_t components = 0;           // connected components the contraction ended with
  double seconds = 0.0;              // build time

  size_t elementCount() const { return order.size(); }
  size_t nodeCount() const { return order.size() + inner.size(); }
  bool isLeaf(uint32_t i) const { return i < order.size(); }
  // Node i whole; a leaf made from `surfaces`, the set the tree was built on.
  FaceCluster node(uint32_t i, const SurfaceSet& surfaces) const;
  // A joined node, without a copy.
  const FaceCluster& joined(uint32_t i) const { return inner[i - order.size()]; }
  uint32_t parent(uint32_t i) const { return isLeaf(i) ? leafParent[i] : joined(i).parent; }
  // The run of order that node i covers.
  uint32_t begin(uint32_t i) const { return isLeaf(i) ? leafAt[i] : joined(i).begin; }
  uint32_t count(uint32_t i) const { return isLeaf(i) ? 1u : joined(i).count; }
  // The deepest leaf's depth (the root's is 0) and the leaves' mean depth: about log2 n for a
  // balanced tree; far more where big clusters grew by a face at a time.
  struct Depth {
    uint32_t max = 0;
    double meanLeaf = 0.0;
  };
  Depth depth() const;
  size_t bytes() const {
    return inner.capacity() * sizeof(FaceCluster) +
           (order.capacity() + leafParent.capacity() + leafAt.capacity()) * sizeof(uint32_t);
  }
};

// The leaf of one element, as a joined node's fields are made from its elements: its place in
// the tree's order and its parent given.
FaceCluster leafCluster(const Element& element, uint32_t at, uint32_t parent);

// Builds the hierarchy over `surfaces.elements`. Elements are adjacent when they share an edge
// (both corners at exactly the same position). Throws Error when there are no elements.
FaceClusterTree buildFaceClusterTree(const SurfaceSet& surfaces);

}  // namespace luxel
