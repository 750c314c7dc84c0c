#include "bench_command.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include "bench_dynamic.h"
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

nlohmann::json probeJson(const std::optional<ProbeError>& e) {
  if (!e) return nullptr;
  return {{"probes", e->probes},  {"nrmse", e->nrmse}, {"noise", e->noise},
          {"bias", e->bias},      {"within_3_percent", e->withinThreePercent},
          {"worst", e->worst}};
}

nlohmann::json probeSamplesJson(const std::vector<CaseResult::Probe>& probes) {
  nlohmann::json a = nlohmann::json::array();
  for (const CaseResult::Probe& p : probes)
    a.push_back({{"element", p.element},
                 {"centroid", {p.centroid.x, p.centroid.y, p.centroid.z}},
                 {"traced", p.traced},
                 {"traced_error", p.tracedError},
                 {"traced_direct", p.tracedDirect},
                 {"solution", p.solution},
                 {"solution_direct", p.solutionDirect}});
  return a;
}

std::string probeText(const ProbeError& e) {
  return fmt::format("NRMSE {:.4f} (noise {:.4f}), bias {:+.2f}%, {:.0f}% of probes within 3%, worst {:.1f}%", e.nrmse,
                     e.noise, 100 * e.bias, 100 * e.withinThreePercent, 100 * e.worst);
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
  if (r.probeError)
    j["probes"] = {{"solution", probeJson(r.probeError)},
                   {"reference", probeJson(r.referenceProbeError)},
                   {"solution_direct", probeJson(r.probeDirectError)},
                   {"solution_indirect", probeJson(r.probeIndirectError)},
                   {"gathered", probeJson(r.probeGatheredError)},
                   {"gathered_indirect", probeJson(r.probeGatheredIndirectError)},
                   {"gather_seconds", r.probeGatherSeconds},
                   {"paths", r.probePaths},
                   {"each", probeSamplesJson(r.probeSamples)},
                   {"seconds", r.probeSeconds}};
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
  if (r.probeError) {
    std::cout << fmt::format("    (irradiance against {} path-traced probes, {:.3g} paths: {})\n", r.probeError->probes,
                             double(r.probePaths), probeText(*r.probeError));
    if (r.probeDirectError && r.probeIndirectError)
      std::cout << fmt::format("    (its direct light: {}; the rest: {})\n", probeText(*r.probeDirectError),
                               probeText(*r.probeIndirectError));
    if (r.probeGatheredError && r.probeGatheredIndirectError)
      std::cout << fmt::format("    (as an hq render gathers it, {:.1f} s: {}; its indirect light: {})\n",
                               r.probeGatherSeconds, probeText(*r.probeGatheredError),
                               probeText(*r.probeGatheredIndirectError));
    if (r.referenceProbeError)
      std::cout << fmt::format("    (the reference against the same probes: {})\n", probeText(*r.referenceProbeError));
  }
  if (c.solve.method == "hierarchical")
    std::cout << fmt::format("    (hierarchy {:.2f} s, {:.1f} MiB; {} leaves, {} links over the sweeps)\n", r.hierarchySeconds,
                             double(r.hierarchyBytes) / (1 << 20), r.leaves, r.links);
  std::cout.flush();
}

}  // namespace

nlohmann::json machineJson(const bench::Machine& m) {
  return {{"cpu", m.cpuModel}, {"hardware_threads", m.cores}, {"threads", m.threads}, {"memory_bytes", m.memoryBytes}, {"os", m.os}};
}

void checkBenchArgs(const BenchArgs& a) {
  if (a.list) return;
  if (a.suite == kDynamicSuiteName) {
    if (a.runsGiven) throw Error("--runs does not apply to the dynamic suite: its frames are its runs (--frames N)");
    if (a.reference != "cpu")
      throw Error("--reference does not apply to the dynamic suite: its references are progressive solves on the CPU");
    if (!a.set.empty()) throw Error("--set does not apply to the dynamic suite: each method's options are its own");
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
    listDynamicSuite();
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
  for (Case c : suite.cases) {
    if (!a.filter.empty() && c.name.find(a.filter) == std::string::npos) continue;
    ++ran;
    for (const std::string& s : a.set) c.solve.settings.parse(s);
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
