// Choosing each chart's parameterisation, checking it, and splitting charts that will not flatten.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "lightmap/atlas_internal.h"

namespace luxel::lightmap {
namespace {

// Charts whose normals all lie within this of their mean are flat: projected, never solved.
constexpr float kFlatAngle = 5.0f * std::numbers::pi_v<float> / 180.0f;
// The resolution of the self-overlap check: texel-centre samples along the chart's longer side.
constexpr int kOverlapGrid = 256;

// True when two faces of the chart claim one sample of a kOverlapGrid raster of its bounds: the
// map folds over itself, which a per-face flip test misses.
bool selfOverlaps(const WeldedMesh& w, const Chart& chart) {
  Vec2 lo(INFINITY), hi(-INFINITY);
  for (const auto& uv : chart.uv)
    for (Vec2 p : uv) lo = glm::min(lo, p), hi = glm::max(hi, p);
  float side = std::max(hi.x - lo.x, hi.y - lo.y);
  if (!(side > 0.0f)) return false;
  float scale = float(kOverlapGrid - 2) / side;
  std::vector<uint8_t> hit(size_t(kOverlapGrid) * kOverlapGrid, 0);
  bool overlap = false;
  auto claim = [&](int x, int y) {
    uint8_t& h = hit[size_t(y) * kOverlapGrid + size_t(x)];
    if (h) overlap = true;
    h = 1;
  };
  for (size_t i = 0; i < chart.faces.size() && !overlap; ++i) {
    std::array<Vec2, 4> t;
    for (int k = 0; k < 4; ++k) t[size_t(k)] = (chart.uv[i][size_t(k)] - lo) * scale + Vec2(1.0f);
    rasteriseTriangle(t[0], t[1], t[2], kOverlapGrid, claim);
    if (w.corners[chart.faces[i]] == 4) rasteriseTriangle(t[0], t[2], t[3], kOverlapGrid, claim);
  }
  return overlap;
}

// True when every face's area stretch (UV area over surface area, against the chart's mean) lies
// within [1/kMaxStretch, kMaxStretch]. Conformal maps keep angles, not areas: a large curved chart
// shrinks away from its pins, and is cut until its pieces pass.
constexpr double kMaxStretch = 2.0;
bool stretchWithinBound(const WeldedMesh& w, const Chart& chart) {
  std::vector<double> ratio(chart.faces.size(), -1.0);
  double uvTotal = 0.0, total = 0.0;
  for (size_t i = 0; i < chart.faces.size(); ++i) {
    uint32_t f = chart.faces[i];
    if (w.area[f] <= 0.0f) continue;
    const auto& t = chart.uv[i];
    double uv = std::abs(signedArea(t[0], t[1], t[2]));
    if (w.corners[f] == 4) uv += std::abs(signedArea(t[0], t[2], t[3]));
    ratio[i] = uv / w.area[f];
    uvTotal += uv, total += w.area[f];
  }
  if (!(uvTotal > 0.0)) return true;
  double mean = uvTotal / total;
  for (double r : ratio)
    if (r >= 0.0 && (r < mean / kMaxStretch || r > mean * kMaxStretch)) return false;
  return true;
}

// Cuts the faces in two at the median of their centroids along the longest axis of their bounds.
std::array<std::vector<uint32_t>, 2> split(const WeldedMesh& w, std::vector<uint32_t> faces) {
  auto centroid = [&](uint32_t f) {
    Vec3 c(0.0f);
    for (int k = 0; k < w.corners[f]; ++k) c += w.positions[w.v[f][size_t(k)]];
    return c / float(w.corners[f]);
  };
  Vec3 lo(INFINITY), hi(-INFINITY);
  for (uint32_t f : faces) lo = glm::min(lo, centroid(f)), hi = glm::max(hi, centroid(f));
  Vec3 d = hi - lo;
  int axis = d.x >= d.y && d.x >= d.z ? 0 : d.y >= d.z ? 1 : 2;
  auto mid = faces.begin() + std::ptrdiff_t(faces.size() / 2);
  std::nth_element(faces.begin(), mid, faces.end(),
                   [&](uint32_t a, uint32_t b) { return centroid(a)[axis] < centroid(b)[axis]; });
  return {std::vector<uint32_t>(faces.begin(), mid), std::vector<uint32_t>(mid, faces.end())};
}

bool flatten(const WeldedMesh& w, Chart& chart) {
  if (chart.faces.size() == 1) {
    planarProject(w, chart);  // only a non-convex quad can fold, and it cannot be cut further
    return true;
  }
  Vec3 mean = meanNormal(w, chart.faces);
  if (maxNormalDeviation(w, chart.faces, mean) <= kFlatAngle)
    if (planarProject(w, chart) && !selfOverlaps(w, chart)) return true;
  if (lscm(w, chart) && !selfOverlaps(w, chart)) return stretchWithinBound(w, chart);
  return planarProject(w, chart) && !selfOverlaps(w, chart) && stretchWithinBound(w, chart);
}

}  // namespace

std::vector<Chart> parameterise(const WeldedMesh& w, std::vector<Chart> charts) {
  std::vector<Chart> done;
  done.reserve(charts.size());
  while (!charts.empty()) {
    Chart chart = std::move(charts.back());
    charts.pop_back();
    if (!flatten(w, chart)) {
      // Neither map works: cut the chart in two (each half into its connected pieces) and retry.
      // A single face always flattens, so this ends.
      for (auto& half : split(w, std::move(chart.faces)))
        for (auto& piece : connectedComponents(w, half)) {
          Chart c;
          c.mesh = chart.mesh;
          c.faces = std::move(piece);
          charts.push_back(std::move(c));
        }
      continue;
    }
    // Scale to metres: the chart's UV area equals its surface area.
    double uvArea = 0.0, area = 0.0;
    for (size_t i = 0; i < chart.faces.size(); ++i) {
      const auto& t = chart.uv[i];
      uvArea += std::abs(signedArea(t[0], t[1], t[2]));
      if (w.corners[chart.faces[i]] == 4) uvArea += std::abs(signedArea(t[0], t[2], t[3]));
      area += w.area[chart.faces[i]];
    }
    if (uvArea > 0.0 && area > 0.0) {
      float s = float(std::sqrt(area / uvArea));
      for (auto& t : chart.uv)
        for (Vec2& p : t) p *= s;
    }
    done.push_back(std::move(chart));
  }
  return done;
}

}  // namespace luxel::lightmap
