// The named benchmark suites. Each case is one static solve; the seed figures beside them are the
// published ones (van de Hoef 2013, Tables 5.1 and 5.2a, GTX 670; Rodriguez 2006, section 5.8),
// copied from ../shared/seeds/notes.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "luxel/bench.h"
#include "luxel/error.h"

namespace luxel::bench {
namespace {

// 001's progressive refinement stops on a fixed budget per frame; ours stops on the unshot
// fraction, set per scene so the error lands at or below the seed's (docs/performance.md has
// the sweep: albedo 0.9 needs many more bounces than the Cornell boxes).
constexpr double kSeedProgressiveUnshot = 3e-3;
constexpr double kIndirectProgressiveUnshot = 1e-3;
// Gauss-Seidel has converged to the form factors' own noise by this residual.
constexpr double kSeedGatherResidual = 1e-4;

Case progressive(const std::string& scene, double unshot, SeedFigure seed) {
  Case c;
  c.name = scene + "/progressive";
  c.scene = scene;
  c.setting = fmt::format("progressive to {:g} unshot", unshot);
  c.solve.method = SolveOptions::Method::Progressive;
  c.solve.unshotThreshold = unshot;
  c.seed = std::move(seed);
  return c;
}

Case gather(const std::string& scene, double residual, SeedFigure seed) {
  Case c;
  c.name = scene + "/gather";
  c.scene = scene;
  c.setting = fmt::format("Gauss-Seidel gather to {:g} residual", residual);
  c.solve.method = SolveOptions::Method::Gather;
  c.solve.residualThreshold = residual;
  c.seed = std::move(seed);
  return c;
}

std::vector<Suite> makeSuites() {
  const std::string t51 = "001 Tables 5.1/5.2a (GTX 670)";
  Suite seeds{"seeds", "001's four scenes (van de Hoef 2013), static solve at the first pose", {}};
  struct Row {
    const char* scene;
    double gatherMs, gatherError, progressiveMs, progressiveError;
  };
  for (const Row& r : {Row{"indirect-light", 4757, 0.0522469, 265, 0.0631117},
                       Row{"cornell-large", 2437, 0.00225834, 116, 0.00675699},
                       Row{"cornell-small", 2440, 0.0028034, 87, 0.0098088},
                       Row{"cornell-low", 150, 0.0110786, 49, 0.0149107}}) {
    const double unshot = std::string(r.scene) == "indirect-light" ? kIndirectProgressiveUnshot : kSeedProgressiveUnshot;
    seeds.cases.push_back(progressive(r.scene, unshot, {t51, r.progressiveMs, r.progressiveError}));
    // The fewest rays that still reach the seed's progressive error (sweep in docs/performance.md):
    // one ray per ordinary pair, 4 near contacts, 16 from emitters, and a looser stop.
    Case fast = progressive(r.scene, 3 * unshot, {t51, r.progressiveMs, r.progressiveError});
    fast.name += "-fast";
    fast.setting += ", 1/4/16 rays (pair/near/emitter)";
    fast.solve.formFactors.raysPerPair = 1;
    fast.solve.formFactors.nearRaysPerPair = 4;
    fast.solve.formFactors.emitterRaysPerPair = 16;
    seeds.cases.push_back(fast);
    seeds.cases.push_back(gather(r.scene, kSeedGatherResidual, {t51, r.gatherMs, r.gatherError}));
  }

  Suite shader{"shader", "000's Cornell-like boxes and the sphere-and-torus scene (Rodriguez 2006)", {}};
  for (const char* box : {"shader-box-774", "shader-box-2734", "shader-box-10254", "shader-box-15814"}) {
    SeedFigure none{"000 Test 1 (graphs lost; no numbers)", 0, 0};
    if (std::string(box) == "shader-box-774") none = {"000 Plate C.9, empty box (settings unstated)", 58000, 0};
    shader.cases.push_back(gather(box, kSeedGatherResidual, none));
    shader.cases.push_back(progressive(box, kSeedProgressiveUnshot, {}));
  }
  shader.cases.push_back(gather("shader-sphere-torus", kSeedGatherResidual,
                                {"000 Plate C.10 (settings unstated)", 203000, 0}));
  shader.cases.push_back(progressive("shader-sphere-torus", kSeedProgressiveUnshot, {}));

  Suite scenes{"scenes", "the shared real scenes (bench/scenes/*.json; run from the repository root)", {}};
  {
    Case cornell = progressive("bench/scenes/cornell-obj.json", 1e-3, {});
    cornell.name = "cornell-obj/progressive";
    cornell.discretise.elementBudget = 10000;
    scenes.cases.push_back(cornell);
    // Tens of thousands of faces, nearly one patch each: progressive shooting is O(elements x
    // shots) until face clusters (seed 002) group them, so these run on a time budget and report
    // the unshot fraction they reach; no reference is feasible at this size.
    Case sibenik = progressive("bench/scenes/sibenik.json", 1e-2, {});
    sibenik.name = "sibenik/progressive-60s";
    sibenik.setting += ", at most 60 s";
    sibenik.solve.timeBudget = 60.0;
    sibenik.discretise.elementBudget = 100000;
    scenes.cases.push_back(sibenik);
    Case conference = progressive("bench/scenes/conference.json", 1e-2, {});
    conference.name = "conference/progressive-60s";
    conference.setting += ", at most 60 s";
    conference.solve.timeBudget = 60.0;
    conference.discretise.elementBudget = 400000;
    scenes.cases.push_back(conference);
  }

  Suite core{"core", "the built-in measured Cornell box at 10,000 elements (the core issue's targets)", {}};
  core.cases.push_back(progressive("cornell", 1e-3, {}));
  core.cases.push_back(gather("cornell", 1e-4, {}));

  Suite quick{"quick", "a smoke run: the built-in Cornell box at 1,000 elements", {}};
  quick.cases.push_back(progressive("cornell", 1e-2, {}));
  quick.cases.back().discretise.elementBudget = 1000;

  // The GL backend (item-buffer hemicubes, default 256 pixels, 2 x 2 per element), on scenes
  // small enough for Mesa's llvmpipe; the error columns are against the same CPU references as
  // the CPU cases. Progressive shooting transposes all rows (the first shot renders them), or
  // renders ID hemicubes on the shooters (the -id case).
  Suite gl{"gl", "the OpenGL backend's hemicubes on cornell-low and the built-in Cornell box at 1,000 elements", {}};
  {
    Case low = gather("cornell-low", kSeedGatherResidual, {t51, 150, 0.0110786});
    low.name = "cornell-low/gl-gather";
    low.backend = "gl";
    low.setting += ", GL hemicubes";
    gl.cases.push_back(low);
    Case box = gather("cornell", kSeedGatherResidual, {});
    box.name = "cornell-1k/gl-gather";
    box.backend = "gl";
    box.setting += ", GL hemicubes";
    box.discretise.elementBudget = 1000;
    gl.cases.push_back(box);
    Case shoot = progressive("cornell", 1e-2, {});
    shoot.name = "cornell-1k/gl-progressive";
    shoot.backend = "gl";
    shoot.setting += ", GL hemicubes";
    shoot.discretise.elementBudget = 1000;
    gl.cases.push_back(shoot);
    Case id = shoot;
    id.name = "cornell-1k/gl-progressive-id";
    id.setting += ", ID-hemicube shooting";
    id.glIdShooting = true;
    gl.cases.push_back(id);
  }
  return {seeds, shader, scenes, core, quick, gl};
}

}  // namespace

const std::vector<Suite>& suites() {
  static const std::vector<Suite> all = makeSuites();
  return all;
}

const Suite& findSuite(const std::string& name) {
  std::vector<std::string> names;
  for (const Suite& s : suites()) {
    if (s.name == name) return s;
    names.push_back(s.name);
  }
  throw Error(fmt::format("unknown benchmark suite '{}' (known: {})", name, fmt::join(names, ", ")));
}

}  // namespace luxel::bench
