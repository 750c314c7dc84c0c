// solve() on a transport the caller built, so that benchmarks can watch the rays it traces (and
// a second backend can plug in) without a second copy of the refinement loop and statistics.
#pragma once

#include "luxel/solve.h"
#include "transport/transport.h"

namespace luxel {

// As solve(), with `transport` built over `scene` and `surfaces` by the caller. stats.secondsSetup
// is 0 (building the transport is the caller's setup); secondsTotal covers this call only.
Solution solveWithTransport(const Scene& scene, SurfaceSet& surfaces, Transport& transport,
                            const SolveOptions& options, const ProgressCallback& progress = {});

}  // namespace luxel
