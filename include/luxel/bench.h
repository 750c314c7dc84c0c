// The benchmark suite behind `luxel bench`: named cases (a scene, a solver, a backend and a
// setting), each run N times and reported with the split of its wall time, its ray throughput
// beside Embree's raw throughput on the same rays, its peak memory, and its error against a
// converged reference of the same discretisation (cached on disk). docs/performance.md explains
// the method and keeps the results.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "luxel/progress.h"
#include "luxel/solve.h"
#include "luxel/surface.h"

namespace luxel::bench {

// What a seed document published for the same work, shown beside luxel's figure.
struct SeedFigure {
  std::string source;        // e.g. "001 Table 5.2a, GTX 670"
  double milliseconds = 0.0; // 0 when the seed gives no time
  double error = 0.0;        // normalised RMS error the seed reached; 0 when none
};

struct Case {
  std::string name;     // unique in its suite, e.g. "cornell-large/progressive"
  std::string scene;    // a built-in name, a scene file or a mesh file (as `luxel render`)
  std::string setting;  // what this case varies, in words
  DiscretiseOptions discretise;
  SolveOptions solve;  // backend "gl": OpenGL hemicubes (skipped, saying why, without a context)
  SeedFigure seed;
  // Cases whose pairs (elements x patches) exceed this get no reference: a gather over them
  // would take hours. Their error column says so.
  double maxReferencePairs = 5e7;
  // How this case's reference is solved when not the default gather (bench/reference.h): for
  // scenes whose pairs no gather could hold, a deep progressive solve on the same elements.
  // Named in the report; cached like the others.
  std::optional<SolveOptions> reference;
  std::string referenceName;  // how the report names it, e.g. "progressive to 1e-4 unshot"
  // Elements whose irradiance is path traced as an independent check of the solution and of the
  // reference (bench/probe_reference.h); 0 for none.
  size_t probes = 0;
};

// The difference between element irradiances and path-traced probes of them, all channels: the
// path tracer's noise is measured, and taken out of the RMS figure.
struct ProbeError {
  size_t probes = 0;
  // sqrt(max(0, sum |H - P|^2 - sum s^2) / sum |P|^2), P the probes' means and s their standard errors.
  double nrmse = 0.0;
  double noise = 0.0;   // sqrt(sum s^2 / sum |P|^2): what the probes' own noise adds before it is taken out
  double bias = 0.0;    // sum (H - P) / sum P
  // Probes whose |H - P| (channels summed) is within 3% of P (or 0.1% of the probes' mean P, if
  // more) plus twice its standard error.
  double withinThreePercent = 0.0;
  double worst = 0.0;   // the largest |H - P| / P, channels summed, over probes with P above 1% of the mean
};

struct Suite {
  std::string name;
  std::string description;
  std::vector<Case> cases;
};

// The named suites: "seeds" (001's four scenes), "shader" (000's boxes), "scenes" (the shared
// real scenes, which skip when absent), "hierarchical" (seed 002's solver on the box and the real
// scenes), "quick" (a smoke run), "gl" (the OpenGL backend on scenes small enough for Mesa's
// llvmpipe).
const std::vector<Suite>& suites();
const Suite& findSuite(const std::string& name);  // throws Error listing the names

struct Options {
  int runs = 5;
  std::string cacheDir;  // where references are kept; created when missing
  bool hardwareLimit = true;
  bool reference = true;
  // How references are solved: gathering over the CPU backend's form factors at high settings,
  // or over cosine-distributed Monte Carlo rays (transport/monte_carlo_transport.h), which share
  // nothing with the CPU's estimator: a check of the estimator itself, noisier and slower.
  enum class ReferenceKind { Cpu, MonteCarlo };
  ReferenceKind referenceKind = ReferenceKind::Cpu;
  ProgressCallback progress;
};

// Median and extremes of one measurement over the runs.
struct Spread {
  double median = 0.0, min = 0.0, max = 0.0;
};

struct CaseResult {
  Case benchCase;
  size_t elements = 0, patches = 0;
  int runs = 0;
  double loadSeconds = 0.0;                 // reading the scene, once, outside the runs
  Spread total, setup, formFactors, solve;  // seconds; setup includes discretisation
  uint64_t rays = 0;                        // per run
  double raysPerSecond = 0.0;               // rays / form-factor time, median run
  uint64_t shots = 0, iterations = 0;
  double unshot = 0.0;
  size_t peakMemoryBytes = 0;  // resident-set high-water mark during one run (0: unknown)
  // Normalised RMS error of element radiosities against the reference (see docs/performance.md);
  // empty when there is no reference, with the reason in errorNote.
  std::optional<double> error;
  std::string errorNote;
  double referenceSeconds = 0.0;  // 0 when the reference came from the cache
  // Against the path-traced probes (Case::probes): the solution's irradiance, and the reference's.
  std::optional<ProbeError> probeError, referenceProbeError;
  // The solution's direct irradiance against probes of the direct light alone, and the rest
  // (the indirect light) against the difference of the two sets of probes.
  std::optional<ProbeError> probeDirectError, probeIndirectError;
  // What an hq render shows of the same elements (render/gather_pipeline.h: the indirect light
  // gathered at vertices from the solution, three bounces, and the direct light its pixels trace,
  // each averaged over the probe element): all of it, and its indirect part; and the seconds the
  // gather took.
  std::optional<ProbeError> probeGatheredError, probeGatheredIndirectError;
  double probeGatherSeconds = 0.0;
  // Each probe, for a look at where the differences are (channels summed, W/m^2): the element,
  // its centroid, the path-traced irradiance and its standard error, the path-traced direct
  // light, and the solution's irradiance and direct irradiance (NaN where it has none).
  struct Probe {
    uint32_t element = 0;
    Vec3 centroid{0.0f};
    double traced = 0.0, tracedError = 0.0, tracedDirect = 0.0;
    double solution = 0.0, solutionDirect = 0.0;
  };
  std::vector<Probe> probeSamples;
  double probeSeconds = 0.0;  // path tracing them; 0 when they came from the cache
  uint64_t probePaths = 0;    // paths over all probes
  // Embree alone on the rays one run cast (same streams, same threads).
  double limitRaysPerSecond = 0.0;
  double limitFraction = 0.0;  // raysPerSecond / limitRaysPerSecond
  // GL cases (0 otherwise), median run: hemicubes rendered per run and per second of
  // form-factor time; milliseconds of form-factor time per element gathered (gather: its k x k
  // hemicubes) and of form-factor plus solve time per shot (progressive; 0 when none was shot).
  std::string device;  // the GL renderer
  uint64_t hemicubes = 0;
  double hemicubesPerSecond = 0.0;
  double msPerGather = 0.0;  // gather: one element's hemicubes, once
  double msPerShot = 0.0;    // progressive: a pass's time over its shooters
  // Hierarchical cases (0 otherwise), last run: the face-cluster tree's build time and memory,
  // the links of the last sweep, the element tree's leaves.
  double hierarchySeconds = 0.0;
  size_t hierarchyBytes = 0;
  uint64_t links = 0;
  size_t leaves = 0;
};

CaseResult runCase(const Case& benchCase, const Options& options);

// `luxel bench dynamic`: seed 001's dynamic radiosity (issue 15). Each of 001's four scenes is
// played as it animates itself (Scene::animation: the box spins about the vertical through its
// centre at 30 degrees a second), at 30 frames a second: frame k is the pose at k / 30 s, one
// degree a frame. Each frame moves the box (Session::placeObject) and solves to the method's
// stopping rule; its error is against a converged solve from scratch at the same pose.
inline constexpr const char* kDynamicSuiteName = "dynamic";  // not in suites(): its cases are frame sequences

struct DynamicCase {
  std::string scene;    // a built-in seed-001 scene
  std::string method;   // "progressive" (from scratch every frame), "incremental", "cross-redistribution"
  std::string backend;  // "cpu" or "gl"
  double seedMs = 0.0;     // 001 Table 5.2a, GTX 670, ms per frame of the same scene and method
  double seedError = 0.0;  // 001 Table 5.1, NRMSE against a high-quality gather
  std::string name() const { return scene + "/" + method + "/" + backend; }
};

// Per scene: progressive on the CPU first (the speed-ups are against it), then incremental and
// cross-redistribution on the CPU, then progressive, incremental and cross-redistribution on GL.
const std::vector<DynamicCase>& dynamicCases();
inline constexpr double kDynamicFramesPerSecond = 30.0;
// The world transform of the scene's first dynamic object at frame k: its animation at time
// k / kDynamicFramesPerSecond. Throws Error when the scene has no dynamic object or does not
// animate it.
glm::mat4 dynamicPose(const Scene& scene, int frame);

struct DynamicOptions {
  int frames = 100;  // moving frames per case
  // GL cases' moving frames (at most `frames`); 0: `frames` on a GPU, and none on a software
  // rasteriser (the case throws, saying so): Mesa's llvmpipe takes seconds a frame.
  int glFrames = 0;
  int untimedFrames = 3;  // the first frames, left out of the times (001, L1146: "the first 1 to 3")
  int settleFrames = 4;   // after the motion stops: frames with no move, each with its error
  // Frames whose error is measured: every frame when `frames` <= kEveryFrameErrorUpTo, else
  // every errorStride-th frame; a case's last moving frame always.
  int errorStride = 10;
  double unshot = 1e-3;           // every method's stopping rule
  double referenceUnshot = 1e-6;  // the references: progressive on the CPU, from scratch
  bool reference = true;          // false: no error column
  std::string cacheDir;           // references are cached here, as the static suites' are
  ProgressCallback progress;
};
inline constexpr int kEveryFrameErrorUpTo = 20;

struct DynamicResult {
  DynamicCase benchCase;
  std::string device;  // the GL renderer (GL cases)
  int frames = 0;      // moving frames run
  double degreesPerFrame = 0.0;  // the box's turn a frame (its animation's spin rate / frames per second)
  size_t elements = 0, movingElements = 0;
  double firstSolveSeconds = 0.0;  // making the session, and its solve at pose 0 (dynamic methods), before the frames
  std::vector<double> frameMs;     // every moving frame: placeObject and the solve to its stopping rule
  double msMedian = 0.0, msP95 = 0.0;  // over the frames after the untimed ones
  double shotsPerFrame = 0.0;          // median over the timed frames
  // Median over the timed frames of SolveStats::factorsRecomputed's growth; dynamic methods on
  // the CPU only (progressive computes every column it shoots with; GL counts no factors).
  std::optional<double> factorsPerFrame;
  std::vector<int> errorFrames;  // 1-based frame numbers
  std::vector<double> errors;    // NRMSE at those frames (empty without references)
  double errorMedian = 0.0, errorMax = 0.0;
  std::vector<double> settleErrors;  // one per settle frame
  double referenceSeconds = 0.0;     // solving references (0 when all came from the cache)
  // GL cases: each phase's median over the timed frames (secondsGpu, secondsCpu; a frame it did
  // not run in counts 0) and, as count, the frames it ran in.
  std::vector<PhaseTime> phases;
};

// Runs one case. Throws Error when a GL context cannot be made or the scene has no dynamic object
// (the bench command reports the case skipped, with the reason).
DynamicResult runDynamicCase(const DynamicCase& benchCase, const DynamicOptions& options);

// The machine and build a result belongs to.
struct Machine {
  std::string cpuModel;
  int cores = 0;    // hardware threads
  int threads = 0;  // threads the runs used
  uint64_t memoryBytes = 0;
  std::string os;
  std::string commit;  // git describe of the source tree, when it can be found
  std::string date;    // UTC, ISO 8601
};
Machine describeMachine(int threads);

// Normalised RMS difference of element radiosities, over the elements that do not emit:
// sqrt(mean |B - R|^2) / sqrt(mean |R|^2), all three channels. Emitters are left out because
// their radiosity is mostly their own exact emission, which would hide the error elsewhere.
double normalisedRmsError(const SurfaceSet& surfaces, const std::vector<Rgb>& radiosity,
                          const std::vector<Rgb>& reference);

}  // namespace luxel::bench
