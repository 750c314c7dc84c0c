// The registry of solvers, keyed by (method, backend). A solver registers once, in
// solve/builtin_solvers.cpp, with its options, its factory and the settings under which it
// converges; the CLI, the sessions, `luxel solvers` and the conformance tests all read it from
// here (docs/extending.md).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "luxel/solver.h"
#include "solve/radiosity_system.h"
#include "solve/solver_options.h"
#include "transport/transport.h"

namespace luxel {

namespace gl {
class Context;
}

// What a solver is made from. All of it outlives the solver.
struct SolverResources {
  const Scene& scene;
  const RadiositySystem& system;  // the surfaces, emission, reflectance, analytic irradiance
  Transport& transport;           // the CPU backend's form factors (unused by GL solvers)
  gl::Context* glContext;         // the GL backend's context, current on this thread; null on the CPU
  std::shared_ptr<void> prepared = nullptr;  // what SolverEntry::prepare made, the first time only
};

// What the conformance suite (tests/conformance) holds a solver to: the relative tolerances the
// method's own quadrature allows (a hemicube is a midpoint rule over its pixels).
struct SolverAccuracy {
  double furnace = 2e-3;     // per element, against Le / (1 - rho)
  double cie = 6e-3;         // mean illuminance, against CIE 171 case 5.8
  double halfShadow = 0.03;  // the partly occluded factor, against its closed form
  double cornell = 0.02;     // NRMSE against the converged CPU gather on the Cornell box
};

struct SolverEntry {
  SolverDescription description;  // name (the method), backend, one line, options
  std::function<std::unique_ptr<Solver>(const SolverResources&, const SolverOptionValues&)> make;
  // Settings (beyond the defaults) under which the solver converges to the discrete system's
  // solution: for the conformance tests and references.
  SolverSettings converged;
  SolverAccuracy accuracy;
  // Whether it reads SurfaceSet::patches. A session whose solver does not drops them.
  bool shootsFromPatches = true;
  // Work on the surfaces alone that the solver does first, which the host runs before it builds
  // the transport so that the two are never in memory together (the face-cluster hierarchy's
  // build, a solve's largest temporaries at millions of faces: docs/performance.md). Its result
  // reaches the first make() as SolverResources::prepared; a solver made again does the work itself.
  std::function<std::shared_ptr<void>(const SurfaceSet&, const SolverOptionValues&)> prepare;
};

class SolverRegistry {
 public:
  // Every solver luxel ships (solve/builtin_solvers.cpp).
  static const SolverRegistry& builtin();

  void add(SolverEntry entry);  // throws Error on a duplicate (method, backend) or option name
  const SolverEntry* find(const std::string& method, const std::string& backend) const;
  // Throws Error listing what exists when there is no such method, or it has no such backend.
  const SolverEntry& get(const std::string& method, const std::string& backend) const;
  bool hasMethod(const std::string& method) const;
  const std::vector<SolverEntry>& entries() const { return entries_; }

 private:
  std::vector<SolverEntry> entries_;
};

}  // namespace luxel
