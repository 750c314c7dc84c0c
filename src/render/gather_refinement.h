// Where a vertex gather's interpolation misses the shape of the light, the elements there get a
// lattice of gathered points. Next to a concave crease or a contact whose other side is lit, the
// indirect irradiance falls off within a fraction of an element (the near surface's form factor
// shrinks with the distance from it), and a straight line from the bright corner at the crease to
// the far corners overstates the element's light (docs/performance.md, "What the gather shows":
// Sibenik's sunlit sills).
//
// An element is refined when one of its corners met a surface nearer than half its size and a
// gather at its centre differs from the corners' interpolation there by more than
// kRefineDeviation (or lies inside a solid): its lattice has 2^L cells along each edge, L the
// levels that bring the lattice's spacing within twice the nearest corner's reach (at most
// kMaxRefineLevels, and in a picture at most what leaves a few pixels a cell), the bound of
// irradiance caching (Ward, Rubinstein and Clear, SIGGRAPH 1988) that VertexGather's split
// vertices follow. A lattice point is gathered where one of its
// element's corners saw a surface nearer than half its distance from the point, and interpolated
// from the corners elsewhere, so only the part of the element near the crease costs rays.
//
// No cracks: lattice points on an edge two elements of one smooth surface share are one gather,
// at the coarser of the two lattices; the finer side interpolates between them, as the coarser
// does. An element that is not refined keeps its straight edges, and its neighbours' lattices
// follow them there.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "luxel/surface.h"
#include "render/final_gather.h"

namespace luxel {

inline constexpr int kMaxRefineLevels = 3;
inline constexpr float kRefineDeviation = 0.1f;

class GatherRefinement {
 public:
  // Refines the elements of `surfaces` (the vertex gather's) with a weight above 0, gathering their
  // corners first; `elementWeights` as VertexGather's (an image's pixels per element). The lattice
  // points take as many rays as the fewest of their element's corners.
  // `pixels` (or none): how many pixels of a picture each element covers; an element's lattice
  // then has cells of a few pixels at least.
  GatherRefinement(const SurfaceSet& surfaces, VertexGather& vertices, std::span<const float> elementWeights,
                   std::span<const float> pixels = {});

  // The gathered irradiance at a hit on element e (RayTracer::intersect's u, v, as
  // interpolateCorners reads them).
  Rgb irradianceAt(uint32_t e, float u, float v) const;
  // Its mean over element e, as the picture interpolates it.
  Rgb mean(uint32_t e) const;

  // Lattice levels of element e (0: its corners alone).
  int level(uint32_t e) const { return levels_.empty() ? 0 : levels_[e]; }
  size_t refinedElements() const { return refined_; }
  // Lattice points made (shared ones once), and of them those gathered by rays.
  size_t pointsMade() const { return pointsMade_; }
  size_t pointsTraced() const { return pointsTraced_; }

 private:
  const SurfaceSet& surfaces_;
  VertexGather& vertices_;
  std::vector<uint8_t> levels_;
  std::vector<uint32_t> latticeStart_;  // per element: its lattice's first value in values_
  std::vector<Rgb> values_;
  size_t refined_ = 0, pointsMade_ = 0, pointsTraced_ = 0;
};

}  // namespace luxel
