// Running one benchmark case: N timed runs of the whole static solve (discretise, build, form
// factors, solve), one untimed run that records its occlusion rays for the hardware limit, and
// the error of the last run against the cached reference.
#include <algorithm>
#include <chrono>
#include <functional>
#include <limits>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "bench/memory.h"
#include "bench/probe_reference.h"
#include "bench/reference.h"
#include "luxel/bench.h"
#include "luxel/error.h"
#include "luxel/import.h"
#include "render/gather_pipeline.h"
#include "session/solver_host.h"
#include "transport/cpu_transport.h"
#include "transport/light_sampling.h"

namespace luxel::bench {
namespace {

// Points per probe element for the direct light an hq render's pixels show there.
constexpr int kProbePixelDirectSamples = 256;

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

Spread spreadOf(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  double median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  return {median, v.front(), v.back()};
}

struct Run {
  double setup = 0, formFactors = 0, solve = 0, total = 0;
  Solution solution;
  size_t patches = 0;
};

// One run of the whole static solve, as a user's `luxel render` does it: discretise, build the
// transport (and on GL the context, hemicubes and GPU-resident solver), solve. `before` and
// `after` see the CPU transport around the solve (recording rays).
Run solveOnce(const Scene& scene, const Case& c, const std::function<void(Transport&)>& before = {},
              const std::function<void(Transport&)>& after = {}) {
  Run r;
  const auto start = Clock::now();
  SurfaceSet surfaces = discretise(scene, c.discretise);
  r.patches = surfaces.patches.size();
  if (!mayShootFromPatches(c.solve, surfaces)) surfaces.dropPatches();  // as a Session does
  const double discretised = secondsSince(start);
  SolverHost host(scene, surfaces, c.solve);
  if (before) before(host.transport());
  while (host.step()) {
  }
  r.solution = host.solution();
  if (after) after(host.transport());
  r.setup = discretised + r.solution.stats.secondsSetup;
  r.formFactors = r.solution.stats.secondsFormFactors;
  r.solve = r.solution.stats.secondsSolve;
  r.total = secondsSince(start);
  return r;
}

// Embree alone on the recorded streams, on the same threads, as the solver issued them (one
// stream per call, many calls in parallel), through the BVH the solver used. The best of three
// passes: the limit, not a typical.
double embreeRawRaysPerSecond(const RayTracer& tracer, const RayTracer::RayRecording& rec) {
  if (rec.rays.empty()) return 0.0;
  std::vector<size_t> offsets(rec.streamSizes.size() + 1, 0);
  for (size_t i = 0; i < rec.streamSizes.size(); ++i) offsets[i + 1] = offsets[i] + rec.streamSizes[i];
  double best = 0.0;
  std::vector<RTCRay> work;
  for (int pass = 0; pass < 3; ++pass) {
    work = rec.rays;  // tracing overwrites tfar
    const auto start = Clock::now();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rec.streamSizes.size(), 1),
                      [&](const tbb::blocked_range<size_t>& r) {
                        for (size_t s = r.begin(); s < r.end(); ++s)
                          tracer.occluded({work.data() + offsets[s], rec.streamSizes[s]});
                      });
    best = std::max(best, double(work.size()) / secondsSince(start));
  }
  return best;
}

}  // namespace

CaseResult runCase(const Case& c, const Options& options) {
  if (options.runs < 1 || options.runs > 1000) throw Error(fmt::format("runs {} must be in 1..1000", options.runs));
  validateSolveOptions(c.solve);
  const bool gl = c.solve.backend == "gl";
  CaseResult result;
  result.benchCase = c;
  result.runs = options.runs;
  // Without an OpenGL 4.5 context a GL case throws, and the bench command reports it skipped
  // with the reason, as it does a missing scene.
  reportProgress(options.progress, c.name, 0.0, "loading");
  const auto loadStart = Clock::now();
  const Scene scene = loadScene(c.scene);
  result.loadSeconds = secondsSince(loadStart);

  std::vector<double> setup, ff, sol, total, hemicubeRates, gatherMs, shotMs;
  Run last;
  for (int i = 0; i < options.runs; ++i) {
    reportProgress(options.progress, c.name, double(i) / options.runs, fmt::format("run {} of {}", i + 1, options.runs));
    if (i == 0) resetPeakMemory();
    Run r = solveOnce(scene, c);
    if (i == 0) result.peakMemoryBytes = peakMemoryBytes();
    setup.push_back(r.setup), ff.push_back(r.formFactors), sol.push_back(r.solve), total.push_back(r.total);
    if (gl) {
      const SolveStats& st = r.solution.stats;
      hemicubeRates.push_back(r.formFactors > 0 ? double(st.hemicubes) / r.formFactors : 0.0);
      // An element gathered once is perSide^2 hemicubes; a shot is a whole pass's share.
      const bool gathering = c.solve.method == "gather";
      const SolverOptionValues values(c.name, SolverRegistry::builtin().get(c.solve.method, "gl").description.options,
                                      c.solve.settings);
      const int perSide = gathering ? values.integer("hemicubes-per-side") : 1;
      const double perElement = double(perSide * perSide);
      gatherMs.push_back(gathering && st.hemicubes ? 1e3 * r.formFactors * perElement / double(st.hemicubes) : 0.0);
      shotMs.push_back(st.shots > 0 ? 1e3 * (r.formFactors + r.solve) / double(st.shots) : 0.0);
    }
    last = std::move(r);
  }
  result.setup = spreadOf(setup);
  result.formFactors = spreadOf(ff);
  result.solve = spreadOf(sol);
  result.total = spreadOf(total);
  const SolveStats& s = last.solution.stats;
  result.elements = s.elements;
  result.patches = last.patches;  // as cut: a hierarchical solve drops them, and its stats say 0
  result.rays = s.rays;
  result.shots = s.shots;
  result.iterations = s.iterations;
  result.unshot = s.unshotFraction;
  result.raysPerSecond = result.formFactors.median > 0 ? double(s.rays) / result.formFactors.median : 0.0;
  result.hierarchySeconds = s.secondsHierarchy, result.hierarchyBytes = s.hierarchyBytes;
  result.links = s.links, result.leaves = s.clusterLeaves;
  if (gl) {
    result.device = s.device;
    result.hemicubes = s.hemicubes;
    result.hemicubesPerSecond = spreadOf(hemicubeRates).median;
    result.msPerGather = spreadOf(gatherMs).median;
    result.msPerShot = spreadOf(shotMs).median;
  }

  // The hardware limit replays the CPU backend's rays; a GL case traces only analytic lights' rays.
  if (options.hardwareLimit && s.rays > 0 && !gl) {
    reportProgress(options.progress, c.name, 1.0, "hardware limit");
    RayTracer::RayRecording rec;
    auto tracerOf = [](Transport& t) -> RayTracer& { return static_cast<CpuTransport&>(t).tracer(); };
    solveOnce(
        scene, c, [&](Transport& t) { tracerOf(t).recordOcclusionRays(&rec); },
        [&](Transport& t) {
          tracerOf(t).recordOcclusionRays(nullptr);
          result.limitRaysPerSecond = embreeRawRaysPerSecond(tracerOf(t), rec);
        });
    if (result.limitRaysPerSecond > 0) result.limitFraction = result.raysPerSecond / result.limitRaysPerSecond;
  }

  if (!options.reference) {
    result.errorNote = "reference off";
    return result;
  }
  if (c.solve.refine.budget > 0) {
    result.errorNote = "no reference: refinement changes the discretisation";
    return result;
  }
  // The reference is solved on the surfaces cut again, patches and all.
  const double pairs = double(s.elements) * double(result.patches);
  const bool tooLarge = !c.reference && pairs > c.maxReferencePairs;
  if (tooLarge) result.errorNote = fmt::format("no reference: {:.2g} element-patch pairs", pairs);
  if (tooLarge && c.probes == 0) return result;  // nothing else needs the surfaces cut again
  const SurfaceSet surfaces = discretise(scene, c.discretise);
  std::optional<Reference> ref;
  if (!tooLarge) {
    reportProgress(options.progress, c.name, 1.0, "reference");
    ref = loadOrComputeReference(scene, surfaces, options.cacheDir, options.progress, options.referenceKind,
                                 c.reference);
    result.referenceSeconds = ref->seconds;
    result.error = normalisedRmsError(surfaces, last.solution.radiosity, ref->radiosity);
    if (c.reference) result.errorNote = "error against " + c.referenceName;
  }
  if (c.probes > 0) {
    reportProgress(options.progress, c.name, 1.0, "probes");
    const ProbeReference probes =
        loadOrComputeProbes(scene, surfaces, options.cacheDir, c.probes, PathTracingOptions{}, options.progress);
    result.probeSeconds = probes.seconds;
    for (const ElementIrradianceEstimate& e : probes.estimates) result.probePaths += e.paths;
    result.probeError = probeError(probes, last.solution.irradiance);
    if (ref) result.referenceProbeError = probeError(probes, irradianceFromRadiosity(surfaces, ref->radiosity));
    const Solution& sol = last.solution;
    if (sol.directIrradiance.size() == sol.irradiance.size()) {
      const ProbeReference direct = loadOrComputeProbes(scene, surfaces, options.cacheDir, c.probes,
                                                        PathTracingOptions{.maxBounces = 0}, options.progress);
      result.probeSeconds += direct.seconds;
      result.probeDirectError = probeError(direct, sol.directIrradiance);
      std::vector<Rgb> indirect(sol.irradiance.size());
      for (size_t e = 0; e < indirect.size(); ++e) indirect[e] = sol.irradiance[e] - sol.directIrradiance[e];
      result.probeIndirectError = probeError(probeDifference(probes, direct), indirect);
      // What a picture shows there, each probe element's mean: the vertex gather's (the indirect
      // light, and the skies' light as a render gathers them) and the direct light its pixels
      // trace (the other lights). Its indirect part is that less the pixels' direct light of every
      // light, so that it holds what interpolating the skies costs too.
      reportProgress(options.progress, c.name, 1.0, "gather at the probes");
      const bool skies = std::any_of(scene.lights.begin(), scene.lights.end(), isSkyLight);
      const Clock::time_point gatherStart = Clock::now();
      const std::vector<Rgb> gathered = gatheredIndirect(scene, surfaces, sol, probes.elements, RenderOptions{}, skies);
      result.probeGatherSeconds = secondsSince(gatherStart);
      const std::vector<Rgb> pixelDirect = pixelDirectLight(scene, surfaces, probes.elements, kProbePixelDirectSamples,
                                                            RenderOptions{}.seed, /*skies=*/false);
      const std::vector<Rgb> allDirect =
          skies ? pixelDirectLight(scene, surfaces, probes.elements, kProbePixelDirectSamples, RenderOptions{}.seed)
                : pixelDirect;
      // Per element, as probeError reads them (NaN where no probe is).
      std::vector<Rgb> renderedIndirect(sol.irradiance.size(), Rgb(std::numeric_limits<float>::quiet_NaN()));
      std::vector<Rgb> rendered = renderedIndirect;
      for (size_t i = 0; i < probes.elements.size(); ++i) {
        rendered[probes.elements[i]] = gathered[i] + pixelDirect[i];
        renderedIndirect[probes.elements[i]] = rendered[probes.elements[i]] - allDirect[i];
      }
      result.probeGatheredError = probeError(probes, rendered);
      result.probeGatheredIndirectError = probeError(probeDifference(probes, direct), renderedIndirect);
      auto total = [](Rgb c) { return double(c.r) + double(c.g) + double(c.b); };
      for (size_t i = 0; i < probes.elements.size(); ++i) {
        const uint32_t e = probes.elements[i];
        const ElementIrradianceEstimate& t = probes.estimates[i];
        result.probeSamples.push_back({e, surfaces.elements[e].centroid, total(t.mean), glm::length(t.standardError),
                                       total(direct.estimates[i].mean), total(sol.irradiance[e]),
                                       total(sol.directIrradiance[e])});
      }
    }
  }
  return result;
}

}  // namespace luxel::bench
