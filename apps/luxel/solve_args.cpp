#include "solve_args.h"

namespace luxel::cli {

void addSolveOptions(CLI::App& c, SolveArgs& a) {
  c.add_option("--solver", a.solver, "progressive or gather")->capture_default_str();
  c.add_option("--backend", a.backend, "cpu, gl (OpenGL 4.5 hemicubes, headless) or auto (gl when a context can be made)")
      ->capture_default_str();
  auto* elements = c.add_option("--elements", a.elements, "Element budget (default 10000)");
  c.add_option("--element-size", a.elementSize, "Element edge length in scene units")->excludes(elements);
  c.add_option("--unshot", a.unshot, "progressive: stop below this unshot fraction")
      ->check(CLI::Range(1e-9, 0.999))
      ->capture_default_str();
  c.add_option("--refine", a.refine, "Adaptive refinement: extra elements allowed (0: off)");
  c.add_option("--rays-per-pair", a.raysPerPair, "Visibility rays per element-patch pair")->check(CLI::Range(1, 256));
  c.add_option("--shooters-per-pass", a.shootersPerPass,
               "progressive: patches shot together in one pass (default 8; 1 on a software rasteriser)")
      ->check(CLI::Range(1, kMaxShootersPerPass));
  c.add_option("--hemicube-resolution", a.hemicubeResolution,
               "GL: hemicube top-face pixels a side (default 64 shooting, 256 gathering)")
      ->check(CLI::Range(8, 4096));
  c.add_option("--hemicubes-per-side", a.hemicubesPerSide,
               "GL: k x k hemicubes per shooting patch (default 3) or per gathering element (default 2)")
      ->check(CLI::Range(1, 8));
  c.add_option("--emitter-hemicubes-per-side", a.emitterHemicubesPerSide,
               "GL progressive: k x k hemicubes for an emitting patch's first shot (default 6; 0: as other shooters)")
      ->check(CLI::Range(0, 8));
  c.add_option("--hemicube-visibility", a.hemicubeVisibility,
               "GL progressive: item (ID hemicubes, seed 001) or distance (depth hemicubes, seed 003)")
      ->capture_default_str();
}

DiscretiseOptions discretiseOptions(const SolveArgs& a) {
  DiscretiseOptions d;
  if (a.elementSize > 0.0f) d.elementSize = a.elementSize;
  if (a.elements > 0) d.elementBudget = a.elements;
  return d;
}

SolveOptions solveOptions(const SolveArgs& a) {
  SolveOptions o;
  o.method = parseSolveMethod(a.solver);
  o.backend = parseSolveBackend(a.backend);
  o.unshotThreshold = a.unshot;
  o.refineBudget = a.refine;
  if (a.shootersPerPass > 0) o.shootersPerPass = a.shootersPerPass;
  if (a.raysPerPair > 0) o.formFactors.raysPerPair = a.raysPerPair;
  o.hemicubeVisibility = parseHemicubeVisibility(a.hemicubeVisibility);
  if (a.emitterHemicubesPerSide >= 0) o.emitterHemicubesPerSide = a.emitterHemicubesPerSide;
  for (SolveOptions::HemicubeSampling* h : {&o.shootingHemicubes, &o.gatheringHemicubes}) {
    if (a.hemicubeResolution > 0) h->resolution = a.hemicubeResolution;
    if (a.hemicubesPerSide > 0) h->perSide = a.hemicubesPerSide;
  }
  return o;
}

}  // namespace luxel::cli
