// The GL backend's solvers in the registry: progressive refinement and gathering with hemicubes,
// resident on the GPU (progressive_gl.h, gather_gl.h). The analytic lights come from the CPU
// transport, so both read its light options too.
#include <fmt/format.h>

#include "gl/gather_gl.h"
#include "gl/gl_context.h"
#include "gl/progressive_gl.h"
#include "luxel/scene.h"
#include "solve/solver_registry.h"
#include "transport/form_factor_options.h"

namespace luxel {

std::vector<SolverOption> progressiveStopOptions();  // solve/progressive_solver.cpp
std::vector<SolverOption> gatherStopOptions();       // solve/gather_solver.cpp
SolverOption settleOption();                          // dynamic/redistribution_solver.cpp

namespace {

int hemicubeResolution(const SolverOptionValues& v) {
  const int r = v.integer("hemicube-resolution");
  if (r % 2) v.fail(fmt::format("hemicube-resolution {} must be even", r));
  return r;
}

void addAll(std::vector<SolverOption>& to, std::vector<SolverOption> from) {
  for (SolverOption& o : from) to.push_back(std::move(o));
}

}  // namespace

namespace {

enum class Follows { Nothing, ByIncremental, ByCrossRedistribution };

// GL progressive refinement, and the same solver following moves and edits by redistribution.
SolverEntry glProgressiveEntry(const char* method, Follows follows, const char* description) {
  const bool followChanges = follows != Follows::Nothing, cross = follows == Follows::ByCrossRedistribution;
  const gl::GlProgressiveSettings d;
  SolverEntry e;
  e.description = {method, "gl", description, progressiveStopOptions()};
  addAll(e.description.options,
         {integerOption("shooters-per-pass", 0, 0, kMaxShootersPerPass,
                        "patches shot together in one pass (0: 8, or 1 on a software rasteriser, where it is faster)"),
          integerOption("hemicube-resolution", d.resolution, 8, 4096, "hemicube top-face pixels a side (even)"),
          integerOption("hemicubes-per-side", d.samplesPerSide, 1, 8, "k x k hemicubes per shooting patch"),
          integerOption("emitter-hemicubes-per-side", d.emitterSamplesPerSide, 0, 8,
                        "k x k hemicubes for an emitting patch's first shot (0: as other shooters)"),
          choiceOption("hemicube-visibility", "item", {"item", "distance"},
                       "a shooter sees a point by face id (seed 001) or by depth (seed 003)"),
          choiceOption("hemicube-layering", "auto", {"auto", "geometry", "vertex"},
                       "how a hemicube's triangles reach its layers: a geometry shader, or the vertex shader "
                       "(ARB_shader_viewport_layer_array; auto: it where the driver has it)")});
  if (followChanges) e.description.options.push_back(settleOption());
  if (cross) {
    const gl::CrossRedistributionSettings c;
    addAll(e.description.options,
           {integerOption("back-hemicube-resolution", c.backResolution, 4, 1024,
                          "pixels a side of each moved patch's back hemicube, which the cross projection samples (even)"),
            integerOption("cross-grid", c.grid, 1, 16, "g: g x g rays from a receiver through each moved patch"),
            choiceOption("cross-behind", "patch", {"patch", "point"},
                         "what a receiver sees behind a moved patch: from its patch's centre, shared by the "
                         "patch's elements, or from each element's 2 x 2 points (slower)"),
            flagOption("keep-gather-hemicubes", c.keepGathers,
                       "keep the moved elements' gather hemicubes from one move to the next (up to 512 MiB), where "
                       "the next move's gather where they were draws the same pixels")});
  }
  addAll(e.description.options, analyticLightOptions());
  e.make = [followChanges, cross](const SolverResources& r, const SolverOptionValues& v) -> std::unique_ptr<Solver> {
    gl::GlProgressiveSettings s;
    s.followChanges = followChanges;
    s.crossRedistribution = cross;
    if (followChanges) s.settleThreshold = v.real("settle-unshot");
    s.resolution = hemicubeResolution(v);
    s.samplesPerSide = v.integer("hemicubes-per-side");
    const std::string layering = v.choice("hemicube-layering");
    s.layering = layering == "geometry" ? gl::HemicubeLayering::GeometryShader
                 : layering == "vertex" ? gl::HemicubeLayering::VertexShader
                                        : gl::HemicubeLayering::Auto;
    s.cross.layering = s.layering;
    s.emitterSamplesPerSide = v.integer("emitter-hemicubes-per-side");
    s.visibility = v.choice("hemicube-visibility") == "item" ? gl::HemicubeVisibility::Item
                                                             : gl::HemicubeVisibility::Distance;
    const int perPass = v.integer("shooters-per-pass");
    s.shootersPerPass = perPass > 0 ? perPass : r.glContext->softwareRasteriser() ? 1 : kDefaultShootersPerPass;
    s.unshotThreshold = v.real("unshot");
    s.timeBudget = v.real("time-budget");
    s.shotBudget = uint64_t(v.integer("shot-budget"));
    s.ambient = v.flag("ambient");
    std::vector<uint32_t> objectOfPatch;
    if (cross) {
      const int back = v.integer("back-hemicube-resolution");
      if (back % 2) v.fail(fmt::format("back-hemicube-resolution {} must be even", back));
      s.cross.backResolution = back;
      s.cross.gatherResolution = s.resolution;
      s.cross.grid = v.integer("cross-grid");
      s.cross.behindPerPatch = v.choice("cross-behind") == "patch";
      s.cross.keepGathers = v.flag("keep-gather-hemicubes");
      const SurfaceSet& set = r.system.surfaces;
      for (const Patch& p : set.patches) objectOfPatch.push_back(r.scene.meshes[set.faces[p.face].mesh].object);
    }
    return gl::makeGlProgressiveSolver(r.system, *r.glContext, s, std::move(objectOfPatch));
  };
  e.converged.set("unshot", 1e-6);
  // Shooting hemicubes are a midpoint rule over k x k points of the shooter: coarser than the
  // CPU's factors where a shadow edge crosses a shooter, and over the Cornell box's larger
  // patches at 300 elements (measured figures: docs/algorithms.md, "Solvers").
  e.accuracy.halfShadow = 0.08;
  e.accuracy.cornell = 0.03;
  return e;
}

}  // namespace

void registerGlProgressive(SolverRegistry& registry) {
  registry.add(glProgressiveEntry(
      "progressive", Follows::Nothing, "progressive refinement resident on the GPU: ID or depth hemicubes per shooter (seeds 001, 003)"));
}

void registerGlIncremental(SolverRegistry& registry) {
  registry.add(glProgressiveEntry("incremental", Follows::ByIncremental,
                                  "dynamic: GL progressive refinement that follows moves and light edits by "
                                  "redistribution (Chen 1990; seed 001 Sec. 4.4): every patch reshoots what it shot, "
                                  "from the old and the new geometry"));
}

void registerGlCrossRedistribution(SolverRegistry& registry) {
  registry.add(glProgressiveEntry("cross-redistribution", Follows::ByCrossRedistribution,
                                  "dynamic: GL progressive refinement that follows moves by cross-redistribution "
                                  "(seed 001 Sec. 3.3, 4.5): only the moved patches render hemicubes, front and back, "
                                  "and the moved elements gather; light edits as incremental"));
}

void registerGlGather(SolverRegistry& registry) {
  const gl::GlGatherSettings d;
  SolverEntry e;
  e.description = {"gather", "gl",
                   "Jacobi gathering with radiosity hemicubes on the GPU, no stored form factors (seeds 000, 001)",
                   gatherStopOptions()};
  addAll(e.description.options,
         {integerOption("hemicube-resolution", d.resolution, 8, 4096, "hemicube top-face pixels a side (even)"),
          integerOption("hemicubes-per-side", d.samplesPerSide, 1, 8, "k x k hemicubes per receiving element")});
  addAll(e.description.options, analyticLightOptions());
  e.make = [](const SolverResources& r, const SolverOptionValues& v) -> std::unique_ptr<Solver> {
    gl::GlGatherSettings s;
    s.resolution = hemicubeResolution(v);
    s.samplesPerSide = v.integer("hemicubes-per-side");
    s.residualThreshold = v.real("residual");
    s.maxIterations = v.integer("max-iterations");
    return gl::makeGlGatherSolver(r.system, *r.glContext, s);
  };
  // Each Jacobi sweep renders every element's hemicubes: 1e-4 is converged well past the
  // closed forms' tolerances (the furnace's error is rho^k after k sweeps) at half the sweeps of 1e-6.
  e.converged.set("residual", 1e-4).set("hemicube-resolution", 64);
  registry.add(std::move(e));
}

}  // namespace luxel
