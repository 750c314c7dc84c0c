#include "scene/stray_geometry.h"

#include <limits>
#include <vector>

#include <fmt/format.h>

namespace luxel {
namespace {

constexpr float kRatio = 1e4f;

struct Box {
  Vec3 lo{std::numeric_limits<float>::max()}, hi{-std::numeric_limits<float>::max()};
  void add(const Box& b) { lo = glm::min(lo, b.lo), hi = glm::max(hi, b.hi); }
  bool empty() const { return lo.x > hi.x; }
  float extent() const { return empty() ? 0.0f : glm::length(hi - lo); }
};

}  // namespace

bool warnAboutStrayMesh(Scene& scene, const std::string& where) {
  const size_t n = scene.meshes.size();
  if (n < 2) return false;
  std::vector<Box> boxes(n);
  for (size_t m = 0; m < n; ++m)
    for (const Face& f : scene.meshes[m].faces)
      for (int i = 0; i < (f.isTriangle() ? 3 : 4); ++i) {
        const Vec3 p = scene.meshes[m].positions[f.v[size_t(i)]];
        boxes[m].lo = glm::min(boxes[m].lo, p), boxes[m].hi = glm::max(boxes[m].hi, p);
      }
  // The box of all meshes but m, from the boxes before and after it: linear in meshes.
  std::vector<Box> before(n + 1), after(n + 1);
  for (size_t m = 0; m < n; ++m) before[m + 1] = before[m], before[m + 1].add(boxes[m]);
  for (size_t m = n; m-- > 0;) after[m] = after[m + 1], after[m].add(boxes[m]);
  const float whole = before[n].extent();
  for (size_t m = 0; m < n; ++m) {
    Box rest = before[m];
    rest.add(after[m + 1]);
    const float others = rest.extent();
    if (rest.empty() || !(whole > kRatio * others)) continue;
    // A scene file's check repeats its mesh file's: one warning is enough.
    const std::string said = fmt::format("mesh '{}' lies far from the rest", scene.meshes[m].name);
    for (const std::string& w : scene.warnings)
      if (w.find(said) != std::string::npos) return true;
    scene.warnings.push_back(fmt::format(
        "{}: mesh '{}' lies far from the rest of the scene: with it the scene is {:.3g} units across, without it "
        "{:.3g}. Elements, small faces (lights included) and ray offsets are sized from the extent it dominates, "
        "so the rest may render dark or black; remove or move it",
        where, scene.meshes[m].name, whole, others));
    return true;
  }
  return false;
}

}  // namespace luxel
