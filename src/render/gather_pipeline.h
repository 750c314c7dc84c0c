// What an hq render's indirect light reads (docs/algorithms.md, "Rendering"), built once per
// image: the elements the pixels find (GatherMesh: the solved ones, split where the gather wants
// finer), the solution's indirect irradiance at their corners, a ray tracer over them, the direct
// light, each element's direct light for the gather's far hits, and the chain of coarse gathers
// that puts the solution gatherBounces bounces away. The vertex gather over it (a VertexGather on
// finalGather()) is the caller's, weighted by what it shows: an image by the pixels each element
// covers, a benchmark by the elements it probes.
#pragma once

#include <deque>
#include <optional>
#include <span>
#include <vector>

#include "luxel/render.h"
#include "render/direct_light.h"
#include "render/final_gather.h"
#include "render/gather_mesh.h"
#include "trace/ray_tracer.h"

namespace luxel {

class GatherPipeline {
 public:
  // `indirect`: what the render resolved (resolvedIndirect); only vertex and pixel gathers use
  // the coarse gathers and the elements' direct light, and only a vertex gather splits elements.
  // `hq`: the corners hold the solution's indirect irradiance (its direct part is traced per
  // pixel); otherwise all of it. Everything given must outlive this.
  GatherPipeline(const Scene& scene, const SurfaceSet& solved, const Solution& solution, const RenderOptions& options,
                 RenderOptions::Indirect indirect, bool hq);
  GatherPipeline(const GatherPipeline&) = delete;
  GatherPipeline& operator=(const GatherPipeline&) = delete;

  const GatherMesh& mesh() const { return *mesh_; }
  const SurfaceSet& shown() const { return mesh_->surfaces(); }
  const RayTracer& tracer() const { return *tracer_; }
  const DirectLight& direct() const { return *direct_; }
  // The solution's field at the corners of shown()'s elements, 4 slots each.
  const std::vector<Rgb>& corners() const { return corners_; }
  // What a vertex or pixel gather's rays read: the solution, or the last coarse gather.
  const FinalGather& finalGather() const;
  // What reads the solution itself where rays land (its indirect light at the corners, the hits'
  // direct light), whatever the coarse gathers above it: for rays whose answer is blurred anyway
  // (a glossy lobe's), where reading a coarse gather would gather its vertices on demand.
  const FinalGather& solutionGather() const { return *gather_; }

 private:
  std::optional<GatherMesh> mesh_;
  std::vector<Rgb> corners_;
  std::vector<Polygon> polygons_;
  std::optional<RayTracer> tracer_;
  std::optional<DirectLight> direct_;
  std::optional<FinalGather::ElementDirect> elementDirect_;
  std::optional<FinalGather> gather_;
  std::vector<Rgb> coarse_;
  std::optional<FinalGather> fromCoarse_;
  std::deque<VertexGather> lazyLevels_;
  std::deque<FinalGather> lazyGathers_;
};

// The irradiance an hq render's vertex gather shows (`options`' gather settings, three bounces by
// default), averaged over each of the solved `elements` (distinct): what a picture of them would
// interpolate. That is the indirect light, and with `skies` the skies' light as well, as a render
// gathers it (VertexGather's skiesOf). For judging the gather against path-traced probes (`luxel
// bench hierarchical`).
std::vector<Rgb> gatheredIndirect(const Scene& scene, const SurfaceSet& solved, const Solution& solution,
                                  std::span<const uint32_t> elements, const RenderOptions& options, bool skies = false);

// The direct light an hq render traces at its pixels, averaged over each of the solved `elements`
// from `samples` points stratified over it (a light point each): what a picture of them shows,
// where the solution's own per-element direct light is an estimate of fewer rays. Without `skies`,
// the other lights only (a render's vertex gather takes the skies).
std::vector<Rgb> pixelDirectLight(const Scene& scene, const SurfaceSet& solved, std::span<const uint32_t> elements,
                                  int samples, uint32_t seed, bool skies = true);

}  // namespace luxel
