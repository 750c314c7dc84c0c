// How long a phase has left, from its progress reports (ProgressEvent::fraction against time).
//
// The average rate since the start of a phase is a poor guide for a progressive solve: its fraction
// is logarithmic in the unshot energy, and each decade of unshot energy takes longer than the last,
// as what is left sits more and more in poorly lit, poorly coupled places (a sum of decays at many
// rates: a stretched exponential, U = exp(-(t / tau)^p), whose log grows as a power of time). So
// fraction = (t / T)^p is fitted to the recent reports (least squares of log fraction against log
// time, over the last `window` of the elapsed time) and followed from the latest report to 1. A
// steady phase (p = 1) comes out exact. docs/algorithms.md has the recorded solves it was checked
// on.
#pragma once

#include <optional>
#include <vector>

namespace luxel {

class EtaEstimator {
 public:
  // `window`: the share of the elapsed time, counted back from now, whose reports the power law is
  // fitted to, in (0, 1]. Throws Error otherwise.
  explicit EtaEstimator(double window = kDefaultWindow);

  // A report `seconds` after the phase began, `fraction` done (0..1). Reports come in time order;
  // an earlier time, a NaN or a fraction outside [0, 1] throws Error.
  void add(double seconds, double fraction);

  // Seconds left, or nothing while the estimate is not reliable: fewer than kMinReports reports
  // (with time and fraction above 0) in the window, less than kMinSeconds elapsed, or no progress
  // over the window.
  std::optional<double> remaining() const;

  static constexpr double kDefaultWindow = 0.5;
  static constexpr int kMinReports = 4;
  static constexpr double kMinSeconds = 1.0;

 private:
  double window_;
  std::vector<double> seconds_, fractions_;
};

}  // namespace luxel
