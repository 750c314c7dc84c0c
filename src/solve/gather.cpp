// Gathering radiosity with an explicit form-factor matrix, solved by Gauss-Seidel (Cohen and
// Greenberg, "The Hemi-Cube: A Radiosity Solution for Complex Environments", SIGGRAPH 1985) or
// Jacobi iteration. The reference solver for scenes of up to tens of thousands of elements: its
// memory is elements x patches floats.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "luxel/error.h"
#include "solve/radiosity_system.h"

namespace luxel {
namespace {

constexpr size_t kMaxMatrixBytes = size_t(16) << 30;
constexpr size_t kRowsPerBlock = 256;

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Irradiance gathered by one row: sum_p F[e <- p] B_p, with B_p in three separate channels so the
// loop vectorises.
Rgb gatherRow(const float* row, const std::vector<float>& r, const std::vector<float>& g,
              const std::vector<float>& b) {
  float hr = 0.0f, hg = 0.0f, hb = 0.0f;
  const size_t n = r.size();
  for (size_t p = 0; p < n; ++p) {
    hr += row[p] * r[p];
    hg += row[p] * g[p];
    hb += row[p] * b[p];
  }
  return Rgb(hr, hg, hb);
}

}  // namespace

Solution solveGather(const RadiositySystem& sys, Transport& transport, const SolveOptions& options,
                     const ProgressCallback& progress, double& formFactorSeconds) {
  const size_t ne = sys.elementCount(), np = sys.patchCount();
  const size_t bytes = ne * np * sizeof(float);
  if (bytes > kMaxMatrixBytes)
    throw Error(fmt::format("gather needs a {} x {} form-factor matrix ({:.1f} GiB, over the {} GiB "
                            "limit): use the progressive solver or fewer elements",
                            ne, np, double(bytes) / double(1 << 30), kMaxMatrixBytes >> 30));

  // The matrix, a block of rows at a time so that progress and cancellation stay responsive.
  std::vector<float> matrix(ne * np);
  {
    const auto t = Clock::now();
    std::vector<uint32_t> ids(ne);
    std::iota(ids.begin(), ids.end(), 0u);
    for (size_t begin = 0; begin < ne; begin += kRowsPerBlock) {
      size_t end = std::min(ne, begin + kRowsPerBlock);
      transport.rows({ids.data() + begin, end - begin}, {matrix.data() + begin * np, (end - begin) * np});
      reportProgress(progress, "form factors", double(end) / double(ne));
    }
    formFactorSeconds += secondsSince(t);
  }

  std::vector<Rgb> radiosity(ne), irradiance(sys.analytic);
  for (size_t e = 0; e < ne; ++e) radiosity[e] = sys.emission[e] + sys.reflectance[e] * sys.analytic[e];
  std::vector<float> pr(np), pg(np), pb(np);
  auto refreshPatches = [&] {
    std::vector<Rgb> means = sys.patchMeans(radiosity);
    for (size_t p = 0; p < np; ++p) pr[p] = means[p].r, pg[p] = means[p].g, pb[p] = means[p].b;
  };
  refreshPatches();

  Solution sol;
  double residual = 1.0;
  int iteration = 0;
  const auto& patchOf = sys.surfaces.elements;
  double best = std::numeric_limits<double>::max();
  int sinceBest = 0;
  while (iteration < options.maxIterations) {
    ++iteration;
    double maxDelta = 0.0, maxB = 0.0;
    if (options.gaussSeidel) {
      // Patch means are updated in place during a sweep; recomputing them at its start keeps
      // float rounding from accumulating over many sweeps.
      refreshPatches();
      for (size_t e = 0; e < ne; ++e) {
        Rgb h = sys.analytic[e] + gatherRow(matrix.data() + e * np, pr, pg, pb);
        Rgb b = sys.emission[e] + sys.reflectance[e] * h;
        Rgb d = b - radiosity[e];
        const uint32_t p = patchOf[e].patch;
        const float w = sys.area[e] / sys.patchArea[p];
        pr[p] += w * d.r, pg[p] += w * d.g, pb[p] += w * d.b;
        radiosity[e] = b;
        irradiance[e] = h;
        maxDelta = std::max(maxDelta, std::abs(d.r) + double(std::abs(d.g)) + std::abs(d.b));
        maxB = std::max(maxB, channelSum(b));
      }
    } else {
      std::vector<double> deltas(ne);
      tbb::parallel_for(tbb::blocked_range<size_t>(0, ne, 64), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t e = r.begin(); e < r.end(); ++e) {
          Rgb h = sys.analytic[e] + gatherRow(matrix.data() + e * np, pr, pg, pb);
          Rgb b = sys.emission[e] + sys.reflectance[e] * h;
          Rgb d = b - radiosity[e];
          deltas[e] = std::abs(d.r) + double(std::abs(d.g)) + std::abs(d.b);
          radiosity[e] = b;
          irradiance[e] = h;
        }
      });
      for (size_t e = 0; e < ne; ++e) {
        maxDelta = std::max(maxDelta, deltas[e]);
        maxB = std::max(maxB, channelSum(radiosity[e]));
      }
      refreshPatches();
    }
    residual = maxB > 0.0 ? maxDelta / maxB : 0.0;
    reportProgress(progress, "solve",
                   std::clamp(std::log(std::max(residual, 1e-30)) / std::log(options.residualThreshold), 0.0, 1.0),
                   fmt::format("residual {:.2e}", residual));
    if (residual <= options.residualThreshold) break;
    // Float rounding bounds how small the residual can get; stop once it no longer falls.
    if (residual < best * 0.99) {
      best = residual;
      sinceBest = 0;
    } else if (++sinceBest >= 8) {
      break;
    }
  }

  // Direct irradiance: the analytic lights plus one bounce from emitting patches.
  const std::vector<Rgb> patchEmission = sys.patchMeans(sys.emission);
  sol.directIrradiance = sys.analytic;
  for (size_t p = 0; p < np; ++p) {
    if (channelSum(patchEmission[p]) <= 0.0) continue;
    for (size_t e = 0; e < ne; ++e) sol.directIrradiance[e] += matrix[e * np + p] * patchEmission[p];
  }

  sol.radiosity = std::move(radiosity);
  sol.irradiance = std::move(irradiance);
  sol.stats.method = "gather";
  sol.stats.iterations = uint64_t(iteration);
  sol.stats.residual = residual;
  return sol;
}

}  // namespace luxel
