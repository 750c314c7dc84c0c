// Gathering radiosity with an explicit form-factor matrix, solved by Gauss-Seidel (Cohen and
// Greenberg, "The Hemi-Cube: A Radiosity Solution for Complex Environments", SIGGRAPH 1985) or
// Jacobi iteration. The reference solver for scenes of up to tens of thousands of elements: its
// memory is elements x patches floats. A step builds the matrix a block of rows at a time, then
// sweeps.
#include <algorithm>
#include <cmath>
#include <numeric>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/stopwatch.h"
#include "luxel/error.h"
#include "solve/incident_sh.h"
#include "solve/solver_registry.h"
#include "solve/step_control.h"
#include "transport/form_factor_options.h"

namespace luxel {
namespace {

constexpr size_t kMaxMatrixBytes = size_t(16) << 30;
constexpr size_t kRowsPerBlock = 256;

// Irradiance gathered by one row: sum_p F[e <- p] B_p, with B_p in three separate channels so the
// loop vectorises.
Rgb gatherRow(const float* row, const std::vector<float>& r, const std::vector<float>& g,
              const std::vector<float>& b) {
  float hr = 0.0f, hg = 0.0f, hb = 0.0f;
  const size_t n = r.size();
  for (size_t p = 0; p < n; ++p) {
    hr += row[p] * r[p];
    hg += row[p] * g[p];
    hb += row[p] * b[p];
  }
  return Rgb(hr, hg, hb);
}

struct GatherSettings {
  double residualThreshold;
  int maxIterations;
  bool gaussSeidel;
};

class GatherSolver final : public Solver {
 public:
  GatherSolver(const RadiositySystem& sys, Transport& transport, const GatherSettings& s)
      : sys_(sys), transport_(transport), s_(s) {
    const size_t ne = sys.elementCount(), np = sys.patchCount();
    const size_t bytes = ne * np * sizeof(float);
    if (bytes > kMaxMatrixBytes)
      throw Error(fmt::format("gather needs a {} x {} form-factor matrix ({:.1f} GiB, over the {} GiB "
                              "limit): use the progressive solver or fewer elements",
                              ne, np, double(bytes) / double(1 << 30), kMaxMatrixBytes >> 30));
    matrix_.resize(ne * np);
    radiosity_.resize(ne);
    irradiance_ = sys.analytic;
    for (size_t e = 0; e < ne; ++e) radiosity_[e] = sys.emission[e] + sys.reflectance[e] * sys.analytic[e];
    pr_.resize(np), pg_.resize(np), pb_.resize(np);
    refreshPatches();
  }

  bool step(const StepLimit& limit, const ProgressCallback& progress) override {
    const Stopwatch watch;
    uint64_t units = 0;
    // The matrix, a block of rows at a time so that progress and cancellation stay responsive.
    const size_t ne = sys_.elementCount(), np = sys_.patchCount();
    while (rowsDone_ < ne && !sliceSpent(limit, units, watch)) {
      const Stopwatch block;
      std::vector<uint32_t> ids(std::min(ne - rowsDone_, kRowsPerBlock));
      std::iota(ids.begin(), ids.end(), uint32_t(rowsDone_));
      transport_.rows(ids, {matrix_.data() + rowsDone_ * np, ids.size() * np});
      rowsDone_ += ids.size();
      formFactorSeconds_ += block.seconds();
      reportProgress(progress, "form factors", double(rowsDone_) / double(ne));
    }
    while (rowsDone_ == ne && !done_ && !sliceSpent(limit, units, watch)) {
      sweep(progress);
      ++units;
    }
    seconds_ += watch.seconds();
    return !done_;
  }

  bool done() const override { return done_; }

  Solution solution() override {
    Solution sol;
    sol.radiosity = radiosity_;
    sol.irradiance = irradiance_;
    // Direct irradiance: the analytic lights plus one bounce from emitting patches (over the rows
    // computed so far).
    const size_t np = sys_.patchCount();
    const std::vector<Rgb> patchEmission = sys_.patchMeans(sys_.emission);
    sol.directIrradiance = sys_.analytic;
    for (size_t p = 0; p < np; ++p) {
      if (channelSum(patchEmission[p]) <= 0.0) continue;
      for (size_t e = 0; e < rowsDone_; ++e) sol.directIrradiance[e] += matrix_[e * np + p] * patchEmission[p];
    }
    sol.stats = stats();
    return sol;
  }

  // Each row's factors against the patches' current radiosity (the Gauss-Seidel sweep's own sums).
  bool incidentSh(int count, std::span<Rgb> out) override {
    const size_t np = sys_.patchCount();
    const std::vector<Rgb> patchRadiosity = sys_.patchMeans(radiosity_);
    std::fill(out.begin(), out.end(), Rgb(0.0f));
    const auto& elements = sys_.surfaces.elements;
    const auto& patches = sys_.surfaces.patches;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rowsDone_, 16), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t e = r.begin(); e < r.end(); ++e) {
        Rgb sum[kShCoefficients] = {};
        for (uint32_t p = 0; p < np; ++p) {
          const float f = matrix_[e * np + p];
          if (f == 0.0f) continue;
          if (!addFarPatchSh(elements[e], patches[p], f, patchRadiosity[p], count, sum))
            addPatchSh(sys_.surfaces, uint32_t(e), p, f, patchRadiosity[p], count, sum);
        }
        std::copy(sum, sum + count, out.begin() + long(e) * count);
      }
    });
    return true;
  }

  // The matrix rows computed so far are the costly part of the state, and are saved with it.
  bool checkpoints() const override { return true; }
  void saveState(StateWriter& out) const override {
    out.value(uint64_t(rowsDone_));
    out.array(std::span<const float>(matrix_.data(), rowsDone_ * sys_.patchCount()));
    out.array(radiosity_), out.array(irradiance_);
    out.value(residual_), out.value(iterations_), out.value(seconds_), out.value(formFactorSeconds_), out.value(done_);
    stagnation_.saveState(out);
  }
  void restoreState(StateReader& in) override {
    const size_t ne = sys_.elementCount(), np = sys_.patchCount();
    const uint64_t rows = in.value<uint64_t>();
    if (rows > ne) throw Error(fmt::format("checkpoint: {} matrix rows where this solve has {} elements", rows, ne));
    const uint64_t n = in.arrayLength(rows * np, sizeof(float));
    in.raw(matrix_.data(), size_t(n) * sizeof(float));
    rowsDone_ = size_t(rows);
    in.array(radiosity_, ne), in.array(irradiance_, ne);
    in.value(residual_), in.value(iterations_), in.value(seconds_), in.value(formFactorSeconds_), in.value(done_);
    stagnation_.restoreState(in);
    refreshPatches();
  }

  SolveStats stats() const override {
    SolveStats st;
    st.method = "gather";
    st.backend = "cpu";
    st.iterations = uint64_t(iterations_);
    st.residual = residual_;
    st.secondsFormFactors = formFactorSeconds_;
    st.secondsSolve = std::max(0.0, seconds_ - formFactorSeconds_);
    return st;
  }

 private:
  void refreshPatches() {
    std::vector<Rgb> means = sys_.patchMeans(radiosity_);
    for (size_t p = 0; p < means.size(); ++p) pr_[p] = means[p].r, pg_[p] = means[p].g, pb_[p] = means[p].b;
  }

  void sweep(const ProgressCallback& progress) {
    const size_t ne = sys_.elementCount(), np = sys_.patchCount();
    ++iterations_;
    double maxDelta = 0.0, maxB = 0.0;
    if (s_.gaussSeidel) {
      // Patch means are updated in place during a sweep; recomputing them at its start keeps
      // float rounding from accumulating over many sweeps.
      refreshPatches();
      const auto& elements = sys_.surfaces.elements;
      for (size_t e = 0; e < ne; ++e) {
        Rgb h = sys_.analytic[e] + gatherRow(matrix_.data() + e * np, pr_, pg_, pb_);
        Rgb b = sys_.emission[e] + sys_.reflectance[e] * h;
        Rgb d = b - radiosity_[e];
        const uint32_t p = elements[e].patch;
        const float w = sys_.area[e] / sys_.patchArea[p];
        pr_[p] += w * d.r, pg_[p] += w * d.g, pb_[p] += w * d.b;
        radiosity_[e] = b;
        irradiance_[e] = h;
        maxDelta = std::max(maxDelta, std::abs(d.r) + double(std::abs(d.g)) + std::abs(d.b));
        maxB = std::max(maxB, channelSum(b));
      }
    } else {
      std::vector<double> deltas(ne);
      tbb::parallel_for(tbb::blocked_range<size_t>(0, ne, 64), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t e = r.begin(); e < r.end(); ++e) {
          Rgb h = sys_.analytic[e] + gatherRow(matrix_.data() + e * np, pr_, pg_, pb_);
          Rgb b = sys_.emission[e] + sys_.reflectance[e] * h;
          Rgb d = b - radiosity_[e];
          deltas[e] = std::abs(d.r) + double(std::abs(d.g)) + std::abs(d.b);
          radiosity_[e] = b;
          irradiance_[e] = h;
        }
      });
      for (size_t e = 0; e < ne; ++e) {
        maxDelta = std::max(maxDelta, deltas[e]);
        maxB = std::max(maxB, channelSum(radiosity_[e]));
      }
      refreshPatches();
    }
    residual_ = maxB > 0.0 ? maxDelta / maxB : 0.0;
    if (residual_ <= s_.residualThreshold || iterations_ >= s_.maxIterations) done_ = true;
    if (stagnation_.stalled(residual_)) done_ = true;
    // Last, so that a cancel read here leaves the sweep's state whole (a checkpoint saves it).
    reportProgress(progress, "solve",
                   std::clamp(std::log(std::max(residual_, 1e-30)) / std::log(s_.residualThreshold), 0.0, 1.0),
                   fmt::format("residual {:.2e}", residual_));
  }

  const RadiositySystem& sys_;
  Transport& transport_;
  const GatherSettings s_;
  std::vector<float> matrix_;
  size_t rowsDone_ = 0;
  std::vector<Rgb> radiosity_, irradiance_;
  std::vector<float> pr_, pg_, pb_;
  double residual_ = 1.0;
  StagnationStop stagnation_;
  int iterations_ = 0;
  double seconds_ = 0.0, formFactorSeconds_ = 0.0;
  bool done_ = false;
};

}  // namespace

// Options shared with GL gather, which iterates the same way on the GPU.
std::vector<SolverOption> gatherStopOptions() {
  return {realOption("residual", 1e-5, 1e-12, 0.999999, "stop when the largest relative change of a sweep falls below this"),
          integerOption("max-iterations", 10000, 1, 100000000, "stop after this many sweeps")};
}

void registerCpuGather(SolverRegistry& registry) {
  SolverEntry e;
  e.description = {"gather", "cpu",
                   "gathering over an explicit form-factor matrix (Cohen and Greenberg 1985), Gauss-Seidel or Jacobi; "
                   "the reference solver",
                   gatherStopOptions()};
  e.description.options.push_back(flagOption("gauss-seidel", true, "Gauss-Seidel sweeps (false: Jacobi, in parallel)"));
  for (SolverOption& o : cpuTransportOptions()) e.description.options.push_back(std::move(o));
  e.make = [](const SolverResources& r, const SolverOptionValues& v) -> std::unique_ptr<Solver> {
    return std::make_unique<GatherSolver>(r.system, r.transport,
                                          GatherSettings{v.real("residual"), v.integer("max-iterations"), v.flag("gauss-seidel")});
  };
  e.converged.set("residual", 1e-7);
  registry.add(std::move(e));
}

}  // namespace luxel
