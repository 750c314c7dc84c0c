// The options every command that solves a scene shares (render, bake): discretisation, solver,
// backend, and the chosen solver's own options. One definition, so the commands cannot drift apart.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "luxel/solve.h"
#include "luxel/surface.h"
#include "output_paths.h"

namespace luxel::cli {

struct SolveArgs {
  std::string solver = "auto";
  std::string backend = "cpu";
  int64_t elements = 0;  // signed, so that "-1" is out of range rather than 2^64 - 1
  float elementSize = 0.0f;
  int64_t refine = 0;
  std::vector<std::string> set;  // --set NAME=VALUE, any option of the chosen solver
  float sky = 0.0f;              // --sky RADIANCE: a uniform sky added to the scene
  std::string sun;               // --sun X,Y,Z: a sun travelling along this direction
  // The solver options that have flags of their own (--unshot, --rays-per-pair, ...), as
  // (option name, value text): only those given on the command line, so that a solver is never
  // handed an option it does not read unless the user asked for it.
  std::vector<std::pair<std::string, std::string>> flagged;
  std::string checkpoint;           // --checkpoint FILE: the solve's state, written at intervals
  std::string resume;               // --resume FILE: continue from it (and keep checkpointing to it)
  double checkpointInterval = 60.0;  // --checkpoint-interval SECONDS
  CLI::App* command = nullptr;
};

// Most elements (or texels) a command line may ask for: a hundred million, about 30 GB of
// surfaces and solution; a bigger scene needs a machine and a plan of its own.
inline constexpr int64_t kMaxElementsOption = 100'000'000;

// A check that a number is finite (CLI11's Range and PositiveNumber let NaN through: every
// comparison with NaN is false) and within [lo, hi].
CLI::Validator finiteRange(double lo, double hi);

// Adds --solver, --backend, --elements / --element-size, --refine, --set NAME=VALUE, and the
// flags kept for solver options: --unshot, --rays-per-pair, --shooters-per-pass,
// --hemicube-resolution, --hemicubes-per-side, --emitter-hemicubes-per-side, --hemicube-visibility.
void addSolveOptions(CLI::App& command, SolveArgs& args);

DiscretiseOptions discretiseOptions(const SolveArgs& args);
// The checkpoint a command writes, for its check of outputs before the solve; throws Error when
// --resume names no file.
std::vector<OutputPath> checkpointOutputs(const SolveArgs& args);
// Adds the lights of --sky and --sun to `scene`. Throws Error on a bad direction.
void addCommandLineLights(Scene& scene, const SolveArgs& args);
// The request: method, backend and settings. Unknown names are caught when the solver is made.
SolveOptions solveOptions(const SolveArgs& args);
// How big a solve was asked for, for messages: "--elements 2000000", "--element-size 0.01" or
// "the default 10,000-element budget".
std::string solveSize(const SolveArgs& args);
// What to reduce when a solve runs out of memory; `lightmaps`: texels are its elements.
std::string solveSizeHint(const SolveArgs& args, bool lightmaps);
// "3,012 elements in 220 patches", or "1,499,755 elements" for a solve without patches (the
// hierarchy's), for the summary line.
std::string elementsAndPatches(const SolveStats& stats);
// Checks what needs no scene and no file (--sun, the solver, backend and options): throws Error.
void checkSolveArgs(const SolveArgs& args);

}  // namespace luxel::cli
