#include "bench_command.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include "io/atomic_file.h"
#include "output_paths.h"
#include "luxel/bench.h"
#include "luxel/error.h"

namespace luxel::cli {
namespace {

using namespace luxel::bench;

std::string defaultCacheDir() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::string(xdg) + "/luxel/references";
  if (const char* home = std::getenv("HOME"); home && *home) return std::string(home) + "/.cache/luxel/references";
  return ".luxel-cache/references";
}

std::string ms(double seconds) { return fmt::format("{:.1f}", seconds * 1e3); }

nlohmann::json spreadJson(const Spread& s) {
  return {{"median", s.median}, {"min", s.min}, {"max", s.max}};
}

nlohmann::json caseJson(const CaseResult& r) {
  const Case& c = r.benchCase;
  nlohmann::json j = {
      {"name", c.name},
      {"scene", c.scene},
      {"backend", c.solve.backend},
      {"setting", c.setting},
      {"solver", c.solve.method},
      {"settings", c.solve.settings.values()},
      {"elements", r.elements},
      {"patches", r.patches},
      {"runs", r.runs},
      {"seconds", {{"load", r.loadSeconds}, {"total", spreadJson(r.total)}, {"setup", spreadJson(r.setup)},
                   {"form_factors", spreadJson(r.formFactors)}, {"solve", spreadJson(r.solve)}}},
      {"rays", r.rays},
      {"rays_per_second", r.raysPerSecond},
      {"embree_raw_rays_per_second", r.limitRaysPerSecond},
      {"fraction_of_embree_raw", r.limitFraction},
      {"shots", r.shots},
      {"iterations", r.iterations},
      {"unshot_fraction", r.unshot},
      {"peak_memory_bytes", r.peakMemoryBytes},
      {"error", r.error ? nlohmann::json(*r.error) : nlohmann::json(nullptr)},
      {"error_note", r.errorNote},
      {"reference_seconds", r.referenceSeconds},
      {"device", r.device},
      {"hemicubes", r.hemicubes},
      {"hemicubes_per_second", r.hemicubesPerSecond},
      {"ms_per_gather", r.msPerGather},
      {"ms_per_shot", r.msPerShot},
  };
  if (c.solve.method == "hierarchical")
    j["hierarchy"] = {{"seconds", r.hierarchySeconds}, {"bytes", r.hierarchyBytes}, {"links", r.links}, {"leaves", r.leaves}};
  if (!c.seed.source.empty())
    j["seed"] = {{"source", c.seed.source}, {"milliseconds", c.seed.milliseconds}, {"error", c.seed.error}};
  return j;
}

void printHeader() {
  std::cout << fmt::format("{:<34} {:>7} {:>19} {:>8} {:>8} {:>8} {:>7} {:>7} {:>5} {:>6} {:>9} {:>9} {:>9}\n", "case",
                           "elems", "total ms (min-max)", "setup", "ff+vis", "solve", "Mray/s", "limit", "lim%",
                           "MiB", "error", "seed ms", "seed err");
}

void printRow(const CaseResult& r) {
  const Case& c = r.benchCase;
  std::string total = fmt::format("{} ({}-{})", ms(r.total.median), ms(r.total.min), ms(r.total.max));
  std::string error = r.error ? fmt::format("{:.5f}", *r.error) : std::string("-");
  std::string seedMs = c.seed.milliseconds > 0 ? fmt::format("{:g}", c.seed.milliseconds) : "-";
  std::string seedErr = c.seed.error > 0 ? fmt::format("{:.5f}", c.seed.error) : "-";
  std::string limit = r.limitRaysPerSecond > 0 ? fmt::format("{:.1f}", r.limitRaysPerSecond / 1e6) : "-";
  std::string frac = r.limitRaysPerSecond > 0 ? fmt::format("{:.0f}%", 100 * r.limitFraction) : "-";
  std::cout << fmt::format("{:<34} {:>7} {:>19} {:>8} {:>8} {:>8} {:>7.1f} {:>7} {:>5} {:>6.0f} {:>9} {:>9} {:>9}\n",
                           c.name, r.elements, total, ms(r.setup.median), ms(r.formFactors.median),
                           ms(r.solve.median), r.raysPerSecond / 1e6, limit, frac,
                           double(r.peakMemoryBytes) / (1 << 20), error, seedMs, seedErr);
  if (!r.errorNote.empty()) std::cout << "    (" << r.errorNote << ")\n";
  if (c.solve.method == "hierarchical")
    std::cout << fmt::format("    (hierarchy {:.2f} s, {:.1f} MiB; {} leaves, {} links over the sweeps)\n", r.hierarchySeconds,
                             double(r.hierarchyBytes) / (1 << 20), r.leaves, r.links);
  std::cout.flush();
}

nlohmann::json machineJson(const Machine& m) {
  return {{"cpu", m.cpuModel}, {"hardware_threads", m.cores}, {"threads", m.threads}, {"memory_bytes", m.memoryBytes}, {"os", m.os}};
}

// ---- the dynamic suite ------------------------------------------------------------------------

constexpr const char* kDynamicMotion =
    "the box turns about the vertical axis through its centre at 30 degrees/s, 30 frames/s: 1 degree a frame";

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
  return j;
}

// Issue 15's targets for a cross-redistribution case; null where this run cannot say (no
// reference, or no progressive case to compare with).
nlohmann::json dynamicTargetJson(const DynamicResult& r, std::optional<double> speedup, double seedSpeedup) {
  const DynamicCase& c = r.benchCase;
  const bool haveError = !r.errors.empty();
  auto orNull = [](bool known, auto value) { return known ? nlohmann::json(value) : nlohmann::json(nullptr); };
  const double settled = r.settleErrors.empty() ? 0.0 : r.settleErrors.back();
  return {
      {"scene", c.scene},
      {"backend", c.backend},
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
  std::string line = fmt::format("{}/{}: p95 {:.1f} ms <= {:g} ms", t["scene"].get<std::string>(), t["backend"].get<std::string>(),
                                 t["p95_ms"].get<double>(), t["seed_ms"].get<double>());
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
                             kDynamicMotion, a.frames,
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
    if (c.method == "cross-redistribution") {
      nlohmann::json t = dynamicTargetJson(r, speedup, seedProgressiveMs[c.scene] / c.seedMs);
      targetLines.push_back(dynamicTargetLine(t));
      targets.push_back(std::move(t));
    }
  }
  if (ran == 0) throw Error(fmt::format("no case of suite 'dynamic' matches the scenes, backends and --case given"));
  if (skipped == ran) throw Error(fmt::format("every case of suite 'dynamic' that ran ({}) was skipped; nothing measured", ran));
  if (!a.quiet && !targetLines.empty()) {
    std::cout << "issue 15's targets for cross-redistribution: p95 at most 001's GTX 670 figure at an error at most "
                 "001's; speed-up over progressive at least 001's; within 1% once the motion stops\n";
    for (const std::string& line : targetLines) std::cout << "  " << line << "\n";
  }

  if (!a.jsonPath.empty()) {
    nlohmann::json j = {
        {"suite", "dynamic"},
        {"description", "seed 001's dynamic radiosity: the four scenes' box turning, frame by frame"},
        {"motion", kDynamicMotion},
        {"degrees_per_frame", kDynamicDegreesPerFrame},
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

}  // namespace

void checkBenchArgs(const BenchArgs& a) {
  if (a.list) return;
  if (a.suite == kDynamicSuiteName) {
    if (a.runsGiven) throw Error("--runs does not apply to the dynamic suite: its frames are its runs (--frames N)");
    if (a.reference != "cpu")
      throw Error("--reference does not apply to the dynamic suite: its references are progressive solves on the CPU");
  } else if (a.dynamicOptionGiven) {
    throw Error(fmt::format("--frames, --gl-frames, --scenes and --backends belong to the dynamic suite, not '{}'", a.suite));
  }
}

int runBench(const BenchArgs& a) {
  if (a.list) {
    for (const Suite& s : suites()) {
      std::cout << s.name << ": " << s.description << "\n";
      for (const Case& c : s.cases) std::cout << "  " << c.name << "  [" << c.setting << "]\n";
    }
    std::cout << kDynamicSuiteName << ": seed 001's four scenes with the box turning, " << kDynamicMotion << "\n";
    for (const DynamicCase& c : dynamicCases()) std::cout << "  " << c.name() << "\n";
    return 0;
  }
  const bool dynamic = a.suite == kDynamicSuiteName;
  const Suite* suitePtr = dynamic ? nullptr : &findSuite(a.suite);
  if (!a.jsonPath.empty()) checkOutputPaths({{"--json", a.jsonPath, {}}});
  std::unique_ptr<tbb::global_control> limit;
  if (a.threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(a.threads));
  const int threads = a.threads > 0 ? a.threads : tbb::info::default_concurrency();

  Options options;
  options.runs = a.runs;
  options.cacheDir = a.cacheDir.empty() ? defaultCacheDir() : a.cacheDir;
  options.reference = !a.noReference;
  options.referenceKind = a.reference == "monte-carlo" ? Options::ReferenceKind::MonteCarlo : Options::ReferenceKind::Cpu;
  options.hardwareLimit = !a.noLimit;

  const Machine m = describeMachine(threads);
  if (!a.quiet)
    std::cout << fmt::format("luxel bench {}: {} ({} hardware threads, {} used), {}, commit {}, {}\n", a.suite,
                             m.cpuModel, m.cores, m.threads, m.os, m.commit.empty() ? "unknown" : m.commit, m.date);
  if (dynamic) return runDynamicBench(a, options, m);
  const Suite& suite = *suitePtr;
  if (!a.quiet) {
    std::cout << fmt::format("{} runs per case; times are medians; {} references in {}\n", a.runs, a.reference,
                             options.cacheDir);
    printHeader();
  }
  nlohmann::json cases = nlohmann::json::array();
  int ran = 0, skipped = 0;
  for (const Case& c : suite.cases) {
    if (!a.filter.empty() && c.name.find(a.filter) == std::string::npos) continue;
    ++ran;
    CaseResult r;
    try {
      r = runCase(c, options);
    } catch (const Cancelled&) {
      throw;
    } catch (const Error& e) {
      // A scene that is not there (the shared scenes) is reported and skipped, not fatal.
      std::cout << fmt::format("{:<34} skipped: {}\n", c.name, e.what());
      cases.push_back({{"name", c.name}, {"skipped", e.what()}});
      ++skipped;
      continue;
    }
    if (!a.quiet) printRow(r);
    cases.push_back(caseJson(r));
  }
  if (ran == 0) throw Error(fmt::format("no case of suite '{}' matches '{}'", suite.name, a.filter));
  if (skipped == ran) throw Error(fmt::format("every case of suite '{}' that ran ({}) was skipped; nothing measured", suite.name, ran));

  if (!a.jsonPath.empty()) {
    nlohmann::json j = {
        {"suite", suite.name},
        {"description", suite.description},
        {"runs", a.runs},
        {"reference", a.noReference ? "none" : a.reference},
        {"machine", machineJson(m)},
        {"commit", m.commit},
        {"date", m.date},
        {"cases", cases},
    };
    writeTextAtomically(a.jsonPath, j.dump(2) + "\n");
    if (!a.quiet) std::cout << "luxel: wrote " << a.jsonPath << "\n";
  }
  return 0;
}

}  // namespace luxel::cli
