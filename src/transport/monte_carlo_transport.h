// An independent reference for the form factors: cosine-distributed rays from points spread
// uniformly (by area) over each element, each landing on the front of a patch adding 1/N to
// F[e <- p]. Unbiased and noisy, with nothing in common with CpuTransport's estimator (no
// analytic factor, no visibility weighting), which is what makes it a check on that estimator:
// it is how the unweighted visibility share was found 2-22% dark on the Cornell box
// (tests/analytic/test_monte_carlo_reference.cpp). The directions are Malley's (T. Malley, "A
// Shading Method for Computer Generated Images", MS thesis, University of Utah, 1988): uniform on
// the unit disc, lifted to the hemisphere, which makes them cosine-distributed.
#pragma once

#include <memory>
#include <vector>

#include "transport/cpu_transport.h"
#include "transport/transport.h"

namespace luxel {

class MonteCarloTransport final : public Transport {
 public:
  // `raysPerElement` (at least 1) per element and row. Analytic lights go through a CpuTransport
  // with `lightOptions`. Throws Error for scenes with two-sided faces, whose coincident sides the
  // ray caster cannot tell apart.
  MonteCarloTransport(const Scene& scene, const SurfaceSet& surfaces, int raysPerElement,
                      const FormFactorOptions& lightOptions = {});
  ~MonteCarloTransport() override;

  void rows(std::span<const uint32_t> elements, std::span<float> out) override;
  // From the rows of every element, computed once and kept (elements x patches floats).
  void columns(std::span<const uint32_t> patches, std::span<float> out) override;
  void pairs(std::span<const ElementPatch> pairs, std::span<float> out) override;
  void analyticIrradiance(std::span<Rgb> out) override { lights_.analyticIrradiance(out); }
  void lightIrradiance(std::span<const uint32_t> lights, std::span<Rgb> out) override {
    lights_.lightIrradiance(lights, out);
  }
  void lightIrradianceAndSh(std::span<const uint32_t> lights, int count, std::span<Rgb> irradiance,
                            std::span<Rgb> sh) override {
    lights_.lightIrradianceAndSh(lights, count, irradiance, sh);
  }
  void lightSh(std::span<const uint32_t> lights, int count, std::span<Rgb> out) override {
    lights_.lightSh(lights, count, out);
  }
  uint64_t raysTraced() const override { return tracer_.raysTraced(); }
  void elementsChanged() override { matrix_.clear(); }
  // A reference for static scenes: its ray tracer holds the patches, not the scene's objects.
  void objectsMoved(std::span<const uint32_t>) override;

 private:
  void ensureMatrix();  // every row, computed once

  const SurfaceSet& surfaces_;
  int raysPerElement_;
  std::vector<Polygon> patchPolygons_;
  RayTracer tracer_;  // over the patches: a hit's primitive is its patch
  CpuTransport lights_;
  std::vector<float> matrix_;  // all rows, once columns() has been asked for
};

}  // namespace luxel
