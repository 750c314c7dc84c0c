#include "command_line.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "luxel/error.h"
#include "luxel/import.h"
#include "solvers_command.h"

namespace luxel::cli {

std::unique_ptr<CommandLine> makeCommandLine() {
  auto line = std::make_unique<CommandLine>();
  CLI::App& app = line->app;
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("luxel ") + LUXEL_VERSION);
  RenderArgs& ra = line->render;
  CLI::App* render = line->renderCommand = app.add_subcommand("render", "Solve a scene and render an image");
  render->add_option("scene", ra.scene, "Built-in name (" + fmt::format("{}", fmt::join(builtinSceneNames(), ", ")) +
                                            "), a scene file (.json) or a mesh file")->required();
  // One value per -o (repeat -o for more): CLI11 lets a vector option take every word up to the
  // next option, so `render -o a.png cornell` took the scene for a second image.
  render->add_option("-o,--output", ra.outputs, "Output image(s): .exr (linear radiance) or .png (tone-mapped); repeat -o for more")
      ->required()
      ->allow_extra_args(false);
  addViewOptions(*render, ra);
  addSolveOptions(*render, ra.solve);
  render->add_option("--threads", ra.threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 4096));
  render->add_flag("-q,--quiet", ra.quiet, "Print nothing but errors");
  render->add_option("--stats", ra.statsPath, "Write statistics as JSON");
  render->add_option("--progress-trace", ra.tracePath, "Write every progress report, timed, as tab-separated lines");
  render->add_option("--mode", ra.mode, "hq (exact direct light per pixel), radiosity (the seeds' display) or lightmap (bake lightmaps and show them as an engine would)")->capture_default_str();
  render->add_option("--directional", ra.directional,
                     "With --mode lightmap: none, sh-l1, sh-l2 or dominant (directional lightmaps, read at the "
                     "normal-mapped normal)")
      ->check(CLI::IsMember({"none", "sh-l1", "sh-l2", "dominant"}))
      ->capture_default_str();
  render->add_option("--transfer", ra.transferBands,
                     "With --mode lightmap: bake SH transfer lightmaps of this many bands (2, 3 or 4) and relight "
                     "them with the scene's suns and skies (seed 004's CaSHL)")
      ->check(CLI::Range(2, 4));
  render->add_option("--sun-direction", ra.sunDirection,
                     "With --transfer: relight with every sun travelling along X,Y,Z (the bake does not change)");

  CLI::App* animate = line->animateCommand =
      app.add_subcommand("animate", "Render a scene's animation frame by frame (images or a video), following its moves");
  addAnimateOptions(*animate, line->animate);

  BakeArgs& ka = line->bake;
  CLI::App* bake = line->bakeCommand = app.add_subcommand("bake", "Solve a scene and write it as glTF binary with the lighting baked in");
  bake->add_option("scene", ka.scene, "Built-in name, a scene file (.json) or a mesh file")->required();
  bake->add_option("-o,--output", ka.output, "Output file (.glb)")->required();
  bake->add_flag("--vertex-colors", ka.vertexColors, "Bake outgoing radiance into per-vertex colours (COLOR_0)");
  addSolveOptions(*bake, ka.solve);
  addLightmapOptions(*bake, ka);
  bake->add_option("--threads", ka.threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 4096));
  bake->add_flag("-q,--quiet", ka.quiet, "Print nothing but errors");
  bake->add_option("--progress-trace", ka.tracePath, "Write every progress report, timed, as tab-separated lines");
  bake->add_flag("--html", ka.html,
                 "Also write OUT.html beside the glb: a page that shows the bake in a browser (three.js; orbit, walk, "
                 "exposure), with everything in it, so that it opens from disk with no network");

  BenchArgs& ba = line->bench;
  CLI::App* bench = line->benchCommand = app.add_subcommand("bench", "Run a benchmark suite: timings, throughput, memory and error");
  bench->add_option("suite", ba.suite, "Suite: seeds, shader, scenes, hierarchical, core, gl, quick or dynamic (--list shows the cases)")->capture_default_str();
  bench->add_option("--runs", ba.runs, "Timed runs per case (not dynamic: its frames are its runs)")->check(CLI::Range(1, 1000))->capture_default_str();
  bench->add_option("--frames", ba.frames, "dynamic: moving frames per case, the box turning 1 degree a frame")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  bench->add_option("--gl-frames", ba.glFrames, "dynamic: moving frames of the GL cases (default: --frames on a GPU, none on a software rasteriser such as llvmpipe)")
      ->check(CLI::Range(1, 100000));
  bench->add_option("--scenes", ba.scenes, "dynamic: only these scenes (indirect-light, cornell-large, cornell-small, cornell-low)")
      ->delimiter(',')
      ->allow_extra_args(false)
      ->check(CLI::IsMember({"indirect-light", "cornell-large", "cornell-small", "cornell-low"}));
  bench->add_option("--backends", ba.backends, "dynamic: only these backends (cpu, gl; default both, GL skipped without a context)")
      ->delimiter(',')
      ->allow_extra_args(false)
      ->check(CLI::IsMember({"cpu", "gl"}));
  bench->add_option("--json", ba.jsonPath, "Write the results as JSON");
  bench->add_option("--case", ba.filter, "Only cases whose name contains this");
  bench->add_option("--set", ba.set, "A solver option NAME=VALUE laid over each case's (repeatable; not the references')")
      ->allow_extra_args(false);
  bench->add_option("--cache", ba.cacheDir, "Folder for reference solutions (default ~/.cache/luxel/references)");
  bench->add_flag("--no-reference", ba.noReference, "Skip the error column (no reference solve)");
  bench->add_option("--reference", ba.reference,
                    "How references are solved: cpu (gathering at high settings) or monte-carlo (cosine-distributed "
                    "rays, 16,384 per element: an independent check of the CPU's form factors)")
      ->check(CLI::IsMember({"cpu", "monte-carlo"}))
      ->capture_default_str();
  bench->add_flag("--no-limit", ba.noLimit, "Skip the Embree hardware-limit measurement");
  bench->add_flag("--list", ba.list, "List the suites and their cases");
  bench->add_option("--threads", ba.threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 4096));
  bench->add_flag("-q,--quiet", ba.quiet, "Print nothing but errors");

  CLI::App* view = line->viewCommand =
      app.add_subcommand("view", "Walk through a scene while it solves; move lights and objects and watch the light follow");
  addViewerOptions(*view, line->view);

  CLI::App* solvers = line->solversCommand = app.add_subcommand("solvers", "List the registered solvers, each with its options and defaults");
  solvers->add_flag("--json", line->solversJson, "Print the list as JSON");

  return line;
}

void parseCommandLine(CommandLine& line, int argc, const char* const* argv) {
  line.app.parse(argc, argv);
  if (*line.renderCommand) checkRenderArgs(line.render);
  if (*line.animateCommand) checkAnimateArgs(line.animate);
  if (*line.bakeCommand) checkBakeArgs(line.bake);
  if (*line.viewCommand) checkViewerArgs(line.view);
  if (*line.benchCommand) {
    CLI::App& b = *line.benchCommand;
    line.bench.runsGiven = b.count("--runs") > 0;
    line.bench.dynamicOptionGiven = b.count("--frames") + b.count("--gl-frames") + b.count("--scenes") + b.count("--backends") > 0;
    checkBenchArgs(line.bench);
  }
}

int runCommand(const CommandLine& line) {
  if (*line.renderCommand) return runRender(line.render);
  if (*line.animateCommand) return runAnimate(line.animate);
  if (*line.solversCommand) return listSolvers(line.solversJson);
  if (*line.benchCommand) return runBench(line.bench);
  if (*line.bakeCommand) return runBake(line.bake);
  if (*line.viewCommand) return runViewer(line.view);
  return 0;
}

}  // namespace luxel::cli
