// What the GL parity tests share: the converged CPU solve they compare against, and names for
// the two hemicube visibility tests in parameterised test names.
#pragma once

#include <string>

#include "luxel/solve.h"

namespace luxel::test {

// Exact factors with 64 visibility rays per pair (256 from emitters), Gauss-Seidel to 1e-6.
inline SolveOptions convergedCpuGather() {
  SolveOptions o;
  o.method = SolveOptions::Method::Gather;
  o.residualThreshold = 1e-6;
  o.formFactors.raysPerPair = 64;
  o.formFactors.nearRaysPerPair = 64;
  o.formFactors.emitterRaysPerPair = 256;
  return o;
}

inline std::string visibilityName(SolveOptions::HemicubeVisibility v) {
  return v == SolveOptions::HemicubeVisibility::Item ? "Item" : "Distance";
}

}  // namespace luxel::test
