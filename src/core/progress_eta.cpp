// EtaEstimator (luxel/progress_eta.h): the rate of a phase over its recent reports, extrapolated.
#include "luxel/progress_eta.h"

#include <cmath>

#include <fmt/format.h>

#include "luxel/error.h"

namespace luxel {
namespace {

// Reports kept: beyond this, every other one of the older half is dropped, so a phase that reports
// every row of a matrix keeps its whole time span in bounded memory.
constexpr size_t kMaxReports = 4096;

}  // namespace

EtaEstimator::EtaEstimator(double window) : window_(window) {
  if (!(window > 0.0 && window <= 1.0)) throw Error(fmt::format("ETA window {} is outside (0, 1]", window));
}

void EtaEstimator::add(double seconds, double fraction) {
  if (!std::isfinite(seconds) || !(fraction >= 0.0 && fraction <= 1.0))
    throw Error(fmt::format("progress report ({} s, fraction {}): not a time and a fraction in [0, 1]", seconds, fraction));
  if (!seconds_.empty() && seconds < seconds_.back())
    throw Error(fmt::format("progress report at {} s comes before the previous one at {} s", seconds, seconds_.back()));
  if (seconds_.size() == kMaxReports) {
    size_t kept = 0;
    for (size_t i = 0; i < seconds_.size(); ++i)
      if (i >= kMaxReports / 2 || i % 2 == 0) seconds_[kept] = seconds_[i], fractions_[kept++] = fractions_[i];
    seconds_.resize(kept), fractions_.resize(kept);
  }
  seconds_.push_back(seconds);
  fractions_.push_back(fraction);
}

std::optional<double> EtaEstimator::remaining() const {
  if (seconds_.empty()) return std::nullopt;
  const double now = seconds_.back(), from = now * (1.0 - window_);
  if (now < kMinSeconds) return std::nullopt;
  // Least-squares slope of fraction against time over the reports in the window.
  double n = 0.0, st = 0.0, sf = 0.0;
  for (size_t i = seconds_.size(); i-- > 0 && seconds_[i] >= from;) n += 1.0, st += seconds_[i], sf += fractions_[i];
  if (n < kMinReports) return std::nullopt;
  const double mt = st / n, mf = sf / n;
  double stt = 0.0, stf = 0.0;
  for (size_t i = seconds_.size(); i-- > 0 && seconds_[i] >= from;) {
    stt += (seconds_[i] - mt) * (seconds_[i] - mt);
    stf += (seconds_[i] - mt) * (fractions_[i] - mf);
  }
  if (!(stt > 0.0) || !(stf > 0.0)) return std::nullopt;
  return (1.0 - fractions_.back()) * stt / stf;
}

}  // namespace luxel
