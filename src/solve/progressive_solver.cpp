// Progressive refinement radiosity (Cohen et al. 1988): see solve/progressive_solver.h.
#include "solve/progressive_solver.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <cmath>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/spherical_harmonics.h"
#include "solve/incident_sh.h"
#include "solve/solver_registry.h"
#include "solve/step_control.h"
#include "core/stopwatch.h"
#include "transport/form_factor_options.h"

namespace luxel {

bool ProgressiveSolver::step(const StepLimit& limit, const ProgressCallback& progress) {
  const Stopwatch watch;
  uint64_t units = 0;
  while (!done_) {
    if (sliceSpent(limit, units, watch)) break;
    shootOnePass(progress, seconds_ + watch.seconds());
    ++units;
  }
  seconds_ += watch.seconds();
  if (done_) reportProgress(progress, "solve", 1.0, fmt::format("unshot {:.3f}%", 100.0 * unshotFraction_));
  return !done_;
}

Solution ProgressiveSolver::solution() {
  const Stopwatch watch;
  Solution sol;
  sol.radiosity = radiosity_;
  sol.irradiance = irradiance_;
  if (s_.ambient) addAmbientTerm(sys_, unshot_, sol.radiosity, sol.irradiance);
  // Direct irradiance: the analytic lights plus one bounce from each emitting patch, added the
  // first time its column is at hand (an emitter that has not shot yet is computed here).
  for (uint32_t p = 0; p < sys_.patchCount(); ++p)
    if (!directAdded_[p] && channelSum(patchEmission_[p]) > 0.0) addDirect(p, column(p, 0));
  sol.directIrradiance = direct_;
  sol.unshot = unshot_;
  sol.stats = stats();
  seconds_ += watch.seconds();
  return sol;
}

bool ProgressiveSolver::incidentSh(int count, std::span<Rgb> out) {
  const size_t ne = sys_.elementCount();
  std::fill(out.begin(), out.end(), Rgb(0.0f));
  // What each patch has shot so far: its elements' radiosity less what they still hold.
  std::vector<Rgb> shotTotal(ne);
  for (size_t e = 0; e < ne; ++e) shotTotal[e] = radiosity_[e] - unshot_[e];
  const std::vector<Rgb> shot = sys_.patchMeans(shotTotal);
  std::vector<uint32_t> shooters;
  for (uint32_t p = 0; p < sys_.patchCount(); ++p)
    if (shot[p] != Rgb(0.0f)) shooters.push_back(p);
  // A block of columns at a time: those the cache lost are computed again, block by block.
  constexpr size_t kBlock = 32;
  std::vector<std::vector<float>> computed(kBlock);
  // L1's blocked pass reads the elements as separate arrays; L2 takes pairs one by one.
  const std::optional<ElementFrames> frames =
      count == kShL1Coefficients ? std::optional<ElementFrames>(std::in_place, sys_.surfaces) : std::nullopt;
  for (size_t first = 0; first < shooters.size(); first += kBlock) {
    const size_t n = std::min(kBlock, shooters.size() - first);
    const float* cols[kBlock];
    for (size_t k = 0; k < n; ++k) {
      const uint32_t p = shooters[first + k];
      if (cache_[p].empty()) {
        computed[k].resize(ne);
        transport_.columns({&p, 1}, computed[k]);
        cols[k] = computed[k].data();
      } else {
        cols[k] = cache_[p].data();
      }
    }
    if (count == kShL1Coefficients) {
      Rgb exitance[kBlock];
      for (size_t k = 0; k < n; ++k) exitance[k] = shot[shooters[first + k]];
      tbb::parallel_for(tbb::blocked_range<size_t>(0, ne, 256), [&](const tbb::blocked_range<size_t>& r) {
        addShooterBlockL1(sys_.surfaces, *frames, std::span(shooters).subspan(first, n), std::span(cols, n),
                          std::span(exitance, n), r.begin(), r.end(), out.data());
      });
      continue;
    }
    const auto& elements = sys_.surfaces.elements;
    const auto& patches = sys_.surfaces.patches;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, ne, 64), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t e = r.begin(); e < r.end(); ++e) {
        Rgb sum[kShCoefficients] = {};  // kept in registers over the block's shooters
        for (size_t k = 0; k < n; ++k) {
          const float f = cols[k][e];
          if (f == 0.0f) continue;
          const uint32_t p = shooters[first + k];
          if (!addFarPatchSh(elements[e], patches[p], f, shot[p], count, sum))
            addPatchSh(sys_.surfaces, uint32_t(e), p, f, shot[p], count, sum);
        }
        for (int i = 0; i < count; ++i) out[e * size_t(count) + size_t(i)] += sum[i];
      }
    });
  }
  // The ambient term, where it is on, arrives evenly over the hemisphere.
  if (s_.ambient) {
    std::vector<Rgb> radiosity = radiosity_, irradiance = irradiance_;
    addAmbientTerm(sys_, unshot_, radiosity, irradiance);
    for (size_t e = 0; e < ne; ++e)
      shAddUniformHemisphere(out.data() + e * size_t(count), count, sys_.surfaces.elements[e].normal,
                             irradiance[e] - irradiance_[e]);
  }
  return true;
}

void ProgressiveSolver::saveState(StateWriter& out) const {
  for (const auto* v : {&radiosity_, &unshot_, &irradiance_, &direct_, &patchUnshot_}) out.array(*v);
  out.array(directAdded_);
  out.value(shots_), out.value(seconds_), out.value(formFactorSeconds_), out.value(done_);
}

void ProgressiveSolver::restoreState(StateReader& in) {
  const size_t ne = sys_.elementCount(), np = sys_.patchCount();
  for (auto* v : {&radiosity_, &unshot_, &irradiance_, &direct_}) in.array(*v, ne);
  in.array(patchUnshot_, np);
  in.array(directAdded_, np);
  in.value(shots_), in.value(seconds_), in.value(formFactorSeconds_), in.value(done_);
  unshotFraction_ = currentUnshotFraction();
}

SolveStats ProgressiveSolver::stats() const {
  SolveStats st;
  st.method = "progressive";
  st.backend = "cpu";
  st.shots = shots_;
  st.unshotFraction = st.residual = unshotFraction_;
  st.secondsFormFactors = formFactorSeconds_;
  st.secondsSolve = std::max(0.0, seconds_ - formFactorSeconds_);
  return st;
}

void ProgressiveSolver::updatePatchUnshot() {
  const auto& patches = sys_.surfaces.patches;
  tbb::parallel_for(size_t(0), sys_.patchCount(), [&](size_t p) {
    Rgb sum(0.0f);
    for (uint32_t e : patches[p].elements) sum += sys_.area[e] * unshot_[e];
    patchUnshot_[p] = sum;
  });
}

double ProgressiveSolver::currentUnshotFraction() {
  double total = 0.0;
  for (size_t p = 0; p < sys_.patchCount(); ++p) {
    const Rgb& u = patchUnshot_[p];
    const double power = double(std::abs(u.r)) + double(std::abs(u.g)) + double(std::abs(u.b));
    total += power;
    ranked_[p] = {power, uint32_t(p)};
  }
  return sourcePower_ > 0.0 ? total / sourcePower_ : 0.0;
}

const std::vector<float>& ProgressiveSolver::column(uint32_t p, size_t slot) {
  if (!cache_[p].empty()) return cache_[p];
  const Stopwatch watch;
  const size_t ne = sys_.elementCount();
  const bool keep = cachedBytes_ + ne * sizeof(float) <= kColumnCacheBytes;
  std::vector<float>& out = keep ? cache_[p] : scratch_[slot];
  out.resize(ne);
  transport_.columns({&p, 1}, out);
  if (keep) cachedBytes_ += ne * sizeof(float);
  formFactorSeconds_ += watch.seconds();
  return out;
}

void ProgressiveSolver::addDirect(uint32_t p, const std::vector<float>& f) {
  for (size_t e = 0; e < sys_.elementCount(); ++e) direct_[e] += f[e] * patchEmission_[p];
  directAdded_[p] = 1;
}

void ProgressiveSolver::shootOnePass(const ProgressCallback& progress, double secondsSpent) {
  const size_t np = sys_.patchCount();
  // unshotFraction_ and ranked_ are current: set by the constructor or the previous pass.
  if (unshotFraction_ <= threshold_ || (s_.shotBudget && shots_ >= s_.shotBudget) ||
      (s_.timeBudget > 0.0 && secondsSpent >= s_.timeBudget)) {
    done_ = true;
    return;
  }
  // Progress is logarithmic in the unshot fraction: each decade takes about as long.
  const double fraction = std::clamp(std::log(unshotFraction_) / std::log(threshold_), 0.0, 1.0);
  if (throttle_.due(fraction))
    reportProgress(progress, "solve", fraction, fmt::format("unshot {:.3f}%", 100.0 * unshotFraction_));

  size_t batch = std::min(s_.shootersPerPass, np);
  if (s_.shotBudget) batch = std::min<size_t>(batch, s_.shotBudget - shots_);
  std::partial_sort(ranked_.begin(), ranked_.begin() + long(batch), ranked_.end(), std::greater<>());
  while (batch > 0 && ranked_[batch - 1].first <= 0.0) --batch;
  if (batch == 0) {
    done_ = true;
    return;
  }
  const auto& patches = sys_.surfaces.patches;
  const float* columns[kMaxShootersPerPass];
  Rgb shot[kMaxShootersPerPass];
  for (size_t k = 0; k < batch; ++k) {
    const uint32_t shooter = ranked_[k].second;
    const std::vector<float>& f = column(shooter, k);
    if (!directAdded_[shooter] && channelSum(patchEmission_[shooter]) > 0.0) addDirect(shooter, f);
    columns[k] = f.data();
    shot[k] = patchUnshot_[shooter] / sys_.patchArea[shooter];
    for (uint32_t e : patches[shooter].elements) unshot_[e] = Rgb(0.0f);
    patchUnshot_[shooter] = Rgb(0.0f);
  }
  // Receivers patch by patch, so each patch's unshot power is updated by the change of its own
  // elements instead of being summed again from scratch.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, np, 8), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t q = r.begin(); q < r.end(); ++q) {
      Rgb added(0.0f);
      for (uint32_t e : patches[q].elements) {
        Rgb dh(0.0f);
        for (size_t k = 0; k < batch; ++k) dh += columns[k][e] * shot[k];
        if (dh.r == 0.0f && dh.g == 0.0f && dh.b == 0.0f) continue;
        const Rgb db = sys_.reflectance[e] * dh;
        irradiance_[e] += dh;
        radiosity_[e] += db;
        unshot_[e] += db;
        added += sys_.area[e] * db;
      }
      patchUnshot_[q] += added;
    }
  });
  shots_ += batch;
  unshotFraction_ = currentUnshotFraction();
}


// Options and defaults shared with GL progressive, which solves the same way on the GPU.
std::vector<SolverOption> progressiveStopOptions() {
  return {realOption("unshot", 1e-3, 1e-12, 0.999999, "stop when unshot power / emitted power falls below this"),
          realOption("time-budget", 0.0, 0.0, 1e9, "stop after this many seconds (0: no limit)"),
          integerOption("shot-budget", 0, 0, 2000000000, "stop after this many shots (0: no limit)"),
          flagOption("ambient", true, "add Cohen et al.'s ambient term (what is unshot) to the displayed solution")};
}

void registerCpuProgressive(SolverRegistry& registry) {
  SolverEntry e;
  e.description = {"progressive", "cpu",
                   "progressive refinement (Cohen et al. 1988): the patches with most unshot power shoot; Embree rays",
                   progressiveStopOptions()};
  e.description.options.push_back(integerOption("shooters-per-pass", kDefaultShootersPerPass, 1, kMaxShootersPerPass,
                                                "patches shot together in one pass over the receivers"));
  for (SolverOption& o : cpuTransportOptions()) e.description.options.push_back(std::move(o));
  e.make = [](const SolverResources& r, const SolverOptionValues& v) -> std::unique_ptr<Solver> {
    ProgressiveSettings s{v.real("unshot"), v.real("time-budget"), uint64_t(v.integer("shot-budget")),
                          size_t(v.integer("shooters-per-pass")), v.flag("ambient")};
    return std::make_unique<ProgressiveSolver>(r.system, r.transport, s);
  };
  e.converged.set("unshot", 1e-7);
  registry.add(std::move(e));
}

}  // namespace luxel
