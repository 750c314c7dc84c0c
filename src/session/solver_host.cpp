#include "session/solver_host.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "gl/gl_context.h"
#include "luxel/error.h"
#include "mesh/surface_hash.h"
#include "session/checkpoint_file.h"
#include "solve/gathered_sh.h"
#include "solve/method_choice.h"
#include "solve/refinement.h"
#include "transport/cpu_transport.h"
#include "transport/form_factor_options.h"

namespace luxel {

namespace {

SolveOptions withMethodChosen(SolveOptions options, const SurfaceSet& surfaces) {
  // A set without patches was cut for the hierarchy (Session drops them): its elements, at least
  // as many as its patches were, keep auto's choice where it was.
  const size_t shooters = surfaces.hasPatches() ? surfaces.patches.size() : surfaces.elements.size();
  options.method = chooseMethod(options.method, options.backend, shooters, options.followsChanges);
  return options;
}

// In a physical scene the light not yet shot only falls: each shot removes a patch's unshot power
// and returns at most its reflectance times it (form factors from a patch sum to at most 1, a little
// more with sampling noise). Several times the emitted power means the transport is not physical.
constexpr double kMaxUnshotFraction = 2.0;
// Nor can surfaces absorb more than enters the scene: a solution that claims to is wrong.
constexpr double kMaxAbsorbedShare = 1.5;
// A solve asked to run to the end is still cut into slices of at most this long, to check it.
constexpr double kHealthCheckSeconds = 0.25;

// The checkpoints' format, in their key: bump it when a solver's saved state changes.
constexpr const char* kCheckpointFormat = "luxel-checkpoint-3";  // 2: lights' refined samples, direct light per element; 3: the hierarchy's changes of light

const char* const kLikelyCauses =
    "likely causes: coincident faces (a mesh loaded twice in one place, which the importers remove but "
    "a caller's own scene may still have), emission or light intensities near the float range, or "
    "reflectance of 1 in a closed scene";

}  // namespace

bool mayShootFromPatches(const SolveOptions& options, const SurfaceSet& surfaces) {
  const std::string method =
      chooseMethod(options.method, options.backend, surfaces.patches.size(), options.followsChanges);
  bool found = false;
  for (const SolverEntry& e : SolverRegistry::builtin().entries()) {
    if (e.description.name != method || (options.backend != "auto" && e.description.backend != options.backend))
      continue;
    found = true;
    if (e.shootsFromPatches) return true;
  }
  return !found;  // no such solver: the host says so
}

SolverHost::SolverHost(const Scene& scene, SurfaceSet& surfaces, const SolveOptions& requested, BorrowedResources borrowed,
                       int incidentShCount)
    : scene_(scene), surfaces_(surfaces), options_(withMethodChosen(requested, surfaces)), recordSh_(incidentShCount) {
  const SolveOptions& options = options_;
  const Stopwatch watch;
  if (!scene.hasLight())
    warnings_.push_back(fmt::format(
        "scene '{}' has no light, so it solves to black: add a sky or a sun (luxel --sky RADIANCE, --sun X,Y,Z; "
        "\"lights\" in a scene file) or emission (Ke in an OBJ's .mtl, emissiveFactor in glTF)",
        scene.name));
  const SolverRegistry& registry = SolverRegistry::builtin();
  const std::string& method = options.method;
  const std::string& backend = options.backend;
  validateSolveOptions(requested);  // method, backend and option names; values when both are fixed
  if (!(options.refine.threshold > 0.0f)) throw Error("refine threshold must be > 0");

  // The backend: GL where asked (or where auto finds a context and the method runs there).
  std::string chosen = backend;
  if (backend == "auto") {
    chosen = "cpu";
    if (!registry.find(method, "gl")) {
      warnings_.push_back(fmt::format("solver '{}' has no GL backend; using the CPU backend", method));
    } else if (borrowed.glContext) {
      chosen = "gl";
    } else {
      try {
        ownContext_ = std::make_unique<gl::Context>([this](const std::string& m) { warnings_.push_back(m); });
        chosen = "gl";
      } catch (const Error& e) {
        warnings_.push_back(fmt::format("{}; using the CPU backend", e.what()));
      }
    }
  }
  entry_ = &registry.get(method, chosen);
  const std::string name = fmt::format("solver {} on {}", method, chosen);
  if (entry_->shootsFromPatches && !surfaces.hasPatches())
    throw Error(fmt::format("{} shoots from patches, and scene '{}' was cut without them (for a solver that does "
                            "not need them); discretise it again",
                            name, scene.name));

  // Options: each one must be read by the chosen solver. When auto fell back to the CPU, options
  // only the GL solver reads are dropped with a warning instead, and so are those only the
  // method `auto` did not choose reads.
  SolverSettings settings = options.settings;
  if ((backend == "auto" && chosen == "cpu") || requested.method == "auto") {
    for (const auto& [key, value] : options.settings.values()) {
      bool read = false;
      for (const SolverOption& o : entry_->description.options) read = read || o.name == key;
      if (!read) {
        warnings_.push_back(fmt::format("option {}={} is not used by {}; ignored", key, value, name));
        settings.erase(key);
      }
    }
  }
  values_ = std::make_unique<SolverOptionValues>(name, entry_->description.options, settings);
  settings_ = settings;

  if (chosen == "gl") {
    if (borrowed.glContext) glContext_ = borrowed.glContext;
    else if (!ownContext_)
      ownContext_ = std::make_unique<gl::Context>([this](const std::string& m) { warnings_.push_back(m); });
    if (!glContext_) glContext_ = ownContext_.get();
  }
  // Before the transport (SolverEntry::prepare); the solver counts its time as its own.
  const Stopwatch preparing;
  if (entry_->prepare) prepared_ = entry_->prepare(surfaces, *values_);
  const double prepareSeconds = preparing.seconds();
  if (borrowed.transport) {
    transport_ = borrowed.transport;
  } else {
    ownTransport_ = std::make_unique<CpuTransport>(scene, surfaces, formFactorOptions(*values_));
    transport_ = ownTransport_.get();
  }
  setupSeconds_ = watch.seconds() - prepareSeconds;
  makeSolver();

  const CheckpointOptions& cp = options.checkpoint;
  if (!cp.path.empty() || !cp.resume.empty()) {
    if (!solver_->checkpoints())
      throw Error(fmt::format("{} cannot be checkpointed (--checkpoint, --resume)", name));
    if (options.refine.budget > 0) throw Error("checkpoints (--checkpoint, --resume) do not combine with --refine");
    if (!(cp.intervalSeconds > 0.0)) throw Error("the checkpoint interval must be > 0 seconds");
    if (!cp.resume.empty()) resumeFrom(cp.resume);
  }
}

SolverHost::~SolverHost() {
  // GL solvers delete their buffers and programs in their own context, which another session
  // may have made not current.
  try {
    useContext();
  } catch (const Error&) {
  }
  solver_.reset();
}

void SolverHost::useContext() {
  if (glContext_) glContext_->makeCurrent();
}

namespace {

bool sameLight(const Light& a, const Light& b) {
  return a.type == b.type && a.color == b.color && a.intensity == b.intensity && a.position == b.position &&
         a.direction == b.direction && a.innerConeAngle == b.innerConeAngle && a.outerConeAngle == b.outerConeAngle &&
         a.angularRadius == b.angularRadius;
}

}  // namespace

void SolverHost::computeAnalytic() {
  const Stopwatch watch;
  const size_t ne = surfaces_.elements.size();
  analytic_.assign(ne, Rgb(0.0f));
  const size_t shSize = ne * size_t(recordSh_);
  analyticSh_.assign(shSize, Rgb(0.0f));
  analyticShCount_ = recordSh_;
  if (scene_.lights.size() > kMaxKeptLightParts) {
    lightParts_.clear();
    if (recordSh_ > 0) {
      std::vector<uint32_t> all(scene_.lights.size());
      for (uint32_t i = 0; i < all.size(); ++i) all[i] = i;
      transport_->lightIrradianceAndSh(all, recordSh_, analytic_, analyticSh_);
    } else {
      transport_->analyticIrradiance(analytic_);
    }
  } else {
    lightParts_.resize(scene_.lights.size());
    for (uint32_t i = 0; i < scene_.lights.size(); ++i) {
      LightPart& part = lightParts_[i];
      if (part.geometry != geometry_ || part.irradiance.size() != ne || part.sh.size() != shSize ||
          !sameLight(part.light, scene_.lights[i])) {
        part.light = scene_.lights[i];
        part.geometry = geometry_;
        part.irradiance.assign(ne, Rgb(0.0f));
        part.sh.assign(shSize, Rgb(0.0f));
        const uint32_t one[] = {i};
        if (recordSh_ > 0) transport_->lightIrradianceAndSh(one, recordSh_, part.irradiance, part.sh);
        else transport_->lightIrradiance(one, part.irradiance);
      }
      for (size_t e = 0; e < ne; ++e) analytic_[e] += part.irradiance[e];
      for (size_t k = 0; k < shSize; ++k) analyticSh_[k] += part.sh[k];
    }
  }
  analyticSeconds_ += watch.seconds();
}

std::vector<Rgb> SolverHost::lightIrradiance(std::span<const uint32_t> lights) {
  const size_t ne = surfaces_.elements.size();
  std::vector<Rgb> out(ne, Rgb(0.0f));
  bool kept = true;
  for (uint32_t i : lights)
    kept = kept && i < lightParts_.size() && i < scene_.lights.size() && lightParts_[i].geometry == geometry_ &&
           lightParts_[i].irradiance.size() == ne && sameLight(lightParts_[i].light, scene_.lights[i]);
  if (!kept) {
    transport_->lightIrradiance(lights, out);
    return out;
  }
  for (uint32_t i : lights)
    for (size_t e = 0; e < ne; ++e) out[e] += lightParts_[i].irradiance[e];
  return out;
}

void SolverHost::retire() {
  // Keep the finished solver's work in the totals before it goes.
  const SolveStats s = solver_->stats();
  finished_.shots += s.shots, finished_.iterations += s.iterations, finished_.hemicubes += s.hemicubes;
  finished_.secondsFormFactors += s.secondsFormFactors, finished_.secondsSolve += s.secondsSolve;
}

void SolverHost::objectsMoved(std::span<const uint32_t> objects) {
  useContext();
  if (objects.empty()) return;
  transport_->objectsMoved(objects);
  // Every light's part follows the move: the transport computes again what the move can have
  // changed (the moved elements, and the shadows of the moved objects where they were and are).
  const uint64_t before = geometry_++;
  const Stopwatch watch;
  const size_t ne = surfaces_.elements.size();
  for (uint32_t i = 0; i < lightParts_.size() && i < scene_.lights.size(); ++i) {
    LightPart& part = lightParts_[i];
    if (part.geometry != before || part.irradiance.size() != ne || !sameLight(part.light, scene_.lights[i])) continue;
    const uint32_t one[] = {i};
    transport_->updateLightIrradianceAfterMove(one, part.irradiance);
    part.geometry = geometry_;
  }
  analyticSeconds_ += watch.seconds();
  computeAnalytic();
  system_->refresh(analytic_);
  checkpointKey_.reset(), finalCheckpointWritten_ = false;
  if (!solver_->objectsMoved(objects)) {
    retire();
    makeSolver(/*analyticIsCurrent=*/true);
  }
}

void SolverHost::sourcesChanged() {
  useContext();
  transport_->sourcesChanged();
  computeAnalytic();
  system_->refresh(analytic_);
  checkpointKey_.reset(), finalCheckpointWritten_ = false;
  if (!solver_->sourcesChanged()) {
    retire();
    makeSolver(/*analyticIsCurrent=*/true);
  }
}

void SolverHost::makeSolver(bool analyticIsCurrent) {
  useContext();
  checkpointKey_.reset(), finalCheckpointWritten_ = false;
  solver_.reset();
  system_.reset();
  if (!analyticIsCurrent) computeAnalytic();
  system_ = std::make_unique<RadiositySystem>(surfaces_, analytic_);
  solver_ = entry_->make(SolverResources{scene_, *system_, *transport_, glContext_, std::move(prepared_)}, *values_);
  if (recordSh_) solver_->recordIncidentSh(recordSh_);
}

void SolverHost::recordIncidentSh(int count) {
  useContext();
  recordSh_ = count;
  solver_->recordIncidentSh(count);
}

bool SolverHost::refine(const ProgressCallback& progress) {
  if (refinementOver_ || refined_ >= options_.refine.budget) return refinementOver_ = true, false;
  const Solution current = solver_->solution();
  const std::vector<uint32_t> split =
      elementsToRefine(surfaces_, current.radiosity, options_.refine, options_.refine.budget - refined_);
  if (split.empty()) return refinementOver_ = true, false;
  retire();
  for (uint32_t e : split) surfaces_.splitElement(e, scene_);
  transport_->elementsChanged();
  ++geometry_;
  refined_ += split.size() * 3;
  ++refinePasses_;
  reportProgress(progress, "refine", 1.0, fmt::format("split {} elements", split.size()));
  makeSolver();
  return true;
}

void SolverHost::checkHealth() const {
  const SolveStats s = solver_->stats();
  if (!std::isfinite(s.unshotFraction) || !std::isfinite(s.residual))
    throw Error(fmt::format("scene '{}': the {} solve diverged: its {} is not finite ({})", scene_.name, s.method,
                            std::isfinite(s.unshotFraction) ? "residual" : "unshot light", kLikelyCauses));
  if (s.unshotFraction > kMaxUnshotFraction)
    throw Error(fmt::format(
        "scene '{}': the {} solve diverged: the light not yet shot grew to {:.3g} times what the scene emits, "
        "where every bounce should shrink it ({})",
        scene_.name, s.method, s.unshotFraction, kLikelyCauses));
}

uint64_t SolverHost::checkpointKey() {
  if (checkpointKey_) return *checkpointKey_;
  // Everything the solver's state was computed from: the surfaces and how they group into
  // patches, the analytic light, the solver, its backend and options, and the state's format.
  ContentHash h;
  h.text(kCheckpointFormat);
  hashSurfaces(h, surfaces_);
  for (const Element& e : surfaces_.elements) h.value(e.patch);
  h.bytes(analytic_.data(), analytic_.size() * sizeof(Rgb));
  for (const std::string* s : {&entry_->description.name, &entry_->description.backend}) h.text(*s), h.value('\0');
  for (const auto& [key, value] : settings_.values()) h.text(key), h.value('='), h.text(value), h.value('\0');
  checkpointKey_ = h.digest();
  return *checkpointKey_;
}

void SolverHost::resumeFrom(const std::filesystem::path& path) {
  useContext();
  const std::vector<std::byte> payload = readCheckpointFile(path, checkpointKey());
  StateReader in(payload, fmt::format("checkpoint {}: the solver's state does not match this solve", path.string()));
  solver_->restoreState(in);
  in.end();
  checkHealth();
}

void SolverHost::checkpoint(bool now) {
  const CheckpointOptions& cp = options_.checkpoint;
  if (cp.path.empty() || finalCheckpointWritten_ || (!now && sinceCheckpoint_.seconds() < cp.intervalSeconds))
    return;
  StateWriter out;
  useContext();
  solver_->saveState(out);
  writeCheckpointFile(cp.path, checkpointKey(), out.bytes());
  sinceCheckpoint_.restart();
}

bool SolverHost::step(const StepLimit& limit, const ProgressCallback& progress) {
  useContext();
  const Stopwatch watch;
  while (true) {
    StepLimit left = limit;
    if (limit.seconds > 0) left.seconds = std::max(1e-9, limit.seconds - watch.seconds());
    // A caller counting units gets its units; one running to the end or for a while gets slices,
    // so that a diverging solve is caught while it runs instead of looping for ever.
    if (!limit.units) left.seconds = left.seconds > 0 ? std::min(left.seconds, kHealthCheckSeconds) : kHealthCheckSeconds;
    bool more = false;
    try {
      more = solver_->step(left, progress);
    } catch (const Cancelled&) {
      checkpoint(/*now=*/true);  // the solver stands at its last whole unit of work: Ctrl-C keeps it
      throw;
    }
    checkHealth();
    checkpoint(/*now=*/!more);
    finalCheckpointWritten_ = !more;
    if (more) {
      if (limit.units || (limit.seconds > 0 && watch.seconds() >= limit.seconds)) return true;  // the caller's slice ended
      continue;
    }
    if (!refine(progress)) return false;
    if (limit.seconds > 0 && watch.seconds() >= limit.seconds) return true;
  }
}

bool SolverHost::done() const { return solver_->done() && (refinementOver_ || refined_ >= options_.refine.budget); }

SolveStats SolverHost::stats() const {
  SolveStats s = solver_->stats();
  s.shots += finished_.shots, s.iterations += finished_.iterations, s.hemicubes += finished_.hemicubes;
  s.secondsFormFactors += finished_.secondsFormFactors + analyticSeconds_;
  s.secondsSolve += finished_.secondsSolve;
  s.secondsSetup = setupSeconds_;
  s.secondsTotal = lifetime_.seconds();
  s.warnings.insert(s.warnings.begin(), warnings_.begin(), warnings_.end());  // the host's, then the solver's
  s.elements = surfaces_.elements.size();
  s.patches = surfaces_.patches.size();
  s.rays = transport_->raysTraced();
  s.refinedElements = refined_;
  s.refinePasses = refinePasses_;
  return s;
}

Solution SolverHost::solution() {
  useContext();
  Solution sol = solver_->solution();
  sol.stats = stats();
  // Energy balance, in the mean of the three channels: what enters the system (emission from each
  // emitting side, analytic light landing on surfaces) against what surfaces absorb.
  double emitted = 0.0, absorbed = 0.0;
  for (size_t e = 0; e < surfaces_.elements.size(); ++e) {
    const Element& el = surfaces_.elements[e];
    emitted += el.area * (channelSum(el.exitance) + channelSum(analytic_[e]));
    absorbed += el.area * channelSum((Rgb(1.0f) - el.reflectance) * sol.irradiance[e]);
  }
  sol.stats.emittedPower = emitted / 3.0;
  sol.stats.absorbedPower = absorbed / 3.0;
  if (!std::isfinite(absorbed) || !std::isfinite(emitted))
    throw Error(fmt::format("scene '{}': the {} solution is not finite ({})", scene_.name, sol.stats.method, kLikelyCauses));
  if (absorbed > kMaxAbsorbedShare * emitted && absorbed > 0.0)
    throw Error(fmt::format("scene '{}': the {} solution absorbs {:.3g} times the power the scene emits ({})",
                            scene_.name, sol.stats.method, absorbed / emitted, kLikelyCauses));
  return sol;
}

std::vector<Rgb> SolverHost::incidentSh(int count, bool* gathered) {
  useContext();
  const size_t ne = surfaces_.elements.size();
  std::vector<Rgb> sh(ne * size_t(count)), lights(ne * size_t(count));
  // Progressive and gather know each patch's share exactly; others are gathered by rays.
  const bool known = solver_->incidentSh(count, sh);
  if (!known) sh = gatherIncidentSh(surfaces_, solver_->solution().radiosity, count, kGatherShRays);
  if (gathered) *gathered = !known;
  if (analyticShCount_ == count) {
    lights = analyticSh_;  // traced with the analytic irradiance
  } else {
    std::vector<uint32_t> all(scene_.lights.size());
    for (uint32_t i = 0; i < all.size(); ++i) all[i] = i;
    transport_->lightSh(all, count, lights);
  }
  for (size_t i = 0; i < sh.size(); ++i) sh[i] += lights[i];
  return sh;
}

Solution solve(const Scene& scene, SurfaceSet& surfaces, const SolveOptions& options, const ProgressCallback& progress) {
  SolverHost host(scene, surfaces, options);
  while (host.step({}, progress)) {
  }
  return host.solution();
}

}  // namespace luxel
