// Running the viewer: in a desktop window (GLFW, with Dear ImGui's panels), or headless (an EGL
// context and an offscreen framebuffer: scripted runs on machines without a display, such as a
// GPU server). Both drive the same Viewer.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "view_script.h"
#include "viewer.h"

namespace luxel::viewer {

struct RunOptions {
  std::vector<ScriptEntry> script;
  std::filesystem::path screenshot;  // written after `frames` frames (then the viewer exits)
  int64_t frames = 0;                 // > 0: exit after this many frames
  std::filesystem::path statsPath;    // frame-time statistics (frame_stats.h), written at exit
  bool hiddenWindow = false;          // a window that is never shown (tests under Xvfb)
  bool vsync = false;
};

// Opens the window (or the headless context), runs until quit (Esc, the window closed, the
// script's `quit`, or `frames` frames) and returns the exit code. Throws luxel::Error when no
// display or no OpenGL 4.5 context can be had, saying which.
int runInWindow(Scene scene, ViewerOptions options, const RunOptions& run);
int runHeadless(Scene scene, ViewerOptions options, const RunOptions& run);

}  // namespace luxel::viewer
