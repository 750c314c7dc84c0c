#include "hierarchical/cluster_points.h"

#include <algorithm>

#include "transport/form_factor.h"

namespace luxel {

namespace {

float radicalInverse(uint32_t i, uint32_t base) {
  float inv = 1.0f / float(base), f = inv, r = 0.0f;
  while (i > 0) {
    r += f * float(i % base);
    i /= base;
    f *= inv;
  }
  return r;
}

float triangleArea(Vec3 a, Vec3 b, Vec3 c) { return 0.5f * glm::length(glm::cross(b - a, c - a)); }

}  // namespace

ClusterPoints::ClusterPoints(const FaceClusterTree& tree, const SurfaceSet& surfaces) : tree_(tree), surfaces_(surfaces) {
  cumulativeArea_.resize(tree.order.size() + 1, 0.0);
  for (size_t k = 0; k < tree.order.size(); ++k)
    cumulativeArea_[k + 1] = cumulativeArea_[k] + double(surfaces.elements[tree.order[k]].area);
}

void ClusterPoints::points(uint32_t node, int side, std::vector<SurfacePoint>& out) const {
  out.clear();
  const uint32_t at = tree_.begin(node), faces = tree_.count(node);  // its run of the tree's order
  const float k = float(side);
  if (faces == 1) {
    const uint32_t e = tree_.order[at];
    const Element& el = surfaces_.elements[e];
    const Polygon& p = el.polygon;
    if (p.count == 3) {
      // Sub-triangles of a regular split: upright ones at (i, j), inverted ones between them.
      const float w = 1.0f / (k * k);
      for (int i = 0; i < side; ++i)
        for (int j = 0; i + j < side; ++j) {
          const float s = (float(i) + 1.0f / 3.0f) / k, t = (float(j) + 1.0f / 3.0f) / k;
          out.push_back({p.v[0] + s * (p.v[1] - p.v[0]) + t * (p.v[2] - p.v[0]), el.normal, w, e});
          if (i + j + 1 < side) {
            const float si = (float(i) + 2.0f / 3.0f) / k, ti = (float(j) + 2.0f / 3.0f) / k;
            out.push_back({p.v[0] + si * (p.v[1] - p.v[0]) + ti * (p.v[2] - p.v[0]), el.normal, w, e});
          }
        }
      return;
    }
    float total = 0.0f;
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j) {
        const float s0 = float(i) / k, s1 = float(i + 1) / k, t0 = float(j) / k, t1 = float(j + 1) / k;
        const Vec3 a = polygonPoint(p, s0, t0), b = polygonPoint(p, s1, t0), cc = polygonPoint(p, s1, t1),
                   d = polygonPoint(p, s0, t1);
        const float area = triangleArea(a, b, cc) + triangleArea(a, cc, d);
        out.push_back({polygonPoint(p, (float(i) + 0.5f) / k, (float(j) + 0.5f) / k), el.normal, area, e});
        total += area;
      }
    for (SurfacePoint& s : out) s.weight = total > 0.0f ? s.weight / total : 1.0f / float(out.size());
    return;
  }
  const int count = side * side;
  const double base = cumulativeArea_[at], area = cumulativeArea_[at + faces] - base;
  const auto first = cumulativeArea_.begin() + std::ptrdiff_t(at) + 1;
  const auto last = cumulativeArea_.begin() + std::ptrdiff_t(at + faces) + 1;
  for (int i = 0; i < count; ++i) {
    const double target = base + area * (double(i) + 0.5) / double(count);
    auto it = std::upper_bound(first, last, target);
    if (it == last) --it;
    const uint32_t e = tree_.order[size_t(it - cumulativeArea_.begin()) - 1];
    const Element& el = surfaces_.elements[e];
    const uint32_t h = uint32_t(i) + 1 + node % 61;  // decorrelated between clusters, fixed per cluster
    out.push_back({polygonPoint(el.polygon, radicalInverse(h, 2), radicalInverse(h, 3)), el.normal, 1.0f / float(count), e});
  }
}

}  // namespace luxel
