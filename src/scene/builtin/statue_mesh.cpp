// Scanned models at a prescribed face count: welding, 1-to-4 midpoint subdivision, and quadric
// error simplification (Garland and Heckbert, SIGGRAPH 1997) through meshoptimizer.
#include "scene/builtin/statue_mesh.h"

#include <fmt/format.h>
#include <meshoptimizer.h>

#include <algorithm>
#include <cfloat>
#include <cstring>
#include <unordered_map>

#include "luxel/error.h"

namespace luxel::builtin {

TriangleMesh weldedTriangles(const Scene& scene) {
  std::vector<Vec3> positions;
  std::vector<uint32_t> indices;
  for (const Mesh& m : scene.meshes) {
    const auto base = uint32_t(positions.size());
    // Adding 0 turns -0 into +0, so that the two weld: the remap compares bits.
    for (Vec3 p : m.positions) positions.push_back(p + Vec3(0.0f));
    for (const Face& f : m.faces) {
      indices.insert(indices.end(), {base + f.v[0], base + f.v[1], base + f.v[2]});
      if (!f.isTriangle())
        indices.insert(indices.end(), {base + f.v[0], base + f.v[2], base + f.v[3]});
    }
  }
  std::vector<uint32_t> remap(positions.size());
  const size_t vertices =
      meshopt_generateVertexRemap(remap.data(), indices.data(), indices.size(), positions.data(),
                                  positions.size(), sizeof(Vec3));
  TriangleMesh out;
  out.positions.resize(vertices);
  meshopt_remapVertexBuffer(out.positions.data(), positions.data(), positions.size(), sizeof(Vec3),
                            remap.data());
  out.triangles.reserve(indices.size() / 3);
  for (size_t i = 0; i < indices.size(); i += 3) {
    const uint32_t a = remap[indices[i]], b = remap[indices[i + 1]], c = remap[indices[i + 2]];
    if (a != b && b != c && c != a) out.triangles.push_back({a, b, c});
  }
  return out;
}

void subdivideMidpoints(TriangleMesh& mesh) {
  // A closed mesh has 3/2 edges a triangle, hence as many midpoints.
  if (mesh.positions.size() + mesh.triangles.size() * 3 / 2 >= size_t(UINT32_MAX))
    throw Error(fmt::format("subdivision: {} triangles would need more than 2^32 vertices",
                            4 * mesh.triangles.size()));
  std::unordered_map<uint64_t, uint32_t> midpoints;
  midpoints.reserve(mesh.triangles.size() * 3 / 2 + 16);
  mesh.positions.reserve(mesh.positions.size() + mesh.triangles.size() * 3 / 2 + 16);
  auto midpoint = [&](uint32_t a, uint32_t b) {
    const uint64_t key = uint64_t(std::min(a, b)) << 32 | std::max(a, b);
    auto [it, inserted] = midpoints.try_emplace(key, uint32_t(mesh.positions.size()));
    if (inserted) {
      const Vec3 p = 0.5f * (mesh.positions[a] + mesh.positions[b]);
      mesh.positions.push_back(p);
    }
    return it->second;
  };
  std::vector<std::array<uint32_t, 3>> out;
  out.reserve(4 * mesh.triangles.size());
  for (const auto& [a, b, c] : mesh.triangles) {
    const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    out.push_back({a, ab, ca});
    out.push_back({ab, b, bc});
    out.push_back({ca, bc, c});
    out.push_back({ab, bc, ca});
  }
  mesh.triangles = std::move(out);
}

TriangleMesh simplifyTo(const TriangleMesh& mesh, size_t triangles) {
  if (mesh.triangles.size() <= triangles) return mesh;
  static_assert(sizeof(std::array<uint32_t, 3>) == 3 * sizeof(uint32_t));
  static_assert(sizeof(Vec3) == 3 * sizeof(float));
  const size_t count = 3 * mesh.triangles.size();
  const auto* indices = reinterpret_cast<const uint32_t*>(mesh.triangles.data());
  std::vector<uint32_t> kept(count);  // meshopt_simplify may write up to the input's count
  // FLT_MAX: no limit on the error, so that the target count is reached whatever it costs.
  kept.resize(meshopt_simplify(kept.data(), indices, count, &mesh.positions[0].x,
                               mesh.positions.size(), sizeof(Vec3), 3 * triangles, FLT_MAX, 0,
                               nullptr));
  TriangleMesh out;
  out.positions.resize(mesh.positions.size());
  out.positions.resize(meshopt_optimizeVertexFetch(out.positions.data(), kept.data(), kept.size(),
                                                   mesh.positions.data(), mesh.positions.size(),
                                                   sizeof(Vec3)));
  out.triangles.resize(kept.size() / 3);
  std::memcpy(out.triangles.data(), kept.data(), kept.size() * sizeof(uint32_t));
  return out;
}

TriangleMesh withTriangleCount(TriangleMesh mesh, size_t triangles) {
  if (mesh.triangles.empty()) throw Error("subdivision: the mesh has no triangles");
  while (mesh.triangles.size() < triangles) subdivideMidpoints(mesh);
  return simplifyTo(mesh, triangles);
}

}  // namespace luxel::builtin
