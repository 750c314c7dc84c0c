#include "solve/refinement.h"

#include <algorithm>
#include <cmath>

#include "mesh/corner_groups.h"
#include "solve/radiosity_system.h"

namespace luxel {

std::vector<uint32_t> elementsToRefine(const SurfaceSet& set, const std::vector<Rgb>& radiosity,
                                       const RefineOptions& options, size_t budgetLeft) {
  CornerGroups groups(set, kDefaultCreaseCosine);
  std::vector<std::pair<float, uint32_t>> candidates;
  for (uint32_t e = 0; e < set.elements.size(); ++e) {
    const Element& el = set.elements[e];
    if (el.depth >= options.maxDepth) continue;
    float be = float(channelSum(radiosity[e])), worst = 0.0f;
    for (int c = 0; c < el.polygon.count; ++c)
      for (uint32_t n : groups.at(e, c)) {
        float bn = float(channelSum(radiosity[n]));
        float scale = std::max(be + bn, 1e-20f);
        worst = std::max(worst, 2.0f * std::abs(be - bn) / scale);
      }
    if (worst > options.threshold) candidates.emplace_back(worst * el.area, e);
  }
  std::sort(candidates.begin(), candidates.end(), std::greater<>());
  std::vector<uint32_t> chosen;
  for (const auto& [score, e] : candidates) {
    if ((chosen.size() + 1) * 3 > budgetLeft) break;
    chosen.push_back(e);
  }
  return chosen;
}

}  // namespace luxel
