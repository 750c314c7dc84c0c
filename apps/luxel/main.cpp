// The luxel command-line tool. Thin: parse options, call the library, print one summary or one
// error. Exit codes: 0 success, 1 error, 2 bad usage, 130 cancelled (Ctrl-C).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include "luxel/error.h"
#include "luxel/image.h"
#include "luxel/import.h"
#include "luxel/lightmap.h"
#include "luxel/render.h"
#include "luxel/session.h"
#include "luxel/solve.h"
#include "luxel/stats.h"
#include "bake_command.h"
#include "solve_args.h"
#include "bench_command.h"
#include "solvers_command.h"
#include "output_paths.h"
#include "progress_bar.h"

namespace fs = std::filesystem;
using namespace luxel;

namespace {

struct RenderArgs {
  std::string scene;
  std::vector<std::string> outputs;
  std::string camera;
  std::optional<std::string> eye, target, up;
  float fov = 0.0f;
  std::string size = "512x512";
  int spp = 16;
  cli::SolveArgs solve;
  int threads = 0;
  bool quiet = false;
  std::string statsPath;
  std::string tracePath;
  std::string mode = "hq";
  std::string toneCurve = "filmic";
  float exposure = 0.0f;
};

Vec3 parseVec3(const std::string& text, const char* what) {
  Vec3 v;
  char c1 = 0, c2 = 0;
  std::istringstream in(text);
  if (!(in >> v.x >> c1 >> v.y >> c2 >> v.z) || c1 != ',' || c2 != ',' || !in.eof() ||
      !std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    throw Error(fmt::format("--{} '{}': expected X,Y,Z", what, text));
  return v;
}

std::pair<int, int> parseSize(const std::string& text) {
  int w = 0, h = 0;
  char x = 0;
  std::istringstream in(text);
  if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || !in.eof() || w < 1 || h < 1 || w > 32768 || h > 32768)
    throw Error(fmt::format("--size '{}': expected WxH with sides from 1 to 32768", text));
  return {w, h};
}

Camera cameraFor(const Scene& scene, const RenderArgs& a) {
  Camera cam = chooseCamera(scene, a.camera, a.fov);
  if (a.eye) cam.eye = parseVec3(*a.eye, "eye");
  if (a.target) cam.target = parseVec3(*a.target, "target");
  if (a.up) cam.up = parseVec3(*a.up, "up");
  if (a.fov > 0.0f) cam.fovY = a.fov;
  return cam;
}

double meanLuminance(const Image& img) {
  double sum = 0.0;
  for (const Rgb& c : img.pixels) sum += 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
  return img.pixels.empty() ? 0.0 : sum / double(img.pixels.size());
}

int runRender(const RenderArgs& a) {
  std::vector<cli::OutputPath> paths;
  for (const std::string& o : a.outputs) paths.push_back({"-o", o, {".exr", ".png"}});
  if (!a.statsPath.empty()) paths.push_back({"--stats", a.statsPath, {}});
  if (!a.tracePath.empty()) paths.push_back({"--progress-trace", a.tracePath, {}});
  for (cli::OutputPath& p : cli::checkpointOutputs(a.solve)) paths.push_back(std::move(p));
  cli::checkOutputPaths(paths);
  auto [width, height] = parseSize(a.size);
  std::unique_ptr<tbb::global_control> threads;
  if (a.threads > 0) threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(a.threads));

  cli::ProgressBar bar(a.quiet);
  if (!a.tracePath.empty()) bar.traceTo(a.tracePath);
  const auto start = std::chrono::steady_clock::now();
  Scene scene = loadScene(a.scene);
  cli::addCommandLineLights(scene, a.solve);
  const std::string sceneName = scene.name;
  if (!a.quiet)
    for (const std::string& w : scene.warnings) std::cerr << "luxel: warning: " << w << "\n";

  RenderOptions ro;
  ro.camera = cameraFor(scene, a);
  ro.width = width, ro.height = height;
  ro.samplesPerPixel = a.spp;
  // "lightmap": bake lightmaps and show them as an engine would (luxel::renderLightmapped).
  const bool lightmapped = a.mode == "lightmap";
  ro.mode = lightmapped ? RenderOptions::Mode::Radiosity : parseRenderMode(a.mode);
  validateRenderOptions(ro);  // before the solve, which can take a while
  ToneMap tm;
  tm.curve = parseToneCurve(a.toneCurve);
  tm.exposure = a.exposure;

  // A bad solver, backend or option fails before any work: the session and the lightmap recipe
  // check them first.
  SolveOptions so = cli::solveOptions(a.solve);
  Solution solution;
  Image image;
  RenderStats rs;
  if (lightmapped) {
    LightmapRecipe recipe;
    recipe.texelsPerMetre = a.solve.elementSize > 0.0f ? 1.0f / a.solve.elementSize : 0.0f;
    recipe.texelBudget = size_t(a.solve.elements);
    recipe.solve = so;
    const BakedLightmaps baked = bakeLightmaps(scene, recipe, bar.callback());
    solution = baked.bake.solution;
    image = renderLightmapped(scene, baked.atlas, baked.bake, ro, bar.callback(), &rs);
  } else {
    Session session(std::move(scene), cli::discretiseOptions(a.solve), {so});
    solution = session.solve(bar.callback());
    image = render(session.scene(), session.surfaces(), solution, ro, bar.callback(), &rs);
  }
  if (!a.quiet)
    for (const std::string& w : solution.stats.warnings) std::cerr << "luxel: warning: " << w << "\n";
  for (const std::string& o : a.outputs) {
    if (cli::ProgressBar::interrupted()) throw Cancelled();  // between outputs, each written whole or not at all
    writeImage(image, o, tm);
  }
  bar.finish();
  bar.writeTrace();
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const SolveStats& s = solution.stats;
  if (!a.statsPath.empty()) {
    RunRecord record;
    record.scene = sceneName;
    record.solve = s;
    record.image = RunRecord::Image{width, height, a.spp, a.mode, meanLuminance(image), rs.rays, rs.seconds};
    record.threads = a.threads > 0 ? a.threads : tbb::info::default_concurrency();
    record.outputs = a.outputs;
    record.totalSeconds = total;
    writeStatsJson(record, a.statsPath);
  }
  if (!a.quiet) {
    std::cout << fmt::format("luxel: {} — {} elements in {} patches, {} on {}{} ({} shots, {} iterations), unshot {:.3f}%\n",
                             sceneName, s.elements, s.patches, s.method, s.backend,
                             s.device.empty() ? "" : " (" + s.device + ")", s.shots, s.iterations, 100.0 * s.unshotFraction);
    std::cout << fmt::format("luxel: solve {:.3f} s (setup {:.3f}, form factors {:.3f}, iterate {:.3f}), {:.1f} M rays/s\n",
                             s.secondsTotal, s.secondsSetup, s.secondsFormFactors, s.secondsSolve, s.raysPerSecond() / 1e6);
    std::cout << fmt::format("luxel: render {}x{} at {} spp ({}) {:.3f} s; total {:.3f} s\n", width, height, a.spp,
                             a.mode, rs.seconds, total);
    for (const std::string& o : a.outputs) std::cout << "luxel: wrote " << o << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"luxel: radiosity global illumination"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("luxel ") + LUXEL_VERSION);
  RenderArgs ra;
  CLI::App* render = app.add_subcommand("render", "Solve a scene and render an image");
  render->add_option("scene", ra.scene, "Built-in name (" + fmt::format("{}", fmt::join(builtinSceneNames(), ", ")) +
                                            "), a scene file (.json) or a mesh file")->required();
  render->add_option("-o,--output", ra.outputs, "Output image(s): .exr (linear radiance) or .png (tone-mapped)")->required();
  render->add_option("--camera", ra.camera, "A named camera of the scene");
  render->add_option("--eye", ra.eye, "Camera position X,Y,Z");
  render->add_option("--target", ra.target, "Point the camera looks at X,Y,Z");
  render->add_option("--up", ra.up, "Camera up vector X,Y,Z");
  render->add_option("--fov", ra.fov, "Vertical field of view in degrees")->check(cli::finiteRange(0.01, 179.0));
  render->add_option("--size", ra.size, "Image size WxH")->capture_default_str();
  render->add_option("--spp", ra.spp, "Samples per pixel")->check(CLI::Range(1, 65536))->capture_default_str();
  cli::addSolveOptions(*render, ra.solve);
  render->add_option("--threads", ra.threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 4096));
  render->add_flag("-q,--quiet", ra.quiet, "Print nothing but errors");
  render->add_option("--stats", ra.statsPath, "Write statistics as JSON");
  render->add_option("--progress-trace", ra.tracePath, "Write every progress report, timed, as tab-separated lines");
  render->add_option("--mode", ra.mode, "hq (exact direct light per pixel), radiosity (the seeds' display) or lightmap (bake lightmaps and show them as an engine would)")->capture_default_str();
  render->add_option("--tonemap", ra.toneCurve, "PNG tone curve: filmic, reinhard or clamp")->capture_default_str();
  render->add_option("--exposure", ra.exposure, "PNG exposure in stops, on top of auto exposure")->check(cli::finiteRange(-64.0, 64.0));

  cli::BakeArgs ka;
  CLI::App* bake = app.add_subcommand("bake", "Solve a scene and write it as glTF binary with the lighting baked in");
  bake->add_option("scene", ka.scene, "Built-in name, a scene file (.json) or a mesh file")->required();
  bake->add_option("-o,--output", ka.output, "Output file (.glb)")->required();
  bake->add_flag("--vertex-colors", ka.vertexColors, "Bake outgoing radiance into per-vertex colours (COLOR_0)");
  cli::addSolveOptions(*bake, ka.solve);
  cli::addLightmapOptions(*bake, ka);
  bake->add_option("--threads", ka.threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 4096));
  bake->add_flag("-q,--quiet", ka.quiet, "Print nothing but errors");
  bake->add_option("--progress-trace", ka.tracePath, "Write every progress report, timed, as tab-separated lines");

  cli::BenchArgs ba;
  CLI::App* bench = app.add_subcommand("bench", "Run a benchmark suite: timings, throughput, memory and error");
  bench->add_option("suite", ba.suite, "Suite: seeds, shader, scenes, hierarchical, core, gl or quick (--list shows the cases)")->capture_default_str();
  bench->add_option("--runs", ba.runs, "Timed runs per case")->check(CLI::Range(1, 1000))->capture_default_str();
  bench->add_option("--json", ba.jsonPath, "Write the results as JSON");
  bench->add_option("--case", ba.filter, "Only cases whose name contains this");
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

  bool solversJson = false;
  CLI::App* solvers = app.add_subcommand("solvers", "List the registered solvers, each with its options and defaults");
  solvers->add_flag("--json", solversJson, "Print the list as JSON");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    if (*render) return runRender(ra);
    if (*solvers) return cli::listSolvers(solversJson);
    if (*bench) return cli::runBench(ba);
    if (*bake) return cli::runBake(ka);
  } catch (const Cancelled&) {
    std::cerr << "\nluxel: cancelled\n";
    return 130;
  } catch (const std::exception& e) {
    std::cerr << "\nluxel: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
