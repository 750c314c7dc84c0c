#include "view_command.h"

#include <filesystem>
#include <iostream>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "luxel/error.h"
#include "luxel/import.h"
#include "output_paths.h"
#include "scene_renderer.h"
#include "view_script.h"
#include "baked_glb.h"
#include "viewer_run.h"

namespace luxel::cli {

void addViewerOptions(CLI::App& c, ViewerArgs& a) {
  a.size = "1280x720";
  c.add_option("scene", a.scene, "Built-in name, a scene file (.json) or a mesh file");
  addCameraOptions(c, a);
  c.add_option("--size", a.size, "Window size WxH")->capture_default_str();
  c.add_option("--tonemap", a.toneCurve, "Tone curve: filmic, reinhard or clamp")->capture_default_str();
  c.add_option("--exposure", a.exposure, "Exposure in stops, on top of auto exposure")->check(finiteRange(-64.0, 64.0));
  c.add_option("--view", a.viewMode,
               "final, indirect, direct, radiosity, patches, elements, density, unshot, baked or texels (default: baked for a glb "
               "written by luxel bake, else final)");
  c.add_option("--shadows", a.shadows, "Shadows of point, spot and sun lights: maps (cube shadow maps) or volumes (stencil shadow volumes)")
      ->capture_default_str();
  addSolveOptions(c, a.solve);
  c.add_option("--script", a.script, "Replay timed input from this file (`luxel view --actions` lists what it may say)");
  c.add_option("--screenshot", a.screenshot, "Write the last frame (.png tone-mapped, .exr radiance) and exit; needs --frames");
  c.add_option("--frames", a.frames, "Exit after this many frames")->check(CLI::Range(int64_t(1), int64_t(100'000'000)));
  c.add_option("--stats", a.statsPath, "Write frame-time statistics as JSON at exit");
  c.add_option("--shaders", a.shaderDir, "A folder whose files replace the built-in shaders (F5 reloads them)");
  c.add_option("--step-ms", a.stepMs, "Milliseconds of solving per frame")->check(finiteRange(0.1, 10000.0))->capture_default_str();
  c.add_option("--texels-per-metre", a.texelsPerMetre, "The density view's texel size (default: luxel bake's)")->check(finiteRange(0.001, 1e6));
  c.add_flag("--headless", a.headless, "No window: an EGL context and an offscreen picture (needs --frames or a script)");
  c.add_flag("--hidden", a.hidden, "Open the window hidden (tests under Xvfb)");
  c.add_flag("--paused", a.paused, "Start with the solver paused");
  c.add_flag("--vsync", a.vsync, "Wait for the display's refresh (off: frames as fast as they come, for timing)");
  c.add_flag("--no-ui", a.noUi, "Hide the panels (Tab shows them)");
  c.add_option("--threads", a.threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 4096));
  c.add_flag("--actions", a.listActions, "List the actions a script (and the menus) can perform, and exit");
}

void checkViewerArgs(const ViewerArgs& a) {
  if (a.listActions) return;
  if (a.scene.empty()) throw Error("luxel view: give a scene (a built-in name, a scene file or a mesh file)");
  parseSize(a.size);
  if (a.eye) parseVec3(*a.eye, "eye");
  if (a.target) parseVec3(*a.target, "target");
  if (a.up) parseVec3(*a.up, "up");
  parseToneCurve(a.toneCurve);
  if (!a.viewMode.empty()) viewer::parseViewMode(a.viewMode);
  viewer::parseShadowMethod(a.shadows);
  checkSolveArgs(a.solve);
  if (!a.screenshot.empty() && a.frames <= 0) throw Error("--screenshot needs --frames N: the frame to write");
}

int runViewer(const ViewerArgs& a) {
  if (a.listActions) {
    for (const viewer::ActionSpec& s : viewer::actionSpecs())
      std::cout << fmt::format("{:<22} {:<32} {}\n", s.name, s.usage, s.help);
    return 0;
  }
  std::vector<OutputPath> paths;
  if (!a.screenshot.empty()) paths.push_back({"--screenshot", a.screenshot, {".png", ".exr"}});
  if (!a.statsPath.empty()) paths.push_back({"--stats", a.statsPath, {}});
  checkOutputPaths(paths);
  std::unique_ptr<tbb::global_control> threads;
  if (a.threads > 0) threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(a.threads));

  viewer::RunOptions run;
  if (!a.script.empty()) run.script = viewer::readScript(a.script);  // before the window: a typo fails at once
  run.screenshot = a.screenshot;
  run.frames = a.frames;
  run.statsPath = a.statsPath;
  run.hiddenWindow = a.hidden;
  run.vsync = a.vsync;

  Scene scene = loadScene(a.scene);
  addCommandLineLights(scene, a.solve);
  for (const std::string& w : scene.warnings) std::cerr << "luxel view: warning: " << w << "\n";
  if (!scene.hasLight())
    std::cerr << fmt::format("luxel view: warning: scene '{}' has no light; press L to place a lamp at the camera, or "
                             "give --sky RADIANCE or --sun X,Y,Z\n",
                             scene.name);

  viewer::ViewerOptions o;
  o.sceneName = scene.name;
  o.sceneSpec = isBuiltinScene(a.scene) ? a.scene : std::filesystem::absolute(a.scene).lexically_normal().string();
  o.discretise = discretiseOptions(a.solve);
  o.solve = solveOptions(a.solve);
  ViewArgs view = a;
  view.mode = "hq";
  const RenderOptions ro = renderOptionsFor(scene, view);
  o.camera = ro.camera;
  o.width = ro.width;
  o.height = ro.height;
  o.tone.curve = parseToneCurve(a.toneCurve);
  o.tone.exposure = a.exposure;
  // A glb that luxel baked: its light is shown as an engine would, beside the live solve.
  const std::string extension = std::filesystem::path(a.scene).extension().string();
  if (extension == ".glb" || extension == ".gltf") {
    auto baked = std::make_shared<viewer::BakedGlb>(viewer::readBakedGlb(a.scene));
    if (baked->baked()) o.baked = std::move(baked);
  }
  o.mode = !a.viewMode.empty() ? viewer::parseViewMode(a.viewMode) : o.baked ? viewer::ViewMode::Baked : viewer::ViewMode::Final;
  o.shadows = viewer::parseShadowMethod(a.shadows);
  o.paused = a.paused;
  o.stepSeconds = a.stepMs / 1000.0;
  o.shaderDir = a.shaderDir;
  o.texelsPerMetre = a.texelsPerMetre;
  o.showUi = !a.noUi;
  return a.headless ? viewer::runHeadless(std::move(scene), std::move(o), run)
                    : viewer::runInWindow(std::move(scene), std::move(o), run);
}

}  // namespace luxel::cli
