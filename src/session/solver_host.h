// Everything one solve needs, owned in one place and alive as long as the solve: the chosen
// solver from the registry, the CPU transport (form factors on the CPU backend, analytic lights
// on every backend), the GL context on the GL backend (made headless, or borrowed from the
// caller), the radiosity system, and adaptive refinement around the solver. Session and solve()
// are built on it.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/stopwatch.h"
#include "luxel/solve.h"
#include "solve/radiosity_system.h"
#include "solve/solver_registry.h"
#include "transport/transport.h"

namespace luxel {

namespace gl {
class Context;
}

// What a caller lends a SolverHost instead of the host making it: a transport built over the same
// scene and surfaces (the benchmark records its rays), a current GL context (a viewer's window).
struct BorrowedResources {
  Transport* transport = nullptr;
  gl::Context* glContext = nullptr;
};

// Whether the solver a host would make for `options` may read the surfaces' patches: any
// registered backend of the method that the options (auto included) can pick. When not, the
// owner of the surfaces can drop them (SurfaceSet::dropPatches) before making the host.
bool mayShootFromPatches(const SolveOptions& options, const SurfaceSet& surfaces);

class SolverHost {
 public:
  // Chooses the method ("auto": solve/method_choice.h, by the surfaces' patches) and the backend
  // ("auto" tries GL and falls back to the CPU with a warning), checks the
  // options against the chosen solver, builds what it needs and makes the solver. Throws Error
  // on an unknown method, backend or option. `scene` and `surfaces` must outlive the host;
  // `surfaces` is refined in place when options.refine.budget > 0.
  // `incidentShCount`: an owner that will ask incidentSh(count) says so here (as recordIncidentSh
  // would), and the analytic light's directions are then taken with its irradiance, by the same
  // rays, instead of traced again when asked.
  SolverHost(const Scene& scene, SurfaceSet& surfaces, const SolveOptions& options, BorrowedResources borrowed = {},
             int incidentShCount = 0);
  ~SolverHost();

  // Advances the solver by at most `limit`; when it is done and refinement has budget left,
  // splits elements and starts a new solver on the refined surfaces. Returns true while there is
  // work left.
  bool step(const StepLimit& limit = {}, const ProgressCallback& progress = {});
  bool done() const;
  // Dynamic objects moved: `scene` and the surfaces are already in their new places (Scene and
  // SurfaceSet::placeObject). The transport updates its instances, the analytic light is
  // recomputed, and the solver continues if it can follow moves or starts afresh otherwise.
  void objectsMoved(std::span<const uint32_t> objects);
  // The scene's lights or the surfaces' reflectance and emission changed (Session::setLights,
  // setMaterial): the analytic light is recomputed, and the solver continues if it can follow the
  // change or starts afresh otherwise.
  void sourcesChanged();
  // The irradiance the scene lights `lights` bring each element: the sum of their parts of the
  // analytic light when they are at hand, else traced again (the same samples either way).
  std::vector<Rgb> lightIrradiance(std::span<const uint32_t> lights);
  // Where the light of solution().irradiance comes from, for directional bakes: the incident
  // radiance at each element in spherical harmonics, `count` (4 or 9) per element (Solver::
  // incidentSh for the interreflected light, or a final gather of kGatherShRays rays an element
  // where the solver keeps no record of directions; Transport::lightSh for the analytic lights).
  // `gathered`, when given, says whether the rays gathered them.
  std::vector<Rgb> incidentSh(int count, bool* gathered = nullptr);
  static constexpr int kGatherShRays = 256;
  // Before the solve, by owners that will ask incidentSh(count): solvers that record directions
  // only as they shoot (the GPU's) start recording, this one and any made after a change.
  void recordIncidentSh(int count);
  // The solution so far, with every statistic filled in (energy balance included).
  Solution solution();
  SolveStats stats() const;

  const SolverEntry& entry() const { return *entry_; }
  const std::string& backend() const { return entry_->description.backend; }
  Transport& transport() { return *transport_; }
  const SurfaceSet& surfaces() const { return surfaces_; }

 private:
  // Throws Error when the solve diverges (non-finite, or the unshot light growing).
  void checkHealth() const;
  // Checkpoints (options.checkpoint): the key of this solve (computed again only after the
  // surfaces or the analytic light change), reading one, writing one when the interval is up (or
  // now, when `now`).
  uint64_t checkpointKey();
  void resumeFrom(const std::filesystem::path& path);
  void checkpoint(bool now);
  // Analytic irradiance (unless current), system and solver for the current surfaces.
  void makeSolver(bool analyticIsCurrent = false);
  // The analytic light: each scene light's part traced again unless it is kept from before for the
  // same light at the same index on the same geometry (a light edit traces only the lights edited).
  void computeAnalytic();
  void retire();  // adds the current solver's work to the totals, before it is replaced
  bool refine(const ProgressCallback& progress);

  const Scene& scene_;
  SurfaceSet& surfaces_;
  SolveOptions options_;
  std::vector<std::string> warnings_;
  const SolverEntry* entry_ = nullptr;
  std::shared_ptr<void> prepared_;  // entry_->prepare's work, for the first solver made
  std::unique_ptr<SolverOptionValues> values_;
  SolverSettings settings_;  // what the solver was given, for the checkpoints' key
  // Makes the GL context current (a no-op on the CPU, or for a borrowed one): every call that
  // reaches a GL solver starts with it, so that sessions in one thread can take turns.
  void useContext();
  std::unique_ptr<gl::Context> ownContext_;  // declared before what uses it: destroyed after
  gl::Context* glContext_ = nullptr;
  std::unique_ptr<Transport> ownTransport_;
  Transport* transport_ = nullptr;
  std::vector<Rgb> analytic_;
  // Where analytic_ comes from, for directional bakes (recordSh_ coefficients an element), kept
  // while analyticShCount_ says it was traced with analytic_ (0: not).
  std::vector<Rgb> analyticSh_;
  int analyticShCount_ = 0;
  // Each light's part of analytic_, for scenes of up to kMaxKeptLightParts lights: the light it was
  // traced for, and the geometry it was traced on (geometry_ counts moves and refinements).
  struct LightPart {
    Light light;
    uint64_t geometry = 0;
    std::vector<Rgb> irradiance;
    std::vector<Rgb> sh;  // recordSh_ coefficients an element where directions were asked for
  };
  static constexpr size_t kMaxKeptLightParts = 16;
  std::vector<LightPart> lightParts_;
  uint64_t geometry_ = 0;
  std::unique_ptr<RadiositySystem> system_;
  std::unique_ptr<Solver> solver_;
  // Work of solvers replaced by refinement, and the host's own time.
  SolveStats finished_;
  size_t refined_ = 0;
  int refinePasses_ = 0;
  bool refinementOver_ = false;
  int recordSh_ = 0;  // recordIncidentSh's count, 0 for none
  double setupSeconds_ = 0.0, analyticSeconds_ = 0.0;
  Stopwatch sinceCheckpoint_;
  std::optional<uint64_t> checkpointKey_;  // reset by makeSolver and objectsMoved
  bool finalCheckpointWritten_ = false;    // a front end may keep stepping a finished solve
  Stopwatch lifetime_;
};

}  // namespace luxel
