// The one entry point for solving: builds the CPU transport, runs the chosen solver, refines
// elements where the solution's gradient is large (Cohen et al. 1986, adaptive subdivision) and
// re-solves, and fills in the statistics.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include <fmt/format.h>

#include "luxel/error.h"
#include "luxel/solve.h"
#include "mesh/corner_groups.h"
#include "gl/gl_context.h"
#include "gl/gather_gl.h"
#include "gl/progressive_gl.h"
#include "solve/radiosity_system.h"
#include "solve/solve_with_transport.h"
#include "transport/cpu_transport.h"

namespace luxel {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

void validate(const SolveOptions& o) {
  auto fail = [](const std::string& what) { throw Error("solver options: " + what); };
  if (!(o.unshotThreshold > 0.0 && o.unshotThreshold < 1.0)) fail(fmt::format("unshot threshold {} must be in (0,1)", o.unshotThreshold));
  if (!(o.residualThreshold > 0.0 && o.residualThreshold < 1.0)) fail(fmt::format("residual threshold {} must be in (0,1)", o.residualThreshold));
  if (!(o.timeBudget >= 0.0)) fail(fmt::format("time budget {} must be >= 0", o.timeBudget));
  if (o.maxIterations < 1) fail("max iterations must be >= 1");
  if (o.shootersPerPass < 0 || o.shootersPerPass > kMaxShootersPerPass)
    fail(fmt::format("shooters per pass {} must be in 1..{} (or 0, automatic)", o.shootersPerPass, kMaxShootersPerPass));
  const FormFactorOptions& f = o.formFactors;
  for (int n : {f.raysPerPair, f.nearRaysPerPair, f.emitterRaysPerPair, f.lightSamples})
    if (n < 1 || n > 256) fail(fmt::format("ray and sample counts must be in 1..256 (got {})", n));
  if (!(f.nearFactor >= 0.0f)) fail("near factor must be >= 0");
  for (const SolveOptions::HemicubeSampling& h : {o.shootingHemicubes, o.gatheringHemicubes}) {
    if (h.resolution < 8 || h.resolution > 4096 || h.resolution % 2)
      fail(fmt::format("hemicube resolution {} must be even, from 8 to 4096", h.resolution));
    if (h.perSide < 1 || h.perSide > 8) fail(fmt::format("hemicubes per side {} must be in 1..8", h.perSide));
  }
  if (o.emitterHemicubesPerSide < 0 || o.emitterHemicubesPerSide > 8)
    fail(fmt::format("hemicubes per emitter side {} must be in 1..8 (or 0: as other shooters)", o.emitterHemicubesPerSide));
  if (!(o.refineThreshold > 0.0f)) fail("refine threshold must be > 0");
}

// Elements whose radiosity differs from a neighbour's on the same surface by more than the
// threshold (relative), largest differences first, as many as the budget allows.
std::vector<uint32_t> elementsToRefine(const SurfaceSet& set, const std::vector<Rgb>& radiosity,
                                       const SolveOptions& options, size_t budgetLeft) {
  CornerGroups groups(set, kDefaultCreaseCosine);
  std::vector<std::pair<float, uint32_t>> candidates;
  for (uint32_t e = 0; e < set.elements.size(); ++e) {
    const Element& el = set.elements[e];
    if (el.depth >= options.maxRefineDepth) continue;
    float be = float(channelSum(radiosity[e])), worst = 0.0f;
    for (int c = 0; c < el.polygon.count; ++c)
      for (uint32_t n : groups.at(e, c)) {
        float bn = float(channelSum(radiosity[n]));
        float scale = std::max(be + bn, 1e-20f);
        worst = std::max(worst, 2.0f * std::abs(be - bn) / scale);
      }
    if (worst > options.refineThreshold) candidates.emplace_back(worst * el.area, e);
  }
  std::sort(candidates.begin(), candidates.end(), std::greater<>());
  std::vector<uint32_t> chosen;
  for (const auto& [score, e] : candidates) {
    if ((chosen.size() + 1) * 3 > budgetLeft) break;
    chosen.push_back(e);
  }
  return chosen;
}

}  // namespace

SolveOptions::Method parseSolveMethod(const std::string& name) {
  if (name == "progressive") return SolveOptions::Method::Progressive;
  if (name == "gather") return SolveOptions::Method::Gather;
  throw Error(fmt::format("unknown solver '{}' (expected progressive or gather)", name));
}

SolveOptions::HemicubeVisibility parseHemicubeVisibility(const std::string& name) {
  if (name == "item") return SolveOptions::HemicubeVisibility::Item;
  if (name == "distance") return SolveOptions::HemicubeVisibility::Distance;
  throw Error(fmt::format("unknown hemicube visibility '{}' (expected item or distance)", name));
}

SolveOptions::Backend parseSolveBackend(const std::string& name) {
  if (name == "cpu") return SolveOptions::Backend::Cpu;
  if (name == "gl") return SolveOptions::Backend::Gl;
  if (name == "auto") return SolveOptions::Backend::Auto;
  throw Error(fmt::format("unknown backend '{}' (expected cpu, gl or auto)", name));
}

Solution solve(const Scene& scene, SurfaceSet& surfaces, const SolveOptions& options,
               const ProgressCallback& progress) {
  validate(options);
  const auto start = Clock::now();
  std::vector<std::string> warnings;
  std::unique_ptr<gl::Context> context;  // outlives the transport (declared first)
  if (options.backend != SolveOptions::Backend::Cpu) {
    try {
      context = std::make_unique<gl::Context>([&](const std::string& m) { warnings.push_back(m); });
    } catch (const Error& e) {
      if (options.backend == SolveOptions::Backend::Gl) throw;
      warnings.push_back(fmt::format("{}; using the CPU backend", e.what()));
    }
  }
  // On GL, both solvers run resident on the GPU (gl/progressive_gl.h, gl/gather_gl.h), with the
  // CPU transport for analytic lights only.
  std::unique_ptr<Transport> transport = std::make_unique<CpuTransport>(scene, surfaces, options.formFactors);
  SystemSolver gpuSolver;
  if (context && options.method == SolveOptions::Method::Progressive) {
    gl::GlProgressiveOptions g;
    g.resolution = options.shootingHemicubes.resolution;
    g.samplesPerSide = options.shootingHemicubes.perSide;
    g.emitterSamplesPerSide = options.emitterHemicubesPerSide;
    g.visibility = options.hemicubeVisibility;
    g.shootersPerPass = options.shootersPerPass > 0 ? options.shootersPerPass
                        : context->softwareRasteriser() ? 1
                                                        : kDefaultShootersPerPass;
    gpuSolver = [&options, &progress, g](const RadiositySystem& system, double& formFactorSeconds) {
      return gl::solveProgressiveGl(system, options, g, progress, formFactorSeconds);
    };
  } else if (context) {
    gl::GlGatherOptions g;
    g.resolution = options.gatheringHemicubes.resolution;
    g.samplesPerSide = options.gatheringHemicubes.perSide;
    gpuSolver = [&options, &progress, g](const RadiositySystem& system, double& formFactorSeconds) {
      return gl::solveGatherGl(system, options, g, progress, formFactorSeconds);
    };
  }
  const double setup = secondsSince(start);
  Solution sol = solveWithTransport(scene, surfaces, *transport, options, progress, gpuSolver);
  sol.stats.secondsSetup += setup;
  sol.stats.secondsTotal = secondsSince(start);
  sol.stats.backend = context ? "gl" : "cpu";
  if (context) sol.stats.device = context->renderer();
  sol.stats.warnings = std::move(warnings);
  return sol;
}

Solution solveWithTransport(const Scene& scene, SurfaceSet& surfaces, Transport& transport,
                            const SolveOptions& options, const ProgressCallback& progress,
                            const SystemSolver& solver) {
  validate(options);
  const auto start = Clock::now();
  SolveStats stats;
  auto t = start;

  Solution sol;
  double formFactorSeconds = 0.0, solveSeconds = 0.0;
  size_t refined = 0;
  uint64_t hemicubes = 0;
  std::vector<Rgb> analytic;
  for (int pass = 0;; ++pass) {
    t = Clock::now();
    analytic.assign(surfaces.elements.size(), Rgb(0.0f));
    transport.analyticIrradiance(analytic);
    formFactorSeconds += secondsSince(t);

    RadiositySystem system(surfaces, analytic);
    t = Clock::now();
    double ff = 0.0;
    sol = solver ? solver(system, ff)
          : options.method == SolveOptions::Method::Gather ? solveGather(system, transport, options, progress, ff)
                                                           : solveProgressive(system, transport, options, progress, ff);
    formFactorSeconds += ff;
    solveSeconds += secondsSince(t) - ff;
    hemicubes += sol.stats.hemicubes;

    if (refined >= options.refineBudget) break;
    std::vector<uint32_t> split = elementsToRefine(surfaces, sol.radiosity, options, options.refineBudget - refined);
    if (split.empty()) break;
    for (uint32_t e : split) surfaces.splitElement(e, scene);
    transport.elementsChanged();
    refined += split.size() * 3;
    stats.refinePasses = pass + 1;
    reportProgress(progress, "refine", 1.0, fmt::format("split {} elements", split.size()));
  }

  const SolveStats solverStats = sol.stats;
  stats.method = solverStats.method;
  stats.shots = solverStats.shots;
  stats.iterations = solverStats.iterations;
  stats.hemicubes = hemicubes;
  stats.residual = solverStats.residual;
  stats.unshotFraction = solverStats.unshotFraction;
  stats.elements = surfaces.elements.size();
  stats.patches = surfaces.patches.size();
  stats.rays = transport.raysTraced();
  stats.refinedElements = refined;
  stats.secondsFormFactors = formFactorSeconds;
  stats.secondsSolve = solveSeconds;
  stats.secondsTotal = secondsSince(start);

  // Energy balance, in the mean of the three channels: what enters the system (emission from each
  // emitting side, analytic light landing on surfaces) against what surfaces absorb.
  double emitted = 0.0, absorbed = 0.0;
  for (size_t e = 0; e < surfaces.elements.size(); ++e) {
    const Element& el = surfaces.elements[e];
    emitted += el.area * (channelSum(el.exitance) + channelSum(analytic[e]));
    absorbed += el.area * channelSum((Rgb(1.0f) - el.reflectance) * sol.irradiance[e]);
  }
  stats.emittedPower = emitted / 3.0;
  stats.absorbedPower = absorbed / 3.0;
  sol.stats = stats;
  return sol;
}

}  // namespace luxel
