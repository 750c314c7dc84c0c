#include "cluster/cluster_visibility.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace luxel {
namespace {

// Where the line org + t dir meets a box: t in [lo, hi], empty when lo > hi. An oriented box grown
// by `pad` each way; an axis-aligned one by its corners and the ray's inverse direction.
struct Span {
  float lo, hi;
};
Span orientedSlabs(const OrientedBox& box, float pad, Vec3 org, Vec3 dir) {
  Span s{-std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity()};
  const Vec3 o = org - box.centre;
  for (int k = 0; k < 3; ++k) {
    const float ok = glm::dot(o, box.axis[size_t(k)]), dk = glm::dot(dir, box.axis[size_t(k)]);
    const float h = box.half[k] + pad;
    if (std::abs(dk) < 1e-30f) {
      if (std::abs(ok) > h) return {1.0f, 0.0f};
      continue;
    }
    float t0 = (-h - ok) / dk, t1 = (h - ok) / dk;
    if (t0 > t1) std::swap(t0, t1);
    s.lo = std::max(s.lo, t0), s.hi = std::min(s.hi, t1);
    if (s.lo > s.hi) return s;
  }
  return s;
}
Span alignedSlabs(Vec3 lo, Vec3 hi, Vec3 org, Vec3 invDir) {
  const Vec3 t0 = (lo - org) * invDir, t1 = (hi - org) * invDir;
  const Vec3 near = glm::min(t0, t1), far = glm::max(t0, t1);
  return {std::max({near.x, near.y, near.z}), std::min({far.x, far.y, far.z})};
}

// Whether the segment meets triangle (a, b, c) at t in (tnear, tfar), from either side
// (Moller and Trumbore 1997).
bool hitsTriangle(Vec3 org, Vec3 dir, float tnear, float tfar, Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 p = glm::cross(dir, e2);
  const float det = glm::dot(e1, p);
  if (det == 0.0f) return false;
  const float inv = 1.0f / det;
  const Vec3 s = org - a;
  const float u = glm::dot(s, p) * inv;
  if (u < 0.0f || u > 1.0f) return false;
  const Vec3 q = glm::cross(s, e1);
  const float v = glm::dot(dir, q) * inv;
  if (v < 0.0f || u + v > 1.0f) return false;
  const float t = glm::dot(e2, q) * inv;
  return t > tnear && t < tfar;
}

// A polygon as the ray tracer cuts it: (0, 1, 2) and, for a quad, (0, 2, 3).
bool hitsPolygon(Vec3 org, Vec3 dir, float tnear, float tfar, const Polygon& poly) {
  if (hitsTriangle(org, dir, tnear, tfar, poly.v[0], poly.v[1], poly.v[2])) return true;
  return poly.count == 4 && hitsTriangle(org, dir, tnear, tfar, poly.v[0], poly.v[2], poly.v[3]);
}

}  // namespace

ClusterVisibility::ClusterVisibility(const FaceClusterTree& tree, const SurfaceSet& surfaces,
                                     float padding)
    : padding_(padding), leaves_(tree.elementCount()) {
  polygons_.reserve(leaves_);
  for (size_t e = 0; e < leaves_; ++e) polygons_.push_back(surfaces.elements[e].polygon);
  // The joined nodes in the walk's own order, depth first from the root (the tree keeps them
  // bottom up, a node's children anywhere before it): a walk then reads nearby memory.
  slot_.assign(tree.inner.size(), 0);
  if (tree.root != kNoCluster && !tree.isLeaf(tree.root)) {
    std::vector<uint32_t> pending = {tree.root};
    uint32_t next = 0;
    while (!pending.empty()) {
      const uint32_t i = pending.back();
      pending.pop_back();
      slot_[i - leaves_] = next++;
      for (int k = 1; k >= 0; --k)
        if (!tree.isLeaf(tree.joined(i).child[size_t(k)]))
          pending.push_back(tree.joined(i).child[size_t(k)]);
    }
    root_ = walkId(tree.root);
  } else {
    root_ = tree.root;
  }
  nodes_.resize(tree.inner.size());
  shapes_.resize(tree.inner.size());
  // Each node's faces are a run of the tree's order: every level scans them all once.
  tbb::parallel_for(size_t(0), tree.inner.size(), [&](size_t k) {
    const FaceCluster& c = tree.inner[k];
    WalkNode& n = nodes_[slot_[k]];
    NodeShape& shape = shapes_[slot_[k]];
    n.child = {walkId(c.child[0]), walkId(c.child[1])};
    n.connected = c.connected;
    // Two boxes measured: along the tree's axes (the normal and its calipers) and along the
    // world's; the one with less surface, so less mean projected area, is kept (a closed cube's
    // vector area is zero, and its tree box turns any way).
    const std::array<std::array<Vec3, 3>, 2> axes = {
        c.box.axis, std::array<Vec3, 3>{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}};
    std::array<Vec3, 2> lo, hi;
    std::array<std::array<float, 6>, 2> areas{};
    lo.fill(Vec3(std::numeric_limits<float>::max())),
        hi.fill(Vec3(-std::numeric_limits<float>::max()));
    for (uint32_t i = c.begin; i < c.begin + c.count; ++i) {
      const Element& e = surfaces.elements[tree.order[i]];
      for (size_t b = 0; b < 2; ++b) {
        for (int v = 0; v < e.polygon.count; ++v) {
          const Vec3 p = e.polygon.v[size_t(v)];
          const Vec3 a(glm::dot(p, axes[b][0]), glm::dot(p, axes[b][1]), glm::dot(p, axes[b][2]));
          lo[b] = glm::min(lo[b], a), hi[b] = glm::max(hi[b], a);
        }
        for (size_t j = 0; j < 3; ++j) {
          const float d = e.area * glm::dot(e.normal, axes[b][j]);
          areas[b][j] += std::max(0.0f, d), areas[b][j + 3] += std::max(0.0f, -d);
        }
      }
    }
    auto surface = [&](size_t b) {
      const Vec3 h = 0.5f * (hi[b] - lo[b]);
      return h.x * h.y + h.y * h.z + h.z * h.x;
    };
    const size_t b = surface(1) <= surface(0) ? 1 : 0;
    OrientedBox& box = shape.box;
    box.axis = axes[b];
    shape.axisAreas = areas[b];
    const Vec3 mid = 0.5f * (lo[b] + hi[b]);
    box.centre = mid.x * box.axis[0] + mid.y * box.axis[1] + mid.z * box.axis[2];
    box.half = 0.5f * (hi[b] - lo[b]);
    n.diagonal = 2.0f * glm::length(box.half);
    // The padded oriented box's extent along each world axis.
    Vec3 extent(0.0f);
    for (int j = 0; j < 3; ++j) extent += glm::abs(box.axis[size_t(j)]) * (box.half[j] + padding);
    n.lo = box.centre - extent, n.hi = box.centre + extent;
    n.aligned = b == 1;
  });
}

float ClusterVisibility::opacity(uint32_t node, Vec3 r) const { return opacityAt(walkId(node), r); }

float ClusterVisibility::opacityAt(uint32_t i, Vec3 r) const {
  const NodeShape& n = shape(i);
  const Vec3 half = n.box.half;
  float boxArea = 0.0f;
  for (int j = 0; j < 3; ++j)
    boxArea +=
        std::abs(glm::dot(r, n.box.axis[size_t(j)])) * 4.0f * half[(j + 1) % 3] * half[(j + 2) % 3];
  if (!(boxArea > 0.0f)) return 0.0f;  // a box seen edge-on: the ray grazes a flat cluster
  // Willmott's bound from the six samples (cluster/cluster_geometry.h), along r and along -r.
  const float front = maxProjectedArea(n.box, n.axisAreas, r),
              back = maxProjectedArea(n.box, n.axisAreas, -r);
  return std::min(1.0f, std::max(front, back) / boxArea);
}

float ClusterVisibility::transmittance(Vec3 org, Vec3 dir, float tnear, float tfar,
                                       float stopSize) const {
  if (root_ == kNoCluster || !(tfar > tnear)) return 1.0f;
  // A zero component divided would give 0 * inf = NaN where org lies on a box's face: a tiny one
  // keeps the products finite or infinite.
  Vec3 invDir;
  for (int k = 0; k < 3; ++k)
    invDir[k] = 1.0f / (std::abs(dir[k]) < 1e-30f ? std::copysign(1e-30f, dir[k]) : dir[k]);
  const Vec3 unitDir = glm::normalize(dir);
  // A depth-first walk; a tree's depth bounds the stack, and trees of hundreds of levels exist
  // (docs/performance.md), so the stack grows rather than being fixed.
  thread_local std::vector<uint32_t> stack;
  stack.clear();
  stack.push_back(root_);
  float passed = 1.0f;
  while (!stack.empty()) {
    const uint32_t i = stack.back();
    stack.pop_back();
    if (i < leaves_) {
      if (hitsPolygon(org, dir, tnear, tfar, polygons_[i])) return 0.0f;
      continue;
    }
    const WalkNode& n = walkNode(i);
    Span s = alignedSlabs(n.lo, n.hi, org, invDir);
    if (std::max(s.lo, tnear) > std::min(s.hi, tfar)) continue;
    if (!n.aligned) {
      s = orientedSlabs(shape(i).box, padding_, org, dir);
    }
    const float enter = std::max(s.lo, tnear), leave = std::min(s.hi, tfar);
    if (enter > leave) continue;
    // A cluster stands for its faces only where its shadow is too small to tell apart on the
    // receiver (its size seen from the emitter's end, t = 1, cast to the receiver's, t = 0), and
    // only as an occluder: never one the ray starts or ends in, whose own faces it leaves or
    // reaches, nor a join of pieces that share no edge, whose parts are separate occluders.
    const bool endsInside = !(s.lo > tnear) || !(s.hi < tfar);
    if (n.connected && !endsInside && n.diagonal < stopSize * std::max(1.0f - leave, 1e-6f)) {
      // The faces lie in the box unpadded: a ray that passes only through the padding (along a
      // flat cluster, just off its plane) meets none of them, and its opacity does not apply.
      const Span faces = orientedSlabs(shape(i).box, 0.0f, org, dir);
      if (std::max(faces.lo, tnear) <= std::min(faces.hi, tfar))
        passed *= 1.0f - opacityAt(i, unitDir);
      if (passed <= 0.0f) return 0.0f;
      continue;
    }
    stack.push_back(n.child[0]);
    stack.push_back(n.child[1]);
  }
  return passed;
}

}  // namespace luxel
