#include "transport/emitting_polygons.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <unordered_map>

#include "core/convex_hull.h"
#include "core/position_key.h"

namespace luxel {
namespace {

// The polygons as the faces and elements give them: a face whose elements all carry one exitance
// is one polygon, its own; otherwise each of its emitting elements is.
std::vector<EmittingPolygon> emittingPieces(const SurfaceSet& surfaces) {
  // A face is uniform when every element of it carries its first element's exitance.
  std::vector<int8_t> uniform(surfaces.faces.size(), -1);
  std::vector<Rgb> first(surfaces.faces.size(), Rgb(0.0f));
  for (const Element& e : surfaces.elements) {
    int8_t& u = uniform[e.face];
    if (u < 0) u = 1, first[e.face] = e.exitance;
    else if (first[e.face] != e.exitance) u = 0;
  }
  std::vector<EmittingPolygon> out;
  std::vector<bool> faceDone(surfaces.faces.size(), false);
  for (const Element& e : surfaces.elements) {
    if (!(e.exitance.r > 0.0f || e.exitance.g > 0.0f || e.exitance.b > 0.0f)) continue;
    if (uniform[e.face] == 1) {
      if (faceDone[e.face]) continue;
      faceDone[e.face] = true;
      const SurfaceFace& f = surfaces.faces[e.face];
      const Polygon polygon{f.corners, f.triangle ? 3 : 4};
      out.push_back({polygon, polygon.normal(), e.exitance});
    } else {
      out.push_back({e.polygon, e.polygon.normal(), e.exitance});
    }
  }
  return out;
}

// Whether two pieces can be parts of one lamp: the same exitance, facing the same way, in one
// plane (to a millionth of their size).
bool sameLamp(const EmittingPolygon& a, const EmittingPolygon& b) {
  if (a.exitance != b.exitance || glm::dot(a.normal, b.normal) < 1.0f - 1e-6f) return false;
  const float size = std::sqrt(std::max(a.polygon.area(), b.polygon.area()));
  for (int k = 0; k < b.polygon.count; ++k)
    if (std::abs(glm::dot(b.polygon.v[size_t(k)] - a.polygon.v[0], a.normal)) > 1e-6f * size) return false;
  return true;
}

// The one polygon of at most four corners that `pieces` tile exactly, if there is one: their
// hull, when it has at most four corners and the pieces' areas add up to its area (they overlap
// nowhere and leave no gap).
std::optional<Polygon> convexUnion(const std::vector<const EmittingPolygon*>& pieces) {
  const Vec3 n = pieces[0]->normal, origin = pieces[0]->polygon.v[0];
  const Vec3 a = std::abs(n.x) < 0.6f ? Vec3(1, 0, 0) : (std::abs(n.y) < 0.6f ? Vec3(0, 1, 0) : Vec3(0, 0, 1));
  const Vec3 u = glm::normalize(glm::cross(n, a)), v = glm::cross(n, u);
  std::vector<glm::dvec2> flat;
  std::vector<Vec3> corner;  // flat[i] is where corner[i] lies in the plane
  double piecesArea = 0.0;
  for (const EmittingPolygon* p : pieces) {
    std::vector<glm::dvec2> own;
    for (int k = 0; k < p->polygon.count; ++k) {
      const Vec3 d = p->polygon.v[size_t(k)] - origin;
      own.emplace_back(glm::dot(d, u), glm::dot(d, v));
      flat.push_back(own.back()), corner.push_back(p->polygon.v[size_t(k)]);
    }
    piecesArea += std::abs(signedArea2d(own));
  }
  const std::vector<glm::dvec2> hull = convexHull2d(flat);
  if (hull.size() < 3 || hull.size() > 4) return std::nullopt;
  if (std::abs(signedArea2d(hull) - piecesArea) > 1e-5 * piecesArea) return std::nullopt;
  Polygon out;
  out.count = int(hull.size());
  for (size_t h = 0; h < hull.size(); ++h)
    out.v[h] = corner[size_t(std::find(flat.begin(), flat.end(), hull[h]) - flat.begin())];
  // Counter-clockwise about u x v = n, so the winding gives the pieces' normal.
  return out;
}

}  // namespace

std::vector<EmittingPolygon> emittingPolygons(const SurfaceSet& surfaces) { return joinLampPieces(emittingPieces(surfaces)); }

std::vector<EmittingPolygon> joinLampPieces(std::vector<EmittingPolygon> pieces) {
  if (pieces.size() < 2) return pieces;
  // A lamp modelled as two triangles or as a grid of cells is one polygon to whatever samples
  // it: each piece took its own shadow rays from every point lit (16 times the rays for seed
  // 002's room, whose light is 4 x 4 cells), and the pieces of one lamp see the same shadows.
  // Each piece is joined (union-find) to the first piece met at each of its corners when the two
  // can belong to one lamp, and a group that tiles a convex polygon of at most four corners
  // becomes that polygon. A corner first met on another lamp joins nothing there: pieces of one
  // lamp share edges, so they meet at another corner, or stay apart, which costs rays, not light.
  std::vector<uint32_t> parent(pieces.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto root = [&](uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::unordered_map<PositionKey, uint32_t, PositionKeyHash> firstAt;
  for (uint32_t i = 0; i < pieces.size(); ++i)
    for (int k = 0; k < pieces[i].polygon.count; ++k) {
      const auto [it, fresh] = firstAt.try_emplace(positionKey(pieces[i].polygon.v[size_t(k)]), i);
      if (!fresh && sameLamp(pieces[it->second], pieces[i])) parent[root(i)] = root(it->second);
    }
  std::vector<std::vector<const EmittingPolygon*>> groups(pieces.size());
  for (uint32_t i = 0; i < pieces.size(); ++i) groups[root(i)].push_back(&pieces[i]);
  // In the order of each group's first piece, so that the list is the same run to run.
  std::vector<EmittingPolygon> out;
  for (uint32_t i = 0; i < pieces.size(); ++i) {
    std::vector<const EmittingPolygon*>& group = groups[root(i)];
    if (group.empty()) continue;  // out already, at an earlier piece of its group
    const std::optional<Polygon> lamp = group.size() > 1 ? convexUnion(group) : std::nullopt;
    if (lamp) out.push_back({*lamp, pieces[i].normal, pieces[i].exitance});
    else
      for (const EmittingPolygon* p : group) out.push_back(*p);
    group.clear();
  }
  return out;
}

}  // namespace luxel
