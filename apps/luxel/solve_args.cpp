#include "solve_args.h"

#include "luxel/error.h"

namespace luxel::cli {
namespace {

// A flag that sets the solver option of the same name when given.
void solverFlag(CLI::App& c, SolveArgs& a, const std::string& option, const std::string& help) {
  c.add_option_function<std::string>(
      "--" + option, [&a, option](const std::string& value) { a.flagged.emplace_back(option, value); }, help);
}

}  // namespace

void addSolveOptions(CLI::App& c, SolveArgs& a) {
  a.command = &c;
  c.add_option("--solver", a.solver, "A registered solver: progressive or gather (luxel solvers lists them)")
      ->capture_default_str();
  c.add_option("--backend", a.backend, "cpu, gl (OpenGL 4.5 hemicubes, headless) or auto (gl when a context can be made)")
      ->capture_default_str();
  auto* elements = c.add_option("--elements", a.elements, "Element budget (default 10000)");
  c.add_option("--element-size", a.elementSize, "Element edge length in scene units")->excludes(elements);
  c.add_option("--refine", a.refine, "Adaptive refinement: extra elements allowed (0: off)");
  c.add_option("--set", a.set, "A solver option NAME=VALUE (repeatable; luxel solvers lists each solver's)");
  solverFlag(c, a, "unshot", "progressive: stop below this unshot fraction (default 0.001)");
  solverFlag(c, a, "rays-per-pair", "cpu: visibility rays per element-patch pair (default 4)");
  solverFlag(c, a, "shooters-per-pass", "progressive: patches shot together in one pass (default 8; 1 on a software rasteriser)");
  solverFlag(c, a, "hemicube-resolution", "gl: hemicube top-face pixels a side (default 64 shooting, 256 gathering)");
  solverFlag(c, a, "hemicubes-per-side", "gl: k x k hemicubes per shooting patch (default 3) or per gathering element (default 2)");
  solverFlag(c, a, "emitter-hemicubes-per-side", "gl progressive: k x k hemicubes for an emitting patch's first shot (default 6; 0: as other shooters)");
  solverFlag(c, a, "hemicube-visibility", "gl progressive: item (ID hemicubes, seed 001) or distance (depth hemicubes, seed 003)");
}

DiscretiseOptions discretiseOptions(const SolveArgs& a) {
  DiscretiseOptions d;
  if (a.elementSize > 0.0f) d.elementSize = a.elementSize;
  if (a.elements > 0) d.elementBudget = a.elements;
  return d;
}

SolveOptions solveOptions(const SolveArgs& a) {
  SolveOptions o;
  o.method = a.solver;
  o.backend = a.backend;
  o.refine.budget = a.refine;
  for (const auto& [name, value] : a.flagged) o.settings.set(name, value);
  for (const std::string& s : a.set) o.settings.parse(s);
  return o;
}

}  // namespace luxel::cli
