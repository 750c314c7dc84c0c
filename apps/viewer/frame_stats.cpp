#include "frame_stats.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "io/atomic_file.h"

namespace luxel::viewer {

Percentiles percentiles(std::vector<double> v) {
  Percentiles p;
  if (v.empty()) return p;
  std::sort(v.begin(), v.end());
  // Nearest rank: the smallest value with at least q of the values at or below it.
  auto rank = [&](double q) {
    const size_t r = size_t(std::ceil(q * double(v.size())));
    return v[std::min(v.size() - 1, r > 0 ? r - 1 : 0)];
  };
  p.median = rank(0.5);
  p.p95 = rank(0.95);
  p.max = v.back();
  double sum = 0.0;
  for (double x : v) sum += x;
  p.mean = sum / double(v.size());
  return p;
}

double FrameStats::idleFps() const {
  double ms = 0.0;
  size_t n = 0;
  for (const FrameSample& f : frames_)
    if (!f.solving) ms += f.frameMs, ++n;
  return ms > 0.0 ? 1000.0 * double(n) / ms : 0.0;
}

namespace {

nlohmann::json describe(const Percentiles& p) {
  return {{"median", p.median}, {"p95", p.p95}, {"max", p.max}, {"mean", p.mean}};
}

nlohmann::json phase(const std::vector<FrameSample>& frames, bool solving) {
  std::vector<double> frame, solve, draw;
  for (const FrameSample& f : frames)
    if (f.solving == solving) frame.push_back(f.frameMs), solve.push_back(f.solveMs), draw.push_back(f.drawMs);
  const Percentiles fp = percentiles(frame);
  return {{"frames", frame.size()},
          {"fps", fp.mean > 0.0 ? 1000.0 / fp.mean : 0.0},
          {"frame_ms", describe(fp)},
          {"solve_ms", describe(percentiles(solve))},
          {"draw_ms", describe(percentiles(draw))}};
}

}  // namespace

std::string FrameStats::json(const std::string& scene, int width, int height, const std::string& renderer,
                             const std::string& backend) const {
  nlohmann::json j;
  j["scene"] = scene;
  j["width"] = width;
  j["height"] = height;
  j["renderer"] = renderer;
  j["backend"] = backend;
  j["frames"] = frames_.size();
  j["idle"] = phase(frames_, false);
  j["solving"] = phase(frames_, true);
  nlohmann::json edits = nlohmann::json::array();
  for (const EditLatency& e : edits_)
    edits.push_back({{"action", e.action}, {"ms", e.ms}, {"edit_ms", e.editMs}, {"solve_ms", e.solveMs}});
  j["edits"] = edits;
  return j.dump(2) + "\n";
}

void FrameStats::write(const std::filesystem::path& path, const std::string& scene, int width, int height,
                       const std::string& renderer, const std::string& backend) const {
  writeTextAtomically(path, json(scene, width, height, renderer, backend));
}

}  // namespace luxel::viewer
