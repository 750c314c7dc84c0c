#include "solve/radiosity_system.h"

namespace luxel {

RadiositySystem::RadiositySystem(const SurfaceSet& set, std::vector<Rgb> analyticIrradiance)
    : surfaces(set), analytic(std::move(analyticIrradiance)) {
  const size_t n = set.elements.size();
  emission.resize(n);
  reflectance.resize(n);
  area.resize(n);
  for (size_t e = 0; e < n; ++e) {
    emission[e] = set.elements[e].exitance;
    reflectance[e] = set.elements[e].reflectance;
    area[e] = set.elements[e].area;
  }
  patchArea.assign(set.patches.size(), 0.0f);
  for (size_t p = 0; p < set.patches.size(); ++p)
    for (uint32_t e : set.patches[p].elements) patchArea[p] += area[e];
}

std::vector<Rgb> RadiositySystem::patchMeans(const std::vector<Rgb>& perElement) const {
  std::vector<Rgb> means(patchCount(), Rgb(0.0f));
  for (size_t p = 0; p < patchCount(); ++p) {
    Rgb sum(0.0f);
    for (uint32_t e : surfaces.patches[p].elements) sum += area[e] * perElement[e];
    means[p] = patchArea[p] > 0.0f ? sum / patchArea[p] : Rgb(0.0f);
  }
  return means;
}

double RadiositySystem::sourcePower() const {
  double p = 0.0;
  for (size_t e = 0; e < elementCount(); ++e)
    p += double(area[e]) * channelSum(emission[e] + reflectance[e] * analytic[e]);
  return p;
}

}  // namespace luxel
