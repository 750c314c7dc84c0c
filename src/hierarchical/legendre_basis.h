// The bases of higher-order face-cluster radiosity (Gobbetti, Spano and Agus 2003, appendix A):
// tensor products of orthonormal shifted Legendre polynomials on the unit square of a cluster's
// box plane, in the paper's order {1, u, v, uv, u^2, v^2, u^3, u^2 v, u v^2, v^3}. A basis is a
// prefix: constant 1 function, linear 3 (not the bilinear product), bilinear 4, quadratic 6,
// cubic 10. The constants are the paper's: sqrt 3, sqrt 5 / 2, 2 / sqrt 5 and 5 sqrt 7 / (3 sqrt 15).
#pragma once

#include <string>

#include "luxel/scene.h"

namespace luxel {

inline constexpr int kMaxBasisFunctions = 10;

// The number of functions in the basis called `name` (constant, linear, bilinear, quadratic,
// cubic); 0 for an unknown name.
inline int basisSize(const std::string& name) {
  if (name == "constant") return 1;
  if (name == "linear") return 3;
  if (name == "bilinear") return 4;
  if (name == "quadratic") return 6;
  if (name == "cubic") return 10;
  return 0;
}

// The first `count` basis functions at (u, v), written to out[0 .. count).
inline void evaluateBasis(Vec2 uv, int count, float* out) {
  const float fu = 1.7320508f * (2.0f * uv.x - 1.0f);
  const float fv = 1.7320508f * (2.0f * uv.y - 1.0f);
  const float fu2 = 1.1180340f * (fu * fu - 1.0f);
  const float fv2 = 1.1180340f * (fv * fv - 1.0f);
  const float all[kMaxBasisFunctions] = {1.0f,
                                         fu,
                                         fv,
                                         fu * fv,
                                         fu2,
                                         fv2,
                                         1.1385501f * fu * (fu2 - 0.8944272f),
                                         fu2 * fv,
                                         fu * fv2,
                                         1.1385501f * fv * (fv2 - 0.8944272f)};
  for (int i = 0; i < count; ++i) out[i] = all[i];
}

}  // namespace luxel
