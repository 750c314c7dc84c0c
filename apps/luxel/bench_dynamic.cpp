// `luxel bench dynamic`: seed 001's spinning box frame by frame (bench.h, runDynamicCase), printed
// beside 001's Tables 5.1 and 5.2a and written as JSON with the machine, commit and date.
#include "bench_dynamic.h"

#include <algorithm>
#include <iostream>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "io/atomic_file.h"
#include "luxel/error.h"
#include "scene/builtin/builtin_scenes.h"

namespace luxel::cli {
namespace {

using namespace luxel::bench;

std::string motion() {
  return fmt::format("each scene's animation: the box spins about the vertical through its centre at {:g} degrees/s, "
                     "shown at {:g} frames/s: {:g} degree a frame",
                     builtin::kSeedBoxDegreesPerSecond, kDynamicFramesPerSecond,
                     builtin::kSeedBoxDegreesPerSecond / kDynamicFramesPerSecond);
}

// 001's cross-redistribution figures for a scene: the targets for every dynamic method.
const DynamicCase& crossFigures(const std::string& scene) {
  for (const DynamicCase& c : dynamicCases())
    if (c.scene == scene && c.method == "cross-redistribution") return c;
  throw Error(fmt::format("no cross-redistribution figures for scene '{}'", scene));
}

bool wanted(const std::vector<std::string>& only, const std::string& value) {
  return only.empty() || std::find(only.begin(), only.end(), value) != only.end();
}

std::string optionalNumber(std::optional<double> v, const char* format) {
  return v ? fmt::format(fmt::runtime(format), *v) : std::string("-");
}

void printDynamicHeader() {
  std::cout << fmt::format("{:<38} {:>6} {:>6} {:>6} {:>9} {:>9} {:>8} {:>9} {:>9} {:>9} | {:>7} {:>7} {:>9}\n", "case",
                           "elems", "moving", "frames", "ms median", "ms p95", "speed-up", "error med", "error max",
                           "settled", "seed ms", "seed x", "seed err");
}

void printDynamicRow(const DynamicResult& r, std::optional<double> speedup, double seedSpeedup) {
  const DynamicCase& c = r.benchCase;
  const bool haveError = !r.errors.empty();
  std::cout << fmt::format(
      "{:<38} {:>6} {:>6} {:>6} {:>9.1f} {:>9.1f} {:>8} {:>9} {:>9} {:>9} | {:>7g} {:>7} {:>9.5f}\n", c.name(), r.elements,
      r.movingElements, r.frames, r.msMedian, r.msP95, optionalNumber(speedup, "{:.1f}x"),
      haveError ? fmt::format("{:.5f}", r.errorMedian) : "-", haveError ? fmt::format("{:.5f}", r.errorMax) : "-",
      r.settleErrors.empty() ? "-" : fmt::format("{:.5f}", r.settleErrors.back()), c.seedMs,
      fmt::format("{:.1f}x", seedSpeedup), c.seedError);
  if (!r.device.empty()) std::cout << "    (" << r.device << ")\n";
  std::cout.flush();
}

nlohmann::json dynamicCaseJson(const DynamicResult& r, std::optional<double> speedup) {
  const DynamicCase& c = r.benchCase;
  const bool haveError = !r.errors.empty();
  nlohmann::json j = {
      {"name", c.name()},
      {"scene", c.scene},
      {"method", c.method},
      {"backend", c.backend},
      {"device", r.device},
      {"frames", r.frames},
      {"degrees_per_frame", r.degreesPerFrame},
      {"ms_per_frame", {{"median", r.msMedian}, {"p95", r.msP95}}},
      {"error", haveError ? nlohmann::json{{"median", r.errorMedian}, {"max", r.errorMax}} : nlohmann::json(nullptr)},
      {"speedup_over_progressive", speedup ? nlohmann::json(*speedup) : nlohmann::json(nullptr)},
      {"elements", r.elements},
      {"moving_elements", r.movingElements},
      {"factors_recomputed_per_frame", r.factorsPerFrame ? nlohmann::json(*r.factorsPerFrame) : nlohmann::json(nullptr)},
      {"shots_per_frame", r.shotsPerFrame},
      {"seed_gtx670_ms", c.seedMs},
      {"seed_error", c.seedError},
      {"settle_error", r.settleErrors},
      {"error_frames", r.errorFrames},
      {"errors", r.errors},
      {"frame_ms", r.frameMs},
      {"first_solve_seconds", r.firstSolveSeconds},
      {"reference_seconds", r.referenceSeconds},
  };
  // GL cases: where a frame's time goes (gl/gpu_timeline.h), medians over the timed frames.
  for (const PhaseTime& p : r.phases)
    j["phases_ms"][p.name] = {{"gpu", 1e3 * p.secondsGpu}, {"cpu", 1e3 * p.secondsCpu}, {"frames", p.count}};
  return j;
}

// Issue 15's targets for a dynamic method's case: 001's cross-redistribution figures for the
// scene (its time, its error, its speed-up over progressive). Null where this run cannot say (no
// reference, or no progressive case to compare with).
nlohmann::json dynamicTargetJson(const DynamicResult& r, std::optional<double> speedup, double seedProgressiveMs) {
  const DynamicCase& c = crossFigures(r.benchCase.scene);
  const double seedSpeedup = seedProgressiveMs / c.seedMs;
  const bool haveError = !r.errors.empty();
  auto orNull = [](bool known, auto value) { return known ? nlohmann::json(value) : nlohmann::json(nullptr); };
  const double settled = r.settleErrors.empty() ? 0.0 : r.settleErrors.back();
  return {
      {"scene", r.benchCase.scene},
      {"method", r.benchCase.method},
      {"backend", r.benchCase.backend},
      {"p95_ms", r.msP95},
      {"seed_ms", c.seedMs},
      {"error_max", orNull(haveError, r.errorMax)},
      {"seed_error", c.seedError},
      {"time_met", orNull(haveError, r.msP95 <= c.seedMs && r.errorMax <= c.seedError)},
      {"speedup", orNull(speedup.has_value(), speedup.value_or(0.0))},
      {"seed_speedup", seedSpeedup},
      {"speedup_met", orNull(speedup.has_value(), speedup.value_or(0.0) >= seedSpeedup)},
      {"settle_error", orNull(!r.settleErrors.empty(), settled)},
      {"settle_met", orNull(!r.settleErrors.empty(), settled <= 0.01)},
  };
}

std::string dynamicTargetLine(const nlohmann::json& t) {
  auto verdict = [](const nlohmann::json& met) {
    return met.is_null() ? std::string("unknown") : met.get<bool>() ? std::string("met") : std::string("not met");
  };
  std::string line = fmt::format("{}/{}/{}: p95 {:.1f} ms <= {:g} ms", t["scene"].get<std::string>(),
                                 t["method"].get<std::string>(), t["backend"].get<std::string>(), t["p95_ms"].get<double>(),
                                 t["seed_ms"].get<double>());
  if (!t["error_max"].is_null())
    line += fmt::format(" at error {:.5f} <= {:.5f}", t["error_max"].get<double>(), t["seed_error"].get<double>());
  line += ": " + verdict(t["time_met"]);
  if (!t["speedup"].is_null())
    line += fmt::format("; speed-up {:.1f}x >= {:.1f}x", t["speedup"].get<double>(), t["seed_speedup"].get<double>());
  line += ": " + verdict(t["speedup_met"]);
  if (!t["settle_error"].is_null()) line += fmt::format("; settled to {:.5f} <= 0.01", t["settle_error"].get<double>());
  line += ": " + verdict(t["settle_met"]);
  return line;
}

}  // namespace

void listDynamicSuite() {
  std::cout << kDynamicSuiteName << ": seed 001's four scenes, " << motion() << "\n";
  for (const DynamicCase& c : dynamicCases()) std::cout << "  " << c.name() << "\n";
}

int runDynamicBench(const BenchArgs& a, const Options& options, const Machine& m) {
  DynamicOptions o;
  o.frames = a.frames;
  o.glFrames = a.glFrames;
  o.reference = options.reference;
  o.cacheDir = options.cacheDir;
  const std::string errorFrames = a.frames <= kEveryFrameErrorUpTo
                                      ? "every frame"
                                      : fmt::format("every {}th frame and each case's last", o.errorStride);
  if (!a.quiet) {
    std::cout << fmt::format("{}; {} moving frames per case{}, the first {} not timed; every method stops at {:g} "
                             "unshot, no ambient term\n",
                             motion(), a.frames,
                             a.glFrames > 0 ? fmt::format(" ({} on GL)", std::min(a.frames, a.glFrames))
                                            : " (GL: on a GPU only, unless --gl-frames)",
                             o.untimedFrames, o.unshot);
    if (o.reference)
      std::cout << fmt::format("error: NRMSE at {} against progressive on the CPU from scratch to {:g} unshot at the same "
                               "pose and elements; settled: {} frames after the motion stops; references in {}\n",
                               errorFrames, o.referenceUnshot, o.settleFrames, options.cacheDir);
    std::cout << "seed: 001 Table 5.2a (ms per frame, GTX 670; seed x: its progressive / this) and Table 5.1 (NRMSE "
                 "against a high-quality gather)\n";
    printDynamicHeader();
  }
  nlohmann::json cases = nlohmann::json::array();
  std::map<std::string, double> progressiveMs;  // scene/backend -> median
  std::map<std::string, double> seedProgressiveMs;
  for (const DynamicCase& c : dynamicCases())
    if (c.method == "progressive") seedProgressiveMs[c.scene] = c.seedMs;
  nlohmann::json targets = nlohmann::json::array();
  std::vector<std::string> targetLines;
  int ran = 0, skipped = 0;
  for (const DynamicCase& c : dynamicCases()) {
    if (!wanted(a.scenes, c.scene) || !wanted(a.backends, c.backend)) continue;
    if (!a.filter.empty() && c.name().find(a.filter) == std::string::npos) continue;
    ++ran;
    DynamicResult r;
    try {
      r = runDynamicCase(c, o);
    } catch (const Cancelled&) {
      throw;
    } catch (const Error& e) {
      std::cout << fmt::format("{:<38} skipped: {}\n", c.name(), e.what());
      cases.push_back({{"name", c.name()}, {"scene", c.scene}, {"method", c.method}, {"backend", c.backend}, {"skipped", e.what()}});
      ++skipped;
      continue;
    }
    const std::string key = c.scene + "/" + c.backend;
    if (c.method == "progressive") progressiveMs[key] = r.msMedian;
    std::optional<double> speedup;
    if (auto p = progressiveMs.find(key); p != progressiveMs.end() && r.msMedian > 0) speedup = p->second / r.msMedian;
    if (!a.quiet) printDynamicRow(r, speedup, seedProgressiveMs[c.scene] / c.seedMs);
    cases.push_back(dynamicCaseJson(r, speedup));
    if (c.method != "progressive") {
      nlohmann::json t = dynamicTargetJson(r, speedup, seedProgressiveMs[c.scene]);
      targetLines.push_back(dynamicTargetLine(t));
      targets.push_back(std::move(t));
    }
  }
  if (ran == 0) throw Error(fmt::format("no case of suite 'dynamic' matches the scenes, backends and --case given"));
  if (skipped == ran) throw Error(fmt::format("every case of suite 'dynamic' that ran ({}) was skipped; nothing measured", ran));
  if (!a.quiet && !targetLines.empty()) {
    std::cout << "issue 15's targets, 001's cross-redistribution figures: p95 at most its GTX 670 time at an error at "
                 "most its; speed-up over progressive (same backend) at least its; within 1% once the motion stops\n";
    for (const std::string& line : targetLines) std::cout << "  " << line << "\n";
  }

  if (!a.jsonPath.empty()) {
    nlohmann::json j = {
        {"suite", "dynamic"},
        {"description", "seed 001's dynamic radiosity: the four scenes' box turning, frame by frame"},
        {"motion", motion()},
        {"degrees_per_frame", builtin::kSeedBoxDegreesPerSecond / kDynamicFramesPerSecond},
        {"frames_per_second", kDynamicFramesPerSecond},
        {"frames", a.frames},
        {"untimed_frames", o.untimedFrames},
        {"unshot", o.unshot},
        {"reference", o.reference ? fmt::format("progressive on the CPU from scratch to {:g} unshot, same pose and elements",
                                                o.referenceUnshot)
                                  : "none"},
        {"error_frames", o.reference ? errorFrames : "none"},
        {"settle_frames", o.settleFrames},
        {"machine", machineJson(m)},
        {"commit", m.commit},
        {"date", m.date},
        {"cases", cases},
        {"targets", targets},
    };
    writeTextAtomically(a.jsonPath, j.dump(2) + "\n");
    if (!a.quiet) std::cout << "luxel: wrote " << a.jsonPath << "\n";
  }
  return 0;
}


}  // namespace luxel::cli
