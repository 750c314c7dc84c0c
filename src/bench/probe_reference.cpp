#include "bench/probe_reference.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>

#include <fmt/format.h>

#include "bench/reference.h"
#include "core/content_hash.h"
#include "core/random.h"
#include "luxel/error.h"

namespace luxel::bench {
namespace {

constexpr char kMagic[8] = {'L', 'X', 'P', 'R', 'B', '0', '0', '1'};

bool emits(const Element& e) { return e.exitance.r > 0.0f || e.exitance.g > 0.0f || e.exitance.b > 0.0f; }

uint64_t probeKey(const Scene& scene, const SurfaceSet& surfaces, std::span<const uint32_t> elements,
                  const PathTracingOptions& o) {
  ContentHash h;
  // Bump when the path tracer's estimate changes (its sampling, the direct light it calls).
  h.text("luxel-probes-1");
  hashLightingProblem(h, scene, surfaces);
  h.bytes(elements.data(), elements.size_bytes());
  h.value(o.minPaths), h.value(o.maxPaths), h.value(o.relativeError), h.value(o.seed), h.value(o.maxBounces);
  return h.digest();
}

}  // namespace

std::vector<uint32_t> chooseProbeElements(const SurfaceSet& surfaces, size_t count) {
  std::vector<uint32_t> candidates;
  std::vector<double> running;
  double total = 0.0;
  for (uint32_t e = 0; e < surfaces.elements.size(); ++e) {
    const Element& el = surfaces.elements[e];
    if (emits(el) || !(el.area > 0.0f)) continue;
    total += el.area;
    candidates.push_back(e);
    running.push_back(total);
  }
  std::vector<uint32_t> out;
  if (candidates.empty() || count == 0) return out;
  Rng rng(0x9e0be5u);
  for (size_t k = 0; k < count; ++k) {
    const double u = (double(k) + rng.next()) / double(count) * total;
    const size_t i = std::min(candidates.size() - 1,
                              size_t(std::lower_bound(running.begin(), running.end(), u) - running.begin()));
    if (out.empty() || out.back() != candidates[i]) out.push_back(candidates[i]);
  }
  return out;
}

ProbeReference loadOrComputeProbes(const Scene& scene, const SurfaceSet& surfaces, const std::string& cacheDir,
                                   size_t count, const PathTracingOptions& options,
                                   const ProgressCallback& progress) {
  ProbeReference probes;
  probes.elements = chooseProbeElements(surfaces, count);
  const uint64_t key = probeKey(scene, surfaces, probes.elements, options);
  std::filesystem::path dir(cacheDir);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error(fmt::format("{}: cannot create the reference cache: {}", cacheDir, ec.message()));
  probes.path = (dir / fmt::format("{}-probes-{:016x}.ref", scene.name, key)).string();
  if (readCacheFile(probes.path, kMagic, key, probes.elements.size(), probes.estimates)) return probes;

  const auto start = std::chrono::steady_clock::now();
  probes.estimates = pathTraceElementIrradiance(scene, surfaces, probes.elements, options, progress);
  probes.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  writeCacheFile(probes.path, kMagic, key, probes.estimates);
  return probes;
}

ProbeReference probeDifference(const ProbeReference& whole, const ProbeReference& part) {
  if (whole.elements != part.elements) throw Error("probe difference: the two sets of probes are of different elements");
  ProbeReference out;
  out.elements = whole.elements;
  for (size_t i = 0; i < whole.estimates.size(); ++i) {
    const ElementIrradianceEstimate &a = whole.estimates[i], &b = part.estimates[i];
    ElementIrradianceEstimate& d = out.estimates.emplace_back();
    d.mean = a.mean - b.mean;
    for (int c = 0; c < 3; ++c)
      d.standardError[c] = std::sqrt(a.standardError[c] * a.standardError[c] + b.standardError[c] * b.standardError[c]);
    d.paths = a.paths + b.paths;
  }
  return out;
}

std::vector<Rgb> irradianceFromRadiosity(const SurfaceSet& surfaces, std::span<const Rgb> radiosity) {
  if (radiosity.size() != surfaces.elements.size())
    throw Error(fmt::format("{} radiosities for {} elements", radiosity.size(), surfaces.elements.size()));
  std::vector<Rgb> out(radiosity.size());
  for (size_t e = 0; e < radiosity.size(); ++e) {
    const Element& el = surfaces.elements[e];
    for (int c = 0; c < 3; ++c)
      out[e][c] = el.reflectance[c] > 0.0f ? (radiosity[e][c] - el.exitance[c]) / el.reflectance[c]
                                           : std::numeric_limits<float>::quiet_NaN();
  }
  return out;
}

ProbeError probeError(const ProbeReference& probes, std::span<const Rgb> irradiance) {
  ProbeError r;
  double squares = 0.0, noise = 0.0, norm = 0.0, diff = 0.0, sum = 0.0;
  // Channel sums per probe, for the per-probe figures.
  std::vector<double> h, p, s;
  for (size_t i = 0; i < probes.elements.size(); ++i) {
    const uint32_t e = probes.elements[i];
    if (e >= irradiance.size())
      throw Error(fmt::format("probe element {} is past the solution's {} elements", e, irradiance.size()));
    const ElementIrradianceEstimate& est = probes.estimates[i];
    double hs = 0.0, ps = 0.0, ss = 0.0;
    bool any = false;
    for (int c = 0; c < 3; ++c) {
      const double x = irradiance[e][c];
      if (std::isnan(x)) continue;
      any = true;
      const double m = est.mean[c], se = est.standardError[c];
      squares += (x - m) * (x - m), noise += se * se, norm += m * m;
      diff += x - m, sum += m;
      hs += x, ps += m, ss += se * se;
    }
    if (!any) continue;
    h.push_back(hs), p.push_back(ps), s.push_back(std::sqrt(ss));
  }
  r.probes = h.size();
  if (r.probes == 0 || !(norm > 0.0)) throw Error("probe error: the probes received no light");
  r.nrmse = std::sqrt(std::max(0.0, squares - noise) / norm);
  r.noise = std::sqrt(noise / norm);
  r.bias = diff / sum;
  double meanP = 0.0;
  for (double v : p) meanP += v / double(p.size());
  size_t within = 0;
  for (size_t i = 0; i < h.size(); ++i) {
    const double d = std::abs(h[i] - p[i]);
    // 3% of the probe, or 0.1% of the probes' mean where it is darker than that: many probes
    // receive no light at all (Sibenik's roof space), and a solution's 1e-4 of the mean there is
    // not an error anyone could see.
    if (d <= std::max(0.03 * p[i], 1e-3 * meanP) + 2.0 * s[i]) ++within;
    if (p[i] > 0.01 * meanP) r.worst = std::max(r.worst, d / p[i]);
  }
  r.withinThreePercent = double(within) / double(h.size());
  return r;
}

}  // namespace luxel::bench
