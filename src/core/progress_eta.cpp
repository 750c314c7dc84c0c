// EtaEstimator (luxel/progress_eta.h): the power law of a phase's recent reports, extrapolated.
#include "luxel/progress_eta.h"

#include <cmath>
#include <utility>

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
  const double now = seconds_.back(), done = fractions_.back(), from = now * (1.0 - window_);
  if (now < kMinSeconds || !(done > 0.0)) return std::nullopt;
  // Least-squares slope of log fraction against log time over the reports in the window: the
  // power of fraction ~ time^power.
  std::vector<std::pair<double, double>> logs;
  for (size_t i = seconds_.size(); i-- > 0 && seconds_[i] >= from;)
    if (seconds_[i] > 0.0 && fractions_[i] > 0.0) logs.emplace_back(std::log(seconds_[i]), std::log(fractions_[i]));
  if (logs.size() < size_t(kMinReports)) return std::nullopt;
  double mx = 0.0, my = 0.0;
  for (auto [x, y] : logs) mx += x, my += y;
  mx /= double(logs.size()), my /= double(logs.size());
  double sxx = 0.0, sxy = 0.0;
  for (auto [x, y] : logs) sxx += (x - mx) * (x - mx), sxy += (x - mx) * (y - my);
  if (!(sxx > 0.0) || !(sxy > 0.0)) return std::nullopt;
  const double power = sxy / sxx;
  // From the latest report along that power to fraction 1.
  const double left = now * (std::pow(done, -1.0 / power) - 1.0);
  return std::isfinite(left) ? std::optional<double>(left) : std::nullopt;
}

}  // namespace luxel
