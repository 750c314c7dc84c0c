#include "solve/radiosity_system.h"

namespace luxel {

RadiositySystem::RadiositySystem(const SurfaceSet& set, std::vector<Rgb> analyticIrradiance) : surfaces(set) {
  refresh(std::move(analyticIrradiance));
}

void RadiositySystem::refresh(std::vector<Rgb> analyticIrradiance) {
  const SurfaceSet& set = surfaces;
  analytic = std::move(analyticIrradiance);
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

void addAmbientTerm(const RadiositySystem& sys, const std::vector<Rgb>& unshot, std::vector<Rgb>& radiosity,
                    std::vector<Rgb>& irradiance) {
  double totalArea = 0.0;
  Rgb meanRho(0.0f), unshotSum(0.0f);
  for (size_t e = 0; e < sys.elementCount(); ++e) {
    totalArea += sys.area[e];
    meanRho += sys.area[e] * sys.reflectance[e];
    unshotSum += sys.area[e] * unshot[e];
  }
  if (totalArea <= 0.0) return;
  meanRho /= float(totalArea);
  const Rgb ambient = unshotSum / float(totalArea) / glm::max(Rgb(1.0f) - meanRho, Rgb(1e-3f));
  for (size_t e = 0; e < sys.elementCount(); ++e) {
    irradiance[e] += ambient;
    radiosity[e] += sys.reflectance[e] * ambient;
  }
}

}  // namespace luxel
