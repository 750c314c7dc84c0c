// How long a phase has left, from its progress reports (ProgressEvent::fraction against time).
//
// The average rate since the start of a phase is a poor guide for a progressive solve: its
// fraction is logarithmic in the unshot energy, and a decade of unshot energy takes longer and
// longer as the energy spreads from the lights over the whole scene (Sibenik: the last tenth of the
// fraction took ten times as long as the first). So the rate is fitted over the recent part of the
// phase only (least squares of fraction against time), and extrapolated to 1. docs/algorithms.md
// has the traces it was checked on.
#pragma once

#include <optional>
#include <vector>

namespace luxel {

class EtaEstimator {
 public:
  // `window`: the share of the elapsed time, counted back from now, whose reports the rate is
  // fitted to, in (0, 1]. Throws Error otherwise.
  explicit EtaEstimator(double window = kDefaultWindow);

  // A report `seconds` after the phase began, `fraction` done (0..1). Reports come in time order;
  // an earlier time, a NaN or a fraction outside [0, 1] throws Error.
  void add(double seconds, double fraction);

  // Seconds left, or nothing while the estimate is not reliable: fewer than kMinReports reports in
  // the window, less than kMinSeconds elapsed, or no progress over the window.
  std::optional<double> remaining() const;

  static constexpr double kDefaultWindow = 0.5;
  static constexpr int kMinReports = 4;
  static constexpr double kMinSeconds = 1.0;

 private:
  double window_;
  std::vector<double> seconds_, fractions_;
};

}  // namespace luxel
