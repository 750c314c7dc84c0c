// `luxel render SCENE -o OUT.exr|OUT.png [...]`: solves a scene and renders an image of it; and the
// view options that `luxel animate` shares with it.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "luxel/render.h"
#include "luxel/scene.h"
#include "solve_args.h"

namespace luxel::cli {

// How an image is made from a solution, shared by render and animate: camera, size, samples,
// mode, tone mapping.
struct ViewArgs {
  std::string camera;
  std::optional<std::string> eye, target, up;
  float fov = 0.0f;
  std::string size = "512x512";
  int spp = 16;
  std::string indirect = "auto";  // hq mode's indirect light (RenderOptions::Indirect)
  int gatherRays = 0;                      // per vertex or per pixel sample; 0: the default
  uint32_t renderSeed = RenderOptions{}.seed;  // the image's samples (not the solver's)
  int gatherBounces = RenderOptions{}.gatherBounces;
  size_t gatherElements = RenderOptions{}.gatherElements;
  int glossyRays = RenderOptions{}.glossyRays;  // per camera sample on glossy materials
  std::string mode = "hq";
  std::string toneCurve = "filmic";
  float exposure = 0.0f;
};

struct RenderArgs : ViewArgs {
  std::string scene;
  std::vector<std::string> outputs;
  SolveArgs solve;
  int threads = 0;
  bool quiet = false;
  std::string statsPath;
  std::string tracePath;
  // --directional MODE (with --mode lightmap): bake directional lightmaps and shade them at the
  // normal-mapped normal (luxel/directional_lightmap.h); "none" by default.
  std::string directional = "none";
  // --transfer BANDS (with --mode lightmap): bake SH transfer lightmaps (luxel/transfer_lightmap.h)
  // and relight them with the scene's suns and skies; 0: off. --sun-direction X,Y,Z turns every sun
  // to travel along it for the relighting (the bake does not depend on it).
  int transferBands = 0;
  std::optional<std::string> sunDirection;
};

// Adds --camera, --eye, --target, --up and --fov.
void addCameraOptions(CLI::App& command, ViewArgs& args);
// Adds those and --size, --spp, --indirect, --gather-rays, --gather-bounces, --gather-elements, --render-seed, --tonemap and --exposure (each
// command adds its own --mode, whose choices differ).
void addViewOptions(CLI::App& command, ViewArgs& args);
// Checks the view options that need no scene (the mode only when it is hq or radiosity): throws Error.
void checkViewArgs(const ViewArgs& args);
// Render options for `scene` (mode hq or radiosity): the camera of --camera (else the scene's
// default) with --eye, --target, --up and --fov applied, checked by validateRenderOptions.
RenderOptions renderOptionsFor(const Scene& scene, const ViewArgs& args);

// "X,Y,Z" for --eye, --target and --up (`what`); throws Error naming the option.
Vec3 parseVec3(const std::string& text, const char* what);
// "WxH" for --size; throws Error.
std::pair<int, int> parseSize(const std::string& text);
// Everything about the arguments that can be checked without a file: throws Error.
void checkRenderArgs(const RenderArgs& args);
int runRender(const RenderArgs& args);

}  // namespace luxel::cli
