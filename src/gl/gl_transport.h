// The GPU backend's transport: form factors from item-buffer hemicubes rendered with OpenGL 4.5
// (Cohen and Greenberg 1985; seeds 000 and 001 section 4.2). A receiver element's hemicube, with
// the patches as items, gives its whole row F[e <- p] at once; columns are the transpose of the
// rows, gathered once and kept. Analytic lights are evaluated by the CPU backend. Progressive
// refinement on the GPU does not go through a transport: see progressive_gl.h.
#pragma once

#include <memory>
#include <vector>

#include "gl/hemicube.h"
#include "luxel/solve.h"
#include "transport/transport.h"

namespace luxel {

class CpuTransport;

namespace gl {

class GlTransport final : public Transport {
 public:
  // Needs a current OpenGL 4.5 context. The hemicube sits `offset` (relative to the scene extent)
  // above each receiver's centroid, so that it does not see through the surface it stands on.
  // Each element's row averages `samplesPerSide` x `samplesPerSide` hemicubes over the element.
  GlTransport(const Scene& scene, const SurfaceSet& surfaces, const FormFactorOptions& formFactors,
              const HemicubeOptions& hemicube = {}, float offset = 1e-4f, int samplesPerSide = 2);
  ~GlTransport() override;

  void columns(std::span<const uint32_t> patches, std::span<float> out) override;
  void rows(std::span<const uint32_t> elements, std::span<float> out) override;
  void analyticIrradiance(std::span<Rgb> out) override;
  uint64_t raysTraced() const override;
  void elementsChanged() override;

  uint64_t hemicubesRendered() const { return hemicubes_; }
  uint64_t rowsComputed() const { return rows_; }  // element rows rendered, whoever asked

 private:
  const SurfaceSet& surfaces_;
  int samplesPerSide_ = 2;
  std::unique_ptr<ItemHemicube> hemicube_;
  std::unique_ptr<CpuTransport> analytic_;  // analytic lights only
  float offset_ = 0.0f;
  std::vector<float> matrix_;  // all rows, gathered on the first columns() call
  uint64_t hemicubes_ = 0, rows_ = 0;
  std::vector<float> sample_;  // one hemicube's factors
};

}  // namespace gl
}  // namespace luxel
