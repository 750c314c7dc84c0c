#include "solve_args.h"

#include <cmath>
#include <optional>
#include <sstream>

#include <fmt/format.h>

#include "io/input_file.h"
#include "luxel/error.h"

namespace luxel::cli {
namespace {

// A flag that sets the solver option of the same name when given.
void solverFlag(CLI::App& c, SolveArgs& a, const std::string& option, const std::string& help) {
  c.add_option_function<std::string>(
      "--" + option, [&a, option](const std::string& value) { a.flagged.emplace_back(option, value); }, help);
}

}  // namespace

CLI::Validator finiteRange(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        double v = 0.0;
        size_t used = 0;
        try {
          v = std::stod(text, &used);
        } catch (const std::exception&) {
          return fmt::format("'{}' is not a number", text);
        }
        if (used != text.size()) return fmt::format("'{}' is not a number", text);
        if (!std::isfinite(v) || v < lo || v > hi) return fmt::format("{} is not a finite number from {:g} to {:g}", text, lo, hi);
        return {};
      },
      fmt::format("FINITE in [{:g}, {:g}]", lo, hi));
}

void addSolveOptions(CLI::App& c, SolveArgs& a) {
  a.command = &c;
  c.add_option("--solver", a.solver, "auto (progressive up to 5,000 patches, hierarchical above), or a registered solver: progressive, gather, "
                "hierarchical (luxel solvers lists them)")
      ->capture_default_str();
  c.add_option("--backend", a.backend, "cpu, gl (OpenGL 4.5 hemicubes, headless) or auto (gl when a context can be made)")
      ->capture_default_str();
  auto* elements = c.add_option("--elements", a.elements, "Element budget (default 10000; 2500 for an hq render's solve, whose vertex gather runs on --gather-elements)")
                       ->check(CLI::Range(int64_t(1), kMaxElementsOption));
  c.add_option("--element-size", a.elementSize, "Element edge length in scene units")
      ->check(finiteRange(1e-9, double(kMaxCoordinate)))
      ->excludes(elements);
  c.add_option("--refine", a.refine, "Adaptive refinement: extra elements allowed (0: off)")
      ->check(CLI::Range(int64_t(0), kMaxElementsOption));
  c.add_option("--sky", a.sky, "Add a uniform sky of this radiance (W/(m2 sr), or cd/m2: 5000 is a bright overcast day)")
      ->check(finiteRange(0.0, double(kMaxRadiance)));
  c.add_option("--sun", a.sun, "Add a sun shining along X,Y,Z (the direction light travels), 100,000 lux, 0.53 degrees wide");
  // One NAME=VALUE per --set: a vector option would otherwise take the scene that follows it.
  c.add_option("--set", a.set, "A solver option NAME=VALUE (repeatable; luxel solvers lists each solver's)")
      ->allow_extra_args(false);
  solverFlag(c, a, "unshot", "progressive: stop below this unshot fraction (default 0.001)");
  solverFlag(c, a, "rays-per-pair", "cpu: visibility rays per element-patch pair (default 4)");
  solverFlag(c, a, "shooters-per-pass", "progressive: patches shot together in one pass (default 8; 1 on a software rasteriser)");
  solverFlag(c, a, "hemicube-resolution", "gl: hemicube top-face pixels a side (default 64 shooting, 256 gathering)");
  solverFlag(c, a, "hemicubes-per-side", "gl: k x k hemicubes per shooting patch (default 3) or per gathering element (default 2)");
  solverFlag(c, a, "emitter-hemicubes-per-side", "gl progressive: k x k hemicubes for an emitting patch's first shot (default 6; 0: as other shooters)");
  c.add_option("--checkpoint", a.checkpoint,
               "Write the solve's state to this file at intervals, on Ctrl-C and at the end, for --resume "
               "(every registered solver)");
  c.add_option("--resume", a.resume,
               "Continue the solve from this checkpoint, written by an earlier run with the same scene and options "
               "(and go on checkpointing to it)");
  c.add_option("--checkpoint-interval", a.checkpointInterval, "Seconds of solving between checkpoints")
      ->check(finiteRange(0.001, 1e9))
      ->capture_default_str();
  solverFlag(c, a, "hemicube-visibility", "gl progressive: item (ID hemicubes, seed 001) or distance (depth hemicubes, seed 003)");
}

DiscretiseOptions discretiseOptions(const SolveArgs& a) {
  DiscretiseOptions d;
  if (a.elementSize > 0.0f) d.elementSize = a.elementSize;
  if (a.elements > 0) d.elementBudget = size_t(a.elements);
  return d;
}

namespace {

// --sun X,Y,Z: a direction, normalised; throws Error.
Vec3 sunDirection(const std::string& text) {
  Vec3 d;
  char c1 = 0, c2 = 0;
  std::istringstream in(text);
  if (!(in >> d.x >> c1 >> d.y >> c2 >> d.z) || c1 != ',' || c2 != ',' || !in.eof() || !std::isfinite(d.x) ||
      !std::isfinite(d.y) || !std::isfinite(d.z) || glm::length(d) < 1e-12f)
    throw Error(fmt::format("--sun '{}': expected a direction X,Y,Z, not zero", text));
  return glm::normalize(d);
}

}  // namespace

void addCommandLineLights(Scene& scene, const SolveArgs& a) {
  if (a.sky > 0.0f) scene.lights.push_back(Light{.type = Light::Type::Sky, .name = "sky (--sky)", .intensity = a.sky});
  if (!a.sun.empty()) {
    // 100,000 lux on a surface facing it: a clear-sky sun; its disc 0.53 degrees across.
    scene.lights.push_back(Light{.type = Light::Type::Directional,
                                 .name = "sun (--sun)",
                                 .intensity = 100000.0f,
                                 .direction = sunDirection(a.sun),
                                 .angularRadius = 0.00465f});
  }
}

std::string solveSize(const SolveArgs& a) {
  if (a.elements > 0) return fmt::format("--elements {}", a.elements);
  if (a.elementSize > 0.0f) return fmt::format("--element-size {:g}", a.elementSize);
  return "the default 10,000-element budget";
}

std::string elementsAndPatches(const SolveStats& s) {
  if (s.patches == 0) return fmt::format("{} elements", s.elements);
  return fmt::format("{} elements in {} patches", s.elements, s.patches);
}

std::string solveSizeHint(const SolveArgs& a, bool lightmaps) {
  std::string hint = lightmaps ? "use fewer texels (--elements, a lower --texels-per-metre or a larger --element-size)"
                               : "use fewer elements (--elements, or a larger --element-size)";
  if (a.refine > 0) hint += " or less refinement (--refine)";
  return hint;
}

void checkSolveArgs(const SolveArgs& a) {
  if (!a.sun.empty()) sunDirection(a.sun);
  validateSolveOptions(solveOptions(a));
}

std::vector<OutputPath> checkpointOutputs(const SolveArgs& a) {
  if (!a.resume.empty())
    if (const std::optional<std::string> why = whyNotARegularFile(a.resume))
      throw Error(fmt::format("--resume {}: {}", a.resume, *why));
  if (!a.checkpoint.empty()) return {{"--checkpoint", a.checkpoint, {}}};
  // Resuming goes on writing to the checkpoint it read.
  if (!a.resume.empty()) return {{"--resume", a.resume, {}}};
  return {};
}

SolveOptions solveOptions(const SolveArgs& a) {
  SolveOptions o;
  o.checkpoint.path = a.checkpoint.empty() ? a.resume : a.checkpoint;
  o.checkpoint.resume = a.resume;
  o.checkpoint.intervalSeconds = a.checkpointInterval;
  o.method = a.solver;
  o.backend = a.backend;
  o.refine.budget = size_t(a.refine);
  for (const auto& [name, value] : a.flagged) o.settings.set(name, value);
  for (const std::string& s : a.set) o.settings.parse(s);
  return o;
}

}  // namespace luxel::cli
