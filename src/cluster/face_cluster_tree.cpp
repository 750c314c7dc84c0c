#include "cluster/face_cluster_tree.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <numeric>
#include <span>
#include <type_traits>
#ifdef __GLIBC__
#include <malloc.h>  // malloc_trim
#endif

#include <fmt/format.h>

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "core/stopwatch.h"
#include "luxel/error.h"

namespace luxel {

float FaceCluster::selfFormFactorBound() const {
  if (convex || area <= 0.0f) return 0.0f;
  // Separate pieces can light each other whatever their normals, which the bound does not see
  // (docs/algorithms.md, "Face-cluster radiosity", item 5).
  if (!connected) return 1.0f;
  return std::clamp(1.0f - glm::length(vectorArea) / area, 0.0f, 1.0f);
}

namespace {

// What contraction needs to know of a cluster (Garland et al. 2001, section 3): moments of its
// area for the best-fit plane, its vector area for the spread of its normals, its perimeter for
// its shape, and its material.
struct Moments {
  double area = 0.0;
  glm::dvec3 vectorArea{0.0};
  glm::dvec3 first{0.0};            // sum A c
  std::array<double, 6> second{};   // sum A c c^T: xx, yy, zz, xy, xz, yz
  double perimeter = 0.0;
  glm::dvec3 reflectance{0.0};      // sum A rho
  bool emits = false;
  bool convex = true;

  void add(const Moments& o) {
    area += o.area, vectorArea += o.vectorArea, first += o.first, perimeter += o.perimeter;
    for (int i = 0; i < 6; ++i) second[size_t(i)] += o.second[size_t(i)];
    reflectance += o.reflectance;
    emits = emits || o.emits;
    convex = convex && o.convex;
  }
};

// A single element's moments.
Moments elementMoments(const Element& el) {
  Moments m;
  const glm::dvec3 c(el.centroid);
  m.area = el.area;
  m.vectorArea = glm::dvec3(el.normal) * double(el.area);
  m.first = c * double(el.area);
  m.second = {el.area * c.x * c.x, el.area * c.y * c.y, el.area * c.z * c.z,
              el.area * c.x * c.y, el.area * c.x * c.z, el.area * c.y * c.z};
  for (int k = 0; k < el.polygon.count; ++k)
    m.perimeter += glm::length(el.polygon.v[size_t((k + 1) % el.polygon.count)] - el.polygon.v[size_t(k)]);
  m.reflectance = glm::dvec3(el.reflectance) * double(el.area);
  m.emits = el.exitance.r > 0 || el.exitance.g > 0 || el.exitance.b > 0;
  return m;
}

struct Neighbour {
  uint32_t node;
  float length;  // of the boundary shared with it
  bool convex;   // no edge of that boundary is concave
};

// Compactness decides between flat merges only: uncapped, a ragged union on a flat grid could cost
// more than crossing a right-angled crease (bend 1).
constexpr double kMostIrregularity = 2.0;

// The cost of contracting a and b (sharing a boundary of `shared` length): how far the union is
// from a plane (mean squared distance over area), how spread its normals are (1 - |sum A n| / A,
// Willmott's bound on its self form factor), how far apart the parts' mean normals are, how much
// less compact it is than either part (perimeter^2 / (4 pi A), weighted 0.1 as Garland et al.
// weigh shape, capped), and whether it joins different materials or an emitter to a non-emitter.
double contractionCost(const Moments& a, const Moments& b, double shared) {
  const double area = a.area + b.area;
  if (area <= 0.0) return 0.0;
  const glm::dvec3 va = a.vectorArea + b.vectorArea;
  const double spread = std::max(0.0, 1.0 - glm::length(va) / area);
  const glm::dvec3 mean = (a.first + b.first) / area;
  std::array<double, 6> c;
  const double mm[6] = {mean.x * mean.x, mean.y * mean.y, mean.z * mean.z, mean.x * mean.y, mean.x * mean.z, mean.y * mean.z};
  for (int i = 0; i < 6; ++i) c[size_t(i)] = (a.second[size_t(i)] + b.second[size_t(i)]) / area - mm[i];
  const double fit = std::max(0.0, smallestEigenvalue(c)) / area;
  auto irregularity = [](double perimeter, double area) {
    return area > 0.0 ? perimeter * perimeter / (4.0 * std::numbers::pi * area) : 0.0;
  };
  const double perimeter = std::max(0.0, a.perimeter + b.perimeter - 2.0 * shared);
  const double shape = std::max(0.0, irregularity(perimeter, area) -
                                          std::max(irregularity(a.perimeter, a.area), irregularity(b.perimeter, b.area)));
  const glm::dvec3 ra = a.area > 0 ? a.reflectance / a.area : glm::dvec3(0), rb = b.area > 0 ? b.reflectance / b.area : glm::dvec3(0);
  const glm::dvec3 dr = glm::abs(ra - rb);
  const double material = std::max({dr.x, dr.y, dr.z}) + (a.emits != b.emits ? 1.0 : 0.0);
  // The angle between the parts' mean normals, whatever their areas: the terms above weigh by
  // area, so one face across a crease joins a large flat cluster almost free, and a wall whose
  // cluster has a fringe of the next wall faces no emitter wholly (the solver then refines it or
  // takes its light as harmonics, hierarchical_solver.cpp).
  const double la = glm::length(a.vectorArea), lb = glm::length(b.vectorArea);
  const double bend = la > 0.0 && lb > 0.0 ? std::max(0.0, 1.0 - glm::dot(a.vectorArea, b.vectorArea) / (la * lb)) : 1.0;
  return fit + spread + 0.1 * std::min(shape, kMostIrregularity) + material + bend;
}

struct DualEdge {
  double cost;
  uint32_t a, b;
  double length;  // of the boundary a and b share
  bool operator>(const DualEdge& o) const {
    if (cost != o.cost) return cost > o.cost;
    return a != o.a ? a > o.a : b > o.b;  // ties broken by index: the same tree every run
  }
};

// Which of the face's corners the parameters (s, t) name, or -1 inside or along an edge.
int faceCornerAt(const SurfaceFace& face, Vec2 st) {
  if (st == Vec2(0, 0)) return 0;
  if (st == Vec2(1, 0)) return 1;
  if (face.triangle) return st == Vec2(0, 1) ? 2 : -1;
  if (st == Vec2(1, 1)) return 2;
  return st == Vec2(0, 1) ? 3 : -1;
}

// Corners at exactly the same position are the same vertex.
std::vector<uint32_t> weldCorners(const SurfaceSet& s, std::vector<uint32_t>& firstCorner) {
  struct Corner {
    std::array<uint32_t, 3> bits;
    uint32_t index;
  };
  std::vector<Corner> corners;
  firstCorner.assign(s.elements.size() + 1, 0);
  for (size_t e = 0; e < s.elements.size(); ++e) {
    firstCorner[e] = uint32_t(corners.size());
    const Element& el = s.elements[e];
    const SurfaceFace& face = s.faces[el.face];
    const Polygon& p = el.polygon;
    // Elements made without face parameters (lightmap texels) have them all zero: their corners
    // are taken as they are, or every corner would become the face's first.
    const bool hasParameters = el.param[1] != el.param[0] || el.param[2] != el.param[0];
    for (int c = 0; c < p.count; ++c) {
      Corner k;
      // A corner at one of its face's corners takes the face's own position: the one computed
      // from the face's parameters can differ from it in the last bit, and then two faces that
      // share a mesh vertex would not be found adjacent.
      Vec3 v = p.v[size_t(c)];
      const Vec2 st = el.param[size_t(c)];
      const int corner = hasParameters ? faceCornerAt(face, st) : -1;
      if (corner >= 0) v = face.corners[size_t(corner)];
      v += Vec3(0.0f);  // -0 and +0 alike
      std::memcpy(k.bits.data(), &v, sizeof(v));
      k.index = uint32_t(corners.size());
      corners.push_back(k);
    }
  }
  firstCorner[s.elements.size()] = uint32_t(corners.size());
  std::vector<Corner> sorted = corners;
  tbb::parallel_sort(sorted.begin(), sorted.end(), [](const Corner& a, const Corner& b) {
    return a.bits != b.bits ? a.bits < b.bits : a.index < b.index;
  });
  std::vector<uint32_t> vertex(corners.size());
  uint32_t id = 0;
  for (size_t i = 0; i < sorted.size(); ++i) {
    if (i > 0 && sorted[i].bits != sorted[i - 1].bits) ++id;
    vertex[sorted[i].index] = id;
  }
  return vertex;
}

}  // namespace

FaceClusterTree::Depth FaceClusterTree::depth() const {
  Depth d;
  const size_t nodes = nodeCount();
  if (nodes == 0) return d;
  std::vector<uint32_t> at(nodes, 0);
  double sum = 0.0;
  // Parents come after their children: a pass from the root down, in reverse index order.
  for (size_t i = nodes; i-- > 0;) {
    const uint32_t p = parent(uint32_t(i));
    if (p != kNoCluster) at[i] = at[p] + 1;
    d.max = std::max(d.max, at[i]);
    if (isLeaf(uint32_t(i))) sum += at[i];
  }
  d.meanLeaf = order.empty() ? 0.0 : sum / double(order.size());
  return d;
}

namespace {

// The fields a cluster, leaf or joined, takes from its moments.
void setFromMoments(FaceCluster& c, const Moments& m) {
  c.area = float(m.area);
  c.vectorArea = Vec3(m.vectorArea);
  c.reflectance = m.area > 0 ? Rgb(m.reflectance / m.area) : Rgb(0.0f);
  c.convex = m.convex;
}

// One element's projected area along +- each of the cluster's box axes, added to the cluster's.
void addAxisAreas(FaceCluster& c, const Element& el) {
  for (int j = 0; j < 3; ++j) {
    const float d = glm::dot(el.normal, c.box.axis[size_t(j)]) * el.area;
    c.axisAreas[size_t(j)] += std::max(0.0f, d), c.axisAreas[size_t(j) + 3] += std::max(0.0f, -d);
  }
}

}  // namespace

FaceCluster leafCluster(const Element& el, uint32_t at, uint32_t parent) {
  // The same arithmetic as a joined node's fields, so that a leaf made here is the leaf the tree
  // once stored, to the bit.
  FaceCluster c;
  c.begin = at, c.count = 1, c.parent = parent;
  setFromMoments(c, elementMoments(el));
  c.cone = {el.normal, 1.0f};
  c.box = fitOrientedBox({el.polygon.v.data(), size_t(el.polygon.count)}, el.normal);
  addAxisAreas(c, el);
  return c;
}

FaceCluster FaceClusterTree::node(uint32_t i, const SurfaceSet& surfaces) const {
  return isLeaf(i) ? leafCluster(surfaces.elements[i], leafAt[i], leafParent[i]) : joined(i);
}

FaceClusterTree buildFaceClusterTree(const SurfaceSet& surfaces) {
  const Stopwatch watch;
  const size_t n = surfaces.elements.size();
  if (n == 0) throw Error("face clusters: the scene has no elements");
  if (n >= size_t(kNoCluster) / 2) throw Error(fmt::format("face clusters: {} elements is more than the hierarchy indexes", n));
  FaceClusterTree tree;
  // The tree's shape while it is built; its nodes (156 bytes each) are made only once the build's
  // temporaries are gone, which at 1.5M faces kept 400 MB off the peak.
  std::vector<std::array<uint32_t, 2>> childOf(2 * n - 1, {kNoCluster, kNoCluster});
  std::vector<uint32_t> parentOf(2 * n - 1, kNoCluster);
  std::vector<uint8_t> joinsPieces(2 * n - 1, 0);  // FaceCluster::connected false
  // The inner nodes' moments; a leaf's come from its element when asked (elementMoments): the
  // leaves are half the nodes, and storing theirs made the build's peak a fifth larger.
  std::vector<Moments> inner(n - 1);
  auto momentsOf = [&](uint32_t i) { return i < n ? elementMoments(surfaces.elements[i]) : inner[i - n]; };
  auto innerMoments = [&](uint32_t i) -> Moments& { return inner[i - n]; };
  std::vector<Vec3> lo(2 * n - 1), hi(2 * n - 1);
  std::vector<std::vector<Neighbour>> adjacency(2 * n - 1);
  std::vector<uint8_t> alive(2 * n - 1, 0);

  for (size_t e = 0; e < n; ++e) {
    const Element& el = surfaces.elements[e];
    lo[e] = hi[e] = el.polygon.v[0];
    for (int k = 1; k < el.polygon.count; ++k)
      lo[e] = glm::min(lo[e], el.polygon.v[size_t(k)]), hi[e] = glm::max(hi[e], el.polygon.v[size_t(k)]);
    alive[e] = 1;
  }

  // The dual graph: elements that share an edge, with the edge's length and whether the surface
  // folds away (convex) or towards itself (concave) across it.
  {
    std::vector<uint32_t> firstCorner;
    const std::vector<uint32_t> vertex = weldCorners(surfaces, firstCorner);
    struct Edge {
      uint64_t key;
      uint32_t element;
      float length;
    };
    std::vector<Edge> edges;
    edges.reserve(vertex.size());
    for (size_t e = 0; e < n; ++e) {
      const Polygon& p = surfaces.elements[e].polygon;
      for (int k = 0; k < p.count; ++k) {
        const uint32_t a = vertex[firstCorner[e] + uint32_t(k)], b = vertex[firstCorner[e] + uint32_t((k + 1) % p.count)];
        if (a == b) continue;
        edges.push_back({uint64_t(std::min(a, b)) << 32 | std::max(a, b), uint32_t(e),
                         glm::length(p.v[size_t((k + 1) % p.count)] - p.v[size_t(k)])});
      }
    }
    tbb::parallel_sort(edges.begin(), edges.end(), [](const Edge& a, const Edge& b) {
      return a.key != b.key ? a.key < b.key : a.element < b.element;
    });
    for (size_t i = 0; i < edges.size();) {
      size_t j = i + 1;
      while (j < edges.size() && edges[j].key == edges[i].key) ++j;
      // Usually two elements; a non-manifold edge links every pair (at most a few).
      for (size_t x = i; x < j && x < i + 8; ++x)
        for (size_t y = x + 1; y < j && y < i + 8; ++y) {
          const uint32_t a = edges[x].element, b = edges[y].element;
          if (a == b) continue;
          const Element &ea = surfaces.elements[a], &eb = surfaces.elements[b];
          const float tolerance = 1e-4f * edges[x].length;
          const bool convex = glm::dot(ea.normal, eb.centroid - ea.centroid) <= tolerance &&
                              glm::dot(eb.normal, ea.centroid - eb.centroid) <= tolerance;
          adjacency[a].push_back({b, edges[x].length, convex});
          adjacency[b].push_back({a, edges[x].length, convex});
        }
      i = j;
    }
  }
  // One entry per neighbour (two elements of a split face can share two edges).
  auto combine = [](std::vector<Neighbour>& list) {
    std::sort(list.begin(), list.end(), [](const Neighbour& a, const Neighbour& b) { return a.node < b.node; });
    size_t out = 0;
    for (size_t i = 0; i < list.size(); ++i) {
      if (out > 0 && list[out - 1].node == list[i].node) {
        list[out - 1].length += list[i].length;
        list[out - 1].convex = list[out - 1].convex && list[i].convex;
      } else {
        list[out++] = list[i];
      }
    }
    list.resize(out);
  };
  for (uint32_t e = 0; e < n; ++e) combine(adjacency[e]);

  auto link = [&](uint32_t parent, uint32_t a, uint32_t b) {
    childOf[parent] = {a, b};
    parentOf[a] = parentOf[b] = parent;
    Moments& m = innerMoments(parent);
    m = momentsOf(a);
    m.add(momentsOf(b));
    lo[parent] = glm::min(lo[a], lo[b]), hi[parent] = glm::max(hi[a], hi[b]);
  };

  uint32_t next = uint32_t(n);  // the next node made

  // Separate pieces (components that share no edge, or a merge's satellites below) are joined by
  // median splits along the widest axis of their boxes' centres: a balanced subtree over them.
  auto join = [&](auto& self, std::span<uint32_t> part) -> uint32_t {
    if (part.size() == 1) return part[0];
    Vec3 clo(std::numeric_limits<float>::max()), chi(-std::numeric_limits<float>::max());
    for (uint32_t r : part) {
      const Vec3 centre = 0.5f * (lo[r] + hi[r]);
      clo = glm::min(clo, centre), chi = glm::max(chi, centre);
    }
    const Vec3 extent = chi - clo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const size_t half = part.size() / 2;
    std::nth_element(part.begin(), part.begin() + std::ptrdiff_t(half), part.end(), [&](uint32_t x, uint32_t y) {
      const float cx = lo[x][axis] + hi[x][axis], cy = lo[y][axis] + hi[y][axis];
      return cx != cy ? cx < cy : x < y;
    });
    const uint32_t left = self(self, part.subspan(0, half));
    const uint32_t right = self(self, part.subspan(half));
    const uint32_t c = next++;
    link(c, left, right);
    innerMoments(c).convex = false;
    joinsPieces[c] = 1;
    return c;
  };

  // Contraction in rounds: in each, the dual edges in order of cost, each cluster paired at most
  // once. Garland et al. contract one edge at a time from a single heap, and on a surface of
  // equal faces (a wall cut into a grid) that grows one cluster a face at a time: a tree
  // thousands of levels deep, whose splits peel single faces off and whose traversal overflows
  // the stack. Rounds keep the tree about log n deep, and the costs of a round are computed in
  // parallel. A cluster waits for a later round rather than take a partner much worse than its
  // best (kWorseFactor, or kCostTie when costs are near zero, as on a flat grid), so that a crease
  // is not crossed while a flat neighbour is still to be had.
  //
  // Waiting alone makes chains on curved scans: a thin or nearly degenerate face whose normal
  // disagrees with its neighbours' waits until they have all become one large cluster, and then
  // that cluster has dozens of such faces on its border and took one per round (the scanned
  // statues' trees were hundreds of levels deep, docs/algorithms.md "The hierarchy"). So a
  // cluster left unpaired in a round joins a neighbour that was paired, when their edge passes the
  // same bar, as a satellite: a pair's satellites are joined into a balanced subtree (by `join`)
  // and that subtree to the pair, so a round adds about log k levels for k satellites, not k.
  constexpr double kWorseFactor = 2.0, kCostTie = 0.05, kSatelliteShare = 0.125;
  std::vector<uint32_t> active(n), rep(2 * n - 1);
  std::iota(active.begin(), active.end(), 0u);
  std::iota(rep.begin(), rep.end(), 0u);
  std::vector<double> best(2 * n - 1);
  std::vector<uint32_t> mergeOf(2 * n - 1, kNoCluster);  // this round's merge a cluster is in
  std::vector<DualEdge> edges;
  struct Merge {
    uint32_t a, b;
    std::vector<uint32_t> satellites;
    uint32_t pair = kNoCluster;  // the union of a and b
    uint32_t node = kNoCluster;  // of a, b and the satellites (the pair when there are none)
  };
  std::vector<Merge> merges;
  auto bar = [&](const DualEdge& edge) {
    return std::max(kWorseFactor * std::min(best[edge.a], best[edge.b]), kCostTie);
  };
  while (true) {
    edges.clear();
    for (uint32_t a : active)
      for (const Neighbour& nb : adjacency[a])
        if (nb.node > a) edges.push_back({0.0, a, nb.node, nb.length});
    if (edges.empty()) break;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, edges.size(), 256), [&](const tbb::blocked_range<size_t>& range) {
      for (size_t k = range.begin(); k != range.end(); ++k) {
        DualEdge& edge = edges[k];
        edge.cost = contractionCost(momentsOf(edge.a), momentsOf(edge.b), edge.length);
      }
    });
    tbb::parallel_sort(edges.begin(), edges.end(), [](const DualEdge& x, const DualEdge& y) { return y > x; });
    for (uint32_t a : active) best[a] = std::numeric_limits<double>::max(), mergeOf[a] = kNoCluster;
    for (const DualEdge& edge : edges) best[edge.a] = std::min(best[edge.a], edge.cost), best[edge.b] = std::min(best[edge.b], edge.cost);
    merges.clear();
    for (const DualEdge& edge : edges) {
      if (mergeOf[edge.a] != kNoCluster || mergeOf[edge.b] != kNoCluster || edge.cost > bar(edge)) continue;
      mergeOf[edge.a] = mergeOf[edge.b] = uint32_t(merges.size());
      merges.push_back({edge.a, edge.b, {}});
    }
    // Satellites attach to a paired cluster (a or b of a merge), never to another satellite, so
    // a round cannot sweep a whole region into one cluster.
    for (const DualEdge& edge : edges) {
      const uint32_t ma = mergeOf[edge.a], mb = mergeOf[edge.b];
      if ((ma == kNoCluster) == (mb == kNoCluster) || edge.cost > bar(edge)) continue;
      const uint32_t host = ma != kNoCluster ? edge.a : edge.b, satellite = ma != kNoCluster ? edge.b : edge.a;
      Merge& merge = merges[mergeOf[host]];
      if ((host != merge.a && host != merge.b) || momentsOf(satellite).area > kSatelliteShare * momentsOf(host).area) continue;
      mergeOf[satellite] = mergeOf[host];
      merge.satellites.push_back(satellite);
    }
    // The new nodes, in order (each after its children); cheap, so sequential.
    for (Merge& merge : merges) {
      merge.pair = merge.node = next++;
      link(merge.pair, merge.a, merge.b);
      if (!merge.satellites.empty()) {
        const uint32_t group = join(join, merge.satellites);
        merge.node = next++;
        link(merge.node, merge.pair, group);
      }
      rep[merge.a] = rep[merge.b] = merge.node;
      for (uint32_t s : merge.satellites) rep[s] = merge.node;
    }
    // Each union's convexity, and the neighbour lists of every cluster of the next round, with the
    // merged clusters renamed (lists are private to their cluster, so this is parallel too).
    tbb::parallel_for(size_t(0), merges.size(), [&](size_t k) {
      const Merge& merge = merges[k];
      const uint32_t c = merge.node;
      bool convex = true;
      std::vector<Neighbour>& list = adjacency[c];
      auto gather = [&](uint32_t member) {
        convex = convex && momentsOf(member).convex;
        for (const Neighbour& nb : adjacency[member]) {
          if (rep[nb.node] == c)
            convex = convex && nb.convex;
          else
            list.push_back({rep[nb.node], nb.length, nb.convex});
        }
      };
      gather(merge.a), gather(merge.b);
      if (merge.pair != c) {
        bool pairConvex = momentsOf(merge.a).convex && momentsOf(merge.b).convex;
        for (const Neighbour& nb : adjacency[merge.a])
          if (nb.node == merge.b) pairConvex = pairConvex && nb.convex;
        innerMoments(merge.pair).convex = pairConvex;
      }
      for (uint32_t s : merge.satellites) gather(s);
      innerMoments(c).convex = convex;
      combine(list);
    });
    tbb::parallel_for(size_t(0), active.size(), [&](size_t k) {
      const uint32_t a = active[k];
      if (mergeOf[a] != kNoCluster) return;
      for (Neighbour& nb : adjacency[a]) nb.node = rep[nb.node];
      combine(adjacency[a]);
    });
    size_t kept = 0;
    for (uint32_t a : active) {
      if (mergeOf[a] != kNoCluster) {
        std::vector<Neighbour>().swap(adjacency[a]);
        alive[a] = 0;
      } else {
        active[kept++] = a;
      }
    }
    active.resize(kept);
    for (const Merge& merge : merges) active.push_back(merge.node), alive[merge.node] = 1;
  }

  // The components that share no edge, joined so that the root holds everything.
  std::vector<uint32_t> roots;
  for (uint32_t i = 0; i < next; ++i)
    if (alive[i]) roots.push_back(i);
  tree.components = uint32_t(roots.size());
  tree.root = join(join, roots);
  auto release = [](auto& v) { std::decay_t<decltype(v)>().swap(v); };
  release(adjacency), release(lo), release(hi), release(alive), release(active), release(rep), release(best);
  release(mergeOf), release(edges), release(merges), release(roots);
#ifdef __GLIBC__
  malloc_trim(0);  // the neighbour lists were many small blocks: give their pages back before the nodes come
#endif
  tree.inner.resize(next - n);
  for (uint32_t i = uint32_t(n); i < next; ++i) {
    FaceCluster& c = tree.inner[i - n];
    c.child = childOf[i], c.parent = parentOf[i], c.connected = joinsPieces[i] == 0;
  }
  tree.leafParent.assign(parentOf.begin(), parentOf.begin() + std::ptrdiff_t(n));
  release(childOf), release(parentOf), release(joinsPieces);

  // Each cluster's elements contiguous: the leaves in depth-first order.
  tree.order.reserve(n);
  tree.leafAt.assign(n, 0);
  std::vector<uint32_t> stack{tree.root};
  while (!stack.empty()) {
    const uint32_t i = stack.back();
    stack.pop_back();
    if (i < n) {  // (not isLeaf, which counts the order being made)
      tree.leafAt[i] = uint32_t(tree.order.size());
      tree.order.push_back(i);
    } else {
      stack.push_back(tree.inner[i - n].child[1]);
      stack.push_back(tree.inner[i - n].child[0]);
    }
  }

  // Each joined node's geometry from its children (a leaf's made from its element when read),
  // level by level (a node's children are below it), each level in parallel. In one sequential
  // pass this was a third of the build at 1.5M faces.
  auto fill = [&](uint32_t i) {
    FaceCluster& c = tree.inner[i - n];
    setFromMoments(c, momentsOf(i));
    const FaceCluster a = tree.node(c.child[0], surfaces), b = tree.node(c.child[1], surfaces);
    c.begin = std::min(a.begin, b.begin), c.count = a.count + b.count;
    c.cone = mergeCones(a.cone, b.cone);
    const float len = glm::length(c.vectorArea);
    Vec3 normal = len > 1e-6f * c.area ? c.vectorArea / len : (a.area >= b.area ? a.box.axis[2] : b.box.axis[2]);
    std::array<Vec3, 16> points;
    const std::array<Vec3, 8> ca = a.box.corners(), cb = b.box.corners();
    std::copy(ca.begin(), ca.end(), points.begin());
    std::copy(cb.begin(), cb.end(), points.begin() + 8);
    // From the children's boxes, not every vertex: O(1) per node. The box is a little larger than
    // the tightest, and still holds every face.
    c.box = fitOrientedBox(points, normal);
    if (c.count <= 64) {  // exact, from the faces
      c.axisAreas.fill(0.0f);
      for (uint32_t k = c.begin; k < c.begin + c.count; ++k) addAxisAreas(c, surfaces.elements[tree.order[k]]);
    } else {  // bounded by the children's bounds along the new axes, so that the build stays linear
      for (int j = 0; j < 3; ++j) {
        const Vec3 u = c.box.axis[size_t(j)];
        c.axisAreas[size_t(j)] = a.maxProjectedArea(u) + b.maxProjectedArea(u);
        c.axisAreas[size_t(j) + 3] = a.maxProjectedArea(-u) + b.maxProjectedArea(-u);
      }
    }
  };
  {
    // Joined nodes by height (a leaf's is 0), in index order within a height.
    std::vector<uint32_t> height(next, 0), byHeight(next - n);
    uint32_t levels = 0;
    for (uint32_t i = uint32_t(n); i < next; ++i) {
      const FaceCluster& c = tree.joined(i);
      height[i] = std::max(height[c.child[0]], height[c.child[1]]) + 1;
      levels = std::max(levels, height[i]);
    }
    std::vector<size_t> start(size_t(levels) + 2, 0);
    for (uint32_t i = uint32_t(n); i < next; ++i) ++start[height[i] + 1];
    for (size_t h = 1; h < start.size(); ++h) start[h] += start[h - 1];
    std::vector<size_t> at(start.begin(), start.end() - 1);
    for (uint32_t i = uint32_t(n); i < next; ++i) byHeight[at[height[i]]++] = i;
    for (uint32_t h = 1; h <= levels; ++h)
      tbb::parallel_for(tbb::blocked_range<size_t>(start[h], start[h + 1], 256), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t k = r.begin(); k != r.end(); ++k) fill(byHeight[k]);
      });
  }
  tree.seconds = watch.seconds();
  return tree;
}

}  // namespace luxel
