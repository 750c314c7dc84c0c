// Micro-benchmarks on the built-in Cornell box at about 10,000 elements (issue: "The core"):
//  - FormFactorRows: every element's row of form factors (analytic factor + visibility rays);
//  - EmbreeRawOcclusion: Embree alone, tracing exactly the rays FormFactorRows cast, in streams
//    of the same size on the same threads: the hardware limit for that visibility work;
//  - Solve: the whole progressive solve to 0.1% unshot, as `luxel render` runs it;
//  - Render: a 256x256 high-quality image at 16 spp from the solved box.
// Run: make bench, or build/luxel-bench --benchmark_min_time=1 --benchmark_repetitions=5
#include <numeric>

#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "luxel/render.h"
#include "luxel/solve.h"
#include "scene/builtin/builtin_scenes.h"
#include "transport/cpu_transport.h"

namespace luxel {
namespace {

constexpr size_t kElements = 10000;

SurfaceSet cornellSurfaces(const Scene& scene) {
  DiscretiseOptions d;
  d.elementBudget = kElements;
  return discretise(scene, d);
}

void FormFactorRows(benchmark::State& state) {
  Scene scene = builtin::cornellBox();
  SurfaceSet surfaces = cornellSurfaces(scene);
  const size_t ne = surfaces.elements.size(), np = surfaces.patches.size();
  std::vector<uint32_t> ids(ne);
  std::iota(ids.begin(), ids.end(), 0u);
  std::vector<float> matrix(ne * np);
  uint64_t rays = 0;
  for (auto _ : state) {
    CpuTransport transport(scene, surfaces, FormFactorOptions{});  // fresh: no cached classification
    transport.rows(ids, matrix);
    rays += transport.raysTraced();
    benchmark::DoNotOptimize(matrix.data());
  }
  state.counters["elements"] = double(ne);
  state.counters["patches"] = double(np);
  state.counters["rays/s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
}

void EmbreeRawOcclusion(benchmark::State& state) {
  Scene scene = builtin::cornellBox();
  SurfaceSet surfaces = cornellSurfaces(scene);
  CpuTransport transport(scene, surfaces, FormFactorOptions{});
  RayTracer::RayRecording recorded;
  recorded.maxRays = size_t(1) << 26;
  transport.tracer().recordOcclusionRays(&recorded);
  std::vector<uint32_t> ids(surfaces.elements.size());
  std::iota(ids.begin(), ids.end(), 0u);
  std::vector<float> matrix(ids.size() * surfaces.patches.size());
  transport.rows(ids, matrix);
  transport.tracer().recordOcclusionRays(nullptr);

  // The same streams the transport issued, in parallel on the same threads.
  std::vector<size_t> offsets(recorded.streamSizes.size() + 1, 0);
  for (size_t i = 0; i < recorded.streamSizes.size(); ++i) offsets[i + 1] = offsets[i] + recorded.streamSizes[i];
  std::vector<RTCRay> work;
  uint64_t rays = 0;
  for (auto _ : state) {
    state.PauseTiming();
    work = recorded.rays;  // tracing overwrites tfar
    state.ResumeTiming();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, recorded.streamSizes.size(), 1), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t s = r.begin(); s < r.end(); ++s) transport.tracer().occluded({work.data() + offsets[s], recorded.streamSizes[s]});
    });
    rays += work.size();
  }
  state.counters["rays"] = double(recorded.rays.size());
  state.counters["rays/s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
}

void Solve(benchmark::State& state) {
  Scene scene = builtin::cornellBox();
  uint64_t rays = 0;
  double unshot = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    SurfaceSet surfaces = cornellSurfaces(scene);
    state.ResumeTiming();
    Solution s = solve(scene, surfaces, SolveOptions{});
    rays += s.stats.rays;
    unshot = s.stats.unshotFraction;
  }
  state.counters["unshot"] = unshot;
  state.counters["rays/s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
}

void Render(benchmark::State& state) {
  Scene scene = builtin::cornellBox();
  SurfaceSet surfaces = cornellSurfaces(scene);
  Solution s = solve(scene, surfaces, SolveOptions{});
  RenderOptions o;
  o.camera = scene.cameras.front();
  o.width = o.height = 256;
  o.samplesPerPixel = 16;
  for (auto _ : state) benchmark::DoNotOptimize(render(scene, surfaces, s, o).pixels.data());
}

BENCHMARK(FormFactorRows)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(EmbreeRawOcclusion)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(Solve)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(Render)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace luxel

BENCHMARK_MAIN();
