// What moving one object costs in a real scene (Sibenik, 75k triangles, sun and sky; the `scenes`
// suite's 100,000-element cut), beside what rebuilding would cost (issue: the engine core):
//  - SibenikTransportBuild/0 and /1: the CPU transport from scratch (BVH build and every element's
//    receiver quadrature), without and with the dynamic object (which adds the two-level form's
//    BVHs to the one-level one);
//  - SibenikMoveObject: one dynamic object moved: the scene's meshes, the surfaces, the ray
//    tracer's instance (transform and top-level commit) and the quadratures near it;
//  - SibenikInstanceCommit: the ray tracer's part of a move alone: the instance's transform and the
//    top-level commit;
//  - SibenikAnalyticLight: the sun and sky's irradiance on every element, traced in full;
//  - SibenikAnalyticLightAfterMove: the same brought up to date after a move of the object
//    (Transport::updateLightIrradianceAfterMove: only where its shadow was or is).
// The object is the scene's mesh at the 90th percentile of face count, made a dynamic object.
// Run: build/luxel-bench --benchmark_filter=Sibenik (skips when the scene is not unzipped).
#include <algorithm>
#include <filesystem>
#include <memory>

#include <benchmark/benchmark.h>
#include <glm/gtc/matrix_transform.hpp>

#include "luxel/import.h"
#include "transport/cpu_transport.h"

namespace luxel {
namespace {

struct Sibenik {
  Scene scene;
  SurfaceSet surfaces;
  uint32_t object = 0;
  size_t objectFaces = 0;
};

// Loaded once for all three benchmarks; null when the scene is absent.
Sibenik* sibenik() {
  static std::unique_ptr<Sibenik> s = []() -> std::unique_ptr<Sibenik> {
    const std::filesystem::path file = std::filesystem::path(LUXEL_SOURCE_DIR) / "bench/scenes/sibenik.json";
    if (!std::filesystem::exists(std::filesystem::path(LUXEL_BENCH_SCENES) / "sibenik-cathedral/sibenik.obj"))
      return nullptr;
    auto out = std::make_unique<Sibenik>();
    out->scene = loadScene(file.string());
    // Sibenik's OBJ is one node, so one object: the mesh at the 90th percentile of face count (a material group
    // of one part of the cathedral) becomes an object of its own, marked dynamic.
    std::vector<std::pair<size_t, uint32_t>> faces;
    for (uint32_t m = 0; m < out->scene.meshes.size(); ++m) faces.emplace_back(out->scene.meshes[m].faces.size(), m);
    std::sort(faces.begin(), faces.end());
    Mesh& mesh = out->scene.meshes[faces[faces.size() * 9 / 10].second];
    out->objectFaces = mesh.faces.size();
    out->object = uint32_t(out->scene.objects.size());
    out->scene.objects.push_back(Object{.name = mesh.name, .dynamic = true});
    mesh.object = out->object;
    DiscretiseOptions d;
    d.elementBudget = 100000;
    out->surfaces = discretise(out->scene, d);
    return out;
  }();
  return s.get();
}

void SibenikTransportBuild(benchmark::State& state) {
  Sibenik* s = sibenik();
  if (!s) return state.SkipWithError("sibenik-cathedral not unzipped under the build folder");
  s->scene.objects[s->object].dynamic = state.range(0) != 0;
  for (auto _ : state) {
    CpuTransport transport(s->scene, s->surfaces, FormFactorOptions{});
    benchmark::DoNotOptimize(&transport);
  }
  s->scene.objects[s->object].dynamic = true;
  state.counters["elements"] = double(s->surfaces.elements.size());
  state.counters["faces"] = double(s->surfaces.faces.size());
}

void SibenikMoveObject(benchmark::State& state) {
  Sibenik* s = sibenik();
  if (!s) return state.SkipWithError("sibenik-cathedral not unzipped under the build folder");
  CpuTransport transport(s->scene, s->surfaces, FormFactorOptions{});
  // One factor first, so that the receiver quadratures exist and a move updates those near it
  // (a transport that has computed no factor makes them only when first asked).
  const Transport::ElementPatch one[] = {{0, 0}};
  float factor = 0.0f;
  transport.pairs(one, {&factor, 1});
  const glm::mat4 rest = s->scene.objects[s->object].transform;
  const uint32_t moved[] = {s->object};
  int k = 0;
  for (auto _ : state) {
    const glm::mat4 to = glm::translate(glm::mat4(1.0f), Vec3(0.0f, 0.01f * float(++k % 10), 0.0f)) * rest;
    s->scene.placeObject(s->object, to);
    s->surfaces.placeObject(s->scene, s->object);
    transport.objectsMoved(moved);
  }
  state.counters["object faces"] = double(s->objectFaces);
  state.counters["receivers redone"] = double(transport.receiversRedoneByMove().size());
}

void SibenikInstanceCommit(benchmark::State& state) {
  Sibenik* s = sibenik();
  if (!s) return state.SkipWithError("sibenik-cathedral not unzipped under the build folder");
  CpuTransport transport(s->scene, s->surfaces, FormFactorOptions{});
  int k = 0;
  for (auto _ : state) {
    transport.tracer().placeInstance(0, glm::translate(glm::mat4(1.0f), Vec3(0.0f, 0.01f * float(++k % 10), 0.0f)));
    transport.tracer().commit();
  }
}

void SibenikAnalyticLight(benchmark::State& state) {
  Sibenik* s = sibenik();
  if (!s) return state.SkipWithError("sibenik-cathedral not unzipped under the build folder");
  CpuTransport transport(s->scene, s->surfaces, FormFactorOptions{});
  std::vector<Rgb> irradiance(s->surfaces.elements.size());
  for (auto _ : state) {
    std::fill(irradiance.begin(), irradiance.end(), Rgb(0.0f));
    transport.analyticIrradiance(irradiance);
    benchmark::DoNotOptimize(irradiance.data());
  }
}

void SibenikAnalyticLightAfterMove(benchmark::State& state) {
  Sibenik* s = sibenik();
  if (!s) return state.SkipWithError("sibenik-cathedral not unzipped under the build folder");
  CpuTransport transport(s->scene, s->surfaces, FormFactorOptions{});
  std::vector<uint32_t> lights(s->scene.lights.size());
  for (uint32_t i = 0; i < lights.size(); ++i) lights[i] = i;
  std::vector<Rgb> irradiance(s->surfaces.elements.size());
  transport.lightIrradiance(lights, irradiance);
  const glm::mat4 rest = s->scene.objects[s->object].transform;
  const uint32_t moved[] = {s->object};
  size_t redone = 0;
  int k = 0;
  for (auto _ : state) {
    state.PauseTiming();
    const glm::mat4 to = glm::translate(glm::mat4(1.0f), Vec3(0.0f, 0.01f * float(++k % 10), 0.0f)) * rest;
    s->scene.placeObject(s->object, to);
    s->surfaces.placeObject(s->scene, s->object);
    transport.objectsMoved(moved);
    state.ResumeTiming();
    redone += transport.updateLightIrradianceAfterMove(lights, irradiance);
    benchmark::DoNotOptimize(irradiance.data());
  }
  state.counters["elements again"] = double(redone) / double(state.iterations());
  state.counters["elements"] = double(s->surfaces.elements.size());
}

BENCHMARK(SibenikTransportBuild)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(SibenikMoveObject)->Unit(benchmark::kMillisecond)->Iterations(20);
BENCHMARK(SibenikInstanceCommit)->Unit(benchmark::kMicrosecond)->Iterations(200);
BENCHMARK(SibenikAnalyticLight)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(SibenikAnalyticLightAfterMove)->Unit(benchmark::kMillisecond)->Iterations(10);

}  // namespace
}  // namespace luxel
