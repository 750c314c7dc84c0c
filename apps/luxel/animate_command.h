// `luxel animate SCENE --frames N [--fps F] [--start T] -o DIR/frame%04d.png|movie.mp4 [...]`:
// renders a scene's animation (luxel/animation.h) frame by frame with one Session, which follows
// the moves (a dynamic solver continues from the last frame; another starts again), and prints one
// stats JSON line per frame.
#pragma once

#include <cstdint>
#include <string>

#include "render_command.h"
#include "solve_args.h"

namespace luxel::cli {

struct AnimateArgs : ViewArgs {
  std::string scene;
  std::string output;  // an image name with %d / %04d, or a video (.mp4, .mkv, .webm)
  int64_t frames = 0;
  double fps = 30.0;
  double start = 0.0;        // seconds: frame k shows time start + k / fps
  double frameBudget = 0.0;  // seconds of solving a frame; 0: each frame to the end
  bool error = false;        // each frame's NRMSE against a from-scratch solve at the same pose
  SolveArgs solve;
  int threads = 0;
  bool quiet = false;
  std::string statsPath;  // JSON lines; default stdout
};

// Adds the animate subcommand's options to `command`.
void addAnimateOptions(CLI::App& command, AnimateArgs& args);
// Everything about the arguments that can be checked without a file: throws Error.
void checkAnimateArgs(const AnimateArgs& args);
int runAnimate(const AnimateArgs& args);

}  // namespace luxel::cli
