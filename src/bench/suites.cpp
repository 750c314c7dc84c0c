// The named benchmark suites. Each case is one static solve; the seed figures beside them are the
// published ones (van de Hoef 2013, Tables 5.1 and 5.2a, GTX 670; Rodriguez 2006, section 5.8),
// copied from ../shared/seeds/notes.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "luxel/bench.h"
#include "luxel/error.h"

namespace luxel::bench {
namespace {

// Path-traced irradiance probes per case that has them: an independent check of the solution
// and of the reference (bench/probe_reference.h), each probe to 0.5% noise where 2^18 paths allow.
constexpr size_t kProbes = 256;

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
  c.solve.method = "progressive";
  c.solve.settings.set("unshot", unshot);
  c.seed = std::move(seed);
  return c;
}

Case gather(const std::string& scene, double residual, SeedFigure seed) {
  Case c;
  c.name = scene + "/gather";
  c.scene = scene;
  c.setting = fmt::format("Gauss-Seidel gather to {:g} residual", residual);
  c.solve.method = "gather";
  c.solve.settings.set("residual", residual);
  c.seed = std::move(seed);
  return c;
}

std::vector<Suite> makeSuites() {
  const std::string t51 = "001 Tables 5.1/5.2a (GTX 670)";
  Suite seeds{"seeds", "001's four scenes (van de Hoef 2013), static solve at the first pose", {}};
  struct Row {
    const char* scene;
    double gatherMs, gatherError, progressiveMs, progressiveError;
    double unshot() const {
      return std::string(scene) == "indirect-light" ? kIndirectProgressiveUnshot : kSeedProgressiveUnshot;
    }
  };
  const Row rows[] = {{"indirect-light", 4757, 0.0522469, 265, 0.0631117},
                      {"cornell-large", 2437, 0.00225834, 116, 0.00675699},
                      {"cornell-small", 2440, 0.0028034, 87, 0.0098088},
                      {"cornell-low", 150, 0.0110786, 49, 0.0149107}};
  for (const Row& r : rows) {
    const double unshot = r.unshot();
    seeds.cases.push_back(progressive(r.scene, unshot, {t51, r.progressiveMs, r.progressiveError}));
    // The fewest rays that still reach the seed's progressive error (sweep in docs/performance.md):
    // one ray per ordinary pair, 4 near contacts, 16 from emitters, and a looser stop.
    Case fast = progressive(r.scene, 3 * unshot, {t51, r.progressiveMs, r.progressiveError});
    fast.name += "-fast";
    fast.setting += ", 1/4/16 rays (pair/near/emitter)";
    fast.solve.settings.set("rays-per-pair", 1).set("near-rays-per-pair", 4).set("emitter-rays-per-pair", 16);
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
    sibenik.solve.settings.set("time-budget", 60.0);
    sibenik.discretise.elementBudget = 100000;
    sibenik.probes = kProbes;  // the same elements as the hierarchical suite's: the same probes
    scenes.cases.push_back(sibenik);
    Case conference = progressive("bench/scenes/conference.json", 1e-2, {});
    conference.name = "conference/progressive-60s";
    conference.setting += ", at most 60 s";
    conference.solve.settings.set("time-budget", 60.0);
    conference.discretise.elementBudget = 400000;
    scenes.cases.push_back(conference);
  }

  // Seed 002's solver on the real scenes, each against a reference no flat solver of its size
  // could give in a benchmark's time: the Cornell box cut so that every element is its own patch
  // (a patch shooting its mean is not what the hierarchy computes), gathered; Sibenik by
  // progressive refinement to 1e-4 unshot on the same elements; the conference room, where a
  // progressive solve is still at 1% after ten minutes, by the hierarchical solver itself at
  // its converged settings (a self-convergence figure, named so in the report).
  Suite hierarchical{"hierarchical",
                     "face-cluster hierarchical radiosity (seed 002) on the Cornell box, Sibenik, the conference room and "
                     "seed 002's room from 160k to 1.5M faces",
                     {}};
  {
    auto faceClusters = [](const std::string& scene, const std::string& name) {
      Case c;
      c.name = name + "/hierarchical";
      c.scene = scene;
      c.setting = "hierarchical, defaults";
      c.solve.method = "hierarchical";
      c.solve.settings.set("cache", false);  // every run builds the hierarchy: its time is measured
      c.probes = kProbes;
      return c;
    };
    // Each scene at the defaults and at a tenth of the default error threshold.
    auto finer = [](Case c) {
      c.name += "-1e-4";
      c.setting = "hierarchical, error 1e-4";
      c.solve.settings.set("error", 1e-4);
      return c;
    };
    Case cornell = faceClusters("cornell", "cornell-3k");
    cornell.discretise.elementBudget = 3000;
    cornell.discretise.elementsPerPatchSide = 1;
    hierarchical.cases.push_back(cornell);
    hierarchical.cases.push_back(finer(cornell));
    auto against = [](Case& c, const std::string& method, SolverSettings settings, const std::string& name) {
      c.reference = SolveOptions{};
      c.reference->method = method;
      c.reference->settings = std::move(settings);
      c.referenceName = name;
    };
    Case sibenik = faceClusters("bench/scenes/sibenik.json", "sibenik");
    sibenik.discretise.elementBudget = 100000;
    against(sibenik, "progressive", SolverSettings().set("unshot", 1e-4).set("seed", 7), "progressive to 1e-4 unshot");
    hierarchical.cases.push_back(sibenik);
    hierarchical.cases.push_back(finer(sibenik));
    Case conference = faceClusters("bench/scenes/conference.json", "conference");
    conference.discretise.elementBudget = 400000;
    against(conference, "hierarchical", SolverSettings().set("error", 1e-5).set("unshot", 1e-6).set("emitter-points", 4),
            "the hierarchical solver at error 1e-5 (self-convergence)");
    hierarchical.cases.push_back(conference);
    hierarchical.cases.push_back(finer(conference));
    // Seed 002's room up its ladder (the bunny statues simplified to each face count): the
    // seed's claim is a solve time and leaf count flat in the face count, and a hierarchy whose
    // memory grows linearly. No reference fits a benchmark's time at these sizes.
    for (const char* room : {"room-160k", "room-500k", "room-1m", "room-1.5m"}) {
      Case c = faceClusters(room, room);  // one element a face, as in the seed
      if (std::string(room) != "room-160k") c.probes = 0;  // the first rung shows the ladder's accuracy
      hierarchical.cases.push_back(c);
    }
  }

  Suite core{"core", "the built-in measured Cornell box at 10,000 elements (the core issue's targets)", {}};
  core.cases.push_back(progressive("cornell", 1e-3, {}));
  core.cases.push_back(gather("cornell", 1e-4, {}));

  Suite quick{"quick", "a smoke run: the built-in Cornell box at 1,000 elements", {}};
  quick.cases.push_back(progressive("cornell", 1e-2, {}));
  quick.cases.back().discretise.elementBudget = 1000;

  // The GL backend on scenes small enough for Mesa's llvmpipe, with the same CPU references as
  // the CPU cases: gathering with radiosity hemicubes (256 pixels, 2 x 2 per element) and
  // progressive refinement resident on the GPU (64 pixels, 3 x 3 per shooting patch), with ID
  // hemicubes (seed 001, the default) and depth hemicubes (seed 003).
  Suite gl{"gl", "the OpenGL backend on cornell-low, cornell-large, indirect-light and the Cornell box at 1,000 elements", {}};
  {
    auto onGl = [](Case c, const std::string& name) {
      c.name = name;
      c.solve.backend = "gl";
      c.setting += ", GL hemicubes";
      return c;
    };
    gl.cases.push_back(onGl(gather("cornell-low", kSeedGatherResidual, {t51, rows[3].gatherMs, rows[3].gatherError}),
                            "cornell-low/gl-gather"));
    Case box = onGl(gather("cornell", kSeedGatherResidual, {}), "cornell-1k/gl-gather");
    box.discretise.elementBudget = 1000;
    gl.cases.push_back(box);
    for (const Row& r : rows) {
      if (std::string(r.scene) == "cornell-small") continue;  // cornell-large's geometry
      Case shoot = onGl(progressive(r.scene, r.unshot(), {t51, r.progressiveMs, r.progressiveError}),
                        fmt::format("{}/gl-progressive", r.scene));
      gl.cases.push_back(shoot);
      Case depth = shoot;
      depth.name += "-depth";
      depth.setting += ", depth hemicubes";
      depth.solve.settings.set("hemicube-visibility", "distance");
      gl.cases.push_back(depth);
    }
  }
  return {seeds, shader, scenes, hierarchical, core, quick, gl};
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
  names.push_back(kDynamicSuiteName);  // luxel bench dynamic: runDynamicCase
  throw Error(fmt::format("unknown benchmark suite '{}' (known: {})", name, fmt::join(names, ", ")));
}

}  // namespace luxel::bench
