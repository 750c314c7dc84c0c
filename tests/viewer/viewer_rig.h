// A Viewer in a headless OpenGL 4.5 context for tests, and comparisons of pictures by region.
#pragma once

#include <memory>
#include <string>

#include "gl/gl_test_context.h"
#include "luxel/image.h"
#include "viewer.h"

namespace luxel::test {

struct ViewerRig {
  std::unique_ptr<gl::Context> context;  // declared first: destroyed after the viewer
  std::unique_ptr<viewer::Viewer> viewer;
  int width = 0, height = 0;

  void frame() { viewer->frame(1.0 / 60.0, width, height); }
  // Frames until the solver is done and its solution is drawn.
  void solve(int maxFrames = 5000) {
    for (int i = 0; i < maxFrames && !viewer->session().done(); ++i) frame();
    frame();
  }
  Image picture() const { return viewer->readRadiance(); }
};

// Null (and `why` set) when no GL 4.5 context can be made.
inline std::unique_ptr<ViewerRig> viewerRig(Scene scene, viewer::ViewerOptions options, std::string& why) {
  auto rig = std::make_unique<ViewerRig>();
  rig->context = glContextOr(why);
  if (!rig->context) return nullptr;
  rig->width = options.width;
  rig->height = options.height;
  rig->viewer = std::make_unique<viewer::Viewer>(std::move(scene), std::move(options));
  return rig;
}

struct RegionDifference {
  double worst = 0.0;  // the largest |a - b| / max(b, floor) over the regions
  int region = -1;
  double a = 0.0, b = 0.0;
};

// Region means of two pictures of the same size (cells x cells regions, radiance summed over
// channels), each region's relative difference against `b`'s, with regions darker than
// `floorShare` of b's mean region compared against that floor instead (a dark corner's small
// absolute error is not a large relative one). Pixels brighter than `cap` in either picture are
// left out: an emitter's edge, a hundred times brighter than what it lights, which a rasteriser
// and a ray caster split differently, would otherwise outweigh every other difference.
inline RegionDifference compareRegions(const Image& a, const Image& b, int cells, double floorShare = 0.1,
                                       double cap = 1e30) {
  std::vector<double> ma(size_t(cells * cells), 0.0), mb = ma, counts = ma;
  const auto sum = [](const Rgb& c) { return double(c.x) + double(c.y) + double(c.z); };
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const double va = sum(a.at(x, y)), vb = sum(b.at(x, y));
      if (va > cap || vb > cap) continue;
      const size_t c = size_t((y * cells / a.height) * cells + x * cells / a.width);
      ma[c] += va, mb[c] += vb, counts[c] += 1.0;
    }
  double mean = 0.0;
  for (size_t i = 0; i < ma.size(); ++i) {
    ma[i] /= std::max(counts[i], 1.0), mb[i] /= std::max(counts[i], 1.0);
    mean += mb[i] / double(mb.size());
  }
  RegionDifference d;
  for (size_t i = 0; i < ma.size(); ++i) {
    const double rel = std::abs(ma[i] - mb[i]) / std::max(mb[i], floorShare * mean);
    if (rel > d.worst) d = {rel, int(i), ma[i], mb[i]};
  }
  return d;
}

}  // namespace luxel::test
