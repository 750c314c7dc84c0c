// Embree behind a small batch interface: closest hits and occlusion for arrays of rays.
// Callers fill RTCRay / RTCRayHit arrays and hand them over in one call (Embree ray streams),
// which lets Embree trace them as packets on the calling TBB thread.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <utility>
#include <vector>

#include <embree3/rtcore.h>

#include <glm/glm.hpp>

#include "luxel/surface.h"

namespace luxel {

class ThinGlass;

class RayTracer {
 public:
  // Builds a BVH over the polygons. Primitive i of a hit is polygons[i]. With `instanceOf` (one
  // per polygon): the polygons with instanceOf[i] = k >= 0 form instance k, a BVH of its own that
  // placeInstance moves by a transform (Embree's two-level scenes: a moving object costs a
  // transform and a commit of the top level, not a rebuild); -1 puts a polygon in the static BVH.
  // With instances both forms are built: the one-level BVH of every polygon, which traces
  // fastest, serves until the first move; the two-level form serves from then on. Scenes of at
  // most `rebuiltFlatLimit` polygons keep the one-level BVH instead: a commit writes the moved
  // polygons' corners into it and rebuilds it, which costs little at that size and keeps rays
  // as fast as before the move (docs/performance.md, "What the two-level ray tracer costs").
  explicit RayTracer(std::span<const Polygon> polygons, std::span<const int32_t> instanceOf = {},
                     size_t rebuiltFlatLimit = kRebuiltFlatLimit);
  static constexpr size_t kRebuiltFlatLimit = 8192;
  ~RayTracer();
  RayTracer(const RayTracer&) = delete;
  RayTracer& operator=(const RayTracer&) = delete;

  // Occlusion: on return, rays[i].tfar is -inf where something lies between tnear and tfar.
  void occluded(std::span<RTCRay> rays, bool coherent = false) const;
  // Thin glass (trace/thin_glass.h): the transmittance of each primitive, which shadow rays pass.
  void setGlass(std::shared_ptr<const ThinGlass> glass) { glass_ = std::move(glass); }
  bool hasGlass() const;
  Rgb transmittanceOf(uint32_t primitive) const;  // zero for an opaque one
  // Shadow rays: `through[i]` is what ray i carries of its light, 1 where nothing is in the way,
  // the panes' transmittance where only glass is, 0 (and marked occluded) where something opaque
  // is. Without glass, occluded().
  void transmitted(std::span<RTCRay> rays, std::vector<Rgb>& through, bool coherent = false) const;
  // Closest hit: on return, hits[i].hit.geomID is RTC_INVALID_GEOMETRY_ID on a miss; otherwise
  // hit.primID is the polygon and hit.u, hit.v its parameters. Triangles: barycentric towards
  // corners 1 and 2. Quads are the triangles (0,1,2) and (0,2,3), as elements, bake and glTF cut
  // them; u runs along 0->1 and v along 0->3, linear on each triangle (bilinear for
  // parallelograms): u >= v is (0,1,2) with weights (1-u, u-v, v), else (0,2,3) with (1-v, u, v-u).
  void intersect(std::span<RTCRayHit> hits, bool coherent = true) const;

  // Calls visit(polygonIndex) for every polygon whose bounds come within `radius` of `p`, until
  // visit returns false.
  void forEachNear(Vec3 p, float radius, const std::function<bool(uint32_t)>& visit) const;

  // Places instance k by `transform`, relative to where its polygons were at construction. The
  // move takes effect at commit(); rays must not be traced between the two.
  void placeInstance(uint32_t instance, const glm::mat4& transform);
  void commit();
  size_t instanceCount() const { return instanceCount_; }
  // Whether rays go through the two-level form (an instance has moved), whose primitives are
  // numbered per part: polygonOf maps a hit's (instID[0], primID) back to the polygon.
  bool layered() const { return moved_; }
  uint32_t polygonOf(unsigned instID, unsigned primID) const { return members_[instID][primID]; }
  // A primitive's four corners as traced (in its part's own space when layered), 12 floats.
  const float* cornersOf(unsigned part, unsigned primID) const {
    const float* corners = moved_ ? partCorners_[part] : flatCorners_;
    return corners ? corners + 12 * size_t(primID) : nullptr;
  }

  // Polygon i as it went in, read back from the one-level BVH's corners: for a tracer none of
  // whose instances has moved (the caller then need not keep its own copy of every polygon).
  Polygon polygonAsBuilt(uint32_t i) const;

  uint64_t raysTraced() const { return rays_.load(std::memory_order_relaxed); }

  // Benchmarks only: occlusion rays as a solver cast them, stream by stream, so that Embree's raw
  // throughput can be measured on exactly that work (same rays, same stream sizes).
  struct RayRecording {
    std::vector<RTCRay> rays;
    std::vector<uint32_t> streamSizes;
    size_t maxRays = size_t(1) << 22;  // streams past this are traced but not recorded
  };
  void recordOcclusionRays(RayRecording* sink) { recorder_ = sink; }
  void resetRayCount() { rays_.store(0, std::memory_order_relaxed); }

 private:
  std::shared_ptr<const ThinGlass> glass_;
  // The one-level BVH of every polygon, traced until an instance moves; with instances, the
  // two-level form (parts_: the static polygons' scene, then each instance's) traced after.
  RTCScene flat_ = nullptr;
  RTCScene layered_ = nullptr;
  bool moved_ = false;
  std::vector<RTCScene> parts_;
  std::vector<RTCGeometry> instances_;   // the instance geometries of the dynamic instances
  // With instances: per top-level geometry (0 static, k + 1 instance k), the polygon of each primitive.
  std::vector<std::vector<uint32_t>> members_;
  RTCScene traced() const { return moved_ ? layered_ : flat_; }
  std::vector<uint8_t> quad_;  // per polygon: 1 for quads, whose hit (u, v) intersect remaps
  size_t instanceCount_ = 0;
  const float* flatCorners_ = nullptr;     // flat_'s vertex buffer
  std::vector<const float*> partCorners_;  // each of parts_'s
  // A one-level BVH rebuilt by commit(): the polygons where they were built, each one's
  // instance, and the instances placed since the last commit with their transforms.
  bool rebuildsFlat_ = false;
  std::vector<Polygon> built_;
  std::vector<int32_t> instanceOf_;
  std::vector<std::pair<uint32_t, glm::mat4>> placed_;
  mutable std::atomic<uint64_t> rays_{0};
  RayRecording* recorder_ = nullptr;
  mutable std::mutex recorderMutex_;
};

// How far rays start off the surface they leave (and stop short of the one they aim at), for a
// scene whose bounding-box diagonal is `extent`: far above float noise at that scale, far below
// any element size.
inline float rayOffsetFor(float extent) { return 1e-5f * (extent > 1e-6f ? extent : 1e-6f); }

// A ray from `org` along `dir` (not necessarily unit) over [tnear, tfar].
inline RTCRay makeRay(Vec3 org, Vec3 dir, float tnear, float tfar) {
  RTCRay r;
  r.org_x = org.x, r.org_y = org.y, r.org_z = org.z;
  r.dir_x = dir.x, r.dir_y = dir.y, r.dir_z = dir.z;
  r.tnear = tnear, r.tfar = tfar;
  r.time = 0.0f, r.mask = 0xFFFFFFFFu, r.id = 0, r.flags = 0;
  return r;
}

inline bool isOccluded(const RTCRay& r) { return r.tfar < 0.0f; }

// The triangle (0, i1, i2) of a polygon that a hit's (u, v) from RayTracer::intersect lies in, and
// the hit's barycentric weights w for corners 0, i1, i2.
struct HitTriangle {
  int i1, i2;
  Vec3 w;
};
inline HitTriangle hitTriangle(int count, float u, float v) {
  if (count == 3) return {1, 2, Vec3(1.0f - u - v, u, v)};
  if (u >= v) return {1, 2, Vec3(1.0f - u, u - v, v)};
  return {2, 3, Vec3(1.0f - v, u, v - u)};
}

}  // namespace luxel
