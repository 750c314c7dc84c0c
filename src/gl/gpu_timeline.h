// Where a GL solver's time goes, phase by phase, on the GPU and on the CPU that feeds it.
// A GPU solver's frame is dozens of small dispatches and draws: whether it is bound by the GPU's
// work, by the driver's per-call cost or by the CPU's own work between them cannot be read from
// wall-clock time, so each phase is bracketed by GL timestamp queries (ARB_timer_query, core
// since 3.3) as well as timed on the CPU. Queries are read back only at collect(), which the
// solver calls after a glFinish it makes anyway: measuring adds no synchronisation.
#pragma once

#include <vector>

#include "core/stopwatch.h"
#include "luxel/solution.h"

namespace luxel::gl {

class GpuTimeline {
 public:
  GpuTimeline() = default;
  ~GpuTimeline();
  GpuTimeline(const GpuTimeline&) = delete;
  GpuTimeline& operator=(const GpuTimeline&) = delete;

  // Ends the phase in progress (if any) and starts `phase` (a string literal: kept by pointer).
  void mark(const char* phase);
  // Ends the phase in progress.
  void stop();
  // Reads the finished phases' queries into the totals; call after glFinish.
  void collect();
  // Totals per phase, in the order phases were first seen.
  const std::vector<PhaseTime>& totals() const { return totals_; }

 private:
  struct Open {
    const char* phase;
    unsigned begin, end;  // timestamp queries
    double cpuBegin, cpuEnd;
  };
  unsigned query();
  PhaseTime& total(const char* phase);

  Stopwatch clock_;
  std::vector<Open> open_;     // marked, not yet collected; the last may be in progress
  bool running_ = false;
  std::vector<unsigned> free_;  // query objects to reuse
  std::vector<PhaseTime> totals_;
};

}  // namespace luxel::gl
