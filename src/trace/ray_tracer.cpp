#include "trace/ray_tracer.h"

#include <algorithm>
#include <mutex>
#include <string>

#include <fmt/format.h>
#include <glm/gtc/type_ptr.hpp>

#include "luxel/error.h"
#include "trace/thin_glass.h"

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

// A polygon's four corners as Embree's quad geometry takes them. Triangles repeat their last
// corner, which Embree treats as a triangle. Embree cuts a quad along its 1-3 diagonal;
// everything else in luxel (elements, bake, glTF) cuts along 0-2, so quads go in rotated by one
// corner (remapped in intersect).
void writeCorners(const Polygon& p, float* out) {
  for (int c = 0; c < 4; ++c) {
    const Vec3& v = p.v[size_t(p.count == 4 ? (c + 1) % 4 : std::min(c, p.count - 1))];
    out[3 * c + 0] = v.x, out[3 * c + 1] = v.y, out[3 * c + 2] = v.z;
  }
}

// Above this many polygons a BVH is built compact (Embree's RTC_SCENE_FLAG_COMPACT: leaves refer
// to the vertex buffer instead of holding copies of the corners): rays somewhat slower, and less
// memory, which is what runs out first at millions of faces (docs/performance.md, "Face-cluster
// radiosity").
constexpr size_t kCompactBvhPolygons = 4'000'000;

// A BVH over the polygons `which` of `polygons` (all when empty).
RTCScene buildPolygonScene(RTCDevice dev, std::span<const Polygon> polygons, const std::vector<uint32_t>* which) {
  const size_t n = which ? which->size() : polygons.size();
  RTCScene scene = rtcNewScene(dev);
  // Embree's default quality, without spatial splits: the rays traced as fast on Sibenik and
  // seed 002's room as with RTC_BUILD_QUALITY_HIGH, and the build takes a third of the time
  // (docs/performance.md, "Face-cluster radiosity").
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
  if (n > kCompactBvhPolygons) rtcSetSceneFlags(scene, RTC_SCENE_FLAG_COMPACT);
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
    writeCorners(polygons[which ? (*which)[i] : i], vertices + 12 * i);
    for (int c = 0; c < 4; ++c) indices[4 * i + c] = uint32_t(4 * i + c);
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene);
  return scene;
}

// The corners a scene's polygons went in with (12 floats each), or null for an empty scene.
const float* cornerBuffer(RTCScene scene) {
  RTCGeometry geom = rtcGetGeometry(scene, 0);
  return geom ? static_cast<const float*>(rtcGetGeometryBufferData(geom, RTC_BUFFER_TYPE_VERTEX, 0)) : nullptr;
}

}  // namespace

RayTracer::RayTracer(std::span<const Polygon> polygons, std::span<const int32_t> instanceOf, size_t rebuiltFlatLimit) {
  if (!instanceOf.empty() && instanceOf.size() != polygons.size())
    throw Error(fmt::format("ray tracer: {} instance indices for {} polygons", instanceOf.size(), polygons.size()));
  RTCDevice dev = device();
  quad_.resize(polygons.size());
  for (size_t i = 0; i < polygons.size(); ++i) quad_[i] = polygons[i].count == 4;
  int32_t instanceCount = 0;
  for (int32_t k : instanceOf) instanceCount = std::max(instanceCount, k + 1);
  flat_ = buildPolygonScene(dev, polygons, nullptr);
  flatCorners_ = cornerBuffer(flat_);
  instanceCount_ = size_t(instanceCount);
  if (instanceCount > 0 && polygons.size() <= rebuiltFlatLimit) {
    rebuildsFlat_ = true;
    built_.assign(polygons.begin(), polygons.end());
    instanceOf_.assign(instanceOf.begin(), instanceOf.end());
  } else if (instanceCount > 0) {
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
      partCorners_.push_back(cornerBuffer(parts_.back()));
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

Polygon RayTracer::polygonAsBuilt(uint32_t i) const {
  if (!flatCorners_ || i >= quad_.size())
    throw Error(fmt::format("ray tracer: polygon {} as built is gone ({} polygons, moved: {})", i, quad_.size(), moved_));
  // writeCorners' order undone: a quad's corner c holds v[(c + 1) % 4], a triangle's its v[c].
  Polygon p;
  p.count = quad_[i] ? 4 : 3;
  const float* c = flatCorners_ + 12 * size_t(i);
  for (int k = 0; k < p.count; ++k) {
    const int at = quad_[i] ? (k + 3) % 4 : k;
    p.v[size_t(k)] = Vec3(c[3 * at], c[3 * at + 1], c[3 * at + 2]);
  }
  return p;
}

void RayTracer::placeInstance(uint32_t instance, const glm::mat4& transform) {
  if (instance >= instanceCount_)
    throw Error(fmt::format("ray tracer: no instance {} ({} instances)", instance, instanceCount_));
  if (rebuildsFlat_) {
    placed_.emplace_back(instance, transform);
    return;
  }
  if (!moved_ && flat_) {  // from now on the one-level BVH is out of date: give its memory back
    rtcReleaseScene(flat_);
    flat_ = nullptr;
    flatCorners_ = nullptr;
  }
  moved_ = true;
  rtcSetGeometryTransform(instances_[instance], 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &transform[0][0]);
  rtcCommitGeometry(instances_[instance]);
}

void RayTracer::commit() {
  if (rebuildsFlat_ && !placed_.empty()) {
    std::vector<const glm::mat4*> transformOf(instanceCount_, nullptr);
    for (const auto& [instance, transform] : placed_) transformOf[instance] = &transform;  // the last placement counts
    placed_.clear();
    RTCGeometry geom = rtcGetGeometry(flat_, 0);
    auto* vertices = static_cast<float*>(rtcGetGeometryBufferData(geom, RTC_BUFFER_TYPE_VERTEX, 0));
    for (size_t i = 0; i < built_.size(); ++i) {
      if (instanceOf_[i] < 0 || !transformOf[size_t(instanceOf_[i])]) continue;
      const glm::mat4& m = *transformOf[size_t(instanceOf_[i])];
      Polygon p = built_[i];
      for (int c = 0; c < p.count; ++c) p.v[size_t(c)] = Vec3(m * glm::vec4(p.v[size_t(c)], 1.0f));
      writeCorners(p, vertices + 12 * i);
    }
    rtcUpdateGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcCommitGeometry(geom);
    rtcCommitScene(flat_);
  }
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

// Embree calls back for every primitive of a leaf whose bounds meet the query: the polygon's own
// bounds decide.
bool visitNearPolygon(RTCPointQueryFunctionArguments* args) {
  const auto* q = static_cast<const NearQuery*>(args->userPtr);
  const bool layered = q->tracer->layered();
  const float* corners = q->tracer->cornersOf(layered ? args->context->instID[0] : 0u, args->primID);
  if (corners) {
    Vec3 p(args->query->x, args->query->y, args->query->z);
    float radius = args->query->radius;
    if (args->context->instStackSize > 0) {  // into the instance's own space (a similarity)
      const glm::mat4 toLocal = glm::make_mat4(args->context->world2inst[args->context->instStackSize - 1]);
      p = Vec3(toLocal * glm::vec4(p, 1.0f));
      radius *= args->similarityScale > 0.0f ? args->similarityScale : 1.0f;
    }
    Vec3 lo(corners[0], corners[1], corners[2]), hi = lo;
    for (int c = 1; c < 4; ++c) {
      const Vec3 v(corners[3 * c], corners[3 * c + 1], corners[3 * c + 2]);
      lo = glm::min(lo, v), hi = glm::max(hi, v);
    }
    const Vec3 gap = glm::max(glm::max(lo - p, p - hi), Vec3(0.0f));
    if (glm::dot(gap, gap) > radius * radius) return false;
  }
  const uint32_t polygon = layered ? q->tracer->polygonOf(args->context->instID[0], args->primID) : args->primID;
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

bool RayTracer::hasGlass() const { return glass_ && glass_->any(); }
Rgb RayTracer::transmittanceOf(uint32_t primitive) const { return glass_ ? glass_->of(primitive) : Rgb(0.0f); }

void RayTracer::transmitted(std::span<RTCRay> rays, std::vector<Rgb>& through, bool coherent) const {
  if (hasGlass()) return glass_->occluded(*this, rays, through, coherent);
  occluded(rays, coherent);
  through.resize(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) through[i] = Rgb(isOccluded(rays[i]) ? 0.0f : 1.0f);
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
