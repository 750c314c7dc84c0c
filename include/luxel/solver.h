// Solvers as objects with state: made for a scene, its surfaces and a backend, advanced in steps,
// read at any step. Every (method, backend) pair luxel knows is registered once, with its own
// options; `luxel solvers` lists them. docs/extending.md shows how to add one.
#pragma once

#include <concepts>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "luxel/checkpoint.h"
#include "luxel/progress.h"
#include "luxel/solution.h"

namespace luxel {

// Solver options by name, as `--set NAME=VALUE` gives them: text until the chosen solver parses
// and checks them against what it declares (SolverOption). A name the solver does not declare is
// an error that lists the names it does.
class SolverSettings {
 public:
  SolverSettings& set(const std::string& name, std::string value);
  SolverSettings& set(const std::string& name, const char* value) { return set(name, std::string(value)); }
  SolverSettings& set(const std::string& name, double value);  // written so that it reads back exactly
  SolverSettings& set(const std::string& name, bool value) { return set(name, std::string(value ? "true" : "false")); }
  template <std::integral T>
    requires(!std::is_same_v<T, bool>)
  SolverSettings& set(const std::string& name, T value) {
    return set(name, std::to_string(value));
  }
  // "NAME=VALUE", as the command line's --set gives it; throws Error when there is no '='.
  SolverSettings& parse(std::string_view assignment);
  void erase(const std::string& name) { values_.erase(name); }

  bool has(const std::string& name) const { return values_.count(name) != 0; }
  const std::string* find(const std::string& name) const;
  const std::map<std::string, std::string>& values() const { return values_; }
  bool empty() const { return values_.empty(); }

 private:
  std::map<std::string, std::string> values_;
};

// One option a solver reads: its name, default, and one line of help. Kinds are checked before
// the solver sees a value: a number in [min, max] (Integer: whole), a flag (true/false/1/0/on/off),
// or one of `choices`.
struct SolverOption {
  enum class Kind { Real, Integer, Flag, Choice };
  std::string name;
  Kind kind = Kind::Real;
  std::string defaultValue;
  std::string help;
  double min = 0.0, max = 0.0;        // Real, Integer
  std::vector<std::string> choices;   // Choice
};

// What the registry says about one solver (for `luxel solvers` and for front ends).
struct SolverDescription {
  std::string name;     // the method, e.g. "progressive"
  std::string backend;  // "cpu" or "gl"
  std::string description;
  std::vector<SolverOption> options;
};

// Every registered solver, in registration order.
std::vector<SolverDescription> registeredSolvers();

// How far one call of Solver::step may go. Both 0: until the solver stops by itself (converged,
// or its own time or shot budget spent).
struct StepLimit {
  double seconds = 0.0;  // stop after the first unit of work that ends past this time
  uint64_t units = 0;    // units of work: passes of shooting, sweeps of gathering
};

// A solver with state. Every registered solver solves the discrete system of luxel/solve.h on
// the surfaces it was made for; the object keeps what it needs to continue (cached form
// factors, unshot radiosity, GPU buffers and shaders), so a front end can step it and show its
// solution between steps, and a later update can continue from where it stopped.
class Solver {
 public:
  virtual ~Solver() = default;

  // Advances by at most `limit`. Returns true while there is work left (false once done()).
  // Throws Cancelled when `progress` says stop; the solver stays usable at its last complete
  // unit of work.
  virtual bool step(const StepLimit& limit = {}, const ProgressCallback& progress = {}) = 0;

  // Whether the solver has stopped by itself: converged, or its own budget spent.
  virtual bool done() const = 0;

  // The current solution, as complete as the steps so far make it (with the ambient estimate
  // of what is not yet shot, where the method has one and it is on). May read back GPU state.
  virtual Solution solution() = 0;

  // Statistics so far: method, backend, work done, residual, seconds split into form factors
  // and solve. Elements, patches, rays and energy are filled in by whoever owns the transport.
  virtual SolveStats stats() const = 0;

  // Dynamic objects moved: the scene, the surfaces, the transport and the system's areas and
  // analytic irradiance are already in their new state. Returns true when the solver has brought
  // its own state along and continues from it (what dynamic radiosity does); false, the default,
  // when it cannot, and its owner replaces it with a fresh solver.
  virtual bool objectsMoved(std::span<const uint32_t> objects) {
    (void)objects;
    return false;
  }

  // The system's emission, reflectance or analytic irradiance changed (lights moved or recoloured,
  // materials edited); the geometry did not. Returns true when the solver has brought its state
  // along (shooting the difference); false, the default, when its owner must replace it.
  virtual bool sourcesChanged() { return false; }

  // Where the interreflected light comes from, for directional bakes: the incident radiance at each
  // element in real spherical harmonics, `count` (4: L1, or 9: L2) coefficients per element,
  // out[e * count + i] = integral of L(w) Y_i(w) over the sphere, w in world space, for all the
  // light of solution().irradiance except the analytic lights' (the owner adds those from the
  // transport). Returns false, the default, when the method keeps no record of directions.
  virtual bool incidentSh(int count, std::span<Rgb> out) {
    (void)count, (void)out;
    return false;
  }
  // Asked before the first step, by owners that will want incidentSh(count): a solver that can
  // only record directions as it shoots (the GPU's) starts doing so. Others ignore it.
  virtual void recordIncidentSh(int count) { (void)count; }

  // Checkpoints (luxel/checkpoint.h). A solver that can be checkpointed says so, writes
  // everything step() needs to go on from where it is, and reads it back into a solver made
  // afresh for the same system and options, which then continues to the same result, bit for
  // bit. What can be recomputed exactly (cached form factors, the hierarchy) need not be written.
  virtual bool checkpoints() const { return false; }
  virtual void saveState(StateWriter& out) const { (void)out; }
  virtual void restoreState(StateReader& in) { (void)in; }
};

}  // namespace luxel
