// Directions per vertex (issue 17, seed 004 section 4): a directional lightmap's texture values at
// the element corners, for bakes to vertex colours. See luxel/bake.h, elementDirections.
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "core/spherical_harmonics.h"
#include "luxel/bake.h"
#include "luxel/error.h"
#include "luxel/render.h"
#include "render/corner_values.h"

namespace luxel {

std::vector<std::vector<Rgb>> elementDirections(const SurfaceSet& surfaces, DirectionalMode mode,
                                                const std::vector<Rgb>& sh) {
  const int count = directionalCoefficients(mode);
  const size_t ne = surfaces.elements.size();
  if (count == 0) throw Error("element directions: no directional mode");
  if (sh.size() != ne * size_t(count))
    throw Error(fmt::format("element directions: {} SH coefficients for {} elements, expected {} each", sh.size(), ne,
                            count));
  // Each coefficient is a linear function of the incident light, so it is carried to the corners
  // exactly as the irradiance is (over corner groups found once: finding them sorts every corner);
  // the ratios the textures hold are taken after, at each corner.
  const CornerGroups groups(surfaces, kDefaultCreaseCosine);
  std::vector<std::vector<Rgb>> atCorners(static_cast<size_t>(count));
  std::vector<Rgb> plane(ne);
  for (int k = 0; k < count; ++k) {
    for (size_t e = 0; e < ne; ++e) plane[e] = sh[e * size_t(count) + size_t(k)];
    atCorners[size_t(k)] = elementCornerValues(surfaces, groups, plane);
  }
  const int textures = directionalTextureCount(mode);
  std::vector<std::vector<Rgb>> out(size_t(textures), std::vector<Rgb>(ne * 4));
  tbb::parallel_for(size_t(0), ne * 4, [&](size_t i) {
    Rgb c[kMaxDirectionalCoefficients];
    for (int k = 0; k < count; ++k) c[k] = atCorners[size_t(k)][i];
    // L2 is read linearly: windowed as a lightmap texel is (lightmap_bake.cpp).
    if (mode == DirectionalMode::ShL2) {
      const float s = shNonNegativeWindow(c, kShCoefficients);
      if (s < 1.0f) shApplyWindow(c, kShCoefficients, s);
    }
    for (int t = 0; t < textures; ++t) out[size_t(t)][i] = encodeDirectionalTexel(mode, c, t);
  });
  return out;
}

}  // namespace luxel
