#include "solve/solver_registry.h"

#include <algorithm>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "luxel/error.h"
#include "luxel/solve.h"
#include "solve/method_choice.h"

namespace luxel {

void registerBuiltinSolvers(SolverRegistry& registry);  // solve/builtin_solvers.cpp

const SolverRegistry& SolverRegistry::builtin() {
  static const SolverRegistry registry = [] {
    SolverRegistry r;
    registerBuiltinSolvers(r);
    return r;
  }();
  return registry;
}

void SolverRegistry::add(SolverEntry entry) {
  const SolverDescription& d = entry.description;
  if (find(d.name, d.backend)) throw Error(fmt::format("solver {} on {} is registered twice", d.name, d.backend));
  std::set<std::string> names;
  for (const SolverOption& o : d.options)
    if (!names.insert(o.name).second)
      throw Error(fmt::format("solver {} on {} declares option '{}' twice", d.name, d.backend, o.name));
  // The defaults and the converged settings must pass the solver's own checks.
  SolverOptionValues(d.name + " on " + d.backend, d.options, entry.converged);
  entries_.push_back(std::move(entry));
}

const SolverEntry* SolverRegistry::find(const std::string& method, const std::string& backend) const {
  for (const SolverEntry& e : entries_)
    if (e.description.name == method && e.description.backend == backend) return &e;
  return nullptr;
}

bool SolverRegistry::hasMethod(const std::string& method) const {
  return std::any_of(entries_.begin(), entries_.end(), [&](const SolverEntry& e) { return e.description.name == method; });
}

const SolverEntry& SolverRegistry::get(const std::string& method, const std::string& backend) const {
  if (const SolverEntry* e = find(method, backend)) return *e;
  std::vector<std::string> all, backends;
  for (const SolverEntry& e : entries_) {
    all.push_back(e.description.name + "/" + e.description.backend);
    if (e.description.name == method) backends.push_back(e.description.backend);
  }
  if (backends.empty())
    throw Error(fmt::format("unknown solver '{}' (registered: {})", method, fmt::join(all, ", ")));
  throw Error(fmt::format("solver '{}' does not run on backend '{}' (it runs on: {})", method, backend,
                          fmt::join(backends, ", ")));
}

std::vector<SolverDescription> registeredSolvers() {
  std::vector<SolverDescription> out;
  for (const SolverEntry& e : SolverRegistry::builtin().entries()) out.push_back(e.description);
  return out;
}

}  // namespace luxel

namespace luxel {

void validateSolveOptions(const SolveOptions& options) {
  const SolverRegistry& registry = SolverRegistry::builtin();
  if (options.backend != "cpu" && options.backend != "gl" && options.backend != "auto")
    throw Error(fmt::format("unknown backend '{}' (expected cpu, gl or auto)", options.backend));
  if (options.method == "auto") {
    // The method is chosen once the scene's patches are known (solve/method_choice.h): each
    // option must be read by one of the methods it may choose; their values are checked then.
    for (const auto& [name, value] : options.settings.values()) {
      bool read = false;
      for (const SolverEntry& e : registry.entries())
        for (const char* m : kAutoMethods)
          if (e.description.name == m && (options.backend == "auto" || e.description.backend == options.backend))
            for (const SolverOption& o : e.description.options) read = read || o.name == name;
      if (!read)
        throw Error(fmt::format("solver auto (progressive or hierarchical) on {} has no option '{}'", options.backend, name));
    }
    return;
  }
  if (options.backend != "auto") {
    const SolverEntry& e = registry.get(options.method, options.backend);
    SolverOptionValues(fmt::format("solver {} on {}", options.method, options.backend), e.description.options,
                       options.settings);
    return;
  }
  // auto: each option must be read by the GL or the CPU solver of the method, and be valid for
  // the GL one when it has it (the backend tried first).
  if (!registry.hasMethod(options.method)) registry.get(options.method, "cpu");
  const SolverEntry* gl = registry.find(options.method, "gl");
  const SolverEntry* cpu = registry.find(options.method, "cpu");
  for (const auto& [name, value] : options.settings.values()) {
    bool read = false;
    for (const SolverEntry* e : {gl, cpu})
      for (const SolverOption& o : e ? e->description.options : std::vector<SolverOption>{}) read = read || o.name == name;
    if (!read)
      throw Error(fmt::format("solver {} has no option '{}' on any backend (its options: {})", options.method, name,
                              optionNames((gl ? gl : cpu)->description.options)));
  }
}

}  // namespace luxel
