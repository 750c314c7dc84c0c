// What every solver's step loop shares: whether the caller's slice is used up, and gathering's
// rule for when a residual has stopped falling.
#pragma once

#include <cstdint>
#include <limits>

#include "core/stopwatch.h"
#include "luxel/solver.h"

namespace luxel {

// True once `units` units of work or the slice's seconds (measured by `watch`) are used up.
inline bool sliceSpent(const StepLimit& limit, uint64_t units, const Stopwatch& watch) {
  return (limit.units && units >= limit.units) || (limit.seconds > 0 && watch.seconds() >= limit.seconds);
}

// Float rounding bounds how small a gathering residual can get: stop once it has not fallen by
// 1% for 8 sweeps.
class StagnationStop {
 public:
  // Takes the latest residual; true when it is time to stop.
  bool stalled(double residual) {
    if (residual < best_ * 0.99) {
      best_ = residual;
      since_ = 0;
      return false;
    }
    return ++since_ >= 8;
  }

 private:
  double best_ = std::numeric_limits<double>::max();
  int since_ = 0;
};

}  // namespace luxel
