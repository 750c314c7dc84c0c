// Frame-time statistics of a viewer run (`luxel view --stats FILE.json`): every frame's time, split
// into the solver's step and the drawing, and the latency from each edit to the first frame that
// shows its updated indirect light.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace luxel::viewer {

struct FrameSample {
  double frameMs = 0.0;   // from the start of this frame to the start of the next
  double solveMs = 0.0;   // stepping the solver and reading its solution
  double drawMs = 0.0;    // drawing (GPU work waited for when timing is asked)
  bool solving = false;   // the solver had work left
};

struct EditLatency {
  std::string action;
  double ms = 0.0;  // from the edit to the end of the first frame drawn with its indirect light
  double editMs = 0.0;   // of which making the edit (the session's update, shadow maps)
  double solveMs = 0.0;  // and the solver's steps until its light was redistributed
};

struct Percentiles {
  double median = 0.0, p95 = 0.0, max = 0.0, mean = 0.0;
};
// Nearest-rank percentiles of `values` (all zero when empty).
Percentiles percentiles(std::vector<double> values);

class FrameStats {
 public:
  void addFrame(const FrameSample& s) { frames_.push_back(s); }
  void addEdit(const EditLatency& e) { edits_.push_back(e); }
  const std::vector<FrameSample>& frames() const { return frames_; }
  const std::vector<EditLatency>& edits() const { return edits_; }

  // Frames per second over the frames in which the solver was idle (nothing to step), and over all.
  double idleFps() const;
  // The JSON document: scene, size, renderer, frame counts, frame/solve/draw ms percentiles for
  // idle and solving frames, fps, and the edit latencies.
  std::string json(const std::string& scene, int width, int height, const std::string& renderer,
                   const std::string& backend) const;
  void write(const std::filesystem::path& path, const std::string& scene, int width, int height,
             const std::string& renderer, const std::string& backend) const;

 private:
  std::vector<FrameSample> frames_;
  std::vector<EditLatency> edits_;
};

}  // namespace luxel::viewer
