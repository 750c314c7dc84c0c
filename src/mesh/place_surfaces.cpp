// SurfaceSet::placeObject (luxel/surface.h): a dynamic object's faces, patches and elements
// follow its transform, computed from their rest pose by one similarity each time.
#include <algorithm>

#include <fmt/format.h>

#include "luxel/error.h"
#include "luxel/surface.h"

namespace luxel {
namespace {

Vec3 point(const glm::mat4& m, Vec3 p) { return Vec3(m * glm::vec4(p, 1.0f)); }

// A normal turned by the similarity m; a zero normal (a face with no area) stays zero, not NaN.
Vec3 turned(const glm::mat4& m, Vec3 n) {
  const Vec3 t = glm::mat3(m) * n;
  const float length = glm::length(t);
  return length > 0.0f ? t / length : t;
}

Polygon moved(const glm::mat4& m, const Polygon& p) {
  Polygon out = p;
  for (size_t i = 0; i < 4; ++i) out.v[i] = point(m, p.v[i]);
  return out;
}

}  // namespace

void SurfaceSet::placeObject(const Scene& scene, uint32_t object) {
  if (object >= scene.objects.size() || object >= objectTransforms.size())
    throw Error(fmt::format("surfaces: no object {} (cut with {} objects)", object, objectTransforms.size()));
  auto rest = std::find_if(restPoses.begin(), restPoses.end(), [&](const RestPose& r) { return r.object == object; });
  if (rest == restPoses.end()) {
    RestPose r;
    r.object = object;
    for (uint32_t f = 0; f < faces.size(); ++f)
      if (scene.meshes[faces[f].mesh].object == object) r.faces.push_back(f), r.faceRest.push_back(faces[f]);
    for (uint32_t p = 0; p < patches.size(); ++p)
      if (scene.meshes[faces[patches[p].face].mesh].object == object)
        r.patches.push_back(p), r.patchRest.push_back(patches[p]);
    for (uint32_t e = 0; e < elements.size(); ++e)
      if (scene.meshes[faces[elements[e].face].mesh].object == object)
        r.elements.push_back(e), r.elementRest.push_back(elements[e]);
    restPoses.push_back(std::move(r));
    rest = restPoses.end() - 1;
  } else {
    size_t count = 0;
    for (const Element& e : elements) count += scene.meshes[faces[e.face].mesh].object == object ? 1 : 0;
    if (count != rest->elements.size())
      throw Error(fmt::format("surfaces: object '{}' was refined after its first move", scene.objects[object].name));
  }
  float scale = 1.0f;
  const glm::mat4 m = similarityBetween(objectTransforms[object], scene.objects[object].transform,
                                        fmt::format("object '{}'", scene.objects[object].name), &scale);
  const float areaScale = scale * scale;
  for (size_t i = 0; i < rest->faces.size(); ++i) {
    SurfaceFace& f = faces[rest->faces[i]];
    const SurfaceFace& r = rest->faceRest[i];
    for (size_t c = 0; c < 4; ++c) f.corners[c] = point(m, r.corners[c]);
    f.normal = turned(m, r.normal);
  }
  // Patches and elements alike: polygon, centroid, normal and area from their rest pose.
  auto place = [&](auto& all, const std::vector<uint32_t>& which, const auto& restPose) {
    for (size_t i = 0; i < which.size(); ++i) {
      auto& x = all[which[i]];
      const auto& r = restPose[i];
      x.polygon = moved(m, r.polygon);
      x.centroid = point(m, r.centroid);
      x.normal = turned(m, r.normal);
      x.area = r.area * areaScale;
    }
  };
  place(patches, rest->patches, rest->patchRest);
  place(elements, rest->elements, rest->elementRest);
}

}  // namespace luxel
