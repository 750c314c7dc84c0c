// The face-cluster solver shoots from every face, so on the Cornell box it must agree face by face
// with a gather in which every element is its own patch, and with the truth: path-traced
// interreflected light per face (transport/path_traced_irradiance.h), which shares neither
// solver's discretisation (docs/algorithms.md, "Face-cluster radiosity", accuracy).
#include <cmath>
#include <cstdio>
#include <map>

#include <gtest/gtest.h>

#include "gl/gl_parity.h"
#include "luxel/solve.h"
#include "solve/solver_registry.h"
#include "transport/path_traced_irradiance.h"

namespace luxel {
namespace {

double channelSum(Rgb c) { return double(c.r) + double(c.g) + double(c.b); }

TEST(HierarchicalCornell, InterreflectionAgreesFaceByFace) {
  const test::CornellReference& ref = test::cornellReference(300, 1);
  SurfaceSet surfaces = ref.surfaces;
  SolveOptions o;
  o.method = "hierarchical";
  o.settings = SolverRegistry::builtin().get("hierarchical", "cpu").converged;
  const Solution h = solve(ref.scene, surfaces, o);

  // Interreflected irradiance (all minus direct), area-weighted per face, all channels: the
  // truth from 16,384 paths an element with and without bounces.
  std::vector<uint32_t> probes;
  for (uint32_t e = 0; e < surfaces.elements.size(); ++e)
    if (channelSum(surfaces.elements[e].exitance) == 0.0) probes.push_back(e);
  PathTracingOptions paths{.minPaths = 1u << 14, .maxPaths = 1u << 14};
  const auto all = pathTraceElementIrradiance(ref.scene, surfaces, probes, paths);
  paths.maxBounces = 0;
  const auto direct = pathTraceElementIrradiance(ref.scene, surfaces, probes, paths);
  struct Face {
    double area = 0, truth = 0, variance = 0, gather = 0, hierarchical = 0;
  };
  std::map<uint32_t, Face> perFace;
  for (size_t i = 0; i < probes.size(); ++i) {
    const uint32_t e = probes[i];
    const Element& el = surfaces.elements[e];
    Face& f = perFace[el.face];
    const double se = glm::length(all[i].standardError) + glm::length(direct[i].standardError);
    f.area += el.area, f.variance += double(el.area) * el.area * se * se;
    f.truth += el.area * (channelSum(all[i].mean) - channelSum(direct[i].mean));
    f.gather += el.area * channelSum(ref.cpu.irradiance[e] - ref.cpu.directIrradiance[e]);
    f.hierarchical += el.area * channelSum(h.irradiance[e] - h.directIrradiance[e]);
  }
  double againstGather = 0.0, againstTruth = 0.0, gatherAgainstTruth = 0.0, area = 0.0;
  for (const auto& [face, f] : perFace) {
    ASSERT_GT(f.truth, 0.0) << "face " << face << " gets no interreflected light";
    const double h = f.hierarchical / f.truth - 1.0, g = f.gather / f.truth - 1.0, noise = std::sqrt(f.variance) / f.truth;
    std::printf("face %u: hierarchical / truth %.4f, gather / truth %.4f (truth's standard error %.4f)\n", face, 1.0 + h,
                1.0 + g, noise);
    // No face further from the truth than the gather by more than 5 points and the truth's noise.
    EXPECT_LT(std::abs(h), std::abs(g) + 0.05 + 4.0 * noise) << "face " << face;
    againstGather += f.area * std::abs(f.hierarchical / f.gather - 1.0);
    againstTruth += f.area * std::abs(h), gatherAgainstTruth += f.area * std::abs(g), area += f.area;
  }
  std::printf("area-weighted mean |difference| per face: hierarchical against the truth %.4f, against the gather "
              "%.4f; the gather against the truth %.4f\n",
              againstTruth / area, againstGather / area, gatherAgainstTruth / area);
  // Measured: the hierarchy 2.7% from the truth and the gather 3.9% (the gather is 6% low on the
  // red wall's two non-coplanar triangles, where the hierarchy is within 1%); both are 15-20%
  // low on two faces meeting the floor at a crease, the discretisation's error there.
  EXPECT_LT(againstTruth / area, 0.035) << "area-weighted mean relative difference per face, against the truth";
  EXPECT_LE(againstTruth / area, gatherAgainstTruth / area) << "the hierarchy is no further from the truth than the gather";
  EXPECT_LT(againstGather / area, 0.04) << "against the gather";
}

}  // namespace
}  // namespace luxel
