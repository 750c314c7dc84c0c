// Solving diffuse interreflection on a SurfaceSet, by any registered solver on any backend.
//
// The discrete system is B_e = E_e + rho_e * (H0_e + sum_p F[e <- p] B_p), where e runs over
// elements, p over patches, B_p is the area-weighted mean radiosity of the patch's elements, and
// H0_e is the irradiance from analytic lights. Every solver solves this same system, so they agree
// to their convergence tolerance. Radiosity B is exitance (W/m^2); radiance is B / pi.
#pragma once

#include <cstddef>
#include <string>

#include "luxel/progress.h"
#include "luxel/scene.h"
#include "luxel/solution.h"
#include "luxel/solver.h"
#include "luxel/surface.h"

namespace luxel {

// Adaptive refinement around any solver: split elements whose radiosity differs from a
// neighbour's by more than `threshold` (relative) and solve again, until `budget` extra elements
// are used (Cohen et al. 1986). It changes the surfaces, so it belongs to whoever owns them, not
// to a solver.
struct RefineOptions {
  size_t budget = 0;  // 0: off
  float threshold = 0.15f;
  int maxDepth = 3;
};

// Which solver, where, and its options.
struct SolveOptions {
  // A registered method (luxel solvers lists them), or "auto": progressive up to 5,000 patches,
  // the face-cluster hierarchy above (solve/method_choice.h, docs/algorithms.md).
  std::string method = "auto";
  // The session will move objects and edit lights (an animation, a viewer): "auto" then picks the
  // dynamic solver where it would pick progressive (cross-redistribution on the CPU, incremental
  // on GL), which corrects its solution after each change instead of solving again.
  bool followsChanges = false;
  // "cpu" (Embree + TBB), "gl" (OpenGL 4.5 through EGL, headless), or "auto": gl when a context
  // can be made and the method runs there, the CPU otherwise (with a warning in
  // SolveStats::warnings).
  std::string backend = "cpu";
  SolverSettings settings;  // checked by the chosen solver: a name it does not read is an error
  RefineOptions refine;
  // Write the solve's state at intervals, and continue from a written state (luxel/checkpoint.h).
  // Solvers that cannot be checkpointed, and refinement, are an Error when either path is set.
  CheckpointOptions checkpoint;
};

// Checks the method, the backend and every option against the registry without solving: what
// solve() and Session would throw for them. For "auto", options must be read by the method on
// some backend.
void validateSolveOptions(const SolveOptions& options);

// Solves to completion with the chosen solver. `surfaces` are refined in place when
// options.refine.budget > 0. Throws Error on an unknown method, backend or option, Cancelled
// when `progress` says stop. Session (luxel/session.h) does the same in steps.
Solution solve(const Scene& scene, SurfaceSet& surfaces, const SolveOptions& options,
               const ProgressCallback& progress = {});

}  // namespace luxel
