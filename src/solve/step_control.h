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

// When a solver that takes many small passes should report progress: after every 1% of the way,
// and at least every 0.1 s whatever the fraction does, because a report is also where a cancel
// request is read (a solve whose fraction stalls or falls must still stop on Ctrl-C).
class ProgressThrottle {
 public:
  bool due(double fraction) {
    const double now = watch_.seconds();
    if (fraction - lastFraction_ < 0.01 && now - lastSeconds_ < 0.1) return false;
    lastFraction_ = fraction, lastSeconds_ = now;
    return true;
  }

 private:
  Stopwatch watch_;
  double lastFraction_ = -1.0, lastSeconds_ = 0.0;
};

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
  void saveState(StateWriter& out) const { out.value(best_), out.value(since_); }
  void restoreState(StateReader& in) { in.value(best_), in.value(since_); }

 private:
  double best_ = std::numeric_limits<double>::max();
  int since_ = 0;
};

}  // namespace luxel
