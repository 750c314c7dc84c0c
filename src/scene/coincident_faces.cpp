#include "scene/coincident_faces.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <fmt/format.h>

namespace luxel {
namespace {

constexpr double kTolerance = 1e-6;  // of the scene's extent: float rounding of placed copies, far below any modelled gap
constexpr double kCellsPerTolerance = 16.0;  // grid cell, in tolerances: most faces search one cell

struct FaceRef {
  uint32_t mesh, face;
};

struct Cell {
  int64_t x, y, z;
  bool operator==(const Cell&) const = default;
};

struct CellHash {
  size_t operator()(const Cell& c) const {
    uint64_t h = uint64_t(c.x) * 0x9E3779B97F4A7C15ull;
    h ^= uint64_t(c.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= uint64_t(c.z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return size_t(h);
  }
};

bool isFinite(Vec3 p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

class CoincidenceFinder {
 public:
  explicit CoincidenceFinder(Scene& scene) : scene_(scene), removed_(scene.meshes.size()) {
    for (size_t m = 0; m < scene.meshes.size(); ++m) removed_[m].assign(scene.meshes[m].faces.size(), 0);
  }

  size_t run() {
    if (!bounds()) return 0;
    size_t count = 0;
    for (uint32_t m = 0; m < scene_.meshes.size(); ++m) {
      if (!considered(m)) continue;
      for (uint32_t f = 0; f < scene_.meshes[m].faces.size(); ++f) count += visit({m, f});
    }
    return count;
  }

  const std::vector<std::vector<uint8_t>>& removed() const { return removed_; }

 private:
  bool considered(uint32_t m) const {
    const Mesh& mesh = scene_.meshes[m];
    return mesh.object == kNoObject || mesh.object >= scene_.objects.size() || !scene_.objects[mesh.object].dynamic;
  }

  bool bounds() {
    lo_ = Vec3(INFINITY), hi_ = Vec3(-INFINITY);
    for (uint32_t m = 0; m < scene_.meshes.size(); ++m)
      if (considered(m))
        for (const Vec3& p : scene_.meshes[m].positions)
          if (isFinite(p)) lo_ = glm::min(lo_, p), hi_ = glm::max(hi_, p);
    const double extent = glm::length(glm::dvec3(hi_) - glm::dvec3(lo_));
    if (!(extent > 0.0) || !std::isfinite(extent)) return false;
    tolerance_ = kTolerance * extent;
    cell_ = kCellsPerTolerance * tolerance_;
    return true;
  }

  // The corners of a face, or 0 when it cannot be compared (indices out of range, not finite:
  // Scene::validate reports those).
  int corners(FaceRef r, glm::dvec3 out[4]) const {
    const Mesh& mesh = scene_.meshes[r.mesh];
    const Face& face = mesh.faces[r.face];
    const int n = face.vertexCount();
    for (int i = 0; i < n; ++i) {
      if (face.v[i] >= mesh.positions.size() || !isFinite(mesh.positions[face.v[i]])) return 0;
      out[i] = glm::dvec3(mesh.positions[face.v[i]]);
    }
    return n;
  }

  // The same corners in the same cyclic order (so the same facing), each within the tolerance.
  bool coincident(const glm::dvec3* a, int na, FaceRef other) const {
    glm::dvec3 b[4];
    if (corners(other, b) != na) return false;
    for (int shift = 0; shift < na; ++shift) {
      bool all = true;
      for (int i = 0; i < na && all; ++i) {
        const glm::dvec3 d = glm::abs(a[i] - b[(i + shift) % na]);
        all = std::max({d.x, d.y, d.z}) <= tolerance_;
      }
      if (all) return true;
    }
    return false;
  }

  bool emits(FaceRef r) const {
    const uint32_t material = scene_.meshes[r.mesh].material;
    return material < scene_.materials.size() && scene_.materials[material].isEmissive();
  }

  Cell cellOf(const glm::dvec3& p) const {
    const glm::dvec3 c = glm::floor((p - glm::dvec3(lo_)) / cell_);
    return {int64_t(c.x), int64_t(c.y), int64_t(c.z)};
  }

  // Returns 1 when `r` or the copy it repeats was removed.
  size_t visit(FaceRef r) {
    glm::dvec3 p[4];
    const int n = corners(r, p);
    if (n == 0) return 0;
    glm::dvec3 centre(0.0);
    for (int i = 0; i < n; ++i) centre += p[i];
    centre /= double(n);
    // A copy's centre is within the tolerance of this one's: search the cells that box touches.
    const Cell from = cellOf(centre - tolerance_), to = cellOf(centre + tolerance_);
    for (int64_t x = from.x; x <= to.x; ++x)
      for (int64_t y = from.y; y <= to.y; ++y)
        for (int64_t z = from.z; z <= to.z; ++z) {
          const auto found = cells_.find({x, y, z});
          if (found == cells_.end()) continue;
          for (FaceRef& kept : found->second) {
            if (removed_[kept.mesh][kept.face] || !coincident(p, n, kept)) continue;
            if (emits(r) && !emits(kept)) {
              removed_[kept.mesh][kept.face] = 1;  // the light stays
              kept = r;
            } else {
              removed_[r.mesh][r.face] = 1;
            }
            return 1;
          }
        }
    cells_[cellOf(centre)].push_back(r);
    return 0;
  }

  Scene& scene_;
  std::vector<std::vector<uint8_t>> removed_;
  std::unordered_map<Cell, std::vector<FaceRef>, CellHash> cells_;
  Vec3 lo_{0.0f}, hi_{0.0f};
  double tolerance_ = 0.0, cell_ = 1.0;
};

}  // namespace

size_t removeCoincidentFaces(Scene& scene) {
  CoincidenceFinder finder(scene);
  const size_t count = finder.run();
  if (count == 0) return 0;
  const auto& removed = finder.removed();
  std::vector<std::string> named;
  std::vector<Mesh> kept;
  kept.reserve(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    Mesh& mesh = scene.meshes[m];
    const size_t gone = size_t(std::count(removed[m].begin(), removed[m].end(), uint8_t(1)));
    if (gone > 0) {
      named.push_back(fmt::format("{} ({} of {})", mesh.name, gone, mesh.faces.size()));
      size_t out = 0;
      for (size_t f = 0; f < mesh.faces.size(); ++f) {
        if (removed[m][f]) continue;
        mesh.faces[out] = mesh.faces[f];
        if (!mesh.elementGrids.empty()) mesh.elementGrids[out] = mesh.elementGrids[f];
        ++out;
      }
      mesh.faces.resize(out);
      if (!mesh.elementGrids.empty()) mesh.elementGrids.resize(out);
      if (out == 0) continue;
    }
    kept.push_back(std::move(mesh));
  }
  scene.meshes = std::move(kept);
  constexpr size_t kNamed = 4;
  std::string list;
  for (size_t i = 0; i < std::min(named.size(), kNamed); ++i) list += (i ? ", " : "") + named[i];
  if (named.size() > kNamed) list += fmt::format(" and {} more meshes", named.size() - kNamed);
  scene.warnings.push_back(fmt::format(
      "scene '{}': removed {} faces that repeat another face in the same place, facing the same way (a mesh "
      "listed or placed twice?); coincident copies would each reflect the same light and multiply it: {}",
      scene.name, count, list));
  return count;
}

}  // namespace luxel
