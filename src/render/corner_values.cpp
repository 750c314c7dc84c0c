// Per-vertex values for smooth display: each element corner takes the area-weighted mean of the
// elements meeting there on the same smooth surface (Cohen and Wallace, "Radiosity and Realistic
// Image Synthesis", 1993, section 9.2: nodal averaging), so values never bleed across creases or
// material boundaries.
#include "render/corner_values.h"

#include <tbb/parallel_for.h>

#include "luxel/render.h"

namespace luxel {

std::vector<Rgb> elementCornerValues(const SurfaceSet& surfaces, const std::vector<Rgb>& perElement) {
  return elementCornerValues(surfaces, CornerGroups(surfaces, kDefaultCreaseCosine), perElement);
}

std::vector<Rgb> elementCornerValues(const SurfaceSet& surfaces, const CornerGroups& groups, const std::vector<Rgb>& perElement) {
  std::vector<Rgb> corners(surfaces.elements.size() * 4, Rgb(0.0f));
  tbb::parallel_for(uint32_t(0), uint32_t(surfaces.elements.size()), [&](uint32_t e) {
    const int count = surfaces.elements[e].polygon.count;
    for (int c = 0; c < count; ++c) {
      Rgb sum(0.0f);
      float area = 0.0f;
      for (uint32_t n : groups.at(e, c)) {
        sum += surfaces.elements[n].area * perElement[n];
        area += surfaces.elements[n].area;
      }
      corners[size_t(e) * 4 + size_t(c)] = area > 0.0f ? sum / area : perElement[e];
    }
  });
  return corners;
}

}  // namespace luxel
