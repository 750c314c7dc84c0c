// What an hq render's indirect light reads: see render/gather_pipeline.h.
#include "render/gather_pipeline.h"

#include <cmath>
#include <limits>
#include <unordered_set>

#include <tbb/parallel_for.h>

#include "core/position_key.h"
#include "core/random.h"
#include "luxel/error.h"
#include "render/corner_values.h"
#include "render/gather_refinement.h"
#include "trace/element_polygons.h"
#include "trace/thin_glass.h"

namespace luxel {
namespace {

// Samples of each element's mean direct light (elementDirectLight), for the gather's far hits.
constexpr int kElementDirectSamples = 16;
// Solved elements this many times the mean area the gather mesh asks for (RenderOptions::
// gatherElements) are split until they are not (GatherMesh's maxArea).
constexpr double kLargeGatherElements = 4.0;

// The elements that are partly inside a solid (some of their corners are, some are not), found by
// the first coarse gather: their mean direct light counts the dark part, so gather rays landing on
// them trace theirs wherever they come from.
void traceStraddlingElements(const VertexGather& gathered, FinalGather::ElementDirect& direct) {
  for (uint32_t e = 0; e < direct.tracedWithin.size(); ++e) {
    int inside = 0;
    const int count = gathered.cornerCount(e);
    for (int c = 0; c < count; ++c) inside += gathered.cornerInside(e, c);
    if (inside > 0 && inside < count) direct.tracedWithin[e] = std::numeric_limits<float>::infinity();
  }
}

}  // namespace

GatherPipeline::GatherPipeline(const Scene& scene, const SurfaceSet& surfaces, const Solution& solution,
                               const RenderOptions& options, RenderOptions::Indirect indirect, bool hq) {
  using Indirect = RenderOptions::Indirect;
  const bool pixelGather = indirect == Indirect::PixelGather;
  const bool vertexGather = indirect == Indirect::VertexGather;
  // The irradiance field to interpolate: all of it in radiosity mode; in HQ mode only the indirect
  // part, since the direct part is traced per pixel (and at every gather ray's hit).
  std::vector<Rgb> field = solution.irradiance;
  if (hq)
    for (size_t e = 0; e < field.size(); ++e) field[e] = glm::max(field[e] - solution.directIrradiance[e], Rgb(0.0f));
  // The elements the pixels find and the vertex gather interpolates over: the solved ones, split
  // where options.gatherElements asks for more (render/gather_mesh.h). Elements four times the
  // mean size the gather asks for are split further: a solve that keeps faces whole (the
  // hierarchical solver's walls) would leave the gather a wall's four corners.
  double totalArea = 0.0;
  for (const Element& e : surfaces.elements) totalArea += e.area;
  mesh_.emplace(scene, surfaces,
                vertexGather ? GatherMesh::splitsFor(surfaces.elements.size(), options.gatherElements) : 0,
                vertexGather && options.gatherElements > 0
                    ? float(kLargeGatherElements * totalArea / double(options.gatherElements))
                    : std::numeric_limits<float>::infinity());
  const SurfaceSet& shown = mesh_->surfaces();
  corners_ = mesh_->corners(elementCornerValues(surfaces, field));
  polygons_ = elementPolygonsTwinsApart(shown);
  tracer_.emplace(polygons_);
  tracer_->setGlass(std::make_shared<ThinGlass>(ThinGlass::overElements(scene, shown)));
  direct_.emplace(scene, surfaces, &shown);
  // A vertex gather's hits a few elements away read their direct light per element, each element's
  // estimated here. Past a million elements the estimates would cost more rays than the hits they
  // spare (the gather's own rays per vertex fall there, kVertexGatherRayBudget): there the
  // solution's own direct light per element is read where the gather's element is a solved one
  // whole (exact over the element as the solver found it, and free), and hits on the pieces of a
  // split one trace theirs.
  const bool estimateElementDirect =
      vertexGather && shown.elements.size() * kElementDirectSamples <= kVertexGatherRayBudget;
  if (vertexGather) {
    FinalGather::ElementDirect& ed = elementDirect_.emplace();
    ed.tracedWithin.resize(shown.elements.size());
    for (uint32_t e = 0; e < shown.elements.size(); ++e)
      ed.tracedWithin[e] = kNearHitElements * std::sqrt(shown.elements[e].area);
    if (estimateElementDirect) {
      ed.irradiance =
          elementDirectLight(shown, *tracer_, *direct_, kElementDirectSamples, hashCombine(options.seed, 0xe1d1u));
    } else {
      ed.irradiance.resize(shown.elements.size());
      for (uint32_t e = 0; e < shown.elements.size(); ++e) {
        ed.irradiance[e] = solution.directIrradiance[mesh_->parent(e)];
        if (!mesh_->whole(e)) ed.tracedWithin[e] = std::numeric_limits<float>::infinity();
      }
    }
  }
  const FinalGather::ElementDirect* readDirect = elementDirect_ ? &*elementDirect_ : nullptr;
  gather_.emplace(shown, *tracer_, *direct_, corners_, /*gatherNearHits=*/options.gatherBounces < 3, readDirect);
  // With two bounces or more gathered, the gather's hits read a coarse gather at every vertex
  // instead of the solution, and each further bounce a coarse gather of that one, so the solution
  // is met gatherBounces bounces away. The first coarse gather also finds the solved elements that
  // solids stand on, whose mean direct light cannot be read (traceStraddlingElements): where the
  // elements' direct light is estimated, the coarse gathers visit every vertex first. Elsewhere
  // (past a million elements, or a per-pixel gather) each level gathers a vertex when a hit above
  // first needs it, the same numbers: the gather rays of a scene of millions of faces meet a
  // fraction of them. (There a straddling element's mean is read from afar; the floor a statue
  // stands on is one element so large that its hits trace anyway.)
  for (int level = 2; (vertexGather || pixelGather) && level <= options.gatherBounces; ++level) {
    const FinalGather& below = finalGather();
    const uint32_t seed = hashCombine(options.seed, 0xc0a25eu + uint32_t(level - 2));
    if (!estimateElementDirect) {
      lazyLevels_.emplace_back(shown, below, kCoarseGatherRays, seed, std::span<const float>{}, &*mesh_);
      lazyGathers_.emplace_back(shown, *tracer_, *direct_, lazyLevels_.back(), readDirect);
      continue;
    }
    VertexGather lower(shown, below, kCoarseGatherRays, seed, {}, &*mesh_);
    coarse_ = lower.all();  // the level below read the previous coarse_ until all() returned
    if (level == 2 && elementDirect_) traceStraddlingElements(lower, *elementDirect_);
    fromCoarse_.emplace(shown, *tracer_, *direct_, coarse_, /*gatherNearHits=*/false, readDirect);
  }
}

const FinalGather& GatherPipeline::finalGather() const {
  return fromCoarse_ ? *fromCoarse_ : !lazyGathers_.empty() ? lazyGathers_.back() : *gather_;
}

std::vector<Rgb> gatheredIndirect(const Scene& scene, const SurfaceSet& solved, const Solution& solution,
                                  std::span<const uint32_t> elements, const RenderOptions& options, bool skies) {
  for (uint32_t e : elements)
    if (e >= solved.elements.size())
      throw Error("gatheredIndirect: element " + std::to_string(e) + " is past the solution's " +
                  std::to_string(solved.elements.size()));
  const GatherPipeline pipeline(scene, solved, solution, options, RenderOptions::Indirect::VertexGather, true);
  const SurfaceSet& shown = pipeline.shown();
  std::vector<int64_t> slot(solved.elements.size(), -1);
  for (size_t i = 0; i < elements.size(); ++i) slot[elements[i]] = int64_t(i);
  // The rays go to the asked elements' pieces alike, as an image's go by pixels, and to the
  // elements around them: in a picture those are seen too, and a refined piece's edges follow
  // its neighbours' lattices (GatherRefinement).
  std::vector<float> weights(shown.elements.size(), 0.0f);
  std::unordered_set<PositionKey, PositionKeyHash> around;
  for (uint32_t e = 0; e < shown.elements.size(); ++e)
    if (slot[pipeline.mesh().parent(e)] >= 0)
      for (int c = 0; c < shown.elements[e].polygon.count; ++c)
        around.insert(positionKey(shown.elements[e].polygon.v[size_t(c)]));
  for (uint32_t e = 0; e < shown.elements.size(); ++e)
    for (int c = 0; c < shown.elements[e].polygon.count && weights[e] == 0.0f; ++c)
      if (around.count(positionKey(shown.elements[e].polygon.v[size_t(c)]))) weights[e] = 1.0f;
  VertexGather vertices(shown, pipeline.finalGather(), options.gatherRays, options.seed, weights, &pipeline.mesh(),
                        skies ? &scene : nullptr);
  const GatherRefinement refinement(shown, vertices, weights);
  // Over each piece, the mean of what the picture interpolates; over the element, the pieces' by
  // area.
  std::vector<Rgb> out(elements.size(), Rgb(0.0f));
  std::vector<double> area(elements.size(), 0.0);
  for (uint32_t e = 0; e < shown.elements.size(); ++e) {
    const int64_t i = slot[pipeline.mesh().parent(e)];
    if (i < 0) continue;
    const Element& el = shown.elements[e];
    out[size_t(i)] += refinement.mean(e) * el.area;
    area[size_t(i)] += el.area;
  }
  for (size_t i = 0; i < out.size(); ++i)
    if (area[i] > 0.0) out[i] /= float(area[i]);
  return out;
}

std::vector<Rgb> pixelDirectLight(const Scene& scene, const SurfaceSet& solved, std::span<const uint32_t> elements,
                                  int samples, uint32_t seed, bool skies) {
  for (uint32_t e : elements)
    if (e >= solved.elements.size())
      throw Error("pixelDirectLight: element " + std::to_string(e) + " is past the surfaces' " +
                  std::to_string(solved.elements.size()));
  const std::vector<Polygon> polygons = elementPolygonsTwinsApart(solved);
  RayTracer tracer(polygons);
  tracer.setGlass(std::make_shared<ThinGlass>(ThinGlass::overElements(scene, solved)));
  const DirectLight direct(scene, solved, &solved, skies);
  return elementDirectLight(solved, tracer, direct, samples, seed, elements);
}

}  // namespace luxel
