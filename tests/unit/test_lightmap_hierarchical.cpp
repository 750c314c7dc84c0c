// Lightmaps from the face-cluster solver (seed 002): the texels are the faces the hierarchy is
// built over, so a large level's bake clusters its texels instead of making each one a shooter.
// On the Cornell box the baked texels agree with the progressive bake of the same atlas.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "luxel/import.h"
#include "luxel/lightmap.h"

namespace luxel {
namespace {

float luminance(Rgb c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// Measured at the defaults: the surfaces 6.8% low (ceiling) to 1.4% high (tall block), texel
// NRMSE 0.066, the hierarchical solver's Cornell error at its defaults (0.064 in `luxel bench
// hierarchical`). These bounds hold that defect where it is (docs/algorithms.md, "Face-cluster
// radiosity"); they are not a tolerance of the method.
TEST(HierarchicalLightmaps, TheCornellBoxAgreesWithTheProgressiveBake) {
  const Scene scene = loadScene("cornell");
  AtlasOptions ao;
  ao.texelsPerMetre = 32.0f / 0.55f;  // 32 texels across a wall
  ao.pageSize = 256;
  const LightmapAtlas atlas = buildLightmapAtlas(scene, ao);
  LightmapBakeOptions progressive, hierarchical;
  progressive.solve.method = "progressive";
  hierarchical.solve.method = "hierarchical";
  const LightmapBake p = bakeLightmaps(scene, atlas, progressive);
  const LightmapBake h = bakeLightmaps(scene, atlas, hierarchical);
  EXPECT_EQ(h.solution.stats.method, "hierarchical");
  ASSERT_EQ(p.surfaces.surfaces.elements.size(), h.surfaces.surfaces.elements.size());
  const SurfaceSet& set = h.surfaces.surfaces;
  std::map<uint32_t, std::array<double, 3>> perMesh;  // progressive, hierarchical, area
  double squared = 0.0, reference = 0.0, area = 0.0;
  for (size_t e = 0; e < set.elements.size(); ++e) {
    if (!h.valid[e]) continue;
    const Element& el = set.elements[e];
    const double a = luminance(p.solution.irradiance[e]), b = luminance(h.solution.irradiance[e]);
    auto& m = perMesh[set.faces[el.face].mesh];
    m[0] += el.area * a, m[1] += el.area * b, m[2] += el.area;
    squared += el.area * (a - b) * (a - b), reference += el.area * a * a, area += el.area;
  }
  for (const auto& [mesh, m] : perMesh) {
    const double ratio = m[1] / m[0];
    std::printf("  %-12s hierarchical / progressive %.4f\n", scene.meshes[mesh].name.c_str(), ratio);
    if (scene.meshes[mesh].name != "light") EXPECT_NEAR(ratio, 1.0, 0.08) << scene.meshes[mesh].name;
  }
  // No texel the progressive bake lights is black (a field gone to NaN clamps to zero).
  size_t dark = 0;
  for (size_t e = 0; e < set.elements.size(); ++e)
    dark += h.valid[e] && luminance(h.solution.irradiance[e]) <= 0.0f && luminance(p.solution.irradiance[e]) > 0.0f;
  EXPECT_EQ(dark, 0u);
  const double nrmse = std::sqrt(squared / reference);
  std::printf("texel NRMSE %.4f\n", nrmse);
  EXPECT_LT(nrmse, 0.08);
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
  const LightmapAtlas atlas = buildLightmapAtlas(scene, ao);
  LightmapBakeOptions progressive, hierarchical;
  progressive.solve.method = "progressive";
  hierarchical.solve.method = "hierarchical";
  const LightmapBake h = bakeLightmaps(scene, atlas, hierarchical);
  const LightmapBake p = bakeLightmaps(scene, atlas, progressive);
  const SurfaceSet& set = h.surfaces.surfaces;
  double squared = 0.0, reference = 0.0, squaredIndirect = 0.0, referenceIndirect = 0.0, sumP = 0.0, sumH = 0.0;
  for (size_t e = 0; e < set.elements.size(); ++e) {
    if (!h.valid[e]) continue;
    const double area = set.elements[e].area;
    const double a = luminance(p.solution.irradiance[e]), b = luminance(h.solution.irradiance[e]);
    const double ai = a - luminance(p.solution.directIrradiance[e]), bi = b - luminance(h.solution.directIrradiance[e]);
    squared += area * (a - b) * (a - b), reference += area * a * a;
    squaredIndirect += area * (ai - bi) * (ai - bi), referenceIndirect += area * ai * ai;
    sumP += area * a, sumH += area * b;
  }
  const double nrmse = std::sqrt(squared / reference);
  std::printf("%zu texels; solve: hierarchical %.2f s, progressive %.2f s\n", set.elements.size(), h.secondsSolve,
              p.secondsSolve);
  std::printf("texel NRMSE %.4f (interreflected light alone %.4f), mean hierarchical / progressive %.4f\n", nrmse,
              std::sqrt(squaredIndirect / referenceIndirect), sumH / sumP);
  EXPECT_LT(nrmse, 0.1);
}

}  // namespace
}  // namespace luxel
