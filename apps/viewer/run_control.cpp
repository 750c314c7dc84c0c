#include "run_control.h"

#include <iostream>

namespace luxel::viewer {

RunControl::RunControl(const RunOptions& run) : run_(run), player_(run.script) {}

double RunControl::beforeFrame(Viewer& viewer) {
  const auto now = std::chrono::steady_clock::now();
  if (!started_) start_ = last_ = now, started_ = true;
  const double dt = std::chrono::duration<double>(now - last_).count();
  last_ = now;
  player_.play(viewer, viewer.frameCount(), std::chrono::duration<double>(now - start_).count());
  // The last frame's picture is the screenshot (taken at the end of the frame).
  if (run_.frames > 0 && !run_.screenshot.empty() && viewer.frameCount() == run_.frames - 1)
    viewer.perform(Action{"screenshot", {run_.screenshot.string()}, "--screenshot"});
  return dt;
}

bool RunControl::afterFrame(Viewer& viewer) {
  for (const std::string& m : viewer.takeMessages()) std::cerr << "luxel view: " << m << "\n";
  if (viewer.quitRequested()) return false;
  return !(run_.frames > 0 && viewer.frameCount() >= run_.frames);
}

void RunControl::finish(const Viewer& viewer, int width, int height) const {
  if (!run_.statsPath.empty())
    viewer.stats().write(run_.statsPath, viewer.session().scene().name, width, height, viewer.renderer(), viewer.session().backend());
}

}  // namespace luxel::viewer
