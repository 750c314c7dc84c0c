#include "gl/gl_transport.h"

#include <algorithm>
#include <numeric>

#include "transport/cpu_transport.h"
#include "transport/form_factor.h"

namespace luxel::gl {

GlTransport::GlTransport(const Scene& scene, const SurfaceSet& surfaces, const FormFactorOptions& formFactors,
                         const HemicubeOptions& hemicube, float offset, int samplesPerSide)
    : surfaces_(surfaces), samplesPerSide_(samplesPerSide), analytic_(std::make_unique<CpuTransport>(scene, surfaces, formFactors)) {
  std::vector<Polygon> patchPolygons(surfaces.patches.size());
  for (size_t p = 0; p < surfaces.patches.size(); ++p) patchPolygons[p] = surfaces.patches[p].polygon;
  hemicube_ = std::make_unique<ItemHemicube>(patchPolygons, surfaces.sceneExtent, hemicube);
  offset_ = offset * (surfaces.sceneExtent > 0.0f ? surfaces.sceneExtent : 1.0f);
}

GlTransport::~GlTransport() = default;

void GlTransport::rows(std::span<const uint32_t> elements, std::span<float> out) {
  const size_t np = surfaces_.patches.size();
  for (size_t i = 0; i < elements.size(); ++i) {
    const Element& e = surfaces_.elements[elements[i]];
    // One hemicube per point of the element's k x k midpoint rule, averaged: visibility and the
    // factor both vary over the element (penumbrae, corners), which one centre point misses.
    const int k = samplesPerSide_;
    std::vector<float> f(np, 0.0f);
    sample_.resize(np);
    for (int j = 0; j < k; ++j)
      for (int q = 0; q < k; ++q) {
        const Vec3 x = polygonPoint(e.polygon, (float(q) + 0.5f) / float(k), (float(j) + 0.5f) / float(k));
        hemicube_->formFactors(x + offset_ * e.normal, e.normal, sample_);
        for (size_t p = 0; p < np; ++p) f[p] += sample_[p] / float(k * k);
        ++hemicubes_;
      }
    ++rows_;
    float* row = out.data() + i * np;
    for (size_t p = 0; p < np; ++p) {
      const Patch& patch = surfaces_.patches[p];
      // The item buffer sees a patch from either side; a one-sided source radiates only in front.
      const bool facing = glm::dot(patch.normal, e.centroid - patch.centroid) > 0.0f;
      row[p] = (facing && patch.face != e.face) ? f[p] : 0.0f;
    }
  }
}

void GlTransport::columns(std::span<const uint32_t> patches, std::span<float> out) {
  const size_t ne = surfaces_.elements.size(), np = surfaces_.patches.size();
  if (matrix_.empty()) {
    std::vector<uint32_t> all(ne);
    std::iota(all.begin(), all.end(), 0u);
    matrix_.resize(ne * np);
    rows(all, matrix_);
  }
  for (size_t c = 0; c < patches.size(); ++c)
    for (size_t e = 0; e < ne; ++e) out[c * ne + e] = matrix_[e * np + patches[c]];
}

void GlTransport::analyticIrradiance(std::span<Rgb> out) { analytic_->analyticIrradiance(out); }

uint64_t GlTransport::raysTraced() const { return analytic_->raysTraced(); }

void GlTransport::elementsChanged() {
  matrix_.clear();
  analytic_->elementsChanged();
}

}  // namespace luxel::gl
