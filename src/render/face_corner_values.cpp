// From elements back to the scene's faces: the value at each face corner of each mesh, for baking
// into vertex attributes. Each face corner coincides exactly with a corner of one of the elements
// cut from its face (elements tile the face's parameter space, and the face corners are the
// parameter corners), so the value is that element corner's smooth value.
#include <cmath>
#include <limits>
#include <numbers>

#include "luxel/bake.h"
#include "luxel/error.h"
#include "luxel/render.h"

namespace luxel {

namespace {

// The surface faces that show a mesh face: its pieces (one, or two when a non-planar quad was
// cut) on the lit side; none when it was dropped as degenerate.
std::vector<std::vector<std::vector<uint32_t>>> frontPieces(const Scene& scene, const SurfaceSet& surfaces) {
  std::vector<std::vector<std::vector<uint32_t>>> pieces(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) pieces[m].resize(scene.meshes[m].faces.size());
  for (uint32_t i = 0; i < surfaces.faces.size(); ++i) {
    const SurfaceFace& f = surfaces.faces[i];
    // The back of a two-sided face is appended after its front: skip it.
    if (f.twin >= 0 && uint32_t(f.twin) < i) continue;
    if (f.mesh >= pieces.size() || f.meshFace >= pieces[f.mesh].size())
      throw Error("surface face out of the scene's range: discretised from another scene?");
    pieces[f.mesh][f.meshFace].push_back(i);
  }
  return pieces;
}

}  // namespace

std::vector<std::vector<uint8_t>> flippedFaceFlags(const Scene& scene, const SurfaceSet& surfaces) {
  std::vector<std::vector<uint8_t>> flags(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) flags[m].assign(scene.meshes[m].faces.size(), 0);
  for (const SurfaceFace& f : surfaces.faces)
    if (f.flipped && f.mesh < flags.size() && f.meshFace < flags[f.mesh].size()) flags[f.mesh][f.meshFace] = 1;
  return flags;
}

FaceCornerValues faceCornerValues(const Scene& scene, const SurfaceSet& surfaces,
                                  const std::vector<Rgb>& perElement) {
  if (perElement.size() != surfaces.elements.size())
    throw Error("faceCornerValues: one value per element expected");
  const std::vector<Rgb> corners = elementCornerValues(surfaces, perElement);
  std::vector<std::vector<uint32_t>> elementsOf(surfaces.faces.size());
  for (uint32_t e = 0; e < surfaces.elements.size(); ++e) elementsOf[surfaces.elements[e].face].push_back(e);
  const auto pieces = frontPieces(scene, surfaces);

  FaceCornerValues values(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    values[m].assign(mesh.faces.size() * 4, Rgb(0.0f));
    std::vector<Rgb> atVertex(mesh.positions.size(), Rgb(0.0f));
    std::vector<uint8_t> known(mesh.positions.size(), 0);
    for (size_t fi = 0; fi < mesh.faces.size(); ++fi) {
      const std::vector<uint32_t>& ps = pieces[m][fi];
      if (ps.empty()) continue;  // degenerate: filled below
      const Face& face = mesh.faces[fi];
      for (int k = 0; k < face.vertexCount(); ++k) {
        const Vec3 p = mesh.positions[face.v[size_t(k)]];
        // The nearest element corner: at distance 0 but for rounding, or for the corner of a
        // split quad whose other half was dropped as degenerate (then on the kept half's edge).
        float best = std::numeric_limits<float>::infinity();
        Rgb value(0.0f);
        for (uint32_t s : ps)
          for (uint32_t e : elementsOf[s]) {
            const Polygon& poly = surfaces.elements[e].polygon;
            for (int c = 0; c < poly.count; ++c) {
              const Vec3 d = poly.v[size_t(c)] - p;
              const float dist = glm::dot(d, d);
              if (dist < best) best = dist, value = corners[size_t(e) * 4 + size_t(c)];
            }
          }
        values[m][fi * 4 + size_t(k)] = value;
        atVertex[face.v[size_t(k)]] = value;
        known[face.v[size_t(k)]] = 1;
      }
    }
    for (size_t fi = 0; fi < mesh.faces.size(); ++fi) {
      if (!pieces[m][fi].empty()) continue;
      const Face& face = mesh.faces[fi];
      for (int k = 0; k < face.vertexCount(); ++k)
        if (known[face.v[size_t(k)]]) values[m][fi * 4 + size_t(k)] = atVertex[face.v[size_t(k)]];
    }
  }
  return values;
}

std::vector<Rgb> elementRadiance(const SurfaceSet& surfaces, const Solution& solution) {
  if (solution.radiosity.size() != surfaces.elements.size())
    throw Error("elementRadiance: one radiosity per element expected");
  std::vector<Rgb> radiance(solution.radiosity.size());
  for (size_t i = 0; i < radiance.size(); ++i) radiance[i] = solution.radiosity[i] / std::numbers::pi_v<float>;
  return elementCornerValues(surfaces, radiance);
}

FaceCornerValues bakedRadiance(const Scene& scene, const SurfaceSet& surfaces, const Solution& solution) {
  std::vector<Rgb> radiance(solution.radiosity.size());
  for (size_t i = 0; i < radiance.size(); ++i) radiance[i] = solution.radiosity[i] / std::numbers::pi_v<float>;
  return faceCornerValues(scene, surfaces, radiance);
}

}  // namespace luxel
