#include "trace/ray_tracer.h"

#include <algorithm>
#include <mutex>
#include <string>

#include <fmt/format.h>

#include "luxel/error.h"

namespace luxel {
namespace {

std::string& lastEmbreeError() {
  static std::string message;
  return message;
}

void onEmbreeError(void*, RTCError code, const char* message) {
  lastEmbreeError() = fmt::format("Embree error {}: {}", int(code), message ? message : "");
}

// One Embree device for the process: creating a device spins up its own task system.
RTCDevice device() {
  static std::once_flag once;
  static RTCDevice dev = nullptr;
  std::call_once(once, [] {
    dev = rtcNewDevice(nullptr);
    if (dev) rtcSetDeviceErrorFunction(dev, onEmbreeError, nullptr);
  });
  if (!dev) throw Error("could not create an Embree device (unsupported CPU?)");
  return dev;
}

// A BVH over the polygons `which` of `polygons` (all when empty).
RTCScene buildPolygonScene(RTCDevice dev, std::span<const Polygon> polygons, const std::vector<uint32_t>* which) {
  const size_t n = which ? which->size() : polygons.size();
  RTCScene scene = rtcNewScene(dev);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  if (n == 0) {  // an object whose faces all had no area: nothing to hit
    rtcCommitScene(scene);
    return scene;
  }
  RTCGeometry geom = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_QUAD);
  auto* vertices = static_cast<float*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), n * 4));
  auto* indices = static_cast<uint32_t*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(uint32_t), n));
  if (!vertices || !indices) {
    rtcReleaseGeometry(geom);
    rtcReleaseScene(scene);
    throw Error(fmt::format("Embree could not allocate buffers for {} polygons: {}", n, lastEmbreeError()));
  }
  for (size_t i = 0; i < n; ++i) {
    const Polygon& p = polygons[which ? (*which)[i] : i];
    for (int c = 0; c < 4; ++c) {
      // Triangles repeat their last corner, which Embree's quad geometry treats as a triangle.
      // Embree cuts a quad along its 1-3 diagonal; everything else in luxel (elements, bake,
      // glTF) cuts along 0-2, so quads go in rotated by one corner (remapped in intersect).
      const int src = p.count == 4 ? (c + 1) % 4 : std::min(c, p.count - 1);
      const Vec3& v = p.v[size_t(src)];
      vertices[12 * i + 3 * c + 0] = v.x;
      vertices[12 * i + 3 * c + 1] = v.y;
      vertices[12 * i + 3 * c + 2] = v.z;
      indices[4 * i + c] = uint32_t(4 * i + c);
    }
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene);
  return scene;
}

}  // namespace

RayTracer::RayTracer(std::span<const Polygon> polygons, std::span<const int32_t> instanceOf) {
  if (!instanceOf.empty() && instanceOf.size() != polygons.size())
    throw Error(fmt::format("ray tracer: {} instance indices for {} polygons", instanceOf.size(), polygons.size()));
  RTCDevice dev = device();
  quad_.resize(polygons.size());
  for (size_t i = 0; i < polygons.size(); ++i) quad_[i] = polygons[i].count == 4;
  int32_t instanceCount = 0;
  for (int32_t k : instanceOf) instanceCount = std::max(instanceCount, k + 1);
  flat_ = buildPolygonScene(dev, polygons, nullptr);
  if (instanceCount > 0) {
    // The two-level form, traced once an instance has moved: the static polygons as one
    // instance, each dynamic object as another, under a top level of a handful of leaves that a
    // commit rebuilds at once. Until then rays go through the one-level BVH of everything, which
    // traces faster with Embree 3's ray streams (docs/performance.md, "The engine core").
    members_.resize(size_t(instanceCount) + 1);
    for (uint32_t i = 0; i < polygons.size(); ++i) members_[size_t(instanceOf[i] + 1)].push_back(i);
    layered_ = rtcNewScene(dev);
    rtcSetSceneFlags(layered_, RTC_SCENE_FLAG_DYNAMIC);
    rtcSetSceneBuildQuality(layered_, RTC_BUILD_QUALITY_LOW);
    const glm::mat4 identity(1.0f);
    for (size_t part = 0; part < members_.size(); ++part) {
      parts_.push_back(buildPolygonScene(dev, polygons, &members_[part]));
      RTCGeometry instance = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_INSTANCE);
      rtcSetGeometryInstancedScene(instance, parts_.back());
      rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &identity[0][0]);
      rtcCommitGeometry(instance);
      rtcAttachGeometryByID(layered_, instance, unsigned(part));
      if (part > 0) instances_.push_back(instance);
      else rtcReleaseGeometry(instance);
    }
    rtcCommitScene(layered_);
  }
  if (rtcGetDeviceError(dev) != RTC_ERROR_NONE)
    throw Error(fmt::format("Embree could not build the scene: {}", lastEmbreeError()));
}

void RayTracer::placeInstance(uint32_t instance, const glm::mat4& transform) {
  if (instance >= instances_.size())
    throw Error(fmt::format("ray tracer: no instance {} ({} instances)", instance, instances_.size()));
  if (!moved_ && flat_) {  // from now on the one-level BVH is out of date: give its memory back
    rtcReleaseScene(flat_);
    flat_ = nullptr;
  }
  moved_ = true;
  rtcSetGeometryTransform(instances_[instance], 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &transform[0][0]);
  rtcCommitGeometry(instances_[instance]);
}

void RayTracer::commit() {
  if (layered_) rtcCommitScene(layered_);
  if (rtcGetDeviceError(device()) != RTC_ERROR_NONE)
    throw Error(fmt::format("Embree could not update the scene: {}", lastEmbreeError()));
}

RayTracer::~RayTracer() {
  for (RTCGeometry g : instances_) rtcReleaseGeometry(g);
  if (layered_) rtcReleaseScene(layered_);
  for (RTCScene part : parts_) rtcReleaseScene(part);
  if (flat_) rtcReleaseScene(flat_);
}

struct NearQuery {
  const RayTracer* tracer;
  const std::function<bool(uint32_t)>* visit;
};

bool visitNearPolygon(RTCPointQueryFunctionArguments* args) {
  const auto* q = static_cast<const NearQuery*>(args->userPtr);
  const uint32_t polygon = q->tracer->layered() ? q->tracer->polygonOf(args->context->instID[0], args->primID) : args->primID;
  if ((*q->visit)(polygon)) return false;
  args->query->radius = 0.0f;  // the visitor has seen enough: shrink the query to end traversal
  return true;                 // the query radius changed
}

void RayTracer::forEachNear(Vec3 p, float radius, const std::function<bool(uint32_t)>& visit) const {
  RTCPointQuery query;
  query.x = p.x, query.y = p.y, query.z = p.z;
  query.radius = radius;
  query.time = 0.0f;
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  NearQuery q{this, &visit};
  rtcPointQuery(traced(), &query, &context, visitNearPolygon, &q);
}

void RayTracer::occluded(std::span<RTCRay> rays, bool coherent) const {
  if (rays.empty()) return;
  if (recorder_) {
    std::lock_guard lock(recorderMutex_);
    if (recorder_->rays.size() + rays.size() <= recorder_->maxRays) {
      recorder_->rays.insert(recorder_->rays.end(), rays.begin(), rays.end());
      recorder_->streamSizes.push_back(uint32_t(rays.size()));
    }
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  rtcOccluded1M(traced(), &context, rays.data(), unsigned(rays.size()), sizeof(RTCRay));
  rays_.fetch_add(rays.size(), std::memory_order_relaxed);
}

void RayTracer::intersect(std::span<RTCRayHit> hits, bool coherent) const {
  if (hits.empty()) return;
  for (RTCRayHit& h : hits) {
    h.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    h.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  rtcIntersect1M(traced(), &context, hits.data(), unsigned(hits.size()), sizeof(RTCRayHit));
  rays_.fetch_add(hits.size(), std::memory_order_relaxed);
  // Rotated quads: Embree's u runs 1->2 and v 1->0, i.e. (u, v) = (1 - v', u') in ours. Exact on
  // both triangles, not only for parallelograms.
  // With instances, primitives are numbered within their part: back to the polygon's index.
  for (RTCRayHit& h : hits) {
    if (h.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
    if (layered()) h.hit.primID = polygonOf(h.hit.instID[0], h.hit.primID);
    if (quad_[h.hit.primID]) {
      const float u = 1.0f - h.hit.v, v = h.hit.u;
      h.hit.u = u, h.hit.v = v;
    }
  }
}

}  // namespace luxel
