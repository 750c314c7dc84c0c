// solve() on a transport the caller built, so that benchmarks can watch the rays it traces (and
// a second backend can plug in) without a second copy of the refinement loop and statistics.
#pragma once

#include <functional>

#include "luxel/solve.h"
#include "solve/radiosity_system.h"
#include "transport/transport.h"

namespace luxel {

// A solver that owns its form factors (the GPU-resident ones): solves one system, adding the
// seconds it spent on form factors and visibility to the second argument.
using SystemSolver = std::function<Solution(const RadiositySystem&, double&)>;

// As solve(), with `transport` built over `scene` and `surfaces` by the caller. stats.secondsSetup
// is 0 (building the transport is the caller's setup); secondsTotal covers this call only. With
// `solver`, it solves each system instead of options.method, and `transport` gives only the
// analytic lights.
Solution solveWithTransport(const Scene& scene, SurfaceSet& surfaces, Transport& transport,
                            const SolveOptions& options, const ProgressCallback& progress = {},
                            const SystemSolver& solver = {});

}  // namespace luxel
