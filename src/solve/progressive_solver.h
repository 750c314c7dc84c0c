// Progressive refinement radiosity: Cohen, Chen, Wallace and Greenberg, "A Progressive Refinement
// Approach to Fast Radiosity Image Generation", SIGGRAPH 1988. The patch with the most unshot
// power shoots it into every element; the ambient term of the same paper estimates, for display,
// the light not yet shot. Columns of form factors are cached, so a patch that shoots again (its
// elements received more light) costs no rays. The dynamic solvers (src/dynamic/) derive from it:
// they change its state after a move or a light edit and let it shoot the difference, which may
// be negative (Puech et al.'s "negative light"), so patches are ranked by the magnitude of their
// unshot power.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "luxel/solver.h"
#include "solve/radiosity_system.h"
#include "solve/step_control.h"
#include "transport/transport.h"

namespace luxel {

// Form-factor columns are kept while they fit in this much memory.
constexpr size_t kColumnCacheBytes = size_t(2) << 30;

struct ProgressiveSettings {
  double unshotThreshold;
  double timeBudget;
  uint64_t shotBudget;
  size_t shootersPerPass;
  bool ambient;
};

class ProgressiveSolver : public Solver {
 public:
  ProgressiveSolver(const RadiositySystem& sys, Transport& transport, const ProgressiveSettings& s)
      : sys_(sys), transport_(transport), s_(s), cache_(sys.patchCount()), scratch_(s.shootersPerPass),
        ranked_(sys.patchCount()), directAdded_(sys.patchCount(), 0) {
    const size_t ne = sys.elementCount();
    radiosity_.resize(ne), unshot_.resize(ne);
    irradiance_ = sys.analytic;
    direct_ = sys.analytic;
    for (size_t e = 0; e < ne; ++e)
      radiosity_[e] = unshot_[e] = sys.emission[e] + sys.reflectance[e] * sys.analytic[e];
    patchUnshot_.resize(sys.patchCount());
    updatePatchUnshot();
    sourcePower_ = sys.sourcePower();
    patchEmission_ = sys.patchMeans(sys.emission);
    unshotFraction_ = currentUnshotFraction();
  }

  bool step(const StepLimit& limit, const ProgressCallback& progress) override;

  bool done() const override { return done_; }

  Solution solution() override;

  // Form-factor columns are not saved: they are computed again, to the same bits, when needed.
  bool checkpoints() const override { return true; }
  void saveState(StateWriter& out) const override;
  void restoreState(StateReader& in) override;

  SolveStats stats() const override;

  // From the cached columns and what each patch has shot in all (a shot's light arrives along the
  // same factor whenever it is shot, so the sum over shots is one pass, after the solve). Exact
  // for a solve without moves: after a dynamic solver's move, shots made along the old factors are
  // counted along the new ones (bakes never move anything).
  bool incidentSh(int count, std::span<Rgb> out) override;

 protected:
  void updatePatchUnshot();

  double currentUnshotFraction();

  // The column of patch p, from the cache or computed (into scratch slot `slot` when the cache
  // is full).
  const std::vector<float>& column(uint32_t p, size_t slot);

  void addDirect(uint32_t p, const std::vector<float>& f);

  // One pass: the patches with the most unshot power shoot together, in one pass over the
  // receivers (the pass costs memory traffic over every element, which one shooter alone does
  // not repay). Sets done_ when the stopping rules say so instead.
  void shootOnePass(const ProgressCallback& progress, double secondsSpent);

  const RadiositySystem& sys_;
  Transport& transport_;
  const ProgressiveSettings s_;
  std::vector<Rgb> radiosity_, unshot_, irradiance_, direct_, patchUnshot_, patchEmission_;
  std::vector<std::vector<float>> cache_, scratch_;
  size_t cachedBytes_ = 0;
  std::vector<std::pair<double, uint32_t>> ranked_;
  std::vector<uint8_t> directAdded_;
  double sourcePower_ = 0.0, unshotFraction_ = 1.0;
  ProgressThrottle throttle_;
  double seconds_ = 0.0, formFactorSeconds_ = 0.0;
  uint64_t shots_ = 0;
  bool done_ = false;
  double threshold_ = s_.unshotThreshold;  // the unshot fraction it stops at (dynamic solvers lower it when idle)
};



}  // namespace luxel
