// The face-cluster solver shoots from every face, so on the Cornell box it must agree face by face
// with a gather in which every element is its own patch (docs/algorithms.md, "Face-cluster
// radiosity", accuracy). Interreflected light is compared, the part an earlier version of the
// docs recorded as a defect of the solver when the reference was one patch a face.
#include <cmath>
#include <cstdio>
#include <map>

#include <gtest/gtest.h>

#include "gl/gl_parity.h"
#include "luxel/solve.h"
#include "solve/solver_registry.h"

namespace luxel {
namespace {

TEST(HierarchicalCornell, InterreflectionAgreesFaceByFace) {
  const test::CornellReference& ref = test::cornellReference(300, 1);
  SurfaceSet surfaces = ref.surfaces;
  SolveOptions o;
  o.method = "hierarchical";
  o.settings = SolverRegistry::builtin().get("hierarchical", "cpu").converged;
  const Solution h = solve(ref.scene, surfaces, o);

  // Interreflected irradiance (all minus direct), area-weighted per face, all channels.
  std::map<uint32_t, std::array<double, 3>> perFace;  // area, reference, hierarchical
  for (size_t e = 0; e < surfaces.elements.size(); ++e) {
    const Element& el = surfaces.elements[e];
    const Rgb a = ref.cpu.irradiance[e] - ref.cpu.directIrradiance[e], b = h.irradiance[e] - h.directIrradiance[e];
    auto& f = perFace[el.face];
    f[0] += el.area, f[1] += el.area * (a.r + a.g + a.b), f[2] += el.area * (b.r + b.g + b.b);
  }
  double worst = 0.0, weighted = 0.0, area = 0.0;
  for (const auto& [face, f] : perFace) {
    ASSERT_GT(f[1], 0.0) << "face " << face << " gets no interreflected light in the reference";
    const double d = std::abs(f[2] / f[1] - 1.0);
    std::printf("face %u: hierarchical / reference %.4f\n", face, f[2] / f[1]);
    worst = std::max(worst, d), weighted += f[0] * d, area += f[0];
  }
  RecordProperty("worst", std::to_string(worst));
  // Measured: the red wall's two non-coplanar triangles 7.7% and 6.3% high, the rest within 2.6%.
  // Against path-traced probes of those two faces (transport/path_traced_irradiance.h, 4,096
  // paths an element) the gather is 6.1% and 6.8% low and the hierarchy 1.1% high and 1.0% low:
  // the difference there is the gather's (docs/algorithms.md, "Face-cluster radiosity").
  EXPECT_LT(weighted / area, 0.02) << "area-weighted mean relative difference per face";
  EXPECT_LT(worst, 0.08) << "worst face";
}

}  // namespace
}  // namespace luxel
