// `luxel render SCENE -o OUT.exr|OUT.png [...]`: solves a scene and renders an image of it.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "luxel/scene.h"
#include "solve_args.h"

namespace luxel::cli {

struct RenderArgs {
  std::string scene;
  std::vector<std::string> outputs;
  std::string camera;
  std::optional<std::string> eye, target, up;
  float fov = 0.0f;
  std::string size = "512x512";
  int spp = 16;
  SolveArgs solve;
  int threads = 0;
  bool quiet = false;
  std::string statsPath;
  std::string tracePath;
  std::string mode = "hq";
  std::string toneCurve = "filmic";
  float exposure = 0.0f;
};

// "X,Y,Z" for --eye, --target and --up (`what`); throws Error naming the option.
Vec3 parseVec3(const std::string& text, const char* what);
// "WxH" for --size; throws Error.
std::pair<int, int> parseSize(const std::string& text);
// Everything about the arguments that can be checked without a file: throws Error.
void checkRenderArgs(const RenderArgs& args);
int runRender(const RenderArgs& args);

}  // namespace luxel::cli
