// Wall-clock seconds since construction (steady clock): the phases that statistics report.
#pragma once

#include <chrono>

namespace luxel {

class Stopwatch {
 public:
  double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  void restart() { start_ = Clock::now(); }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_ = Clock::now();
};

}  // namespace luxel
