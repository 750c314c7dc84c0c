// Progressive refinement radiosity: Cohen, Chen, Wallace and Greenberg, "A Progressive Refinement
// Approach to Fast Radiosity Image Generation", SIGGRAPH 1988. The patch with the most unshot
// power shoots it into every element; the ambient term of the same paper estimates, for display,
// the light not yet shot. Columns of form factors are cached, so a patch that shoots again (its
// elements received more light) costs no rays.
#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "solve/radiosity_system.h"

namespace luxel {
namespace {

// Form-factor columns are kept while they fit in this much memory.
constexpr size_t kColumnCacheBytes = size_t(2) << 30;

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

}  // namespace

Solution solveProgressive(const RadiositySystem& sys, Transport& transport, const SolveOptions& options,
                          const ProgressCallback& progress, double& formFactorSeconds) {
  const size_t ne = sys.elementCount(), np = sys.patchCount();
  const auto& patches = sys.surfaces.patches;
  const auto start = Clock::now();

  std::vector<Rgb> radiosity(ne), unshot(ne), irradiance(sys.analytic);
  for (size_t e = 0; e < ne; ++e) radiosity[e] = unshot[e] = sys.emission[e] + sys.reflectance[e] * sys.analytic[e];

  // Unshot power per patch, and the patch's mean unshot radiosity.
  std::vector<Rgb> patchUnshot(np);
  auto updatePatchUnshot = [&] {
    tbb::parallel_for(size_t(0), np, [&](size_t p) {
      Rgb sum(0.0f);
      for (uint32_t e : patches[p].elements) sum += sys.area[e] * unshot[e];
      patchUnshot[p] = sum;
    });
  };
  updatePatchUnshot();

  const double sourcePower = sys.sourcePower();
  std::vector<std::vector<float>> cache(np);
  size_t cachedBytes = 0;
  const size_t shootersPerPass = size_t(options.shootersPerPass > 0 ? options.shootersPerPass : kDefaultShootersPerPass);
  std::vector<std::vector<float>> scratch(shootersPerPass);
  // The column of patch p, from the cache or computed (into scratch slot `slot` when the cache
  // is full).
  auto column = [&](uint32_t p, int slot) -> const std::vector<float>& {
    if (!cache[p].empty()) return cache[p];
    const auto t = Clock::now();
    const bool keep = cachedBytes + ne * sizeof(float) <= kColumnCacheBytes;
    std::vector<float>& out = keep ? cache[p] : scratch[size_t(slot)];
    out.resize(ne);
    transport.columns({&p, 1}, out);
    if (keep) cachedBytes += ne * sizeof(float);
    formFactorSeconds += secondsSince(t);
    return out;
  };

  Solution sol;
  double unshotFraction = 1.0;
  uint64_t shots = 0;
  double lastReported = -1.0;
  std::vector<std::pair<double, uint32_t>> ranked(np);
  while (true) {
    double total = 0.0;
    for (size_t p = 0; p < np; ++p) {
      const double power = channelSum(patchUnshot[p]);
      total += power;
      ranked[p] = {power, uint32_t(p)};
    }
    unshotFraction = sourcePower > 0.0 ? total / sourcePower : 0.0;
    if (unshotFraction <= options.unshotThreshold) break;
    if (options.shotBudget && shots >= options.shotBudget) break;
    if (options.timeBudget > 0.0 && secondsSince(start) >= options.timeBudget) break;

    // Progress is logarithmic in the unshot fraction: each decade takes about as long.
    double fraction = std::clamp(std::log(unshotFraction) / std::log(options.unshotThreshold), 0.0, 1.0);
    if (fraction - lastReported >= 0.01) {
      reportProgress(progress, "solve", fraction, fmt::format("unshot {:.3f}%", 100.0 * unshotFraction));
      lastReported = fraction;
    }

    // The patches with the most unshot power shoot together, in one pass over the receivers:
    // the pass costs memory traffic over every element, which one shooter alone does not repay.
    size_t batch = std::min<size_t>(shootersPerPass, np);
    if (options.shotBudget) batch = std::min<size_t>(batch, options.shotBudget - shots);
    std::partial_sort(ranked.begin(), ranked.begin() + long(batch), ranked.end(), std::greater<>());
    while (batch > 0 && ranked[batch - 1].first <= 0.0) --batch;
    if (batch == 0) break;
    const float* columns[kMaxShootersPerPass];
    Rgb shot[kMaxShootersPerPass];
    for (size_t k = 0; k < batch; ++k) {
      const uint32_t shooter = ranked[k].second;
      columns[k] = column(shooter, int(k)).data();
      shot[k] = patchUnshot[shooter] / sys.patchArea[shooter];
      for (uint32_t e : patches[shooter].elements) unshot[e] = Rgb(0.0f);
      patchUnshot[shooter] = Rgb(0.0f);
    }
    // Receivers patch by patch, so each patch's unshot power is updated by the change of its own
    // elements instead of being summed again from scratch.
    tbb::parallel_for(tbb::blocked_range<size_t>(0, np, 8), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t q = r.begin(); q < r.end(); ++q) {
        Rgb added(0.0f);
        for (uint32_t e : patches[q].elements) {
          Rgb dh(0.0f);
          for (size_t k = 0; k < batch; ++k) dh += columns[k][e] * shot[k];
          if (dh.r == 0.0f && dh.g == 0.0f && dh.b == 0.0f) continue;
          const Rgb db = sys.reflectance[e] * dh;
          irradiance[e] += dh;
          radiosity[e] += db;
          unshot[e] += db;
          added += sys.area[e] * db;
        }
        patchUnshot[q] += added;
      }
    });
    shots += batch;
  }
  reportProgress(progress, "solve", 1.0, fmt::format("unshot {:.3f}%", 100.0 * unshotFraction));

  if (options.ambient) addAmbientTerm(sys, unshot, radiosity, irradiance);

  // Direct irradiance: the analytic lights plus one bounce from emitting patches.
  const std::vector<Rgb> patchEmission = sys.patchMeans(sys.emission);
  sol.directIrradiance = sys.analytic;
  for (uint32_t p = 0; p < np; ++p) {
    if (channelSum(patchEmission[p]) <= 0.0) continue;
    const std::vector<float>& f = column(p, 0);
    for (size_t e = 0; e < ne; ++e) sol.directIrradiance[e] += f[e] * patchEmission[p];
  }

  sol.radiosity = std::move(radiosity);
  sol.irradiance = std::move(irradiance);
  sol.stats.method = "progressive";
  sol.stats.shots = shots;
  sol.stats.unshotFraction = unshotFraction;
  sol.stats.residual = unshotFraction;
  return sol;
}

}  // namespace luxel
