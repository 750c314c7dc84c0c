// `luxel view SCENE [options]`: the interactive viewer (apps/viewer/): walk through a scene while it
// solves, move lights and objects and watch the light follow. Scriptable (--script, --screenshot,
// --frames, --stats) and runnable without a display (--headless).
#pragma once

#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

#include "render_command.h"
#include "solve_args.h"

namespace luxel::cli {

struct ViewerArgs : ViewArgs {
  std::string scene;
  SolveArgs solve;
  std::string viewMode;  // empty: baked for a glb written by luxel bake, else final
  std::string shadows = "maps";
  std::string script;
  std::string screenshot;
  int64_t frames = 0;
  std::string statsPath;
  std::string shaderDir;
  double stepMs = 12.0;
  bool headless = false;
  bool hidden = false;
  bool paused = false;
  bool vsync = false;
  bool noUi = false;
  float texelsPerMetre = 0.0f;
  int threads = 0;
  bool listActions = false;
};

void addViewerOptions(CLI::App& command, ViewerArgs& args);
// What can be checked without a file or a display: throws Error.
void checkViewerArgs(const ViewerArgs& args);
int runViewer(const ViewerArgs& args);

}  // namespace luxel::cli
