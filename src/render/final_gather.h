// The final gather of two-pass methods (Chen, Rushmeier, Miller and Turner, "A Progressive
// Multi-Pass Method for Global Illumination", SIGGRAPH 1991; the per-pixel gathers over a radiosity
// solution of Reichert 1992 and Lischinski, Tampieri and Greenberg 1993): the indirect irradiance
// at a point is gathered by rays over its hemisphere, each reading the radiance the solution leaves
// where the ray lands. Where it lands, the direct light is traced again (a shadow ray per light)
// and only the indirect part is interpolated from the elements; so the element solution is met one
// bounce away and only through its indirect light, where its discretisation error (patches shooting
// their mean, elements averaged across a block's footprint) is smallest. A hit within two of its
// element's edge lengths sees those elements large, and gathers its own indirect light in turn (9
// rays) from the solution one bounce further. The corners read at the hits may instead be a coarse
// gather of their own (VertexGather over this class), or a coarse gather of a coarse gather: the
// solution is then two or more bounces away. Where a hit is a few elements away, its direct light
// may be read per element instead of traced (ElementDirect).
//
// Emission met by a gather ray is not counted, nor is the sky met by one that escapes: both are
// direct light, which the caller traces at the point itself (a VertexGather asked to take the
// skies counts them from its escaping rays instead: its skiesOf).
#pragma once

#include <atomic>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "luxel/render.h"
#include "render/direct_light.h"
#include "trace/ray_tracer.h"

namespace luxel {

class GatherMesh;
class VertexGather;

inline constexpr size_t kVertexGatherRayBudget = size_t(1) << 24;
inline constexpr int kMinVertexGatherRays = 16;
inline constexpr float kMaxRaysOverMean = 8.0f;
// A hit nearer than this many of its element's edge lengths is near: it sees the element large,
// and with it the element's averaging.
inline constexpr float kNearHitElements = 2.0f;
// On a split mesh (VertexGather's `refined`), a vertex inside a solved element is interpolated from
// the element's corners when it lies within this fraction of each corner's reach (the nearest
// surface its rays met), and gathered otherwise.
inline constexpr float kInterpolationReach = 0.5f;

class FinalGather {
 public:
  // The direct light where gather rays land is traced there (a shadow ray per light, as at a
  // pixel), or read per element: the element's mean direct irradiance (elementDirectLight), exact
  // over the element in total and blurred within it. Seen from a few elements away the blur is what
  // the gather's rays average over anyway, and reading it costs no ray; nearer it shows (a block's
  // footprint darkening the floor beside it), so hits within `tracedWithin` of their ray's origin
  // still trace it. An element partly inside a solid (the floor under a block's edge) has the dark
  // part in its mean, which shows from any distance: its tracedWithin is infinite.
  struct ElementDirect {
    std::vector<Rgb> irradiance;      // per element of the gather's surfaces
    std::vector<float> tracedWithin;  // per element: hits nearer than this trace their direct light
  };

  // `indirectCorners`: the solution's indirect irradiance at element corners (elementCornerValues
  // of irradiance minus direct irradiance). `tracer` holds the elements with twins apart
  // (trace/element_polygons.h).
  // `gatherNearHits`: a hit within two of its element's edge lengths gathers its own indirect
  // light (9 rays) instead of reading the corners there: for corners taken from the solution, whose
  // elements average across a block's footprint; gathered corners (VertexGather) need it not.
  // `elementDirect`: see ElementDirect; null traces the direct light at every hit.
  FinalGather(const SurfaceSet& surfaces, const RayTracer& tracer, const DirectLight& direct,
              const std::vector<Rgb>& indirectCorners, bool gatherNearHits = true,
              const ElementDirect* elementDirect = nullptr);
  // The same reading a coarse gather's corners as it gathers them, each element's when a hit
  // first lands on it (`lowerLevel` must outlive this): a scene of millions of elements, whose
  // gather rays meet a fraction of them, gathers only those.
  FinalGather(const SurfaceSet& surfaces, const RayTracer& tracer, const DirectLight& direct,
              VertexGather& lowerLevel, const ElementDirect* elementDirect = nullptr);

  // One batch of gather rays, traced here. Adds weights[i] * L_i to *targets[i], where L_i is the
  // reflected radiance (rho / pi times the irradiance) at the point rays[i] lands on; misses and
  // the backs of one-sided surfaces bring nothing. `seed` picks the hits' light samples. Returns
  // how many of the rays met the back of a surface (an element whose gather rays mostly do is
  // inside a solid).
  size_t add(std::span<RTCRayHit> rays, std::span<const Rgb> weights, std::span<Rgb* const> targets,
             uint32_t seed) const;
  const RayTracer& tracer() const { return tracer_; }

 private:
  size_t add(std::span<RTCRayHit> rays, std::span<const Rgb> weights, std::span<Rgb* const> targets, uint32_t seed,
             bool gatherNearHits) const;
  bool gatherNearHits_;

  const SurfaceSet& surfaces_;
  const RayTracer& tracer_;
  const DirectLight& direct_;
  const std::vector<Rgb>& corners_;
  VertexGather* lowerLevel_ = nullptr;  // read instead of corners_ when set
  const ElementDirect* elementDirect_;
  float rayOffset_;
};

// Each element's mean direct irradiance (DirectLight, shadow rays traced through `tracer`), from
// `samples` points stratified over the element, each with a light point stratified over each lamp:
// of every element, or of `elements` only, in their order. `direct`'s receivers, if any, must be
// `surfaces`.
std::vector<Rgb> elementDirectLight(const SurfaceSet& surfaces, const RayTracer& tracer, const DirectLight& direct,
                                    int samples, uint32_t seed, std::span<const uint32_t> elements = {});

// The indirect irradiance gathered at element corners, `rays` cosine-stratified rays per vertex,
// each vertex on first demand (an image gathers only what it sees). Corners that meet on one
// smooth surface (mesh/corner_groups.h) share one gather, at a point moved a hundredth of the way
// towards the elements' centroids so that rays along a crease meet the other wall. A vertex inside
// a solid (under a block standing on the floor: most of its rays meet backs) takes the mean of its
// element's other corners, so that a floor element the block half covers is not darkened by the
// corners under it.
class VertexGather {
 public:
  // `rays` per vertex; 0 takes kDefaultVertexGatherRays, fewer (down to 16) where the scene has so
  // many vertices that the gather would pass kVertexGatherRayBudget rays: there the elements are
  // small on screen and neighbouring pixels average the noise.
  // `elementWeights` (one per element, or none): the rays go to the vertices in proportion to the
  // weights of the elements around them, `rays` on average over the vertices of weight above 0, at
  // least kMinVertexGatherRays and at most kMaxRaysOverMean times that average. An image weights
  // elements by the pixels they cover, so that each part of it is gathered with as many rays as
  // any other: uniform rays leave the few vertices of a surface near the eye to carry a whole
  // region's noise.
  // `refined` (or null): `surfaces` are this GatherMesh's split of the solved elements. Then the
  // vertices at the solved elements' corners are gathered, and a vertex the splits made is gathered
  // only where its solved element's corners found a surface near (a crease, a contact, a block
  // beside them: within 1 / kInterpolationReach of its distance from them), and interpolated from
  // those corners elsewhere: the irradiance a corner gathers is good over a fraction of the
  // distance to the nearest surface its rays meet (Ward, Rubinstein and Clear, "A Ray Tracing
  // Solution for Diffuse Interreflection", SIGGRAPH 1988: irradiance caching's error bound).
  // The split's interior vertices are most of them, and most of them are far from everything.
  // `skiesOf` (or null): the scene whose skies the gather takes too, from the rays that escape,
  // for the pixels to interpolate with the indirect light instead of sampling per pixel. Seen
  // through a window a sky is a few of a pixel's sixteen light points or none, a speckle; a
  // vertex's hundreds of rays find it evenly. Only the gather the pixels read may: a lower level's
  // corners are read at hits whose direct light, skies included, is traced there.
  VertexGather(const SurfaceSet& surfaces, const FinalGather& gather, int rays, uint32_t seed,
               std::span<const float> elementWeights = {}, const GatherMesh* refined = nullptr,
               const Scene* skiesOf = nullptr);
  ~VertexGather();
  VertexGather(const VertexGather&) = delete;
  VertexGather& operator=(const VertexGather&) = delete;

  // Element e's 4 corner slots (as elementCornerValues lays them out), gathered now if they were
  // not before. Safe to call from many threads at once.
  const Rgb* corners(uint32_t e);
  // Every element's corners, gathered in parallel: 4 slots per element.
  std::vector<Rgb> all();
  size_t vertexCount() const { return vertices_.size(); }
  // The rays corner c of element e is gathered with (elementWeights share them out).
  int cornerRays(uint32_t e, int c) const {
    const int side = vertices_[vertexOf_[size_t(e) * 4 + size_t(c)]].side;
    return side * side;
  }
  int cornerCount(uint32_t e) const { return surfaces_.elements[e].polygon.count; }
  // Whether corner c of element e lies inside a solid (most of its rays met backs); valid once
  // corners(e) has been gathered.
  bool cornerInside(uint32_t e, int c) const {
    return vertices_[vertexOf_[size_t(e) * 4 + size_t(c)]].inside;
  }
  // Whether corner c of element e was gathered by rays (not interpolated); valid once corners(e)
  // has been gathered.
  bool cornerTraced(uint32_t e, int c) const {
    return vertices_[vertexOf_[size_t(e) * 4 + size_t(c)]].traced;
  }
  // Vertices resolved so far (gathered or interpolated), and of them those gathered by rays.
  size_t verticesGathered() const;
  size_t verticesTraced() const { return traced_.load(std::memory_order_relaxed); }

  // What GatherRefinement (render/gather_refinement.h) reads of the vertices: corner c of element
  // e is vertex vertexOf(e, c), shared by the corners that meet on one smooth surface; a vertex's
  // fields are valid once an element that has it was gathered (corners()).
  uint32_t vertexOf(uint32_t e, int c) const { return vertexOf_[size_t(e) * 4 + size_t(c)]; }
  struct VertexView {
    Vec3 position;
    Rgb irradiance;
    float reach;  // the nearest hit of its rays (infinite when interpolated or nothing was hit)
    int side;     // its rays' strata per side
    bool inside;
  };
  VertexView vertex(uint32_t v) const;
  // A gather at a point of the surfaces that is no vertex, as a vertex is gathered: side x side
  // cosine strata from `position` (moved a hundredth of the way towards `towards`, a point inside
  // its element), seeded by `index` (distinct from every vertex's: vertexCount() and up).
  struct PointGather {
    Rgb irradiance{0.0f};
    float reach = std::numeric_limits<float>::infinity();
    bool inside = false;
  };
  PointGather gatherAt(Vec3 position, Vec3 normal, Vec3 towards, int side, uint32_t index) const;

 private:
  struct Vertex {
    Vec3 position{0.0f};
    Vec3 normal{0.0f};
    Vec3 centroids{0.0f};  // summed over the slots that share it, for the nudge inwards
    uint32_t slots = 0;
    Rgb irradiance{0.0f};
    float weight = 0.0f;  // from elementWeights
    int side = 0;         // its rays are side x side strata
    bool inside = false;
    bool traced = false;
    float reach = std::numeric_limits<float>::infinity();  // the nearest hit of its rays
    // On a split mesh, a vertex that is not a solved element's corner: the solved element it may
    // be interpolated in, and its coordinates there.
    uint32_t parent = kNoParent;
    Vec2 local{0.0f};
  };
  static constexpr uint32_t kNoParent = ~uint32_t(0);
  static constexpr uint32_t kNoVertex = ~uint32_t(0);
  void gatherVertex(uint32_t v);
  void resolveVertex(uint32_t v);
  template <typename Publish>
  void once(std::atomic<uint8_t>& state, Publish&& publish);

  const SurfaceSet& surfaces_;
  const FinalGather& gather_;
  uint32_t seed_;
  std::vector<const Light*> skies_;  // taken from escaping rays (skiesOf)
  Vec3 up_{0.0f, 1.0f, 0.0f};
  std::vector<uint32_t> vertexOf_;  // 4 slots per element
  std::vector<Vertex> vertices_;
  const GatherMesh* refined_;
  std::vector<uint32_t> solvedCorners_;  // on a split mesh: 4 vertices per solved element, or kNoVertex
  std::atomic<size_t> traced_{0};
  std::vector<Rgb> corners_;  // 4 slots per element, valid once the element's state is done
  std::unique_ptr<std::atomic<uint8_t>[]> vertexState_, elementState_;
};

}  // namespace luxel
