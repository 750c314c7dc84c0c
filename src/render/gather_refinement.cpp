// Lattices of gathered points where a vertex gather's interpolation misses the light's shape: see
// render/gather_refinement.h.
#include "render/gather_refinement.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include <tbb/parallel_for.h>

#include "render/corner_values.h"

namespace luxel {
namespace {

// Elements darker at every corner than this share of the seen corners' mean are not refined: what
// their interpolation misses is no error anyone could see.
constexpr float kRefineFloor = 0.01f;
// A lattice finer than this many pixels a cell would gather what no pixel shows apart; coarser,
// the light a crease takes from a sky stays underestimated (docs/performance.md, "The sky in the
// gather").
constexpr float kPixelsPerCell = 4.0f;

float channelSum(const Rgb& c) { return c.r + c.g + c.b; }

uint64_t edgeKey(uint32_t a, uint32_t b) {
  return a < b ? uint64_t(a) << 32 | b : uint64_t(b) << 32 | a;
}

// A lattice of n = 2^L intervals along each edge of an element, in its hit parameters (u, v):
// points (i, j) at (i / n, j / n), row by row; on a triangle only those with i + j <= n.
struct Lattice {
  int count;  // the element's corners: 3 or 4
  int n;
  size_t rowStart(int j) const {
    return count == 4 ? size_t(j) * size_t(n + 1) : size_t(j) * size_t(n + 1) - size_t(j) * size_t(j - 1) / 2;
  }
  size_t size() const { return rowStart(n + 1); }
  size_t at(int i, int j) const { return rowStart(j) + size_t(i); }
  // Point k (0 to n) of the edge from corner c to the next one.
  std::array<int, 2> onEdge(int c, int k) const {
    if (count == 4) {
      switch (c) {
        case 0: return {k, 0};
        case 1: return {n, k};
        case 2: return {n - k, n};
        default: return {0, n - k};
      }
    }
    switch (c) {
      case 0: return {k, 0};
      case 1: return {n - k, k};
      default: return {0, n - k};
    }
  }
  // The interior points, in the order their gathers are listed.
  template <typename Visit>
  void forInterior(Visit&& visit) const {
    for (int j = 1; j < n; ++j)
      for (int i = 1; i < (count == 4 ? n : n - j); ++i) visit(i, j);
  }
};

// A point of a lattice gathered or interpolated: where, which way it faces, and the corners it is
// interpolated from (the element's, or the two ends of its edge) with their weights.
struct Point {
  Vec3 position, normal, towards;
  int side;
  int corners;
  std::array<uint32_t, 4> vertex;
  std::array<float, 4> weight;
};

struct Edge {
  int level = kMaxRefineLevels;  // the lowest lattice among the elements that share it
  int sharers = 0;
  Vec3 normal{0.0f}, centroids{0.0f};
  uint32_t firstPoint = 0;  // its points 1 to 2^level - 1, from its lower vertex up
};

}  // namespace

GatherRefinement::GatherRefinement(const SurfaceSet& surfaces, VertexGather& vertices,
                                   std::span<const float> elementWeights, std::span<const float> pixels)
    : surfaces_(surfaces), vertices_(vertices) {
  const size_t ne = surfaces.elements.size();
  std::vector<uint32_t> seen;
  for (uint32_t e = 0; e < ne; ++e)
    if (elementWeights.empty() || elementWeights[e] > 0.0f) seen.push_back(e);
  tbb::parallel_for(size_t(0), seen.size(), [&](size_t k) { vertices.corners(seen[k]); });
  double seenSum = 0.0;
  size_t seenCorners = 0;
  for (uint32_t e : seen) {
    const Rgb* c = vertices.corners(e);
    for (int k = 0; k < surfaces.elements[e].polygon.count; ++k) seenSum += channelSum(c[k]), ++seenCorners;
  }
  const float floor = seenCorners > 0 ? kRefineFloor * float(seenSum / double(seenCorners)) : 0.0f;

  // Each seen element's levels, from its own corners and centre alone (so any order of work gives
  // the same). An element is a candidate when one of its corners met a surface nearer than half
  // its size, and refined when a gather at its centre differs from the corners' interpolation
  // there by more than kRefineDeviation: a corner at a crease with a dark surface beyond, or the
  // corners all at creases and the middle darker, both show there.
  const uint32_t centreIndex = uint32_t(vertices.vertexCount());
  std::vector<uint8_t> levels(ne, 0);
  tbb::parallel_for(size_t(0), seen.size(), [&](size_t k) {
    const uint32_t e = seen[k];
    const Element& el = surfaces.elements[e];
    const Polygon& polygon = el.polygon;
    const Rgb* c = vertices.corners(e);
    float most = 0.0f, nearest = std::numeric_limits<float>::infinity(), size = 0.0f;
    int side = std::numeric_limits<int>::max();
    for (int i = 0; i < polygon.count; ++i) {
      most = std::max(most, channelSum(c[i]));
      const VertexGather::VertexView v = vertices.vertex(vertices.vertexOf(e, i));
      if (!v.inside) nearest = std::min(nearest, v.reach);
      side = std::min(side, v.side);
      size = std::max(size, glm::length(polygon.v[size_t((i + 1) % polygon.count)] - polygon.v[size_t(i)]));
    }
    // The spacing that the nearest corner's gather stays good over: within twice its reach; and
    // in a picture, cells of at least kPixelsPerCell pixels.
    float wanted = std::ceil(std::log2(size / (2.0f * nearest)));
    if (!pixels.empty()) wanted = std::min(wanted, std::floor(0.5f * std::log2(pixels[e] / kPixelsPerCell)));
    if (!(most > floor) || !(wanted > 0.0f)) return;
    const float centre = polygon.count == 4 ? 0.5f : 1.0f / 3.0f;
    const std::array<float, 4> w = cornerWeights(polygon.count, centre, centre);
    Vec3 position(0.0f);
    for (int i = 0; i < polygon.count; ++i) position += w[size_t(i)] * polygon.v[size_t(i)];
    const VertexGather::PointGather g = vertices.gatherAt(position, el.normal, el.centroid, side, centreIndex + e);
    // A centre inside a solid (one stands on the element) is refined too: its lattice keeps the
    // light beside the solid's foot apart from the hidden part.
    const float gathered = channelSum(g.irradiance);
    const float interpolated = channelSum(interpolateCorners(c, polygon.count, centre, centre));
    if (!g.inside && std::abs(gathered - interpolated) <= kRefineDeviation * std::max(gathered, interpolated)) return;
    levels[e] = uint8_t(std::min(wanted, float(kMaxRefineLevels)));
  });
  std::vector<uint32_t> refined;
  for (uint32_t e : seen)
    if (levels[e] > 0) refined.push_back(e);
  refined_ = refined.size();
  if (refined.empty()) return;

  // The refined elements' edges, and every element that shares one: an edge's points are one
  // gather at the coarsest lattice beside it, or none where an element there is not refined.
  // Edge c of element e, from corner c to the next, by its two vertices.
  const auto edgeOf = [&](uint32_t e, int c) {
    return edgeKey(vertices.vertexOf(e, c), vertices.vertexOf(e, (c + 1) % surfaces.elements[e].polygon.count));
  };
  std::unordered_map<uint64_t, Edge> edges;
  for (uint32_t e : refined) {
    const Element& el = surfaces.elements[e];
    for (int c = 0; c < el.polygon.count; ++c) {
      Edge& edge = edges[edgeOf(e, c)];
      edge.level = std::min(edge.level, int(levels[e]));
      ++edge.sharers;
      edge.normal += el.area * el.normal;
      edge.centroids += el.centroid;
    }
  }
  std::vector<uint8_t> sharesAnEdge(ne, 0);
  tbb::parallel_for(uint32_t(0), uint32_t(ne), [&](uint32_t e) {
    if (levels[e] > 0) return;
    for (int c = 0; c < surfaces.elements[e].polygon.count; ++c)
      if (edges.count(edgeOf(e, c))) sharesAnEdge[e] = 1;
  });
  for (uint32_t e = 0; e < ne; ++e) {
    if (!sharesAnEdge[e]) continue;
    for (int c = 0; c < surfaces.elements[e].polygon.count; ++c) {
      auto it = edges.find(edgeOf(e, c));
      if (it == edges.end()) continue;
      it->second.level = 0;
      ++it->second.sharers;
    }
  }

  // The points to gather: the shared edges' (in a fixed order, so the seeds are the same every
  // run), then each refined element's interior.
  std::vector<Point> points;
  std::vector<uint64_t> edgeOrder;
  edgeOrder.reserve(edges.size());
  for (const auto& [key, edge] : edges) edgeOrder.push_back(key);
  std::sort(edgeOrder.begin(), edgeOrder.end());
  for (uint64_t key : edgeOrder) {
    Edge& edge = edges[key];
    if (edge.sharers > 2) edge.level = 0;  // not one smooth surface: each side keeps its straight edge
    edge.firstPoint = uint32_t(points.size());
    const uint32_t a = uint32_t(key >> 32), b = uint32_t(key);
    const VertexGather::VertexView va = vertices.vertex(a), vb = vertices.vertex(b);
    const int n = 1 << edge.level;
    for (int m = 1; m < n; ++m) {
      const float f = float(m) / float(n);
      Point& p = points.emplace_back();
      p.position = va.position + f * (vb.position - va.position);
      p.normal = glm::normalize(edge.normal);
      p.towards = edge.centroids / float(std::max(edge.sharers, 1));
      p.side = std::min(va.side, vb.side);
      p.corners = 2;
      p.vertex = {a, b, 0, 0};
      p.weight = {1.0f - f, f, 0.0f, 0.0f};
    }
  }
  std::vector<uint32_t> interiorStart(ne, 0);
  for (uint32_t e : refined) {
    const Element& el = surfaces.elements[e];
    const Lattice lattice{el.polygon.count, 1 << levels[e]};
    interiorStart[e] = uint32_t(points.size());
    int side = std::numeric_limits<int>::max();
    std::array<uint32_t, 4> corner{};
    for (int c = 0; c < el.polygon.count; ++c) {
      corner[size_t(c)] = vertices.vertexOf(e, c);
      side = std::min(side, vertices.vertex(corner[size_t(c)]).side);
    }
    lattice.forInterior([&](int i, int j) {
      const std::array<float, 4> w =
          cornerWeights(el.polygon.count, float(i) / float(lattice.n), float(j) / float(lattice.n));
      Point& p = points.emplace_back();
      p.position = Vec3(0.0f);
      for (int c = 0; c < el.polygon.count; ++c) p.position += w[size_t(c)] * el.polygon.v[size_t(c)];
      p.normal = el.normal;
      p.towards = el.centroid;
      p.side = side;
      p.corners = el.polygon.count;
      p.vertex = corner;
      p.weight = w;
    });
  }

  // Each point gathered where a corner it is interpolated from saw a surface nearer than half
  // the point's distance from it, and interpolated elsewhere (VertexGather's split vertices).
  // A point inside a solid takes its corners outside one.
  std::vector<Rgb> pointValues(points.size());
  std::vector<uint8_t> traced(points.size(), 0);
  const uint32_t firstIndex = centreIndex + uint32_t(ne);
  tbb::parallel_for(size_t(0), points.size(), [&](size_t k) {
    const Point& p = points[k];
    Rgb interpolated(0.0f), outside(0.0f);
    float outsideWeight = 0.0f;
    bool trace = false;
    for (int c = 0; c < p.corners; ++c) {
      if (p.weight[size_t(c)] <= 0.0f) continue;
      const VertexGather::VertexView v = vertices.vertex(p.vertex[size_t(c)]);
      interpolated += p.weight[size_t(c)] * v.irradiance;
      if (!v.inside) outside += p.weight[size_t(c)] * v.irradiance, outsideWeight += p.weight[size_t(c)];
      trace = trace || v.inside || glm::length(p.position - v.position) * kInterpolationReach > v.reach;
    }
    pointValues[k] = interpolated;
    if (!trace) return;
    const VertexGather::PointGather g =
        vertices.gatherAt(p.position, p.normal, p.towards, p.side, firstIndex + uint32_t(k));
    traced[k] = 1;
    pointValues[k] = !g.inside ? g.irradiance : outsideWeight > 0.0f ? outside / outsideWeight : interpolated;
  });
  pointsMade_ = points.size();
  pointsTraced_ = size_t(std::count(traced.begin(), traced.end(), uint8_t(1)));

  // The lattices: corners as the element's corner slots, edges from their shared points (or
  // between them, where the edge's lattice is coarser), the interior from the element's own.
  latticeStart_.assign(ne, 0);
  size_t total = 0;
  for (uint32_t e : refined) {
    latticeStart_[e] = uint32_t(total);
    total += Lattice{surfaces.elements[e].polygon.count, 1 << levels[e]}.size();
  }
  values_.assign(total, Rgb(0.0f));
  tbb::parallel_for(size_t(0), refined.size(), [&](size_t r) {
    const uint32_t e = refined[r];
    const int count = surfaces.elements[e].polygon.count;
    const Lattice lattice{count, 1 << levels[e]};
    Rgb* out = &values_[latticeStart_[e]];
    const Rgb* slots = vertices.corners(e);
    const int n = lattice.n;
    for (int c = 0; c < count; ++c) {
      const auto [ci, cj] = lattice.onEdge(c, 0);
      out[lattice.at(ci, cj)] = slots[c];
    }
    for (int c = 0; c < count; ++c) {
      const int next = (c + 1) % count;
      const uint32_t va = vertices.vertexOf(e, c), vb = vertices.vertexOf(e, next);
      const Edge& edge = edges.at(edgeOf(e, c));
      const int steps = 1 << edge.level;
      // The edge's values from its lower vertex up: its ends (this element's slots there) and
      // its shared points.
      const bool forward = va < vb;
      const Rgb low = forward ? slots[c] : slots[next], high = forward ? slots[next] : slots[c];
      const auto edgeValue = [&](int m) {
        return m == 0 ? low : m == steps ? high : pointValues[edge.firstPoint + uint32_t(m - 1)];
      };
      for (int k = 1; k < n; ++k) {
        const float along = float(forward ? k : n - k) / float(n) * float(steps);  // exact: powers of two
        const int m = std::min(int(along), steps - 1);
        const float t = along - float(m);
        const auto [i, j] = lattice.onEdge(c, k);
        out[lattice.at(i, j)] = t == 0.0f ? edgeValue(m) : (1.0f - t) * edgeValue(m) + t * edgeValue(m + 1);
      }
    }
    uint32_t next = interiorStart[e];
    lattice.forInterior([&](int i, int j) { out[lattice.at(i, j)] = pointValues[next++]; });
  });
  levels_ = std::move(levels);
}

Rgb GatherRefinement::irradianceAt(uint32_t e, float u, float v) const {
  const int count = surfaces_.elements[e].polygon.count;
  if (levels_.empty() || levels_[e] == 0) return interpolateCorners(vertices_.corners(e), count, u, v);
  const Lattice lattice{count, 1 << levels_[e]};
  const Rgb* values = &values_[latticeStart_[e]];
  const float n = float(lattice.n);
  const float x = std::clamp(u, 0.0f, 1.0f) * n, y = std::clamp(v, 0.0f, 1.0f) * n;
  int i = std::min(int(x), lattice.n - 1), j = std::min(int(y), lattice.n - 1);
  if (count == 4) {
    const float s = x - float(i), t = y - float(j);
    return (1.0f - s) * (1.0f - t) * values[lattice.at(i, j)] + s * (1.0f - t) * values[lattice.at(i + 1, j)] +
           s * t * values[lattice.at(i + 1, j + 1)] + (1.0f - s) * t * values[lattice.at(i, j + 1)];
  }
  // A triangle's cell (i, j) is the one at (i, j), (i + 1, j), (i, j + 1), and above its diagonal
  // the one at (i + 1, j + 1), (i, j + 1), (i + 1, j).
  if (i + j > lattice.n - 1) {
    // Past the long edge by rounding: the last cell of the row.
    i = std::max(0, lattice.n - 1 - j);
  }
  const float s = x - float(i), t = y - float(j);
  if (s + t <= 1.0f || i + j == lattice.n - 1)
    return (1.0f - s - t) * values[lattice.at(i, j)] + s * values[lattice.at(i + 1, j)] +
           t * values[lattice.at(i, j + 1)];
  return (1.0f - t) * values[lattice.at(i + 1, j)] + (1.0f - s) * values[lattice.at(i, j + 1)] +
         (s + t - 1.0f) * values[lattice.at(i + 1, j + 1)];
}

Rgb GatherRefinement::mean(uint32_t e) const {
  const int count = surfaces_.elements[e].polygon.count;
  if (levels_.empty() || levels_[e] == 0) {
    const Rgb* c = vertices_.corners(e);
    Rgb sum(0.0f);
    for (int k = 0; k < count; ++k) sum += c[k];
    return sum / float(count);
  }
  // Over each cell the interpolation's mean is its corners' (triangles; quads as parallelograms).
  const Lattice lattice{count, 1 << levels_[e]};
  const Rgb* values = &values_[latticeStart_[e]];
  const int n = lattice.n;
  Rgb sum(0.0f);
  if (count == 4) {
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        sum += 0.25f * (values[lattice.at(i, j)] + values[lattice.at(i + 1, j)] + values[lattice.at(i + 1, j + 1)] +
                        values[lattice.at(i, j + 1)]);
    return sum / float(n * n);
  }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i + j < n; ++i) {
      sum += (values[lattice.at(i, j)] + values[lattice.at(i + 1, j)] + values[lattice.at(i, j + 1)]) / 3.0f;
      if (i + j < n - 1)
        sum += (values[lattice.at(i + 1, j)] + values[lattice.at(i, j + 1)] + values[lattice.at(i + 1, j + 1)]) / 3.0f;
    }
  return sum / float(n * n);
}

}  // namespace luxel
