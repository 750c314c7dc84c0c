// What a viewer run does around each frame, the same in a window and headless: the script before
// it, the exit conditions and the final screenshot after it, the statistics at the end.
#pragma once

#include <chrono>

#include "script_player.h"
#include "viewer_run.h"

namespace luxel::viewer {

class RunControl {
 public:
  explicit RunControl(const RunOptions& run);
  // Seconds since the last frame (0 for the first), after performing what the script has due (and
  // asking for the screenshot when the next frame is the last).
  double beforeFrame(Viewer& viewer);
  // Prints the viewer's messages; says stop when `frames` are done or the viewer was asked to quit.
  bool afterFrame(Viewer& viewer);
  // Writes the statistics, when asked for.
  void finish(const Viewer& viewer, int width, int height) const;

 private:
  const RunOptions& run_;
  ScriptPlayer player_;
  std::chrono::steady_clock::time_point start_, last_;
  bool started_ = false;
};

}  // namespace luxel::viewer
