// Dynamic radiosity by redistribution: after objects move or lights change, the last solution is
// corrected instead of solved again. M. van de Hoef, "Real-Time Dynamic Radiosity for High Quality
// Global Illumination", Utrecht 2013, Sec. 3.1 to 3.3 (shared/seeds/notes/001-dynamic-radiosity.md,
// sections 2.7 to 2.11); S. E. Chen, "Incremental Radiosity: An Extension of Progressive Radiosity
// to an Interactive Image Synthesis System", SIGGRAPH 1990; Puech, Sillion and Vedel, "Improving
// Interaction with Radiosity-based Lighting Simulation Programs", I3D 1990 (light edits).
//
// Progressive refinement keeps, for every element, B = E + rho H with H = H0 + sum_p F[e <- p] S_p,
// S_p the radiosity patch p has shot so far (the area mean of B - B_unshot over its elements).
// When the factors change from F to F' (a move), the analytic irradiance from H0 to H0' (a move,
// a light edit) and E, rho to E', rho' (a material edit), the redistribution of the thesis's
// Eq. 3.1.1 is, for every element,
//   H' = H + sum_p (F' - F)[e <- p] S_p + (H0' - H0),   B' = E' + rho' H',
// and B' - B is added to the unshot radiosity too, so that progressive refinement goes on to
// shoot the difference (negative where light was taken away: Puech's "negative light"). Nothing
// already shot changes during the redistribution (the thesis's chronological-order rule, L443):
// every difference is computed from the same S before any is applied. The correction is exact
// for the factors the transport gives, so after the shooting that follows, the solution is the
// one a solve from scratch at the new pose reaches, up to its stopping threshold; errors do not
// build up over frames.
//
// Only factors that can have changed are computed again. The methods differ in how they find
// them, as in the thesis (001 notes, section 2.8 and 2.9):
//  - incremental (Chen): every patch's column again, the old and the new hemicube of every patch
//    (O(2|M| + 2|C|) in the thesis's terms).
//  - cross-redistribution: the moved patches' columns (R_p(M, .)), the moved elements' factors
//    from the static patches (R_g(C, M), gathered), and of the static-to-static factors (R(C, C))
//    only those whose light passes through the space the moved objects left or entered: "all
//    redistributed radiosity passes through the modified geometry in either the new or old
//    position" (L482). The thesis estimates R(C, C) by cross projection through back hemicubes;
//    on the CPU we trace those factors exactly instead (notes 7.2, point 4), which removes the
//    projection's undersampling and the drift that made the thesis reject an incremental
//    projection. Three tests narrow R(C, C) to the factors that changed, exactly: no plane may
//    separate the receiver from the mover's box on the source's side, before or after the move
//    (dynamic/separating_planes.h); the receiver's patch must not lie in the umbra of a closed
//    convex mover at both places (trace/convex_solid.h); and one of the pair's rays must meet the
//    mover at one place and not the other (Transport::visibilityChangedByMove).
// Both keep every factor they have computed, so the columns of static patches that shoot after a
// move are current: progressive iterations may run between moves without the "remove M, iterate,
// insert M" wrapper of L843.
#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/stopwatch.h"
#include "trace/convex_solid.h"
#include "dynamic/separating_planes.h"
#include "solve/progressive_solver.h"
#include "solve/solver_registry.h"
#include "transport/form_factor_options.h"

namespace luxel {

std::vector<SolverOption> progressiveStopOptions();  // solve/progressive_solver.cpp
SolverOption settleOption();

namespace {

// Certificates are asked for moves of at most this share of the object's size, and kept for this
// many places. They take 4 bytes a cached factor, so only while the factor cache is this small.
constexpr float kCertifiedMoveShare = 0.05f;
constexpr size_t kCertifiedPoses = 64;
constexpr size_t kCertificateBytes = size_t(256) << 20;
// A pair whose factor a small move changed lies near the object's silhouette, and the next few
// moves are likely to change it again, so testing it would mostly be followed by recomputing it
// anyway: for this many moves it is recomputed without the ray test. Recomputing is never wrong;
// it only costs where the pair did not change. Its certificate slot holds the move it changed
// in, with this level.
constexpr uint32_t kChangedLevel = 15;
constexpr uint32_t kMovesRecomputedUntested = 3;
static_assert(kCertificateLevels < int(kChangedLevel), "a changed pair's mark must not read as a certificate");

enum class ChangedFactors {
  All,             // incremental: every column again
  ThroughMovers,   // cross-redistribution: only what the moved objects' old and new places touch
};

// An oriented box round a dynamic object's patches: centre, unit axes, half extents.
struct Region {
  Vec3 centre{0.0f};
  glm::mat3 axes{1.0f};
  Vec3 half{-1.0f};  // negative: empty
  bool empty() const { return half.x < 0.0f; }
};

// The box's corners, each axis grown by `margin`: corner i has bit a set for +half[a].
std::array<Vec3, 8> cornersOf(const Region& box, float margin) {
  std::array<Vec3, 8> corners;
  for (int i = 0; i < 8; ++i) {
    Vec3 c = box.centre;
    for (int a = 0; a < 3; ++a) c += box.axes[a] * ((i >> a & 1 ? 1.0f : -1.0f) * (box.half[a] + margin));
    corners[size_t(i)] = c;
  }
  return corners;
}

class RedistributionSolver final : public ProgressiveSolver {
 public:
  RedistributionSolver(const Scene& scene, const RadiositySystem& sys, Transport& transport,
                       const ProgressiveSettings& s, double settleThreshold, ChangedFactors changed, const char* method)
      : ProgressiveSolver(sys, transport, s), scene_(scene), changed_(changed), method_(method),
        settleThreshold_(settleThreshold) {
    bounds_.resize(scene.objects.size());
    shapes_.resize(scene.objects.size());
    convex_.resize(scene.objects.size(), 0);
    for (uint32_t o : scene.dynamicObjects()) {
      bounds_[o] = boundsOf(o);
      shapes_[o] = shapeOf(o);
      // A rigid move keeps a solid closed and convex: decided once.
      convex_[o] = ConvexSolid::fromPolygons(shapes_[o], 0.1f * slack()).valid();
    }
    remember();
  }

  bool objectsMoved(std::span<const uint32_t> objects) override {
    const Stopwatch watch;
    const SurfaceSet& set = sys_.surfaces;
    const size_t ne = sys_.elementCount(), np = sys_.patchCount();
    std::vector<uint8_t> moved(scene_.objects.size(), 0);
    for (uint32_t o : objects) moved[o] = 1;
    auto objectOf = [&](uint32_t face) { return scene_.meshes[set.faces[face].mesh].object; };
    auto isMoved = [&](uint32_t face) {
      const uint32_t o = objectOf(face);
      return o != kNoObject && moved[o];
    };
    // Every factor that has been used must still be at hand: a column that was computed into
    // scratch space (the cache was full) cannot be corrected, and then the owner solves afresh.
    const std::vector<Rgb> shot = patchShot();
    for (size_t p = 0; p < np; ++p)
      if (cache_[p].empty() && channelSum(glm::abs(shot[p])) > 0.0) return false;

    std::vector<uint32_t> movedPatches, staticPatches, movedElements;
    for (uint32_t p = 0; p < np; ++p)
      if (!cache_[p].empty()) (isMoved(set.patches[p].face) ? movedPatches : staticPatches).push_back(p);
    for (uint32_t e = 0; e < ne; ++e)
      if (isMoved(set.elements[e].face)) movedElements.push_back(e);

    std::vector<Rgb> deltaH(ne, Rgb(0.0f));
    uint64_t recomputed = 0;
    // Whole columns: the moved patches' always, every patch's for the incremental method.
    std::vector<uint32_t> whole = movedPatches;
    if (changed_ == ChangedFactors::All) whole.insert(whole.end(), staticPatches.begin(), staticPatches.end());
    if (!whole.empty()) recomputed += recomputeColumns(whole, shot, deltaH);
    // Single factors of the static patches, for cross-redistribution.
    if (changed_ == ChangedFactors::ThroughMovers && !staticPatches.empty()) {
      std::vector<Region> regions;
      std::vector<Blocker> blockers;
      std::vector<std::vector<Polygon>> was;  // the moved objects' patches before the move
      float movedMost = 0.0f, sizeLeast = std::numeric_limits<float>::max();
      for (uint32_t o : objects) {
        regions.push_back(bounds_[o]);  // where it was
        bounds_[o] = boundsOf(o);
        regions.push_back(bounds_[o]);  // where it is
        std::vector<Polygon> now = shapeOf(o);
        // No point of the object moved farther than its farthest corner (an affine move's
        // displacement is affine, its length convex).
        const float moved = farthestCorner(shapes_[o], now);
        movedMost = std::max(movedMost, moved);
        sizeLeast = std::min(sizeLeast, 2.0f * glm::length(bounds_[o].half));
        if (convex_[o]) {
          // So the solid where it was, inset by that distance, lies inside the solid where it
          // is too. The faces lie within the solid's tolerance of its planes.
          blockers.push_back({ConvexSolid::fromPolygons(shapes_[o], 0.1f * slack()), moved + 1.1f * slack()});
        }
        was.push_back(std::move(shapes_[o]));
        shapes_[o] = std::move(now);
      }
      // Every move gets an id, certified or not, so that a pair's mark of the move that changed
      // it ages by moves. Certificates from earlier moves that still hold: the objects have
      // stayed, before this move and after it, within the reach of the place the certificate was
      // made for.
      const std::vector<uint32_t> movedNow(objects.begin(), objects.end());
      if (movedNow != certifiedObjects_) forgetCertificates(), certifiedObjects_ = movedNow;
      // Per pose, the widest certificate level that still holds (0: none).
      const uint32_t moveId = nextPose_++;
      std::vector<uint8_t> poseHolds(nextPose_, 0);
      for (const Pose& pose : poses_) {
        float far = 0.0f;
        for (size_t k = 0; k < objects.size(); ++k)
          far = std::max({far, farthestCorner(pose.shapes[k], was[k]), farthestCorner(pose.shapes[k], shapes_[objects[k]])});
        uint8_t narrowest = 0;
        for (int level = kCertificateLevels; level >= 1 && std::ldexp(pose.reach, level - 1) >= far; --level)
          narrowest = uint8_t(level);
        poseHolds[pose.id] = narrowest;
      }
      const std::vector<uint32_t> redone = transport_.receiversRedoneByMove();
      std::vector<uint8_t> always(ne, 0);
      for (uint32_t e : movedElements) always[e] = 1;
      for (uint32_t e : redone) always[e] = 1;
      // A certificate (pose << 4 | level) holds when its level is at least the narrowest that
      // still covers how far the objects have gone from its pose.
      auto certified = [&](uint32_t patch, uint32_t element) {
        const std::vector<uint32_t>& c = certificate_[patch];
        if (c.empty() || c[element] == 0 || (c[element] & 15u) == kChangedLevel) return false;
        const uint8_t narrowest = poseHolds[c[element] >> 4];
        return narrowest != 0 && (c[element] & 15u) >= narrowest;
      };
      auto changedLately = [&](const Transport::ElementPatch& x) {
        const std::vector<uint32_t>& c = certificate_[x.patch];
        return !c.empty() && (c[x.element] & 15u) == kChangedLevel && moveId - (c[x.element] >> 4) <= kMovesRecomputedUntested;
      };
      std::vector<Transport::ElementPatch> pairs = pairsThrough(staticPatches, regions, blockers, always, isMoved, certified);
      // Of the pairs whose rays can pass where the movers were or are, the transport tells which
      // rays' verdicts the move changed (a box that turns a degree changes only the rays that
      // graze it); the rest keep their factors.
      const auto firstTested = std::stable_partition(pairs.begin(), pairs.end(), [&](const Transport::ElementPatch& x) {
        return always[x.element] != 0 || changedLately(x);
      });
      const std::span<const Transport::ElementPatch> tested(firstTested, pairs.end());
      std::vector<uint8_t> changed(tested.size());
      // A small move asks for certificates good for 2, 4, 8 or 16 times its distance, so that the
      // next moves can skip the pairs whose rays pass well clear of the objects or well inside
      // them; the pairs nearest the silhouette get the narrowest, so re-tests spread over frames.
      const bool certify = movedMost > 0.0f && movedMost <= kCertifiedMoveShare * sizeLeast &&
                           cachedBytes_ <= kCertificateBytes;
      std::vector<uint8_t> newlyCertified(certify ? tested.size() : 0);
      transport_.visibilityChangedByMove(tested, changed, 2.0f * movedMost, newlyCertified);
      if (certify) remember(moveId, tested, newlyCertified, changed, std::move(was), 2.0f * movedMost);
      size_t kept = size_t(firstTested - pairs.begin());
      for (size_t i = 0; i < tested.size(); ++i)
        if (changed[i]) pairs[kept++] = tested[i];
      pairs.resize(kept);
      std::vector<float> fresh(pairs.size());
      transport_.pairs(pairs, fresh);
      recomputed += pairs.size();
      for (size_t i = 0; i < pairs.size(); ++i) {
        float& f = cache_[pairs[i].patch][pairs[i].element];
        deltaH[pairs[i].element] += (fresh[i] - f) * shot[pairs[i].patch];
        f = fresh[i];
      }
    } else {
      for (uint32_t o : objects) bounds_[o] = boundsOf(o), shapes_[o] = shapeOf(o);
    }
    apply(deltaH);
    factorsRecomputed_ += recomputed;
    redistributions_ += 1;
    secondsRedistributing_ += watch.seconds();
    seconds_ += watch.seconds();
    return true;
  }

  // A frame after a change stops at the unshot threshold; asked to step again with nothing
  // changed (the motion has stopped), the solver goes on a decade at a time down to the settle
  // threshold, so that a still scene converges while it is shown.
  bool step(const StepLimit& limit, const ProgressCallback& progress) override {
    if (done_ && threshold_ > settleThreshold_ && unshotFraction_ > settleThreshold_ && !budgetSpent()) {
      threshold_ = std::max(settleThreshold_, threshold_ * 0.1);
      done_ = false;
    }
    return ProgressiveSolver::step(limit, progress);
  }

  bool sourcesChanged() override {
    const Stopwatch watch;
    forgetCertificates();  // emitters may have changed, and with them the rays of their pairs
    const size_t ne = sys_.elementCount();
    std::vector<Rgb> deltaH(ne, Rgb(0.0f));
    // Patches that started or stopped emitting take other rays in the transport: their columns
    // are computed again, as a move's are.
    std::vector<uint32_t> redone;
    for (uint32_t p : transport_.patchesRedoneBySources())
      if (!cache_[p].empty()) redone.push_back(p);
    if (!redone.empty()) {
      const std::vector<Rgb> shot = patchShot();
      factorsRecomputed_ += recomputeColumns(redone, shot, deltaH);
    }
    apply(deltaH);
    redistributions_ += 1;
    secondsRedistributing_ += watch.seconds();
    seconds_ += watch.seconds();
    return true;
  }

  void restoreState(StateReader& in) override {
    ProgressiveSolver::restoreState(in);
    remember();
  }

  SolveStats stats() const override {
    SolveStats st = ProgressiveSolver::stats();
    st.method = method_;
    st.redistributions = redistributions_;
    st.factorsRecomputed = factorsRecomputed_;
    st.secondsRedistribution = secondsRedistributing_;
    return st;
  }

 private:
  // Computes the cached columns of `patches` again, adding what the change of each factor does
  // to the irradiance its patch has shot (deltaH); returns the factors computed.
  size_t recomputeColumns(const std::vector<uint32_t>& patches, const std::vector<Rgb>& shot, std::vector<Rgb>& deltaH) {
    const size_t ne = sys_.elementCount();
    std::vector<float> fresh(patches.size() * ne);
    transport_.columns(patches, fresh);
    for (size_t k = 0; k < patches.size(); ++k) {
      std::vector<float>& f = cache_[patches[k]];
      const float* g = fresh.data() + k * ne;
      const Rgb s = shot[patches[k]];
      tbb::parallel_for(tbb::blocked_range<size_t>(0, ne, 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t e = r.begin(); e < r.end(); ++e) {
          deltaH[e] += (g[e] - f[e]) * s;
          f[e] = g[e];
        }
      });
    }
    return fresh.size();
  }

  // Each patch's shot radiosity S_p: the area mean of B - B_unshot over its elements.
  std::vector<Rgb> patchShot() const {
    std::vector<Rgb> shot(sys_.elementCount());
    for (size_t e = 0; e < shot.size(); ++e) shot[e] = radiosity_[e] - unshot_[e];
    return sys_.patchMeans(shot);
  }

  // A box round a dynamic object's patches where they are now, aligned with the object's own
  // axes (its transform's rotation), so that it stays as tight as the object is in any pose.
  Region boundsOf(uint32_t object) const {
    const SurfaceSet& set = sys_.surfaces;
    Region box;
    const glm::mat3 m(scene_.objects[object].transform);
    for (int i = 0; i < 3; ++i) box.axes[i] = glm::normalize(m[i]);
    const glm::mat3 toLocal = glm::transpose(box.axes);
    Vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    bool any = false;
    for (const Patch& p : set.patches) {
      if (scene_.meshes[set.faces[p.face].mesh].object != object) continue;
      for (int i = 0; i < p.polygon.count; ++i) {
        const Vec3 x = toLocal * p.polygon.v[size_t(i)];
        lo = glm::min(lo, x), hi = glm::max(hi, x);
      }
      any = true;
    }
    if (!any) return box;
    box.centre = box.axes * (0.5f * (lo + hi));
    box.half = 0.5f * (hi - lo);
    return box;
  }

  // How far the farthest corner of the same patches lies between two places.
  static float farthestCorner(const std::vector<Polygon>& a, const std::vector<Polygon>& b) {
    float far = 0.0f;
    for (size_t i = 0; i < a.size() && i < b.size(); ++i)
      for (int c = 0; c < a[i].count; ++c) far = std::max(far, glm::length(b[i].v[size_t(c)] - a[i].v[size_t(c)]));
    return far;
  }

  // Keeps the certificates the transport gave `pairs` (certified[i], a level) for the moved
  // objects' place before this move (`shapes`, per moved object) and `reach` * 2^(level - 1)
  // round it, and marks the pairs this move changed (kChangedLevel).
  void remember(uint32_t id, std::span<const Transport::ElementPatch> pairs, const std::vector<uint8_t>& certified,
                const std::vector<uint8_t>& changed, std::vector<std::vector<Polygon>> shapes, float reach) {
    poses_.push_back({id, std::move(shapes), reach});
    if (poses_.size() > kCertifiedPoses) poses_.pop_front();
    const size_t ne = sys_.elementCount();
    for (size_t i = 0; i < pairs.size(); ++i) {
      if (!certified[i] && !changed[i]) continue;
      std::vector<uint32_t>& c = certificate_[pairs[i].patch];
      if (c.empty()) c.assign(ne, 0);
      c[pairs[i].element] = id << 4 | (changed[i] ? kChangedLevel : certified[i]);
    }
  }

  void forgetCertificates() {
    for (std::vector<uint32_t>& c : certificate_) std::vector<uint32_t>().swap(c);
    poses_.clear();
  }

  // A dynamic object's patches where they are now, in patch order.
  std::vector<Polygon> shapeOf(uint32_t object) const {
    const SurfaceSet& set = sys_.surfaces;
    std::vector<Polygon> shape;
    for (const Patch& p : set.patches)
      if (scene_.meshes[set.faces[p.face].mesh].object == object) shape.push_back(p.polygon);
    return shape;
  }

  // Slack for the rays' offsets from the surfaces (RayTracer's rayOffsetFor is 1e-5 of the extent).
  float slack() const { return 1e-4f * sys_.surfaces.sceneExtent; }

  // A moved object's solid where it was, when it is closed and convex, and how deep a segment
  // must pass through it to meet the object where it is too: every pair whose segments all pass
  // that deep was blocked before the move and still is.
  struct Blocker {
    ConvexSolid before;
    float depth;
  };

  // The (static receiver, static patch) pairs whose light can pass through one of `regions`,
  // plus every pair of the receivers marked `always`. A receiver on the source's side of a plane
  // that separates the source from a region (dynamic/separating_planes.h) is clear of it; one
  // clear of every region cannot have changed its visibility. Receiver patches are tested first,
  // then their elements. Receiver patches in the umbra of one of `blockers` both before and after
  // the move are left out too (for single elements the test costs more than the rays it saves,
  // which the transport settles against the solid one by one).
  // Pairs with a certificate that holds (`certified`) are left out as well.
  template <typename IsMoved, typename Certified>
  std::vector<Transport::ElementPatch> pairsThrough(const std::vector<uint32_t>& sources,
                                                    const std::vector<Region>& regions,
                                                    const std::vector<Blocker>& blockers,
                                                    const std::vector<uint8_t>& always, const IsMoved& isMoved,
                                                    const Certified& certified) const {
    const SurfaceSet& set = sys_.surfaces;
    const size_t np = sys_.patchCount();
    std::vector<std::vector<Transport::ElementPatch>> perSource(sources.size());
    const float slack = this->slack();
    // A ray meets a closed solid's faces when it passes through the inside and one end lies
    // outside; the polygons' corners stand in for the rays' ends, which lie within slack of them.
    auto blocked = [&](const Polygon& a, const Polygon& b) {
      for (const Blocker& k : blockers)
        if (k.before.blocksEverySegment(a, b, k.depth) &&
            (k.before.separatedFrom(a, k.depth) || k.before.separatedFrom(b, k.depth)))
          return true;
      return false;
    };
    tbb::parallel_for(size_t(0), sources.size(), [&](size_t k) {
      const uint32_t p = sources[k];
      const Patch& src = set.patches[p];
      // The planes that bound each region's shadow from this source. Rays leave surfaces up to
      // slack off them (RayTracer's offset is a tenth of it), and the boxes are grown by it.
      std::vector<SeparatingPlanes> shadows;
      for (const Region& r : regions)
        if (!r.empty()) shadows.emplace_back(src.polygon, src.normal * slack, cornersOf(r, slack), 0.01f * slack);
      auto clear = [&](const Polygon& poly, Vec3 normal) {
        for (const SeparatingPlanes& shadow : shadows)
          if (!shadow.separates(poly, normal * slack)) return false;
        return true;
      };
      std::vector<Transport::ElementPatch>& out = perSource[k];
      for (uint32_t q = 0; q < np; ++q) {
        const Patch& rec = set.patches[q];
        if (isMoved(rec.face)) {
          for (uint32_t e : rec.elements) out.push_back({e, p});
          continue;
        }
        const bool unchanged = clear(rec.polygon, rec.normal) || blocked(rec.polygon, src.polygon);
        for (uint32_t e : rec.elements) {
          const Element& el = set.elements[e];
          if (always[e] || (!unchanged && !certified(p, e) && !clear(el.polygon, el.normal)))
            out.push_back({e, p});
        }
      }
    });
    std::vector<Transport::ElementPatch> all;
    for (auto& v : perSource) all.insert(all.end(), v.begin(), v.end());
    return all;
  }

  // Applies the redistribution: the factor changes' irradiance `deltaH`, and the differences of
  // analytic irradiance, emission and reflectance since the last update (see the top of the file).
  void apply(const std::vector<Rgb>& deltaH) {
    const size_t ne = sys_.elementCount();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, ne, 4096), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t e = r.begin(); e < r.end(); ++e) {
        const Rgb h = irradiance_[e] + deltaH[e] + (sys_.analytic[e] - analyticUsed_[e]);
        const Rgb b = sys_.emission[e] + sys_.reflectance[e] * h;
        unshot_[e] += b - radiosity_[e];
        radiosity_[e] = b;
        irradiance_[e] = h;
      }
    });
    // The direct light for display: the analytic lights, and the emitters' first bounce added
    // again from their current columns when the solution is next read.
    direct_ = sys_.analytic;
    std::fill(directAdded_.begin(), directAdded_.end(), 0);
    patchEmission_ = sys_.patchMeans(sys_.emission);
    updatePatchUnshot();
    sourcePower_ = sys_.sourcePower();
    unshotFraction_ = currentUnshotFraction();
    done_ = false;
    threshold_ = s_.unshotThreshold;
    remember();
  }

  bool budgetSpent() const {
    return (s_.shotBudget && shots_ >= s_.shotBudget) || (s_.timeBudget > 0.0 && seconds_ >= s_.timeBudget);
  }

  // What the state was computed from, for the next update's differences.
  void remember() { analyticUsed_ = sys_.analytic; }

  const Scene& scene_;
  const ChangedFactors changed_;
  const char* method_;
  const double settleThreshold_;
  std::vector<Rgb> analyticUsed_;
  std::vector<Region> bounds_;  // each dynamic object's patches, where the solution last saw them
  std::vector<std::vector<Polygon>> shapes_;  // the same patches' polygons
  std::vector<uint8_t> convex_;               // per object: its patches close a convex solid
  // Certificates (Transport::visibilityChangedByMove with `certify`): per cached static column,
  // per element, the pose whose neighbourhood the pair's rays keep their verdicts in, and how
  // wide (pose << 4 | level; 0: none). Level kChangedLevel is no certificate but a mark: the
  // move (its id in the pose bits) changed the pair.
  // Only for one list of moving objects at a time; forgotten when another list moves.
  struct Pose {
    uint32_t id;
    std::vector<std::vector<Polygon>> shapes;  // per certified object, its patches there
    float reach;  // of level 1
  };
  std::vector<std::vector<uint32_t>> certificate_ = std::vector<std::vector<uint32_t>>(sys_.patchCount());
  std::deque<Pose> poses_;
  uint32_t nextPose_ = 1;
  std::vector<uint32_t> certifiedObjects_;
  uint64_t redistributions_ = 0, factorsRecomputed_ = 0;
  double secondsRedistributing_ = 0.0;
};

void registerRedistribution(SolverRegistry& registry, const char* method, ChangedFactors changed,
                            const char* description) {
  SolverEntry e;
  e.description = {method, "cpu", description, progressiveStopOptions()};
  e.description.options.push_back(integerOption("shooters-per-pass", kDefaultShootersPerPass, 1, kMaxShootersPerPass,
                                                "patches shot together in one pass over the receivers"));
  e.description.options.push_back(settleOption());
  for (SolverOption& o : cpuTransportOptions()) e.description.options.push_back(std::move(o));
  e.make = [method, changed](const SolverResources& r, const SolverOptionValues& v) -> std::unique_ptr<Solver> {
    ProgressiveSettings s{v.real("unshot"), v.real("time-budget"), uint64_t(v.integer("shot-budget")),
                          size_t(v.integer("shooters-per-pass")), v.flag("ambient")};
    return std::make_unique<RedistributionSolver>(r.scene, r.system, r.transport, s, v.real("settle-unshot"), changed,
                                                  method);
  };
  e.converged.set("unshot", 1e-7);
  registry.add(std::move(e));
}

}  // namespace

// The dynamic solvers' idle refinement (shared with GL incremental, gl/gl_solvers.cpp).
SolverOption settleOption() {
  return realOption("settle-unshot", 1e-5, 1e-12, 1.0,
                    "with nothing moving, each further step goes a decade below --unshot, down to this");
}

void registerCpuIncremental(SolverRegistry& registry) {
  registerRedistribution(registry, "incremental", ChangedFactors::All,
                         "dynamic: progressive refinement that follows moves and light edits by redistribution "
                         "(Chen 1990): every column of factors again after a move");
}

void registerCpuCrossRedistribution(SolverRegistry& registry) {
  registerRedistribution(registry, "cross-redistribution", ChangedFactors::ThroughMovers,
                         "dynamic: redistribution after van de Hoef 2013: the moved patches' factors, and the static "
                         "ones whose light passes where the moved objects were or are, traced exactly");
}

}  // namespace luxel
