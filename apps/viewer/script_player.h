// Replays a viewer script (view_script.h) against a Viewer: before each frame, every entry whose
// frame has come or whose time has passed is performed, in order.
#pragma once

#include <chrono>
#include <vector>

#include "view_script.h"

namespace luxel::viewer {

class Viewer;

class ScriptPlayer {
 public:
  explicit ScriptPlayer(std::vector<ScriptEntry> entries);
  // Performs what is due at frame `frame`, `seconds` after the first frame. Throws what an action
  // throws (a script's mistake ends the run: a test must not pass over it).
  void play(Viewer& viewer, int64_t frame, double seconds);
  bool finished() const { return nextFrame_ >= byFrame_.size() && nextTime_ >= byTime_.size(); }

 private:
  std::vector<ScriptEntry> byFrame_, byTime_;
  size_t nextFrame_ = 0, nextTime_ = 0;
};

}  // namespace luxel::viewer
