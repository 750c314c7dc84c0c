// Lightmaps from the face-cluster solver (seed 002): the texels are the faces the hierarchy is
// built over, so a large level's bake clusters its texels instead of making each one a shooter.
// The baked texels are compared with the progressive bake of the same atlas.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "luxel/import.h"
#include "luxel/lightmap.h"

namespace luxel {
namespace {

float luminance(Rgb c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// One atlas baked by the progressive solver (the reference) and by the hierarchy.
struct TwoBakes {
  LightmapBake progressive, hierarchical;
};

TwoBakes bakeBoth(const Scene& scene, const AtlasOptions& ao) {
  const LightmapAtlas atlas = buildLightmapAtlas(scene, ao);
  LightmapBakeOptions progressive, hierarchical;
  progressive.solve.method = "progressive";
  hierarchical.solve.method = "hierarchical";
  TwoBakes b;
  b.hierarchical = bakeLightmaps(scene, atlas, hierarchical);
  b.progressive = bakeLightmaps(scene, atlas, progressive);
  return b;
}

// Area-weighted sums over texels of a luminance, the progressive bake's (a) against the
// hierarchy's (b): their squared difference, the reference's square, and each.
struct Sums {
  double squared = 0.0, reference2 = 0.0, reference = 0.0, hierarchical = 0.0;
  double nrmse() const { return std::sqrt(squared / reference2); }
  void add(double area, double a, double b) {
    squared += area * (a - b) * (a - b), reference2 += area * a * a, reference += area * a, hierarchical += area * b;
  }
};

// Measured at the defaults: the surfaces 4.9% low (floor) to 1.5% high (tall block), texel
// NRMSE 0.060, the hierarchical solver's Cornell error at its defaults (0.064 in `luxel bench
// hierarchical`). These bounds hold that defect where it is (docs/algorithms.md, "Face-cluster
// radiosity"); they are not a tolerance of the method.
TEST(HierarchicalLightmaps, TheCornellBoxAgreesWithTheProgressiveBake) {
  const Scene scene = loadScene("cornell");
  AtlasOptions ao;
  ao.texelsPerMetre = 32.0f / 0.55f;  // 32 texels across a wall
  ao.pageSize = 256;
  const TwoBakes b = bakeBoth(scene, ao);
  const LightmapBake &p = b.progressive, &h = b.hierarchical;
  EXPECT_EQ(h.solution.stats.method, "hierarchical");
  ASSERT_EQ(p.surfaces.surfaces.elements.size(), h.surfaces.surfaces.elements.size());
  const SurfaceSet& set = h.surfaces.surfaces;
  std::map<uint32_t, Sums> perMesh;
  Sums all;
  size_t dark = 0;  // texels the progressive bake lights that are black (a field gone to NaN clamps to zero)
  for (size_t e = 0; e < set.elements.size(); ++e) {
    if (!h.valid[e]) continue;
    const Element& el = set.elements[e];
    const double a = luminance(p.solution.irradiance[e]), c = luminance(h.solution.irradiance[e]);
    perMesh[set.faces[el.face].mesh].add(el.area, a, c);
    all.add(el.area, a, c);
    dark += c <= 0.0 && a > 0.0;
  }
  for (const auto& [mesh, m] : perMesh) {
    const double ratio = m.hierarchical / m.reference;
    std::printf("  %-12s hierarchical / progressive %.4f\n", scene.meshes[mesh].name.c_str(), ratio);
    if (scene.meshes[mesh].name != "light") EXPECT_NEAR(ratio, 1.0, 0.08) << scene.meshes[mesh].name;
  }
  EXPECT_EQ(dark, 0u);
  std::printf("texel NRMSE %.4f\n", all.nrmse());
  EXPECT_LT(all.nrmse(), 0.08);
}

// Sibenik's lightmaps at 5 texels per metre (220k texels): the hierarchical bake against the
// progressive one, texel by texel. Not run by default (the progressive bake takes minutes):
//   build/luxel-tests --gtest_also_run_disabled_tests --gtest_filter='*SibenikAgrees*'
// It prints both solve times, the texel NRMSE of all light and of the interreflected part alone,
// and the ratio of the means (docs/baking.md has the figures).
TEST(HierarchicalLightmaps, DISABLED_SibenikAgreesWithTheProgressiveBake) {
  const Scene scene = loadScene(LUXEL_SOURCE_DIR "/bench/scenes/sibenik.json");
  AtlasOptions ao;
  ao.texelsPerMetre = 5.0f;
  const TwoBakes b = bakeBoth(scene, ao);
  const LightmapBake &p = b.progressive, &h = b.hierarchical;
  const SurfaceSet& set = h.surfaces.surfaces;
  Sums all, interreflected;
  for (size_t e = 0; e < set.elements.size(); ++e) {
    if (!h.valid[e]) continue;
    const double area = set.elements[e].area;
    const double a = luminance(p.solution.irradiance[e]), c = luminance(h.solution.irradiance[e]);
    all.add(area, a, c);
    interreflected.add(area, a - luminance(p.solution.directIrradiance[e]), c - luminance(h.solution.directIrradiance[e]));
  }
  std::printf("%zu texels; solve: hierarchical %.2f s, progressive %.2f s\n", set.elements.size(), h.secondsSolve,
              p.secondsSolve);
  std::printf("texel NRMSE %.4f (interreflected light alone %.4f), mean hierarchical / progressive %.4f\n", all.nrmse(),
              interreflected.nrmse(), all.hierarchical / all.reference);
  EXPECT_LT(all.nrmse(), 0.1);
}

}  // namespace
}  // namespace luxel
