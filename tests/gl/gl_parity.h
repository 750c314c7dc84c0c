// What the GL parity tests share: the converged CPU solve they compare against (of the built-in
// Cornell box, computed once per element budget and test process), and names for the two
// hemicube visibility tests in parameterised test names.
#pragma once

#include <map>
#include <string>
#include <utility>

#include "luxel/solve.h"
#include "scene/builtin/builtin_scenes.h"

namespace luxel::test {

// Exact factors with 64 visibility rays per pair (256 from emitters), Gauss-Seidel to 1e-6.
inline SolveOptions convergedCpuGather() {
  SolveOptions o;
  o.method = "gather";
  o.settings.set("residual", 1e-6);
  o.settings.set("rays-per-pair", 64);
  o.settings.set("near-rays-per-pair", 64);
  o.settings.set("emitter-rays-per-pair", 256);
  return o;
}

// The built-in Cornell box cut for `elementBudget`, patches of about elementsPerPatchSide^2
// elements, and its converged CPU solution.
struct CornellReference {
  Scene scene;
  SurfaceSet surfaces;
  Solution cpu;
};

inline const CornellReference& cornellReference(size_t elementBudget, int elementsPerPatchSide = 8) {
  static std::map<std::pair<size_t, int>, CornellReference> solved;
  const std::pair<size_t, int> key{elementBudget, elementsPerPatchSide};
  auto it = solved.find(key);
  if (it != solved.end()) return it->second;
  CornellReference r{builtin::cornellBox(), {}, {}};
  DiscretiseOptions d;
  d.elementBudget = elementBudget;
  d.elementsPerPatchSide = elementsPerPatchSide;
  r.surfaces = discretise(r.scene, d);
  SurfaceSet copy = r.surfaces;
  r.cpu = solve(r.scene, copy, convergedCpuGather());
  return solved.emplace(key, std::move(r)).first->second;
}

inline std::string visibilityName(const std::string& v) {
  return v == "item" ? "Item" : "Distance";
}

}  // namespace luxel::test
