// Adaptive subdivision (Cohen, Greenberg, Immel and Brock 1986): which elements to split where
// the solution's gradient is large.
#pragma once

#include <cstdint>
#include <vector>

#include "luxel/solve.h"

namespace luxel {

// Elements whose radiosity differs from a neighbour's on the same surface by more than the
// threshold (relative), largest differences (times area) first, as many as `budgetLeft` extra
// elements allow (a split adds three).
std::vector<uint32_t> elementsToRefine(const SurfaceSet& set, const std::vector<Rgb>& radiosity,
                                       const RefineOptions& options, size_t budgetLeft);

}  // namespace luxel
