// The vertex gather's mesh: see render/gather_mesh.h.
#include "render/gather_mesh.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "mesh/element_split.h"
#include "render/corner_values.h"

namespace luxel {

int GatherMesh::splitsFor(size_t solved, size_t wanted) {
  if (solved == 0 || wanted <= solved) return 0;
  // Each split multiplies the elements by 4: the nearest power in the ratio's logarithm.
  int splits = int(std::clamp(std::round(std::log(double(wanted) / double(solved)) / std::log(4.0)), 0.0, 4.0));
  while (splits > 0 && (solved << (2 * splits)) > kMaxGatherElements) --splits;
  return splits;
}

GatherMesh::GatherMesh(const Scene& scene, const SurfaceSet& solved, int splits, float maxArea)
    : solved_(solved) {
  bool large = false;
  for (const Element& e : solved.elements) large |= e.area > maxArea;
  if (splits <= 0 && !large) return;
  SurfaceSet& set = split_.emplace();
  set.faces = solved.faces;
  set.elements = solved.elements;
  for (Element& e : set.elements) e.patch = kNoPatch;
  set.elementSize = solved.elementSize / float(1 << splits);
  set.sceneExtent = solved.sceneExtent;
  set.objectTransforms = solved.objectTransforms;
  const size_t n = solved.elements.size();
  parent_.resize(n);
  local_.resize(n);
  for (uint32_t e = 0; e < n; ++e) {
    parent_[e] = e;
    local_[e] = wholeCorners(set.faces[set.elements[e].face].triangle);
  }
  set.elements.reserve(n << (2 * std::max(splits, 0)));
  const auto split = [&](uint32_t e) {
    const auto children = splitCorners(local_[e], set.faces[set.elements[e].face].triangle);
    set.splitElement(e, scene);  // child 0 stays at e, children 1 to 3 are appended in order
    local_[e] = children[0];
    for (int c = 1; c < 4; ++c) {
      local_.push_back(children[size_t(c)]);
      parent_.push_back(parent_[e]);
    }
  };
  for (int s = 0; s < splits; ++s) {
    const size_t count = set.elements.size();
    for (uint32_t e = 0; e < count; ++e) split(e);
  }
  for (int s = 0; s < kMaxLargeSplits && large; ++s) {
    large = false;
    const size_t count = set.elements.size();
    for (uint32_t e = 0; e < count; ++e)
      if (set.elements[e].area > maxArea) split(e), large = true;
  }
}

std::vector<Rgb> GatherMesh::corners(const std::vector<Rgb>& solvedCorners) const {
  if (!split_) return solvedCorners;
  std::vector<Rgb> out(split_->elements.size() * 4, Rgb(0.0f));
  tbb::parallel_for(uint32_t(0), uint32_t(split_->elements.size()), [&](uint32_t e) {
    const Rgb* c = &solvedCorners[size_t(parent_[e]) * 4];
    const int count = solved_.elements[parent_[e]].polygon.count;
    for (int k = 0; k < split_->elements[e].polygon.count; ++k)
      out[size_t(e) * 4 + size_t(k)] =
          interpolateCorners(c, count, local_[e][size_t(k)].x, local_[e][size_t(k)].y);
  });
  return out;
}
}  // namespace luxel
