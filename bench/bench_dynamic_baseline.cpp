// The baseline of `luxel bench dynamic`: what a progressive solve from scratch costs per frame of
// seed 001's spinning box (1 degree a frame, to 1e-3 unshot, no ambient term), done two ways:
//  - ProgressiveNewSession: a new Session of the scene with the box at the frame's pose
//    (discretisation, BVH, transport, solve), which traces the one-level BVH;
//  - ProgressiveRestartInSession: one Session whose placeObject restarts the solver, which after
//    the first move traces the two-level BVH kept for moves (instances).
// The suite times progressive the first way, the faster. Argument 0: cornell-low, 1: cornell-large.
// Run: build/luxel-bench --benchmark_filter=Progressive
#include <memory>

#include <benchmark/benchmark.h>

#include "luxel/bench.h"
#include "luxel/import.h"
#include "luxel/session.h"

namespace luxel {
namespace {

const char* sceneName(int64_t arg) { return arg == 0 ? "cornell-low" : "cornell-large"; }

SessionOptions frameOptions() {
  SessionOptions o;
  o.solve.method = "progressive";
  o.solve.settings.set("unshot", 1e-3).set("ambient", false);
  return o;
}

void ProgressiveNewSession(benchmark::State& state) {
  const Scene scene = loadScene(sceneName(state.range(0)));
  const uint32_t box = scene.dynamicObjects().at(0);
  int frame = 0;
  for (auto _ : state) {
    Scene there = scene;
    there.placeObject(box, bench::dynamicPose(scene, ++frame));
    Session session(std::move(there), DiscretiseOptions{}, frameOptions());
    while (session.step()) {
    }
    benchmark::DoNotOptimize(session.done());
  }
}

void ProgressiveRestartInSession(benchmark::State& state) {
  const Scene scene = loadScene(sceneName(state.range(0)));
  const uint32_t box = scene.dynamicObjects().at(0);
  Session session(scene, DiscretiseOptions{}, frameOptions());
  int frame = 0;
  session.placeObject(box, bench::dynamicPose(scene, ++frame));  // the two-level BVH from here on
  for (auto _ : state) {
    session.placeObject(box, bench::dynamicPose(scene, ++frame));
    while (session.step()) {
    }
  }
}

}  // namespace

BENCHMARK(ProgressiveNewSession)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(10);
BENCHMARK(ProgressiveRestartInSession)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(10);

}  // namespace luxel
