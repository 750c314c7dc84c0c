#include "render_command.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>
#include <tuple>

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include "luxel/error.h"
#include "luxel/image.h"
#include "luxel/import.h"
#include "luxel/directional_lightmap.h"
#include "luxel/lightmap.h"
#include "luxel/transfer_lightmap.h"
#include "luxel/render.h"
#include "luxel/session.h"
#include "luxel/solve.h"
#include "luxel/stats.h"
#include "out_of_memory.h"
#include "output_paths.h"
#include "progress_bar.h"

namespace luxel::cli {
namespace {

Camera cameraFor(const Scene& scene, const ViewArgs& a) {
  Camera cam = chooseCamera(scene, a.camera, a.fov);
  if (a.eye) cam.eye = parseVec3(*a.eye, "eye");
  if (a.target) cam.target = parseVec3(*a.target, "target");
  if (a.up) cam.up = parseVec3(*a.up, "up");
  if (a.fov > 0.0f) cam.fovY = a.fov;
  return cam;
}

std::string renderingWhat(const RenderArgs& a, const std::string& sceneName) {
  return fmt::format("rendering scene '{}' ({} image, {} samples per pixel)", sceneName, a.size, a.spp);
}

double meanLuminance(const Image& img) {
  double sum = 0.0;
  for (const Rgb& c : img.pixels) sum += 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
  return img.pixels.empty() ? 0.0 : sum / double(img.pixels.size());
}

}  // namespace

RenderOptions renderOptionsFor(const Scene& scene, const ViewArgs& a) {
  RenderOptions ro;
  ro.camera = cameraFor(scene, a);
  std::tie(ro.width, ro.height) = parseSize(a.size);
  ro.samplesPerPixel = a.spp;
  ro.indirect = parseIndirect(a.indirect);
  ro.gatherRays = a.gatherRays;
  ro.seed = a.renderSeed;
  ro.gatherBounces = a.gatherBounces;
  ro.gatherElements = a.gatherElements;
  ro.glossyRays = a.glossyRays;
  ro.mode = parseRenderMode(a.mode);
  validateRenderOptions(ro);
  return ro;
}

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

void addCameraOptions(CLI::App& c, ViewArgs& a) {
  c.add_option("--camera", a.camera, "A named camera of the scene");
  c.add_option("--eye", a.eye, "Camera position X,Y,Z");
  c.add_option("--target", a.target, "Point the camera looks at X,Y,Z");
  c.add_option("--up", a.up, "Camera up vector X,Y,Z");
  c.add_option("--fov", a.fov, "Vertical field of view in degrees")->check(finiteRange(0.01, 179.0));
}

void addViewOptions(CLI::App& c, ViewArgs& a) {
  addCameraOptions(c, a);
  c.add_option("--size", a.size, "Image size WxH")->capture_default_str();
  c.add_option("--spp", a.spp, "Samples per pixel")->check(CLI::Range(1, 65536))->capture_default_str();
  c.add_option("--indirect", a.indirect,
               "hq mode's indirect light: auto (vertex-gather where faces were cut into elements, else "
               "interpolated), vertex-gather (gathered at element vertices), pixel-gather (per pixel sample: "
               "sharper, noisier), interpolated (the solution's, fastest) or none (the direct light alone)")
      ->capture_default_str();
  c.add_option("--gather-rays", a.gatherRays,
               fmt::format("Gather rays per vertex (default {}) or per pixel sample (default {})",
                           kDefaultVertexGatherRays, kDefaultPixelGatherRays))
      ->check(CLI::Range(0, 65536));
  c.add_option("--gather-bounces", a.gatherBounces,
               "Bounces gathered before the solution is read: 1, or 2 to 4 (coarse gathers of every vertex first, each "
               "reading the one before)")
      ->check(CLI::Range(1, 4))
      ->capture_default_str();
  c.add_option("--gather-elements", a.gatherElements,
               "hq's vertex gather runs on the solved elements split (each into 4, as often as it takes) until "
               "they are nearest this many; 0 or fewer than solved: on the solved elements")
      ->check(CLI::Range(size_t(0), size_t(100000000)))
      ->capture_default_str();
  c.add_option("--glossy-rays", a.glossyRays,
               "hq mode: rays per camera sample drawn from a glossy material's highlight (specular and shininess), "
               "reading the light where they land; 0: no highlights")
      ->check(CLI::Range(0, 65536))
      ->capture_default_str();
  c.add_option("--render-seed", a.renderSeed,
               "Seed of the image's samples (pixel jitter, light points, gather rays); the solver's is --set seed=N")
      ->capture_default_str();
  c.add_option("--tonemap", a.toneCurve, "PNG tone curve: filmic, reinhard or clamp")->capture_default_str();
  c.add_option("--exposure", a.exposure, "PNG exposure in stops, on top of auto exposure")->check(finiteRange(-64.0, 64.0));
}

void checkViewArgs(const ViewArgs& a) {
  parseSize(a.size);
  parseIndirect(a.indirect);
  if (a.eye) parseVec3(*a.eye, "eye");
  if (a.target) parseVec3(*a.target, "target");
  if (a.up) parseVec3(*a.up, "up");
  if (a.mode != "lightmap") parseRenderMode(a.mode);
  parseToneCurve(a.toneCurve);
}

void checkRenderArgs(const RenderArgs& a) {
  checkViewArgs(a);
  if (parseDirectionalMode(a.directional) != DirectionalMode::None && a.mode != "lightmap")
    throw Error("--directional shows directional lightmaps: it needs --mode lightmap");
  if (a.transferBands > 0 && a.mode != "lightmap") throw Error("--transfer bakes transfer lightmaps: it needs --mode lightmap");
  if (a.transferBands > 0 && parseDirectionalMode(a.directional) != DirectionalMode::None)
    throw Error("--transfer and --directional exclude each other (a transfer bake is relit, not read by direction)");
  if (a.sunDirection && a.transferBands == 0) throw Error("--sun-direction relights a transfer bake: it needs --transfer");
  if (a.sunDirection && !(glm::length(parseVec3(*a.sunDirection, "sun-direction")) > 0.0f))
    throw Error("--sun-direction must not be zero");
  checkSolveArgs(a.solve);
}

int runRender(const RenderArgs& a) {
  std::vector<OutputPath> paths;
  for (const std::string& o : a.outputs) paths.push_back({"-o", o, {".exr", ".png"}});
  if (!a.statsPath.empty()) paths.push_back({"--stats", a.statsPath, {}});
  if (!a.tracePath.empty()) paths.push_back({"--progress-trace", a.tracePath, {}});
  for (OutputPath& p : checkpointOutputs(a.solve)) paths.push_back(std::move(p));
  checkOutputPaths(paths);
  auto [width, height] = parseSize(a.size);
  std::unique_ptr<tbb::global_control> threads;
  if (a.threads > 0) threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(a.threads));

  ProgressBar bar(a.quiet);
  if (!a.tracePath.empty()) bar.traceTo(a.tracePath);
  const auto start = std::chrono::steady_clock::now();
  nowDoing(fmt::format("loading scene '{}'", a.scene), "the scene is too big for this machine's memory");
  Scene scene = loadScene(a.scene);
  addCommandLineLights(scene, a.solve);
  const std::string sceneName = scene.name;
  if (!a.quiet)
    for (const std::string& w : scene.warnings) std::cerr << "luxel: warning: " << w << "\n";

  // "lightmap": bake lightmaps and show them as an engine would (luxel::renderLightmapped).
  const bool lightmapped = a.mode == "lightmap";
  ViewArgs view = a;
  if (lightmapped) view.mode = "radiosity";
  const RenderOptions ro = renderOptionsFor(scene, view);  // checked before the solve, which can take a while
  ToneMap tm;
  tm.curve = parseToneCurve(a.toneCurve);
  tm.exposure = a.exposure;

  // A bad solver, backend or option fails before any work: the session and the lightmap recipe
  // check them first.
  SolveOptions so = solveOptions(a.solve);
  Solution solution;
  Image image;
  RenderStats rs;
  nowDoing(fmt::format("solving scene '{}' ({})", sceneName, solveSize(a.solve)), solveSizeHint(a.solve, lightmapped));
  if (lightmapped && a.transferBands > 0) {
    LightmapRecipe recipe;
    recipe.texelsPerMetre = a.solve.elementSize > 0.0f ? 1.0f / a.solve.elementSize : 0.0f;
    recipe.texelBudget = size_t(a.solve.elements);
    if (a.sunDirection && std::none_of(scene.lights.begin(), scene.lights.end(),
                                       [](const Light& l) { return l.type == Light::Type::Directional; }))
      throw Error(fmt::format("scene '{}' has no sun for --sun-direction to turn (add one with --sun)", sceneName));
    const BakedTransfer baked = bakeTransfer(scene, recipe, a.transferBands, bar.callback());
    const LightmapAtlas& atlas = baked.atlas;
    const TransferBake& transfer = baked.transfer;
    if (a.sunDirection) {  // turned after the bake: the transfer does not depend on the light
      const Vec3 d = glm::normalize(parseVec3(*a.sunDirection, "sun-direction"));
      for (Light& l : scene.lights)
        if (l.type == Light::Type::Directional) l.direction = d;
    }
    const auto projectStart = std::chrono::steady_clock::now();
    const DistantLightSh light = distantLightSh(scene, a.transferBands);
    const auto relightStart = std::chrono::steady_clock::now();
    std::vector<std::vector<Rgb>> pages = relightTransfer(transfer, light);
    const auto relightEnd = std::chrono::steady_clock::now();
    LightmapBake relit = transfer.texels;  // the texel layout, for the renderer (not part of relighting)
    relit.pages = std::move(pages);
    const double projectSeconds = std::chrono::duration<double>(relightStart - projectStart).count();
    const double relightSeconds = std::chrono::duration<double>(relightEnd - relightStart).count();
    solution.stats.warnings = light.warnings;
    solution.stats.method = "transfer";
    solution.stats.backend = "cpu";
    solution.stats.elements = transfer.texels.texels;
    solution.stats.patches = transfer.texels.surfaces.surfaces.patches.size();
    solution.stats.shots = transfer.shots;
    solution.stats.unshotFraction = transfer.unshotFraction;
    solution.stats.secondsTotal = transfer.secondsDirect + transfer.secondsShoot;
    if (!a.quiet)
      std::cout << fmt::format("luxel: transfer — {} bands, {} texels, direct {:.3f} s, shooting {:.3f} s ({} shots); "
                               "light projected in {:.2f} ms, texels relit in {:.2f} ms\n",
                               a.transferBands, transfer.texels.texels, transfer.secondsDirect, transfer.secondsShoot,
                               transfer.shots, 1000.0 * projectSeconds, 1000.0 * relightSeconds);
    nowDoing(renderingWhat(a, sceneName), "use a smaller image (--size)");
    image = renderLightmapped(scene, atlas, relit, ro, bar.callback(), &rs);
  } else if (lightmapped) {
    LightmapRecipe recipe;
    recipe.texelsPerMetre = a.solve.elementSize > 0.0f ? 1.0f / a.solve.elementSize : 0.0f;
    recipe.texelBudget = size_t(a.solve.elements);
    recipe.solve = so;
    recipe.directional = parseDirectionalMode(a.directional);
    const BakedLightmaps baked = bakeLightmaps(scene, recipe, bar.callback());
    solution = baked.bake.solution;
    nowDoing(renderingWhat(a, sceneName), "use a smaller image (--size)");
    image = renderLightmapped(scene, baked.atlas, baked.bake, ro, bar.callback(), &rs);
  } else {
    DiscretiseOptions discretise = discretiseOptions(a.solve);
    // An hq render reads its solution three bounces away and gathers on a mesh of its own
    // (RenderOptions::gatherElements), so its solve, unless asked otherwise, is a smaller one;
    // not where the smaller budget would leave faces uncut (at least two elements a face): there
    // the solution would be no finer than the model.
    size_t faces = 0;
    for (const Mesh& m : scene.meshes) faces += m.faces.size();
    if (ro.mode == RenderOptions::Mode::HighQuality && a.solve.elements == 0 && a.solve.elementSize == 0.0f &&
        2 * faces <= kHqSolveElements)
      discretise.elementBudget = kHqSolveElements;
    Session session(std::move(scene), discretise, {so});
    solution = session.solve(bar.callback());
    // The solver's memory goes back before the renderer takes its own: at seed 002's 1.5M faces
    // the hierarchy and the transport's ray tracer are a third of the peak.
    const Session::Solved solved = std::move(session).release();
    nowDoing(renderingWhat(a, sceneName), "use a smaller image (--size)");
    image = render(solved.scene, solved.surfaces, solution, ro, bar.callback(), &rs);
  }
  if (!a.quiet)
    for (const std::string& w : solution.stats.warnings) std::cerr << "luxel: warning: " << w << "\n";
  for (const std::string& o : a.outputs) {
    if (ProgressBar::interrupted()) throw Cancelled();  // between outputs, each written whole or not at all
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
    record.image = RunRecord::Image{width, height, a.spp, a.mode, meanLuminance(image), rs.rays, rs.seconds,
                                    a.mode == "hq" ? std::string(indirectName(rs.indirect)) : std::string()};
    record.threads = a.threads > 0 ? a.threads : tbb::info::default_concurrency();
    record.outputs = a.outputs;
    record.totalSeconds = total;
    writeStatsJson(record, a.statsPath);
  }
  if (!a.quiet) {
    std::cout << fmt::format("luxel: {} — {}, {} on {}{} ({} shots, {} iterations), unshot {:.3f}%\n",
                             sceneName, elementsAndPatches(s), s.method, s.backend,
                             s.device.empty() ? "" : " (" + s.device + ")", s.shots, s.iterations, 100.0 * s.unshotFraction);
    std::cout << fmt::format("luxel: solve {:.3f} s (setup {:.3f}, form factors {:.3f}, iterate {:.3f}), {:.1f} M rays/s\n",
                             s.secondsTotal, s.secondsSetup, s.secondsFormFactors, s.secondsSolve, s.raysPerSecond() / 1e6);
    const std::string gathered = rs.gatherElements > 0 ? fmt::format(", gathered on {} elements", rs.gatherElements) : "";
    std::cout << fmt::format("luxel: render {}x{} at {} spp ({}{}) {:.3f} s; total {:.3f} s\n", width, height, a.spp,
                             a.mode, gathered, rs.seconds, total);
    for (const std::string& o : a.outputs) std::cout << "luxel: wrote " << o << "\n";
  }
  return 0;
}

}  // namespace luxel::cli
