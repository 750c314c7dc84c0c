#include "trace/thin_glass.h"

#include <cmath>
#include <limits>

namespace luxel {
namespace {

// Panes a ray passes before it counts as blocked: a window of a few layers, many times over.
constexpr int kMaxPanes = 16;

Rgb faceTransmittance(const Scene& scene, const SurfaceFace& face) {
  return face.material < scene.materials.size() ? scene.materials[face.material].transmittance : Rgb(0.0f);
}

// Where a ray last passed a pane: its point, unit normal and primitive.
struct Pane {
  Vec3 point{0.0f}, normal{0.0f};
  uint32_t primitive = 0;
  bool any = false;
};

// Whether any material transmits: when none does, no array a primitive is made (12 bytes a face,
// at ten million faces a transient 120 MB for nothing).
bool anyGlass(const Scene& scene) {
  for (const Material& m : scene.materials)
    if (m.transmits()) return true;
  return false;
}

}  // namespace

ThinGlass::ThinGlass(std::vector<Rgb> perPrimitive, float offset) : offset_(offset) {
  for (const Rgb& t : perPrimitive) any_ = any_ || t.r > 0.0f || t.g > 0.0f || t.b > 0.0f;
  if (any_) transmittance_ = std::move(perPrimitive);
}

ThinGlass ThinGlass::overFaces(const Scene& scene, const SurfaceSet& surfaces) {
  if (!anyGlass(scene)) return ThinGlass({}, 0.0f);
  std::vector<Rgb> t(surfaces.faces.size());
  for (size_t f = 0; f < t.size(); ++f) t[f] = faceTransmittance(scene, surfaces.faces[f]);
  return ThinGlass(std::move(t), rayOffsetFor(surfaces.sceneExtent));
}

ThinGlass ThinGlass::overElements(const Scene& scene, const SurfaceSet& surfaces) {
  if (!anyGlass(scene)) return ThinGlass({}, 0.0f);
  std::vector<Rgb> t(surfaces.elements.size());
  for (size_t e = 0; e < t.size(); ++e) t[e] = faceTransmittance(scene, surfaces.faces[surfaces.elements[e].face]);
  return ThinGlass(std::move(t), rayOffsetFor(surfaces.sceneExtent));
}

void ThinGlass::occluded(const RayTracer& tracer, std::span<RTCRay> rays, std::vector<Rgb>& through, bool coherent) const {
  through.assign(rays.size(), Rgb(1.0f));
  std::vector<float> tfar(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) tfar[i] = rays[i].tfar;
  tracer.occluded(rays, coherent);
  // The blocked rays again, pane by pane: each search starts just past the last pane found.
  std::vector<size_t> pending;
  for (size_t i = 0; i < rays.size(); ++i)
    if (isOccluded(rays[i]) && rays[i].id != kOpaqueToGlass) pending.push_back(i);
    else if (isOccluded(rays[i])) through[i] = Rgb(0.0f);
  std::vector<float> from(rays.size(), 0.0f);
  for (size_t i : pending) from[i] = rays[i].tnear;
  std::vector<Pane> last(rays.size());
  std::vector<RTCRayHit> hits;
  for (int pane = 0; pane < kMaxPanes && !pending.empty(); ++pane) {
    hits.assign(pending.size(), RTCRayHit{});
    for (size_t k = 0; k < pending.size(); ++k) {
      RTCRay r = rays[pending[k]];
      r.tnear = from[pending[k]], r.tfar = tfar[pending[k]];
      hits[k].ray = r;
    }
    tracer.intersect(hits, coherent);
    std::vector<size_t> next;
    for (size_t k = 0; k < pending.size(); ++k) {
      const size_t i = pending[k];
      const RTCRayHit& h = hits[k];
      if (h.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;  // past the last pane: it arrives
      const Rgb t = of(h.hit.primID);
      const Vec3 dir(h.ray.dir_x, h.ray.dir_y, h.ray.dir_z);
      const Vec3 point = Vec3(h.ray.org_x, h.ray.org_y, h.ray.org_z) + h.ray.tfar * dir;
      Vec3 normal(h.hit.Ng_x, h.hit.Ng_y, h.hit.Ng_z);
      normal = glm::dot(normal, normal) > 0.0f ? glm::normalize(normal) : Vec3(0.0f);
      // The other side of the pane just passed (a two-sided glass face's twin, in its plane or
      // nudged a ray offset off it) is the same glass: it filters the light once.
      const Pane& was = last[i];
      const bool sameGlass = was.any && t == of(was.primitive) &&
                             std::abs(glm::dot(normal, was.normal)) > 0.999f &&
                             std::abs(glm::dot(point - was.point, was.normal)) < 4.0f * offset_;
      if (!sameGlass) through[i] *= t;
      if (through[i] == Rgb(0.0f)) continue;  // opaque
      last[i] = Pane{point, normal, h.hit.primID, true};
      const float length = glm::length(dir);
      from[i] = h.ray.tfar + (length > 0.0f ? offset_ / length : 0.0f);
      next.push_back(i);
    }
    pending.swap(next);
  }
  for (size_t i : pending) through[i] = Rgb(0.0f);  // more panes than a window has
  for (size_t i = 0; i < rays.size(); ++i)
    rays[i].tfar = through[i] == Rgb(0.0f) ? -std::numeric_limits<float>::infinity() : tfar[i];
}

}  // namespace luxel
