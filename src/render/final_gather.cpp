// A final gather over a radiosity solution: see render/final_gather.h.
#include "render/final_gather.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <unordered_map>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/multi_jitter.h"
#include "core/random.h"
#include "mesh/corner_groups.h"
#include "render/corner_values.h"
#include "render/gather_mesh.h"
#include "trace/hemisphere_rays.h"
#include "transport/form_factor.h"
#include "transport/light_sampling.h"

namespace luxel {
namespace {

constexpr float kInvPi = std::numbers::inv_pi_v<float>;
// A near hit (kNearHitElements) gathers its own indirect light with kNearHitSide^2 rays.
constexpr int kNearHitSide = 3;

}  // namespace

FinalGather::FinalGather(const SurfaceSet& surfaces, const RayTracer& tracer,
                         const DirectLight& direct, const std::vector<Rgb>& indirectCorners,
                         bool gatherNearHits, const ElementDirect* elementDirect)
    : gatherNearHits_(gatherNearHits),
      surfaces_(surfaces),
      tracer_(tracer),
      direct_(direct),
      corners_(indirectCorners),
      elementDirect_(elementDirect),
      rayOffset_(rayOffsetFor(surfaces.sceneExtent)) {}

namespace {
const std::vector<Rgb> kNoCorners;
}

FinalGather::FinalGather(const SurfaceSet& surfaces, const RayTracer& tracer, const DirectLight& direct,
                         VertexGather& lowerLevel, const ElementDirect* elementDirect)
    : FinalGather(surfaces, tracer, direct, kNoCorners, /*gatherNearHits=*/false, elementDirect) {
  lowerLevel_ = &lowerLevel;
}

size_t FinalGather::add(std::span<RTCRayHit> rays, std::span<const Rgb> weights, std::span<Rgb* const> targets,
                        uint32_t seed) const {
  return add(rays, weights, targets, seed, gatherNearHits_);
}

size_t FinalGather::add(std::span<RTCRayHit> rays, std::span<const Rgb> weights, std::span<Rgb* const> targets,
                        uint32_t seed, bool gatherNearHits) const {
  tracer_.intersect(rays, false);
  // Per thread and per depth of nesting (a near hit's own gather, or a lazy lower level gathering
  // a vertex for a hit, calls add again before this call is done), kept between calls.
  struct Scratch {
    std::vector<RTCRay> shadowRays;
    std::vector<Rgb> shadowValues, shadowThrough;
    std::vector<Rgb*> shadowTargets;
    std::vector<RTCRayHit> second;  // the near hits' own gathers
    std::vector<Rgb> secondWeights;
    std::vector<Rgb*> secondTargets;
  };
  thread_local std::vector<std::unique_ptr<Scratch>> levels;
  thread_local size_t depth = 0;
  struct Nested {
    size_t& depth;
    explicit Nested(size_t& d) : depth(d) { ++depth; }
    ~Nested() { --depth; }
  } nested(depth);
  if (levels.size() < depth) levels.push_back(std::make_unique<Scratch>());
  Scratch& scratch = *levels[depth - 1];
  auto& [shadowRays, shadowValues, shadowThrough, shadowTargets, second, secondWeights, secondTargets] = scratch;
  shadowRays.clear(), shadowValues.clear(), shadowTargets.clear();
  second.clear(), secondWeights.clear(), secondTargets.clear();
  size_t backs = 0;
  const MultiJitter lightPattern{uint32_t(rays.size())};
  for (size_t k = 0; k < rays.size(); ++k) {
    const RTCRayHit& rh = rays[k];
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
    const uint32_t h = rh.hit.primID;
    const Element& hit = surfaces_.elements[h];
    const Vec3 d(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z);
    if (glm::dot(hit.normal, d) >= 0.0f) {
      ++backs;
      continue;
    }
    const Rgb weight = weights[k] * hit.reflectance * kInvPi;
    const Vec3 q = Vec3(rh.ray.org_x, rh.ray.org_y, rh.ray.org_z) + d * rh.ray.tfar;
    if (gatherNearHits && rh.ray.tfar < kNearHitElements * std::sqrt(hit.area)) {
      // A hit within a couple of elements: the elements there are seen large, and their
      // averaging (a block's footprint, a crease) with them, so the hit gathers its own indirect
      // light, from the solution one bounce further.
      std::array<Vec3, kNearHitSide * kNearHitSide> dirs;
      HemisphereStrata(hit.normal, kNearHitSide, hashCombine(seed, uint32_t(k)), 0x6e656172u)
          .directions(HemisphereStrata::Warp::Cosine, dirs);
      const Vec3 origin = q + rayOffset_ * hit.normal;
      const Rgb perRay = weight * (std::numbers::pi_v<float> / float(dirs.size()));
      for (const Vec3& d : dirs) {
        second.emplace_back().ray = makeRay(origin, d, 0.0f, std::numeric_limits<float>::infinity());
        secondWeights.push_back(perRay);
        secondTargets.push_back(targets[k]);
      }
    } else {
      const Rgb* corners = lowerLevel_ ? lowerLevel_->corners(h) : &corners_[size_t(h) * 4];
      *targets[k] += weight * interpolateCorners(corners, hit.polygon.count, rh.hit.u, rh.hit.v);
    }
    if (elementDirect_ && rh.ray.tfar >= elementDirect_->tracedWithin[h]) {
      *targets[k] += weight * elementDirect_->irradiance[h];
      continue;
    }
    Rng rng(hashCombine(seed, uint32_t(k)));
    const size_t before = shadowRays.size();
    // The form-factor estimator here too: the kernel alone (A k(y) V(y)) would skip the analytic
    // factor and is unbiased, but heavy-tailed next to a large emitter (docs/performance.md).
    // The batch's light points are stratified over each light (as a pixel's samples are), so a
    // vertex's hits in a penumbra see the lamp evenly covered rather than at random points.
    const Vec2 u = lightPattern(uint32_t(k), hashCombine(seed, 0x11647u));
    *targets[k] += weight * direct_.sample(q, hit.normal, hit.normal, Sides::Front, u, rng, rayOffset_, shadowRays,
                                           shadowValues, h);
    for (size_t r = before; r < shadowRays.size(); ++r) {
      shadowValues[r] *= weight;
      shadowTargets.push_back(targets[k]);
    }
  }
  tracer_.transmitted(shadowRays, shadowThrough);
  for (size_t r = 0; r < shadowRays.size(); ++r)
    if (!isOccluded(shadowRays[r])) *shadowTargets[r] += shadowValues[r] * shadowThrough[r];
  if (!second.empty()) add(second, secondWeights, secondTargets, hashCombine(seed, 0x5ec0u), false);
  return backs;
}

std::vector<Rgb> elementDirectLight(const SurfaceSet& surfaces, const RayTracer& tracer, const DirectLight& direct,
                                    int samples, uint32_t seed, std::span<const uint32_t> elements) {
  const size_t count = elements.empty() ? surfaces.elements.size() : elements.size();
  std::vector<Rgb> out(count, Rgb(0.0f));
  if (samples <= 0) return out;
  const MultiJitter pattern{uint32_t(samples)};
  const float rayOffset = rayOffsetFor(surfaces.sceneExtent);
  const float perSample = 1.0f / float(samples);
  const auto estimate = [&](const tbb::blocked_range<uint32_t>& range) {
    std::vector<RTCRay> rays;
    std::vector<Rgb> values, through;
    std::vector<uint32_t> owners;
    for (uint32_t i = range.begin(); i < range.end(); ++i) {
      const uint32_t e = elements.empty() ? i : elements[i];
      const Element& el = surfaces.elements[e];
      Rng rng(hashCombine(seed ^ 0xd17ec7u, e));
      Rgb always(0.0f);
      for (int k = 0; k < samples; ++k) {
        const Vec2 st = pattern(uint32_t(k), hashCombine(seed, e));
        const Vec2 u = pattern(uint32_t(k), hashCombine(seed ^ 0x119u, e));
        const size_t before = rays.size();
        always += direct.sample(polygonPoint(el.polygon, st.x, st.y), el.normal, el.normal, Sides::Front, u, rng,
                                rayOffset, rays, values, e);
        owners.insert(owners.end(), rays.size() - before, i);
      }
      out[i] = always * perSample;
    }
    tracer.transmitted(rays, through);
    for (size_t r = 0; r < rays.size(); ++r)
      if (!isOccluded(rays[r])) out[owners[r]] += values[r] * through[r] * perSample;
  };
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, uint32_t(count), 64), estimate);
  return out;
}

namespace {

struct VertexKey {
  uint32_t x, y, z, firstElement;
  bool operator==(const VertexKey&) const = default;
};
struct VertexKeyHash {
  size_t operator()(const VertexKey& k) const {
    return hashCombine(hashCombine(hashCombine(k.x, k.y), k.z), k.firstElement);
  }
};

uint32_t bitsOf(float f) {
  uint32_t b;
  std::memcpy(&b, &f, sizeof b);
  return b;
}

enum : uint8_t { kPending = 0, kRunning = 1, kDone = 2 };

}  // namespace

VertexGather::VertexGather(const SurfaceSet& surfaces, const FinalGather& gather, int rays, uint32_t seed,
                           std::span<const float> elementWeights, const GatherMesh* refined, const Scene* skiesOf)
    : surfaces_(surfaces), gather_(gather), seed_(seed), refined_(refined && refined->isSplit() ? refined : nullptr) {
  if (skiesOf) {
    for (const Light& l : skiesOf->lights)
      if (isSkyLight(l)) skies_.push_back(&l);
    up_ = glm::normalize(skiesOf->up);
  }
  const CornerGroups groups(surfaces, kDefaultCreaseCosine);
  const size_t ne = surfaces.elements.size();
  // Slots that share a position and a smooth surface (the group's first member names it) are one
  // vertex.
  vertexOf_.assign(ne * 4, 0);
  std::unordered_map<VertexKey, uint32_t, VertexKeyHash> index;
  index.reserve(ne * 2);
  for (uint32_t e = 0; e < ne; ++e) {
    const Element& el = surfaces.elements[e];
    for (int c = 0; c < el.polygon.count; ++c) {
      const Vec3 p = el.polygon.v[size_t(c)];
      uint32_t first = e;
      for (uint32_t m : groups.at(e, c)) first = std::min(first, m);
      const VertexKey key{bitsOf(p.x), bitsOf(p.y), bitsOf(p.z), first};
      auto [it, added] = index.try_emplace(key, uint32_t(vertices_.size()));
      if (added) vertices_.push_back(Vertex{p});
      Vertex& v = vertices_[it->second];
      v.normal += el.area * el.normal;
      v.centroids += el.centroid;
      if (!elementWeights.empty()) v.weight += elementWeights[e] / float(el.polygon.count);
      ++v.slots;
      vertexOf_[size_t(e) * 4 + size_t(c)] = it->second;
    }
  }
  if (refined_) {
    // Which vertices are solved elements' corners (weight 1 on one of them: the splits' coordinates
    // are exact binary fractions), and where the others lie in a solved element.
    const SurfaceSet& solved = refined_->solved();
    solvedCorners_.assign(solved.elements.size() * 4, kNoVertex);
    std::vector<uint8_t> isCorner(vertices_.size(), 0);
    for (uint32_t e = 0; e < ne; ++e) {
      const uint32_t parent = refined_->parent(e);
      const int parentCount = solved.elements[parent].polygon.count;
      for (int c = 0; c < surfaces.elements[e].polygon.count; ++c) {
        const uint32_t vi = vertexOf_[size_t(e) * 4 + size_t(c)];
        const Vec2 st = refined_->local(e, c);
        const std::array<float, 4> w = cornerWeights(parentCount, st.x, st.y);
        const auto k = std::find(w.begin(), w.end(), 1.0f);
        if (k != w.end()) {
          solvedCorners_[size_t(parent) * 4 + size_t(k - w.begin())] = vi;
          isCorner[vi] = 1;
        } else if (vertices_[vi].parent == kNoParent) {
          vertices_[vi].parent = parent;
          vertices_[vi].local = st;
        }
      }
    }
    for (size_t v = 0; v < vertices_.size(); ++v)
      if (isCorner[v]) vertices_[v].parent = kNoParent;
  }
  // The budget is shared by the vertices that will be gathered: with element weights (an image's
  // pixels), those the image sees.
  size_t sharing = vertices_.size();
  if (!elementWeights.empty()) sharing = size_t(std::count_if(vertices_.begin(), vertices_.end(), [](const Vertex& v) {
                                 return v.weight > 0.0f;
                               }));
  if (rays <= 0)
    rays = int(std::clamp(kVertexGatherRayBudget / std::max<size_t>(sharing, 1), size_t(kMinVertexGatherRays),
                          size_t(kDefaultVertexGatherRays)));
  const int uniformSide = strataSide(rays);
  double total = 0.0;
  size_t weighted = 0;
  for (const Vertex& v : vertices_)
    if (v.weight > 0.0f) total += v.weight, ++weighted;
  const double mean = weighted > 0 ? total / double(weighted) : 0.0;
  for (Vertex& v : vertices_) {
    const double share = mean > 0.0 ? double(v.weight) / mean : 1.0;
    v.side = mean > 0.0 ? strataSide(int(std::clamp(double(rays) * share, double(std::min(rays, kMinVertexGatherRays)),
                                                    double(rays) * kMaxRaysOverMean)))
                        : uniformSide;
  }
  corners_.assign(ne * 4, Rgb(0.0f));
  vertexState_ = std::make_unique<std::atomic<uint8_t>[]>(vertices_.size());
  elementState_ = std::make_unique<std::atomic<uint8_t>[]>(ne);
  for (size_t v = 0; v < vertices_.size(); ++v) vertexState_[v].store(kPending, std::memory_order_relaxed);
  for (size_t e = 0; e < ne; ++e) elementState_[e].store(kPending, std::memory_order_relaxed);
}

VertexGather::~VertexGather() = default;

// Runs `publish` once for `state`: the first caller runs it, later ones wait until it is done.
// Within a gather, work waits only on solved corners' gathers (resolveVertex), which wait on
// nothing of this gather; a gather's rays may wait on a lower level's vertices (a FinalGather over
// a VertexGather), never a higher one's. No wait can close a cycle, so every wait ends.
template <typename Publish>
void VertexGather::once(std::atomic<uint8_t>& state, Publish&& publish) {
  if (state.load(std::memory_order_acquire) == kDone) return;
  uint8_t expected = kPending;
  if (state.compare_exchange_strong(expected, kRunning, std::memory_order_acq_rel)) {
    publish();
    state.store(kDone, std::memory_order_release);
    state.notify_all();
    return;
  }
  while (state.load(std::memory_order_acquire) != kDone) state.wait(kRunning, std::memory_order_acquire);
}

VertexGather::PointGather VertexGather::gatherAt(Vec3 position, Vec3 n, Vec3 towards, int side, uint32_t index) const {
  PointGather out;
  const Vec3 origin = position + 0.01f * (towards - position) + rayOffsetFor(surfaces_.sceneExtent) * n;
  const int count = side * side;
  std::vector<Vec3> dirs(static_cast<size_t>(count));
  HemisphereStrata(n, side, index, seed_).directions(HemisphereStrata::Warp::Cosine, dirs);
  std::vector<RTCRayHit> hits(dirs.size());
  for (size_t k = 0; k < hits.size(); ++k)
    hits[k].ray = makeRay(origin, dirs[k], 0.0f, std::numeric_limits<float>::infinity());
  // Cosine-distributed: the irradiance is pi times the mean radiance.
  const std::vector<Rgb> weights(static_cast<size_t>(count), Rgb(std::numbers::pi_v<float> / float(count)));
  const std::vector<Rgb*> targets(static_cast<size_t>(count), &out.irradiance);
  const size_t backs = gather_.add(hits, weights, targets, hashCombine(seed_, index));
  out.inside = 2 * backs > size_t(count);
  // What the rays met nearest, and the skies (skiesOf) through those that met nothing, or only glass:
  // a sky is a light, and the lights' rays pass glass (trace/thin_glass.h).
  const RayTracer& tracer = gather_.tracer();
  std::vector<RTCRay> throughGlass;
  for (const RTCRayHit& h : hits) {
    const Vec3 dir(h.ray.dir_x, h.ray.dir_y, h.ray.dir_z);
    if (h.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
      out.reach = std::min(out.reach, h.ray.tfar);
      if (!skies_.empty() && tracer.transmittanceOf(h.hit.primID) != Rgb(0.0f))
        throughGlass.push_back(makeRay(origin, dir, 0.0f, std::numeric_limits<float>::infinity()));
      continue;
    }
    for (const Light* sky : skies_) out.irradiance += weights[0] * skyRadiance(*sky, dir, up_);
  }
  if (!throughGlass.empty()) {
    std::vector<Rgb> through;
    tracer.transmitted(throughGlass, through);
    for (size_t k = 0; k < throughGlass.size(); ++k) {
      if (isOccluded(throughGlass[k])) continue;
      const Vec3 dir(throughGlass[k].dir_x, throughGlass[k].dir_y, throughGlass[k].dir_z);
      for (const Light* sky : skies_) out.irradiance += weights[0] * through[k] * skyRadiance(*sky, dir, up_);
    }
  }
  return out;
}

void VertexGather::gatherVertex(uint32_t vi) {
  Vertex& v = vertices_[vi];
  const float length = glm::length(v.normal);
  if (!(length > 0.0f)) return;
  const PointGather g = gatherAt(v.position, v.normal / length, v.centroids / float(v.slots), v.side, vi);
  v.irradiance = g.irradiance;
  v.inside = g.inside;
  v.reach = g.reach;
  v.traced = true;
  traced_.fetch_add(1, std::memory_order_relaxed);
}

VertexGather::VertexView VertexGather::vertex(uint32_t vi) const {
  const Vertex& v = vertices_[vi];
  return {v.position, v.irradiance, v.reach, v.side, v.inside};
}

// A vertex the splits made is interpolated from its solved element's corners (gathered first: they
// wait on nothing, so this wait ends) unless a corner is inside a solid or saw a surface nearer
// than the vertex's distance from it over kInterpolationReach.
void VertexGather::resolveVertex(uint32_t vi) {
  once(vertexState_[vi], [&] {
    Vertex& v = vertices_[vi];
    if (v.parent == kNoParent) return gatherVertex(vi);
    const uint32_t* corner = &solvedCorners_[size_t(v.parent) * 4];
    const std::array<float, 4> w =
        cornerWeights(refined_->solved().elements[v.parent].polygon.count, v.local.x, v.local.y);
    Rgb interpolated(0.0f);
    for (size_t k = 0; k < 4; ++k) {
      if (w[k] <= 0.0f) continue;
      if (corner[k] == kNoVertex) return gatherVertex(vi);  // a solved corner no split element has
      once(vertexState_[corner[k]], [&] { gatherVertex(corner[k]); });
      const Vertex& c = vertices_[corner[k]];
      if (c.inside || glm::length(v.position - c.position) * kInterpolationReach > c.reach) return gatherVertex(vi);
      interpolated += w[k] * c.irradiance;
    }
    v.irradiance = interpolated;
  });
}

const Rgb* VertexGather::corners(uint32_t e) {
  once(elementState_[e], [&] {
    const int n = surfaces_.elements[e].polygon.count;
    const uint32_t* vs = &vertexOf_[size_t(e) * 4];
    for (int c = 0; c < n; ++c) resolveVertex(vs[c]);
    Rgb outside(0.0f);
    int outsideCount = 0;
    for (int c = 0; c < n; ++c) {
      const Vertex& v = vertices_[vs[c]];
      corners_[size_t(e) * 4 + size_t(c)] = v.irradiance;
      if (!v.inside) outside += v.irradiance, ++outsideCount;
    }
    if (outsideCount > 0 && outsideCount < n)
      for (int c = 0; c < n; ++c)
        if (vertices_[vs[c]].inside) corners_[size_t(e) * 4 + size_t(c)] = outside / float(outsideCount);
  });
  return &corners_[size_t(e) * 4];
}

std::vector<Rgb> VertexGather::all() {
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, uint32_t(surfaces_.elements.size()), 16),
                    [&](const tbb::blocked_range<uint32_t>& r) {
                      for (uint32_t e = r.begin(); e < r.end(); ++e) corners(e);
                    });
  return corners_;
}

size_t VertexGather::verticesGathered() const {
  size_t n = 0;
  for (size_t v = 0; v < vertices_.size(); ++v) n += vertexState_[v].load(std::memory_order_relaxed) == kDone;
  return n;
}

}  // namespace luxel
