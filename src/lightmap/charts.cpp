// Chart segmentation: welding by position, edge adjacency, and region growing by normal.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <unordered_map>

#include "lightmap/atlas_internal.h"

namespace luxel::lightmap {
namespace {

uint64_t edgeKey(uint32_t a, uint32_t b) {
  if (a > b) std::swap(a, b);
  return (uint64_t(a) << 32) | b;
}

// Faces across each edge shared by exactly two faces (manifold edges); other edges are borders.
std::vector<std::vector<uint32_t>> adjacency(const WeldedMesh& w) {
  std::unordered_map<uint64_t, std::array<int64_t, 2>> edges;  // first face, second face (-1 none, -2 more)
  edges.reserve(w.v.size() * 3);
  for (uint32_t f = 0; f < w.v.size(); ++f) {
    int n = w.corners[f];
    for (int i = 0; i < n; ++i) {
      uint32_t a = w.v[f][size_t(i)], b = w.v[f][size_t((i + 1) % n)];
      if (a == b) continue;
      auto [it, fresh] = edges.try_emplace(edgeKey(a, b), std::array<int64_t, 2>{f, -1});
      if (fresh) continue;
      if (it->second[1] == -1 && it->second[0] != f) it->second[1] = f;
      else it->second[1] = -2;
    }
  }
  std::vector<std::vector<uint32_t>> adj(w.v.size());
  for (const auto& [key, faces] : edges) {
    if (faces[1] < 0) continue;
    adj[size_t(faces[0])].push_back(uint32_t(faces[1]));
    adj[size_t(faces[1])].push_back(uint32_t(faces[0]));
  }
  return adj;
}

}  // namespace

WeldedMesh weld(const Mesh& mesh) {
  WeldedMesh w;
  Vec3 lo(INFINITY), hi(-INFINITY);
  for (Vec3 p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  // Positions closer than a millionth of the mesh's size are one vertex (cells of that size).
  float cell = std::max(glm::length(hi - lo) * 1e-6f, 1e-12f);
  std::unordered_map<uint64_t, uint32_t> cells;
  std::vector<uint32_t> remap(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    glm::dvec3 q = glm::floor(glm::dvec3(mesh.positions[i] - lo) / double(cell) + 0.5);
    uint64_t key = (uint64_t(q.x) * 73856093ull) ^ (uint64_t(q.y) * 19349663ull << 21) ^
                   (uint64_t(q.z) * 83492791ull << 42);
    // Collisions of the hash are told apart by comparing the cells exactly.
    for (;; ++key) {
      auto [it, fresh] = cells.try_emplace(key, uint32_t(w.positions.size()));
      if (fresh) {
        w.positions.push_back(mesh.positions[i]);
        remap[i] = it->second;
        break;
      }
      glm::dvec3 other = glm::floor(glm::dvec3(w.positions[it->second] - lo) / double(cell) + 0.5);
      if (other == q) {
        remap[i] = it->second;
        break;
      }
    }
  }
  size_t n = mesh.faces.size();
  w.v.resize(n), w.corners.resize(n), w.normal.resize(n), w.area.resize(n);
  for (size_t f = 0; f < n; ++f) {
    const Face& face = mesh.faces[f];
    int k = face.vertexCount();
    w.corners[f] = k;
    for (int i = 0; i < 4; ++i) w.v[f][size_t(i)] = remap[face.v[size_t(i)]];
    // Newell's normal: twice the vector area, for triangles and (possibly warped) quads alike.
    glm::dvec3 nv(0.0);
    for (int i = 0; i < k; ++i) {
      glm::dvec3 a = mesh.positions[face.v[size_t(i)]], b = mesh.positions[face.v[size_t((i + 1) % k)]];
      nv += glm::cross(a, b);
    }
    double len = glm::length(nv);
    w.area[f] = float(0.5 * len);
    w.normal[f] = len > 0.0 ? Vec3(nv / len) : Vec3(0.0f);
  }
  return w;
}

Vec3 meanNormal(const WeldedMesh& w, const std::vector<uint32_t>& faces) {
  glm::dvec3 sum(0.0);
  for (uint32_t f : faces) sum += glm::dvec3(w.normal[f]) * double(w.area[f]);
  double len = glm::length(sum);
  return len > 0.0 ? Vec3(sum / len) : Vec3(0, 0, 1);
}

float maxNormalDeviation(const WeldedMesh& w, const std::vector<uint32_t>& faces, Vec3 mean) {
  float minDot = 1.0f;
  for (uint32_t f : faces)
    if (w.area[f] > 0.0f) minDot = std::min(minDot, glm::dot(w.normal[f], mean));
  return std::acos(std::clamp(minDot, -1.0f, 1.0f));
}

std::vector<Chart> segmentCharts(const WeldedMesh& w, uint32_t meshIndex, float maxAngle) {
  const auto adj = adjacency(w);
  const float cosMax = std::cos(maxAngle);
  std::vector<int64_t> chartOf(w.v.size(), -1);
  std::vector<Chart> charts;
  // Seeds in order of decreasing area, so the big flat parts start charts and keep them whole.
  std::vector<uint32_t> order(w.v.size());
  for (uint32_t f = 0; f < order.size(); ++f) order[f] = f;
  std::stable_sort(order.begin(), order.end(),
                   [&](uint32_t a, uint32_t b) { return w.area[a] > w.area[b]; });
  std::deque<uint32_t> queue;
  for (uint32_t seed : order) {
    if (chartOf[seed] >= 0) continue;
    Chart chart;
    chart.mesh = meshIndex;
    const int64_t id = int64_t(charts.size());
    chartOf[seed] = id;
    chart.faces.push_back(seed);
    // Degenerate faces (no normal) stay alone: they cover nothing and flatten to nothing.
    if (w.area[seed] > 0.0f) {
      glm::dvec3 sum = glm::dvec3(w.normal[seed]) * double(w.area[seed]);
      queue.assign(1, seed);
      while (!queue.empty()) {
        uint32_t f = queue.front();
        queue.pop_front();
        for (uint32_t g : adj[f]) {
          if (chartOf[g] >= 0 || w.area[g] <= 0.0f) continue;
          Vec3 mean = Vec3(glm::normalize(sum));
          if (glm::dot(w.normal[g], mean) < cosMax) continue;
          chartOf[g] = id;
          chart.faces.push_back(g);
          sum += glm::dvec3(w.normal[g]) * double(w.area[g]);
          queue.push_back(g);
        }
      }
    }
    charts.push_back(std::move(chart));
  }
  return charts;
}

std::vector<std::vector<uint32_t>> connectedComponents(const WeldedMesh& w,
                                                       const std::vector<uint32_t>& faces) {
  // Union-find over the faces, joined where two of them share a welded edge.
  std::vector<uint32_t> parent(faces.size());
  for (uint32_t i = 0; i < parent.size(); ++i) parent[i] = i;
  auto find = [&](uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::unordered_map<uint64_t, uint32_t> edges;
  for (uint32_t i = 0; i < faces.size(); ++i) {
    uint32_t f = faces[i];
    int n = w.corners[f];
    for (int k = 0; k < n; ++k) {
      uint32_t a = w.v[f][size_t(k)], b = w.v[f][size_t((k + 1) % n)];
      if (a == b) continue;
      auto [it, fresh] = edges.try_emplace(edgeKey(a, b), i);
      if (!fresh) parent[find(i)] = find(it->second);
    }
  }
  std::unordered_map<uint32_t, size_t> index;
  std::vector<std::vector<uint32_t>> out;
  for (uint32_t i = 0; i < faces.size(); ++i) {
    auto [it, fresh] = index.try_emplace(find(i), out.size());
    if (fresh) out.emplace_back();
    out[it->second].push_back(faces[i]);
  }
  return out;
}

}  // namespace luxel::lightmap
