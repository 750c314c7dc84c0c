// The error measure of the benchmark suite: van de Hoef (2013, Table 5.1) reports a "normalised
// RMS error" against a high-quality gather reference without saying how it normalises; ours is
// stated in bench.h and docs/performance.md.
#include <cmath>

#include <fmt/format.h>

#include "luxel/bench.h"
#include "luxel/error.h"

namespace luxel::bench {

double normalisedRmsError(const SurfaceSet& surfaces, const std::vector<Rgb>& radiosity,
                          const std::vector<Rgb>& reference) {
  const size_t n = surfaces.elements.size();
  if (radiosity.size() != n || reference.size() != n)
    throw Error(fmt::format("error measure: {} radiosities and {} reference values for {} elements",
                            radiosity.size(), reference.size(), n));
  double diff = 0.0, norm = 0.0;
  for (size_t e = 0; e < n; ++e) {
    const Rgb& x = surfaces.elements[e].exitance;
    if (x.r > 0.0f || x.g > 0.0f || x.b > 0.0f) continue;
    for (int c = 0; c < 3; ++c) {
      double d = double(radiosity[e][c]) - double(reference[e][c]);
      diff += d * d;
      norm += double(reference[e][c]) * double(reference[e][c]);
    }
  }
  if (!(norm > 0.0)) throw Error("error measure: the reference is black everywhere it does not emit");
  return std::sqrt(diff / norm);
}

}  // namespace luxel::bench
