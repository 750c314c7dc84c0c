// Peak resident memory of this process, for the benchmark suite.
#pragma once

#include <cstddef>

namespace luxel::bench {

// Starts a new high-water mark (Linux; a no-op elsewhere).
void resetPeakMemory();
// The resident-set high-water mark since the last reset, in bytes (0 when unknown).
size_t peakMemoryBytes();

}  // namespace luxel::bench
