#include "transport/cpu_transport.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <type_traits>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "core/random.h"
#include "core/spherical_harmonics.h"
#include "luxel/error.h"
#include "transport/form_factor.h"
#include "transport/light_sampling.h"
#include "transport/shaft.h"
#include "trace/convex_solid.h"
#include "trace/element_polygons.h"

namespace luxel {
namespace {

// Pairs handed to Embree in one stream: large enough to amortise the call, small enough to stay
// in cache.
constexpr size_t kPairsPerBatch = 128;
// The densest midpoint rule for the unoccluded factor, 2 x 2 receiver points. Every element uses
// its rule for every patch (so rows sum to 1 in a closed scene), which makes it the largest cost
// of a solve. Measured against 3 x 3: element radiosities of cornell-large differ by 5e-5 NRMSE
// (0.05% at most), energy balance of shader-box-774 (the coarsest) 1.0016 against 1.0007; 15% less
// time. One point (1 x 1) gives 1.0066 there: too coarse for reciprocity near contacts.
constexpr int kMaxAnalyticSide = 2;
// Receiver patches with fewer elements than this are not shaft-tested.
constexpr size_t kMinElementsToClassify = 4;
// Patch-pair classification keeps one byte per pair: up to 64 MiB.
constexpr size_t kMaxClassifiedPatches = 8192;

float polygonRadius(const Polygon& p, Vec3 centre) {
  float r = 0.0f;
  for (int i = 0; i < p.count; ++i) r = std::max(r, glm::length(p.v[size_t(i)] - centre));
  return r;
}

// Per face, the ray tracer instance it belongs to: the index among the scene's dynamic objects of
// the object that places it, or -1 for static geometry. Empty when nothing is dynamic.
std::vector<int32_t> faceInstances(const Scene& scene, const SurfaceSet& set) {
  std::vector<int32_t> instanceOfObject(scene.objects.size(), -1);
  int32_t count = 0;
  for (uint32_t o : scene.dynamicObjects()) instanceOfObject[o] = count++;
  if (count == 0) return {};
  std::vector<int32_t> out(set.faces.size(), -1);
  for (size_t f = 0; f < set.faces.size(); ++f) {
    const uint32_t object = scene.meshes[set.faces[f].mesh].object;
    if (object != kNoObject) out[f] = instanceOfObject[object];
  }
  return out;
}

int squareCount(int n) { return std::clamp(int(std::sqrt(float(n)) + 1e-3f), 1, 16); }

// Stratum i of a k x k grid is cell (i % k, i / k); tabulated for every k up to 16, because the
// divisions cost more than the rest of generating a ray.
const std::array<std::array<uint8_t, 2>, 256>& strataCells(int k) {
  static const auto table = [] {
    std::array<std::array<std::array<uint8_t, 2>, 256>, 17> t{};
    for (int n = 1; n <= 16; ++n)
      for (int i = 0; i < n * n; ++i) t[size_t(n)][size_t(i)] = {uint8_t(i % n), uint8_t(i / n)};
    return t;
  }();
  return table[size_t(k)];
}

// A random permutation of 0..m-1 (m <= 256), to pair strata of two domains without correlation.
void shuffledStrata(Rng& rng, int m, int* out) {
  for (int i = 0; i < m; ++i) out[i] = i;
  // Lemire's multiply-shift maps a 32-bit draw onto [0, i] without a division (one per ray).
  for (int i = m - 1; i > 0; --i)
    std::swap(out[i], out[uint32_t((uint64_t(rng.nextUint()) * uint64_t(i + 1)) >> 32)]);
}

}  // namespace

struct CpuTransport::Workspace {
  std::vector<RTCRay> rays;  // each ray's id holds the bits of its point-to-point kernel (a float)
  // The pairs that cast rays: their rays are rays[first, first + count); *out becomes
  // `analytic` times the kernel-weighted share of them that arrive.
  struct Traced {
    float* out;
    uint32_t first, count;
    float analytic;
  };
  std::vector<Traced> traced;
  std::vector<RTCRay> movedRays;  // visibilityChangedByMove: the same rays, for the moved faces' second place
};

struct CpuTransport::ThreadLocal {
  tbb::enumerable_thread_specific<Workspace> workspaces;
};

CpuTransport::CpuTransport(const Scene& scene, const SurfaceSet& surfaces,
                           const FormFactorOptions& options)
    : scene_(scene),
      surfaces_(surfaces),
      options_(options),
      facePolygons_(facePolygons(surfaces)),
      tracer_(facePolygons_, faceInstances(scene, surfaces)),
      threadLocal_(std::make_unique<ThreadLocal>()) {
  rayOffset_ = rayOffsetFor(surfaces.sceneExtent);
  tracer_.setGlass(std::make_shared<ThinGlass>(ThinGlass::overFaces(scene, surfaces)));
  for (uint32_t o : scene.dynamicObjects()) builtAt_.emplace_back(o, scene.objects[o].transform);
  // A static scene's polygons never change: the tracer's corners serve (facePolygon), and a copy
  // of every face here would be 52 bytes a face for nothing.
  if (builtAt_.empty()) std::vector<Polygon>().swap(facePolygons_);
  patchRadius_.resize(surfaces.patches.size());
  for (size_t p = 0; p < surfaces.patches.size(); ++p)
    patchRadius_[p] = polygonRadius(surfaces.patches[p].polygon, surfaces.patches[p].centroid);
  findEmitters(patchEmits_);

  const size_t np = surfaces.patches.size();
  if (options.classifyVisibility && np <= kMaxClassifiedPatches) {
    pairVisibility_.reset(new std::atomic<uint8_t>[np * np]);
    for (size_t i = 0; i < np * np; ++i) pairVisibility_[i].store(0, std::memory_order_relaxed);
  }

  elementsChanged();
}

void CpuTransport::objectsMoved(std::span<const uint32_t> objects) {
  for (uint32_t o : objects) {
    auto it = std::find_if(builtAt_.begin(), builtAt_.end(), [&](const auto& b) { return b.first == o; });
    if (it == builtAt_.end())
      throw Error(fmt::format("object {} is not one of the dynamic objects the transport was built with", o));
    // The instance's polygons are where they stood at construction: place them relative to that.
    const std::string what = fmt::format("object '{}'", scene_.objects[o].name);
    tracer_.placeInstance(uint32_t(it - builtAt_.begin()), similarityBetween(it->second, scene_.objects[o].transform, what));
  }
  tracer_.commit();
  // Faces and patches of the moved objects are where the surfaces now say.
  std::vector<uint8_t> moved(scene_.objects.size(), 0);
  for (uint32_t o : objects) moved[o] = 1;
  auto movedFace = [&](uint32_t f) {
    const uint32_t o = scene_.meshes[surfaces_.faces[f].mesh].object;
    return o != kNoObject && moved[o];
  };
  // Where the moved faces were and are: the elements near either place get new quadratures.
  Vec3 lo[2], hi[2];
  for (int k = 0; k < 2; ++k) lo[k] = Vec3(std::numeric_limits<float>::max()), hi[k] = -lo[k];
  auto grow = [&](int k, const Polygon& p) {
    for (int c = 0; c < p.count; ++c) lo[k] = glm::min(lo[k], p.v[size_t(c)]), hi[k] = glm::max(hi[k], p.v[size_t(c)]);
  };
  std::vector<Polygon> before, after;
  for (uint32_t f = 0; f < surfaces_.faces.size(); ++f) {
    if (!movedFace(f)) continue;
    grow(0, facePolygons_[f]);
    before.push_back(facePolygons_[f]);
    facePolygons_[f].v = surfaces_.faces[f].corners;
    after.push_back(facePolygons_[f]);
    grow(1, facePolygons_[f]);
  }
  // The moved faces alone, where they were and where they are, for visibilityChangedByMove; and
  // when every moved object is closed and convex, its solid where it was and where it is, with
  // how far its corners moved.
  if (movedBefore_) movedRays_ += movedBefore_->raysTraced() + movedAfter_->raysTraced();
  movedBefore_.reset(), movedAfter_.reset();
  if (!before.empty()) {
    movedBefore_ = std::make_unique<RayTracer>(before);
    movedAfter_ = std::make_unique<RayTracer>(after);
  }
  movedObjects_.assign(objects.begin(), objects.end());
  for (int k = 0; k < 2; ++k) movedLo_[k] = lo[k], movedHi_[k] = hi[k];
  movedSolids_.clear();
  for (uint32_t o : objects) {
    std::vector<Polygon> was, now;
    float moved = 0.0f;
    for (uint32_t f = 0, k = 0; f < surfaces_.faces.size(); ++f) {
      if (!movedFace(f)) continue;
      if (scene_.meshes[surfaces_.faces[f].mesh].object == o) {
        was.push_back(before[k]);
        now.push_back(after[k]);
        for (int c = 0; c < before[k].count; ++c)
          moved = std::max(moved, glm::length(after[k].v[size_t(c)] - before[k].v[size_t(c)]));
      }
      ++k;
    }
    // The faces lie within the tolerance of the solid's planes; Embree's verdicts are sure a few
    // ray offsets away from them.
    const float tolerance = rayOffset_;
    ConvexSolid solidWas = ConvexSolid::fromPolygons(was, tolerance), solidNow = ConvexSolid::fromPolygons(now, tolerance);
    if (!solidWas.valid() || !solidNow.valid()) {
      movedSolids_.clear();
      break;
    }
    movedSolids_.push_back({std::move(solidWas), std::move(solidNow), moved, tolerance + 10.0f * rayOffset_});
  }
  for (uint32_t p = 0; p < surfaces_.patches.size(); ++p)
    if (movedFace(surfaces_.patches[p].face))
      patchRadius_[p] = polygonRadius(surfaces_.patches[p].polygon, surfaces_.patches[p].centroid);
  // Any pair's shaft may now hold a moved object, or have lost one: classify again as asked.
  // Verdicts carry the generation they were made in, so forgetting them all is one increment
  // (the table is cleared only when the 6-bit generation wraps).
  if (pairVisibility_ && ++pairGeneration_ == 64) {
    const size_t np = surfaces_.patches.size();
    for (size_t i = 0; i < np * np; ++i) pairVisibility_[i].store(0, std::memory_order_relaxed);
    pairGeneration_ = 1;
  }
  // Receiver quadratures depend on how near other faces come (within nearFactor times the
  // element's radius): only the moved elements and those that reach the moved faces' old or new
  // bounds can change.
  redoneByMove_.clear();
  if (!quadratureReady_.load()) return;  // made from scratch when first needed
  std::vector<uint32_t>& near = redoneByMove_;
  for (uint32_t e = 0; e < surfaces_.elements.size(); ++e) {
    const Element& el = surfaces_.elements[e];
    const float reach = options_.nearFactor * elementRadius_[e];
    bool affected = movedFace(el.face);
    for (int k = 0; k < 2 && !affected; ++k) {
      const Vec3 gap = glm::max(glm::max(lo[k] - el.centroid, el.centroid - hi[k]), Vec3(0.0f));
      affected = glm::dot(gap, gap) <= reach * reach;
    }
    if (affected) near.push_back(e);
  }
  updateQuadrature(near);
}

void CpuTransport::findEmitters(std::vector<uint8_t>& emits) const {
  emits.assign(surfaces_.patches.size(), 0);
  for (size_t p = 0; p < surfaces_.patches.size(); ++p)
    for (uint32_t e : surfaces_.patches[p].elements) {
      const Rgb& x = surfaces_.elements[e].exitance;
      emits[p] |= (x.r + x.g + x.b) > 0.0f;
    }
}

void CpuTransport::sourcesChanged() {
  std::vector<uint8_t> emits;
  findEmitters(emits);
  redoneBySources_.clear();
  for (uint32_t p = 0; p < emits.size(); ++p)
    if (emits[p] != patchEmits_[p]) redoneBySources_.push_back(p);
  patchEmits_ = std::move(emits);
}

void CpuTransport::elementsChanged() {
  const std::lock_guard lock(quadratureMutex_);
  quadratureReady_.store(false);
}

void CpuTransport::ensureQuadrature() {
  if (quadratureReady_.load(std::memory_order_acquire)) return;
  const std::lock_guard lock(quadratureMutex_);
  if (quadratureReady_.load(std::memory_order_relaxed)) return;
  const size_t ne = surfaces_.elements.size();
  elementRadius_.resize(ne);
  elementQuadrature_.resize(ne);
  std::vector<uint32_t> all(ne);
  for (uint32_t e = 0; e < ne; ++e) all[e] = e;
  updateQuadrature(all);
  quadratureReady_.store(true, std::memory_order_release);
}

void CpuTransport::updateQuadrature(std::span<const uint32_t> elements) {
  const SurfaceSet& surfaces = surfaces_;
  // Each element's receiver quadrature: denser the closer another face's patch comes, so that
  // the midpoint rule's error stays a small fraction of the factor of the nearest source.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, elements.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) {
      const uint32_t ei = elements[i];
      const Element& e = surfaces.elements[ei];
      const float radius = polygonRadius(e.polygon, e.centroid);
      elementRadius_[ei] = radius;
      // Only faces closer than nearFactor * radius make the rule denser than one point; the
      // search stops once a face is near enough to give the densest rule.
      const float floor = std::max(0.1f * radius, options_.nearFactor * radius / float(kMaxAnalyticSide));
      float gap = std::numeric_limits<float>::max();
      tracer_.forEachNear(e.centroid, options_.nearFactor * radius, [&](uint32_t face) {
        if (face != e.face) gap = std::min(gap, pointPolygonDistance(e.centroid, facePolygon(face)));
        return gap > floor;
      });
      gap = std::max(gap, 0.1f * radius);
      elementQuadrature_[ei] = uint8_t(std::clamp(int(std::ceil(options_.nearFactor * radius / gap)), 1, kMaxAnalyticSide));
    }
  });
}

CpuTransport::~CpuTransport() = default;

CpuTransport::PairVisibility CpuTransport::classify(uint32_t q, uint32_t p) {
  std::atomic<uint8_t>& slot = pairVisibility_[size_t(q) * surfaces_.patches.size() + p];
  const uint8_t stored = slot.load(std::memory_order_relaxed);
  if (stored >> 2 == pairGeneration_) return PairVisibility(stored & 3u);
  // Only what can be proved: an empty shaft means clear. A verdict of "blocked" from a few test
  // rays between the patches, which an earlier version used, darkened whole patches that in fact
  // saw a sliver of a light (1% RMS error on the Cornell box, measured against the reference).
  // Two threads may classify the same pair at once; both reach the same verdict.
  PairVisibility verdict = shaftIsEmpty(surfaces_.patches[q], surfaces_.patches[p]) ? PairVisibility::Clear
                                                                                      : PairVisibility::Partial;
  // The shaft is symmetric: one test serves both directions.
  const uint8_t value = uint8_t(pairGeneration_ << 2 | uint8_t(verdict));
  slot.store(value, std::memory_order_relaxed);
  pairVisibility_[size_t(p) * surfaces_.patches.size() + q].store(value, std::memory_order_relaxed);
  return verdict;
}

bool CpuTransport::shaftIsEmpty(const Patch& a, const Patch& b) const {
  return shaftIsClear(Shaft(a.polygon, b.polygon, 2.0f * rayOffset_), tracer_,
                      [&](uint32_t face) { return facePolygon(face); }, a.face, b.face);
}

CpuTransport::Workspace& CpuTransport::workspace() { return threadLocal_->workspaces.local(); }

void CpuTransport::computeAnalytic(std::span<const Pair> pairs, float* out) const {
  // Pending one-point receivers towards one patch, evaluated four at a time.
  Vec3 points[4], normals[4];
  size_t pending[4];
  int count = 0;
  uint32_t pendingPatch = 0;
  auto flush = [&] {
    if (count == 0) return;
    const Patch& p = surfaces_.patches[pendingPatch];
    if (count == 1) {  // rows change patch every pair: one lane would waste three
      out[pending[0]] = pointToPolygonFormFactor(points[0], normals[0], p.polygon, p.normal, Sides::Front, Sides::Front);
      count = 0;
      return;
    }
    for (int i = count; i < 4; ++i) points[i] = points[0], normals[i] = normals[0];
    float f[4];
    pointToPolygonFormFactors4(points, normals, p.polygon, p.normal, f);
    for (int i = 0; i < count; ++i) out[pending[i]] = f[i];
    count = 0;
  };
  for (size_t i = 0; i < pairs.size(); ++i) {
    const Element& e = surfaces_.elements[pairs[i].element];
    const Patch& p = surfaces_.patches[pairs[i].patch];
    out[i] = 0.0f;
    if (e.face == p.face) continue;  // a flat face does not see itself
    const int ka = elementQuadrature_[pairs[i].element];
    if (ka == 1) {
      if (count > 0 && pendingPatch != pairs[i].patch) flush();
      pendingPatch = pairs[i].patch;
      points[count] = e.centroid, normals[count] = e.normal, pending[count] = i;
      if (++count == 4) flush();
      continue;
    }
    static_assert(kMaxAnalyticSide <= 2, "the dense rule fills the four lanes of one call");
    Vec3 rule[4], ruleNormals[4];
    for (int j = 0; j < 4; ++j) {
      rule[j] = polygonPoint(e.polygon, (float(j % 2) + 0.5f) * 0.5f, (float(j / 2) + 0.5f) * 0.5f);
      ruleNormals[j] = e.normal;
    }
    float f[4];
    pointToPolygonFormFactors4(rule, ruleNormals, p.polygon, p.normal, f);
    out[i] = 0.25f * ((f[0] + f[1]) + (f[2] + f[3]));
  }
  flush();
}

template <typename Visit>
void CpuTransport::forEachPairRay(uint32_t element, uint32_t patch, Visit&& visit) const {
  const Element& e = surfaces_.elements[element];
  const Patch& p = surfaces_.patches[patch];
  const float distance = glm::length(e.centroid - p.centroid);
  const bool nearField = distance < options_.nearFactor * (elementRadius_[element] + patchRadius_[patch]);
  int wanted = patchEmits_[patch] ? options_.emitterRaysPerPair : options_.raysPerPair;
  if (nearField) wanted = std::max(wanted, options_.nearRaysPerPair);
  const int k = squareCount(wanted);
  const int m = k * k;

  // Deterministic per pair, so a row and a column compute the same number.
  Rng rng(hashCombine(hashCombine(options_.seed, element), patch));
  int permutation[256];
  shuffledStrata(rng, m, permutation);
  const float invK = 1.0f / float(k);
  const auto& cells = strataCells(k);  // (column, row) of each stratum: no division per ray
  for (int i = 0; i < m; ++i) {
    const auto [ix, iy] = cells[size_t(i)];
    float s = (float(ix) + rng.next()) * invK, t = (float(iy) + rng.next()) * invK;
    Vec3 x = polygonPoint(e.polygon, s, t);
    const auto [jx, jy] = cells[size_t(permutation[i])];
    float su = (float(jx) + rng.next()) * invK, sv = (float(jy) + rng.next()) * invK;
    Vec3 y = polygonPoint(p.polygon, su, sv);
    Vec3 d = y - x;
    // Where the two polygons cross each other's planes, some point pairs face away; A already
    // accounts for that geometry, so V is measured over the point pairs that face each other.
    const float cosE = glm::dot(e.normal, d), cosP = -glm::dot(p.normal, d);
    if (cosE <= 0.0f || cosP <= 0.0f) continue;
    const float r2 = glm::dot(d, d);
    // A visitor that returns false has seen enough of this pair.
    if constexpr (std::is_same_v<std::invoke_result_t<Visit&, Vec3, Vec3, float>, bool>) {
      if (!visit(x + e.normal * rayOffset_, y + p.normal * rayOffset_, cosE * cosP / (r2 * r2))) return;
    } else {
      visit(x + e.normal * rayOffset_, y + p.normal * rayOffset_, cosE * cosP / (r2 * r2));
    }
  }
}

void CpuTransport::computePairs(std::span<const Pair> pairs) {
  if (pairs.size() > kPairsPerBatch) {
    for (size_t i = 0; i < pairs.size(); i += kPairsPerBatch)
      computePairs(pairs.subspan(i, std::min(kPairsPerBatch, pairs.size() - i)));
    return;
  }
  Workspace& ws = workspace();
  ws.rays.clear();
  ws.traced.clear();

  // A, the unoccluded factor averaged over the receiver by a midpoint rule, for the whole batch
  // first: four receiver points at a time (an element's 2 x 2 rule, or the centroids of four
  // elements facing the same patch, as a column batch has them).
  float analyticOf[kPairsPerBatch];
  computeAnalytic(pairs, analyticOf);

  for (size_t pi = 0; pi < pairs.size(); ++pi) {
    const Pair& pair = pairs[pi];
    *pair.out = 0.0f;
    const Element& e = surfaces_.elements[pair.element];
    // F = A * V (Wallace et al. 1989). Each element uses one point set for every patch, dense
    // when other geometry is close: then A's row sums in an enclosure are exactly 1, so closed
    // scenes conserve energy. V is the share of stratified, jittered rays between the two that
    // arrive, each weighted by its point-to-point kernel G = cos cos / r^2: the ratio
    // sum(G V) / sum(G) tends to the true visible share of the factor. The unweighted share
    // (Wallace's) does not: near points carry more of the factor and are seen more often than
    // far ones, so it came out 2-22% low on the Cornell box's interreflected light against
    // cosine-sampled rays, and 51% low against a closed form
    // (tests/analytic/test_visibility_weighting.cpp).
    const float analytic = analyticOf[pi];
    if (analytic <= 0.0f) continue;
    // A shaft test pays for itself over the receiver patch's elements; for a patch of one or two
    // elements (scenes built of many small faces) it would cost more than their rays.
    if (pairVisibility_ && surfaces_.patches[e.patch].elements.size() >= kMinElementsToClassify &&
        classify(e.patch, pair.patch) == PairVisibility::Clear) {
      *pair.out = analytic;
      continue;
    }

    const size_t first = ws.rays.size();
    forEachPairRay(pair.element, pair.patch, [&](Vec3 xo, Vec3 yo, float kernel) {
      RTCRay& ray = ws.rays.emplace_back(makeRay(xo, yo - xo, 0.0f, 1.0f));
      ray.id = std::bit_cast<uint32_t>(kernel);  // Embree leaves id to its caller
    });
    const size_t valid = ws.rays.size() - first;
    if (valid == 0) {
      *pair.out = analytic;  // a sliver no sample pair straddles: too small to test, assume visible
      continue;
    }
    ws.traced.push_back({pair.out, uint32_t(first), uint32_t(valid), analytic});
  }

  tracer_.occluded(ws.rays);
  for (const Workspace::Traced& t : ws.traced) {
    float all = 0.0f, arrived = 0.0f;
    for (uint32_t i = t.first; i < t.first + t.count; ++i) {
      const float g = std::bit_cast<float>(ws.rays[i].id);
      all += g;
      arrived += isOccluded(ws.rays[i]) ? 0.0f : g;
    }
    *t.out = all > 0.0f ? t.analytic * (arrived / all) : t.analytic;
  }
}

bool CpuTransport::movedRaySettled(Vec3 a, Vec3 b, float reach) const {
  // A ray that misses the solid grown by `reach` misses it wherever it stands within reach, and
  // one that passes deeper than that meets it everywhere.
  if (movedSolids_.empty()) return false;
  bool clear = true;
  for (const MovedSolid& m : movedSolids_) {
    const ConvexSolid::Segment s = m.was.classify(a, b, reach + m.pad);
    if (s == ConvexSolid::Segment::Crosses) return true;
    clear &= s == ConvexSolid::Segment::Clear;
  }
  return clear;
}

CpuTransport::MoveVerdict CpuTransport::moveVerdict(Vec3 a, Vec3 b) const {
  // Closed convex movers decide most rays without tracing, at each place on its own: a ray that
  // crosses one solid is blocked there, one that misses every solid (grown by the rounding pad)
  // is clear. Only rays that graze a solid, at either place, are traced against the moved faces.
  // (Classifying against the old place grown by the whole move, as certificates do, leaves every
  // ray within that distance of the surface unsure: docs/algorithms.md, "Dynamic radiosity".)
  if (movedSolids_.empty()) return MoveVerdict::Unsure;
  using Segment = ConvexSolid::Segment;
  auto at = [&](const ConvexSolid MovedSolid::*place) {
    Segment verdict = Segment::Clear;
    for (const MovedSolid& m : movedSolids_) {
      const Segment s = (m.*place).classify(a, b, m.pad);
      if (s == Segment::Crosses) return s;
      if (s == Segment::Unsure) verdict = s;
    }
    return verdict;
  };
  const Segment was = at(&MovedSolid::was);
  if (was == Segment::Unsure) return MoveVerdict::Unsure;
  const Segment now = at(&MovedSolid::now);
  if (now == Segment::Unsure) return MoveVerdict::Unsure;
  return was == now ? MoveVerdict::Same : MoveVerdict::Changed;
}

void CpuTransport::visibilityChangedByMove(std::span<const ElementPatch> pairs, std::span<uint8_t> changed, float certify,
                                           std::span<uint8_t> certified) {
  std::fill(certified.begin(), certified.end(), uint8_t(0));
  if (!movedBefore_) {
    std::fill(changed.begin(), changed.end(), uint8_t(1));
    return;
  }
  // Certificates need every ray settled against the solids for a wider reach; a ray settled so
  // is settled for this move too (the solids grown and shrunk by less).
  bool certifying = !certified.empty() && !movedSolids_.empty();
  for (const MovedSolid& m : movedSolids_) certifying &= certify >= m.moved;
  ensureQuadrature();
  // A pair's rays are blocked in the scene where they are blocked by the static faces or by the
  // moved ones; where no ray's verdict against the moved faces differs between their two places,
  // no ray's verdict in the scene does, and the factor is the same number as before. Against
  // closed convex movers most rays are decided without tracing (moveVerdict; movedRaySettled for
  // the certificates' wider reaches), and a pair stops at its first ray proved changed; the rest
  // are traced against the moved faces alone, a fraction of the scene's BVH.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pairs.size(), kPairsPerBatch), [&](const tbb::blocked_range<size_t>& r) {
    Workspace& ws = workspace();
    std::vector<RTCRay>& before = ws.rays;
    std::vector<RTCRay>& after = ws.movedRays;
    uint32_t first[kPairsPerBatch + 1];
    uint8_t preset[kPairsPerBatch];  // pairs whose change the solids proved
    for (size_t begin = r.begin(); begin < r.end(); begin += kPairsPerBatch) {
      const size_t count = std::min(kPairsPerBatch, r.end() - begin);
      before.clear();
      for (size_t i = 0; i < count; ++i) {
        first[i] = uint32_t(before.size());
        // The widest reach every ray so far is settled for: certified levels are tried from the
        // widest down, and a ray settled for none of them is settled (or traced) for this move.
        int level = certifying ? kCertificateLevels : 0;
        bool differs = false;
        forEachPairRay(pairs[begin + i].element, pairs[begin + i].patch, [&](Vec3 a, Vec3 b, float) {
          while (level > 0 && !movedRaySettled(a, b, std::ldexp(certify, level - 1))) --level;
          if (level > 0) return true;
          switch (moveVerdict(a, b)) {
            case MoveVerdict::Same: return true;
            case MoveVerdict::Changed: return !(differs = true);  // the pair is recomputed: stop
            case MoveVerdict::Unsure: before.push_back(makeRay(a, b - a, 0.0f, 1.0f)); return true;
          }
          return true;
        });
        if (differs) before.resize(first[i]);  // no need to trace what is already known
        preset[i] = differs;
        if (certifying) certified[begin + i] = uint8_t(level);
      }
      first[count] = uint32_t(before.size());
      after = before;
      movedBefore_->occluded(before);
      movedAfter_->occluded(after);
      for (size_t i = 0; i < count; ++i) {
        uint8_t differs = preset[i];
        for (uint32_t j = first[i]; j < first[i + 1] && !differs; ++j)
          differs = isOccluded(before[j]) != isOccluded(after[j]);
        changed[begin + i] = differs;
      }
    }
  });
}

void CpuTransport::columns(std::span<const uint32_t> patches, std::span<float> out) {
  ensureQuadrature();
  const size_t n = surfaces_.elements.size();
  for (size_t c = 0; c < patches.size(); ++c) {
    float* column = out.data() + c * n;
    const uint32_t patch = patches[c];
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kPairsPerBatch), [&](const tbb::blocked_range<size_t>& r) {
      Pair batch[kPairsPerBatch];
      size_t count = 0;
      for (size_t e = r.begin(); e < r.end(); ++e) {
        batch[count++] = Pair{uint32_t(e), patch, column + e};
        if (count == kPairsPerBatch) computePairs({batch, count}), count = 0;
      }
      if (count) computePairs({batch, count});
    });
  }
}

void CpuTransport::rows(std::span<const uint32_t> elements, std::span<float> out) {
  ensureQuadrature();
  const size_t np = surfaces_.patches.size();
  const size_t total = elements.size() * np;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, total, kPairsPerBatch), [&](const tbb::blocked_range<size_t>& r) {
    Pair batch[kPairsPerBatch];
    size_t count = 0;
    for (size_t i = r.begin(); i < r.end(); ++i) {
      batch[count++] = Pair{elements[i / np], uint32_t(i % np), out.data() + i};
      if (count == kPairsPerBatch) computePairs({batch, count}), count = 0;
    }
    if (count) computePairs({batch, count});
  });
}

void CpuTransport::pairs(std::span<const ElementPatch> pairs, std::span<float> out) {
  ensureQuadrature();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pairs.size(), kPairsPerBatch), [&](const tbb::blocked_range<size_t>& r) {
    Pair batch[kPairsPerBatch];
    size_t count = 0;
    for (size_t i = r.begin(); i < r.end(); ++i) {
      batch[count++] = Pair{pairs[i].element, pairs[i].patch, out.data() + i};
      if (count == kPairsPerBatch) computePairs({batch, count}), count = 0;
    }
    if (count) computePairs({batch, count});
  });
}

void CpuTransport::analyticIrradiance(std::span<Rgb> out) {
  std::vector<uint32_t> all(scene_.lights.size());
  for (uint32_t i = 0; i < all.size(); ++i) all[i] = i;
  lightIrradiance(all, out);
}

void CpuTransport::appendSamplesOfLight(uint32_t element, uint32_t li, int k, uint32_t pass, std::vector<RTCRay>& rays,
                                        std::vector<LightSample>& samples) const {
  const Vec3 up = glm::normalize(scene_.up);
  const int m = k * k;
  const Element& e = surfaces_.elements[element];
  // Every sample would be dark (a sun behind the element): none drawn, as none would be kept.
  if (!lightMayReachFront(scene_.lights[li], e.polygon, e.normal)) return;
  const PreparedLight light = prepareLight(scene_.lights[li]);
  // Seeded by the light's index in the scene, so that a light's samples do not depend on
  // which other lights are asked for.
  Rng rng(hashCombine(hashCombine(options_.seed ^ 0xA5A5A5A5u ^ pass, element), li));
  int permutation[256];
  shuffledStrata(rng, m, permutation);
  for (int i = 0; i < m; ++i) {
    float s = (float(i % k) + rng.next()) / float(k), t = (float(i / k) + rng.next()) / float(k);
    Vec3 x = polygonPoint(e.polygon, s, t);
    // Light samples are stratified independently of the point strata (shuffled index).
    float u1 = (float(permutation[i]) + rng.next()) / float(m), u2 = rng.next();
    LightSample ls = sampleLight(light, x, e.normal, Sides::Front, up, u1, u2);
    if (!ls.valid()) continue;
    Vec3 xo = x + e.normal * (glm::dot(e.normal, ls.direction) >= 0.0f ? rayOffset_ : -rayOffset_);
    rays.push_back(makeRay(xo, ls.direction, 0.0f, ls.tfar));
    ls.irradiance /= float(m);
    samples.push_back(ls);
  }
}

void CpuTransport::appendLightSamples(uint32_t element, std::span<const uint32_t> lights, std::vector<RTCRay>& rays,
                                      std::vector<LightSample>& samples, std::vector<uint32_t>* lightOf) const {
  for (size_t q = 0; q < lights.size(); ++q) {
    const size_t before = rays.size();
    appendSamplesOfLight(element, lights[q], firstLightSide(lights[q]), 0, rays, samples);
    if (lightOf) lightOf->insert(lightOf->end(), rays.size() - before, uint32_t(q));
  }
}

int CpuTransport::firstLightSide(uint32_t light) const {
  const int k = squareCount(options_.lightSamples);
  return isSkyLight(scene_.lights[light]) ? std::min(16, kSkySampleSide * k) : k;
}

int CpuTransport::refinedLightSide(uint32_t light) const {
  // A sky is not refined: inside a building an element sees it through windows that fill a few
  // per cent of its hemisphere, where the first samples all agree (none reaches) as often as not,
  // so their disagreement does not find where its light is uncertain.
  if (isSkyLight(scene_.lights[light])) return firstLightSide(light);
  return std::min(16, kLightRefinement * firstLightSide(light));
}

template <typename Visit>
void CpuTransport::visitLightSamples(std::span<const uint32_t> lights, Visit&& visit, std::span<const uint32_t> elements) {
  for (uint32_t li : lights)
    if (li >= scene_.lights.size())
      throw Error(fmt::format("light {} does not exist: the scene has {} lights", li, scene_.lights.size()));
  if (lights.empty()) return;
  if (refinedLight_.size() < scene_.lights.size()) refinedLight_.resize(scene_.lights.size());
  for (uint32_t li : lights) refinedLight_[li].resize(surfaces_.elements.size(), 0);
  const size_t count = elements.empty() ? surfaces_.elements.size() : elements.size();
  // An element's rays towards lamps and suns leave a small patch in nearly one direction, which
  // Embree traces faster as packets; a sky's go every way.
  bool coherent = true;
  for (uint32_t li : lights) coherent = coherent && !isSkyLight(scene_.lights[li]);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 16), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<RTCRay> rays, finer;
    std::vector<LightSample> samples, reached, finerSamples;
    std::vector<uint32_t> lightOf;
    std::vector<uint32_t> arrived, traced;
    std::vector<Rgb> through, finerThrough;  // what glass passes of each ray (trace/thin_glass.h)
    for (size_t i = r.begin(); i < r.end(); ++i) {
      const uint32_t ei = elements.empty() ? uint32_t(i) : elements[i];
      rays.clear(), samples.clear(), lightOf.clear();
      appendLightSamples(ei, lights, rays, samples, &lightOf);
      tracer_.transmitted(rays, through, coherent);
      arrived.assign(lights.size(), 0), traced.assign(lights.size(), 0);
      for (size_t j = 0; j < rays.size(); ++j) ++traced[lightOf[j]], arrived[lightOf[j]] += !isOccluded(rays[j]);
      // A light whose samples disagree has a shadow's edge across the element: its light there
      // is sampled again, kLightRefinement^2 times as densely, in place of the first samples.
      reached.clear();
      finer.clear(), finerSamples.clear();
      for (size_t q = 0; q < lights.size(); ++q) {
        const bool edge = arrived[q] > 0 && arrived[q] < traced[q];
        const int side = refinedLightSide(lights[q]);
        const bool refine = edge && side > firstLightSide(lights[q]);
        refinedLight_[lights[q]][ei] = refine;
        if (refine) appendSamplesOfLight(ei, lights[q], side, kRefinedPass, finer, finerSamples);
      }
      auto reach = [&](LightSample s, const Rgb& passed) {
        s.irradiance *= passed;
        reached.push_back(s);
      };
      for (size_t j = 0; j < rays.size(); ++j)
        if (!isOccluded(rays[j]) && !refinedLight_[lights[lightOf[j]]][ei]) reach(samples[j], through[j]);
      if (!finer.empty()) {
        tracer_.transmitted(finer, finerThrough, coherent);
        for (size_t j = 0; j < finer.size(); ++j)
          if (!isOccluded(finer[j])) reach(finerSamples[j], finerThrough[j]);
      }
      visit(ei, std::span<const LightSample>(reached));
    }
  });
}

void CpuTransport::lightIrradiance(std::span<const uint32_t> lights, std::span<Rgb> out) {
  std::fill(out.begin(), out.end(), Rgb(0.0f));
  visitLightSamples(lights, [&](size_t e, std::span<const LightSample> reached) {
    Rgb sum(0.0f);
    for (const LightSample& ls : reached) sum += ls.irradiance;
    out[e] = sum;
  });
}

size_t CpuTransport::updateLightIrradianceAfterMove(std::span<const uint32_t> lights, std::span<Rgb> irradiance) {
  bool known = true;  // each light's refined elements are those of its last computation
  for (uint32_t li : lights) known = known && li < refinedLight_.size() && refinedLight_[li].size() == surfaces_.elements.size();
  // With glass a ray's light is not decided by its first hit alone, which the verdicts below are.
  if (!movedBefore_ || !known || tracer_.hasGlass()) {
    lightIrradiance(lights, irradiance);
    return surfaces_.elements.size();
  }
  // An element keeps its sum when it did not move and none of its sample rays meets the moved
  // faces at one of their places and not the other: the same samples, the same verdicts.
  const size_t ne = surfaces_.elements.size();
  std::vector<uint8_t> again(ne, 0);
  const float reach = 2.0f * surfaces_.sceneExtent;  // no ray meets anything farther than this
  tbb::parallel_for(tbb::blocked_range<size_t>(0, ne, 64), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<RTCRay> rays, before, after;
    std::vector<LightSample> samples;
    for (size_t ei = r.begin(); ei < r.end(); ++ei) {
      const Element& e = surfaces_.elements[ei];
      const uint32_t object = scene_.meshes[surfaces_.faces[e.face].mesh].object;
      if (object != kNoObject && std::find(movedObjects_.begin(), movedObjects_.end(), object) != movedObjects_.end()) {
        again[ei] = 1;
        continue;
      }
      // Samples leave the element's front: a mover wholly behind its plane, before and after,
      // cannot shade it.
      bool behind = true;
      for (int k = 0; k < 2 && behind; ++k) {
        const Vec3 centre = 0.5f * (movedLo_[k] + movedHi_[k]), half = 0.5f * (movedHi_[k] - movedLo_[k]);
        behind = glm::dot(e.normal, centre - e.centroid) + glm::dot(glm::abs(e.normal), half) < -10.0f * rayOffset_;
      }
      if (behind) continue;
      rays.clear(), samples.clear(), before.clear();
      appendLightSamples(uint32_t(ei), lights, rays, samples);
      // A light refined here at its last computation keeps its finer samples while the first
      // ones' verdicts stand (if they change, the element is redone anyway).
      for (uint32_t li : lights)
        if (refinedLight_[li][ei]) appendSamplesOfLight(uint32_t(ei), li, refinedLightSide(li), kRefinedPass, rays, samples);
      for (const RTCRay& ray : rays) {
        const Vec3 a(ray.org_x, ray.org_y, ray.org_z), d(ray.dir_x, ray.dir_y, ray.dir_z);
        const float length = glm::length(d) * ray.tfar;
        const Vec3 b = a + d * (std::min(length, reach) / glm::length(d));
        const MoveVerdict verdict = moveVerdict(a, b);
        if (verdict == MoveVerdict::Changed) {
          again[ei] = 1;
          break;
        }
        if (verdict == MoveVerdict::Unsure) before.push_back(ray);
      }
      if (again[ei]) continue;
      after = before;
      movedBefore_->occluded(before);
      movedAfter_->occluded(after);
      for (size_t j = 0; j < before.size() && !again[ei]; ++j) again[ei] = isOccluded(before[j]) != isOccluded(after[j]);
    }
  });
  std::vector<uint32_t> redo;
  for (uint32_t e = 0; e < ne; ++e)
    if (again[e]) redo.push_back(e);
  visitLightSamples(lights, [&](size_t e, std::span<const LightSample> reached) {
    Rgb sum(0.0f);
    for (const LightSample& ls : reached) sum += ls.irradiance;
    irradiance[e] = sum;
  }, redo);
  return redo.size();
}

namespace {

void addSamplesSh(std::span<const LightSample> reached, Vec3 n, int count, Rgb* c) {
  for (const LightSample& ls : reached) {
    const Vec3 w = glm::normalize(ls.direction);
    shAddDirection(c, count, w, ls.irradiance / std::max(glm::dot(n, w), kShMinimumCosine));
  }
}

void checkShCount(int count) {
  if (count != kShL1Coefficients && count != kShCoefficients)
    throw Error(fmt::format("spherical harmonics of {} coefficients: 4 (L1) or 9 (L2)", count));
}

}  // namespace

void CpuTransport::lightSh(std::span<const uint32_t> lights, int count, std::span<Rgb> out) {
  checkShCount(count);
  std::fill(out.begin(), out.end(), Rgb(0.0f));
  visitLightSamples(lights, [&](size_t e, std::span<const LightSample> reached) {
    addSamplesSh(reached, surfaces_.elements[e].normal, count, out.data() + e * size_t(count));
  });
}

void CpuTransport::lightIrradianceAndSh(std::span<const uint32_t> lights, int count, std::span<Rgb> irradiance,
                                        std::span<Rgb> sh) {
  checkShCount(count);
  std::fill(irradiance.begin(), irradiance.end(), Rgb(0.0f));
  std::fill(sh.begin(), sh.end(), Rgb(0.0f));
  visitLightSamples(lights, [&](size_t e, std::span<const LightSample> reached) {
    Rgb sum(0.0f);
    for (const LightSample& ls : reached) sum += ls.irradiance;
    irradiance[e] = sum;
    addSamplesSh(reached, surfaces_.elements[e].normal, count, sh.data() + e * size_t(count));
  });
}

}  // namespace luxel
