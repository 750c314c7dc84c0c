// The GPU backend's transport: form factors from item-buffer hemicubes rendered with OpenGL 4.5
// (Cohen and Greenberg 1985; seeds 000 and 001 section 4.2). A receiver element's hemicube, with
// the patches as items, gives its whole row F[e <- p] at once; columns are the transpose of the
// rows, gathered once and kept, by default; or, as an option, ID-hemicube shooting (001 section
// 4.3): a hemicube on the shooting patch with the elements as items gives F[p -> e], and
// F[e <- p] = F[p -> e] A_p / A_e (reciprocity). Analytic lights are evaluated by the CPU backend.
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
  // How columns() (progressive shooting) gets F[e <- p].
  enum class Shooting {
    TransposeRows,  // every element's row rendered once (hemicubes at the receivers), then transposed
    IdHemicube,     // k x k hemicubes over the shooting patch, elements as items, by reciprocity
  };

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

  // `samplesPerSide`: hemicubes per shooting-patch side for IdHemicube (0: as for the rows).
  void setShooting(Shooting shooting, int samplesPerSide = 0) {
    shooting_ = shooting;
    shootSamplesPerSide_ = samplesPerSide;
  }
  Shooting shooting() const { return shooting_; }

  uint64_t hemicubesRendered() const { return hemicubes_; }
  uint64_t rowsComputed() const { return rows_; }  // element rows rendered, whoever asked

 private:
  const SurfaceSet& surfaces_;
  int samplesPerSide_ = 2;
  HemicubeOptions hemicubeOptions_;
  Shooting shooting_ = Shooting::TransposeRows;
  int shootSamplesPerSide_ = 0;
  std::unique_ptr<ItemHemicube> hemicube_;
  std::unique_ptr<ItemHemicube> elementHemicube_;  // elements as items, for ID-hemicube shooting
  std::unique_ptr<CpuTransport> analytic_;  // analytic lights only
  float offset_ = 0.0f;
  std::vector<float> matrix_;  // all rows, gathered on the first columns() call
  uint64_t hemicubes_ = 0, rows_ = 0;
  std::vector<float> sample_;  // one hemicube's factors
  std::vector<float> shot_;    // one shooting hemicube's factors, per element

  void shootColumns(std::span<const uint32_t> patches, std::span<float> out);
};

}  // namespace gl
}  // namespace luxel
