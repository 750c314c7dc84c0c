// The CPU backend: exact unoccluded form factors times a visibility fraction from stratified,
// jittered Embree rays, in the manner of Wallace, Elmquist and Haines, "A Ray Tracing Algorithm
// for Progressive Radiosity" (SIGGRAPH 1989), with the analytic point-to-polygon factor of
// Baum et al. 1989 in place of the disc approximation, and each ray's verdict weighted by its
// point-to-point kernel (a ratio estimator of the visible share, unbiased as rays increase).
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "luxel/solve.h"
#include "transport/form_factor_options.h"
#include "transport/light_sampling.h"
#include "trace/convex_solid.h"
#include "trace/ray_tracer.h"
#include "trace/thin_glass.h"
#include "transport/transport.h"

namespace luxel {

class CpuTransport final : public Transport {
 public:
  CpuTransport(const Scene& scene, const SurfaceSet& surfaces, const FormFactorOptions& options);
  ~CpuTransport() override;

  void columns(std::span<const uint32_t> patches, std::span<float> out) override;
  void rows(std::span<const uint32_t> elements, std::span<float> out) override;
  void pairs(std::span<const ElementPatch> pairs, std::span<float> out) override;
  void analyticIrradiance(std::span<Rgb> out) override;
  void lightIrradiance(std::span<const uint32_t> lights, std::span<Rgb> out) override;
  void lightSh(std::span<const uint32_t> lights, int count, std::span<Rgb> out) override;
  void lightIrradianceAndSh(std::span<const uint32_t> lights, int count, std::span<Rgb> irradiance,
                            std::span<Rgb> sh) override;
  uint64_t raysTraced() const override {
    return tracer_.raysTraced() + movedRays_ + (movedBefore_ ? movedBefore_->raysTraced() + movedAfter_->raysTraced() : 0);
  }
  void elementsChanged() override;
  // Moves the objects' ray tracer instances (a commit, no rebuild) and forgets what depended on
  // where they were: pair classifications and receiver quadratures.
  void objectsMoved(std::span<const uint32_t> objects) override;
  std::vector<uint32_t> receiversRedoneByMove() const override { return redoneByMove_; }
  void sourcesChanged() override;
  std::vector<uint32_t> patchesRedoneBySources() const override { return redoneBySources_; }
  // Exact per ray: each pair's rays are tested against the moved faces alone, where they were
  // and where they are.
  void visibilityChangedByMove(std::span<const ElementPatch> pairs, std::span<uint8_t> changed, float certify = 0.0f,
                               std::span<uint8_t> certified = {}) override;
  // Exact: the same samples as lightIrradiance, tested against the moved faces alone.
  size_t updateLightIrradianceAfterMove(std::span<const uint32_t> lights, std::span<Rgb> irradiance) override;

  RayTracer& tracer() { return tracer_; }
  RayTracer* rayTracer() override { return &tracer_; }

  // One element-patch pair, written to *out.
  struct Pair {
    uint32_t element;
    uint32_t patch;
    float* out;
  };
  // Computes a batch of pairs (at most 128) on the calling thread: one ray stream for the batch.
  void computePairs(std::span<const Pair> pairs);

 private:
  struct Workspace;
  Workspace& workspace();

  const Scene& scene_;
  const SurfaceSet& surfaces_;
  FormFactorOptions options_;
  std::vector<Polygon> facePolygons_;  // where each face is now: kept for scenes with dynamic objects only
  Polygon facePolygon(uint32_t face) const {
    return facePolygons_.empty() ? tracer_.polygonAsBuilt(face) : facePolygons_[face];
  }
  RayTracer tracer_;  // with the faces' glass (trace/thin_glass.h), for the lights' shadow rays
  float rayOffset_ = 0.0f;
  enum class PairVisibility : uint8_t { Unknown, Clear, Partial };
  // Traces the samples of `lights` at every element and calls visit(element, samples) with the
  // ones that reach it: lightIrradiance and lightSh read the same samples.
  template <typename Visit>
  void visitLightSamples(std::span<const uint32_t> lights, Visit&& visit, std::span<const uint32_t> elements = {});
  // The shadow rays and samples of `lights` at one element, deterministic per element and light
  // (the first pass: lightSamples of each); with `lightOf`, each sample's light as its place in
  // `lights`.
  void appendLightSamples(uint32_t element, std::span<const uint32_t> lights, std::vector<RTCRay>& rays,
                          std::vector<LightSample>& samples, std::vector<uint32_t>* lightOf = nullptr) const;
  // Light `light`'s k x k stratified samples at one element; `pass` seeds them (0 first, then
  // kRefinedPass).
  void appendSamplesOfLight(uint32_t element, uint32_t light, int k, uint32_t pass, std::vector<RTCRay>& rays,
                            std::vector<LightSample>& samples) const;
  // The side of an element's grid of samples of `light`, k = sqrt(lightSamples) in the first pass,
  // and kSkySampleSide k for skies: a sky's light comes through whatever of the hemisphere is
  // open (a window, the gaps of a colonnade), which 16 samples an element find or miss by chance
  // (docs/algorithms.md, "Analytic lights", has the measurements).
  int firstLightSide(uint32_t light) const;
  static constexpr int kSkySampleSide = 2;
  // Where the first pass finds a shadow's edge across an element (some samples reach, some do
  // not), lamps and suns are sampled again on a kLightRefinement times finer grid (at most 16 x
  // 16), in place of the first samples; skies are not.
  int refinedLightSide(uint32_t light) const;
  static constexpr int kLightRefinement = 4;
  static constexpr uint32_t kRefinedPass = 0x5EF1u;
  // Per scene light, per element: whether its last computation refined it (visitLightSamples), so
  // that a move's update checks the finer samples' verdicts too.
  std::vector<std::vector<uint8_t>> refinedLight_;
  // Whether the segment's verdict against the last move's objects is the same wherever they stand
  // within `reach` of where they were, proved against their solids without tracing (certificates).
  bool movedRaySettled(Vec3 a, Vec3 b, float reach) const;
  // What the last move did to the segment's verdict against the moved faces, proved against the
  // movers' solids where they were and where they are; Unsure when it must be traced.
  enum class MoveVerdict { Same, Changed, Unsure };
  MoveVerdict moveVerdict(Vec3 a, Vec3 b) const;
  PairVisibility classify(uint32_t receiverPatch, uint32_t sourcePatch);
  // The unoccluded factor A of each pair, by each receiver element's midpoint rule.
  void computeAnalytic(std::span<const Pair> pairs, float* out) const;
  // True when no face other than the two patches' own reaches into the shaft between them.
  bool shaftIsEmpty(const Patch& a, const Patch& b) const;

  std::vector<std::pair<uint32_t, glm::mat4>> builtAt_;  // dynamic objects, by instance: transform at construction
  std::vector<float> patchRadius_;
  // Receiver patch x source patch verdicts, filled lazily; empty when classification is off.
  // Each byte is generation << 2 | verdict; a verdict of an older generation (objects have moved
  // since) counts as unknown.
  std::unique_ptr<std::atomic<uint8_t>[]> pairVisibility_;
  uint32_t pairGeneration_ = 1;
  // Receiver quadratures are made when the first factor is asked for: a solver that never asks
  // (the hierarchical one computes its own couplings) does not pay for the near-face search.
  void ensureQuadrature();
  void updateQuadrature(std::span<const uint32_t> elements);
  std::mutex quadratureMutex_;
  std::atomic<bool> quadratureReady_{false};
  std::vector<float> elementRadius_;
  std::vector<uint8_t> elementQuadrature_;  // receiver midpoint rule: k x k points
  std::vector<uint8_t> patchEmits_;
  std::vector<uint32_t> redoneByMove_;  // the receivers whose quadrature the last move made again
  std::vector<uint32_t> redoneBySources_;  // the patches the last emission change made emitters or not
  // Whether any of each patch's elements emits (such pairs take emitterRaysPerPair rays).
  void findEmitters(std::vector<uint8_t>& emits) const;
  std::unique_ptr<RayTracer> movedBefore_, movedAfter_;  // the last move's faces, before and after it
  // When every object the last move moved is a closed convex solid: each one where it was and
  // where it is, how far its farthest corner moved, and the padding for rounding its verdicts need.
  struct MovedSolid {
    ConvexSolid was, now;
    float moved, pad;
  };
  std::vector<MovedSolid> movedSolids_;
  std::vector<uint32_t> movedObjects_;  // the objects the last move moved
  Vec3 movedLo_[2], movedHi_[2];         // the bounds of their faces before and after it
  uint64_t movedRays_ = 0;                                // rays earlier moves' tracers traced
  // Calls visit(from, to, kernel) for each visibility ray of one pair, deterministic per pair
  // (computePairs and visibilityChangedByMove cast the same ones), with its point-to-point kernel;
  // a visitor returning bool stops the pair's rays when it returns false.
  template <typename Visit>
  void forEachPairRay(uint32_t element, uint32_t patch, Visit&& visit) const;
  struct ThreadLocal;
  std::unique_ptr<ThreadLocal> threadLocal_;
};

}  // namespace luxel
