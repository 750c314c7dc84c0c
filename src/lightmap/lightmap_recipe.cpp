// bakeLightmaps(scene, recipe) (luxel/lightmap.h): the atlas and the bake, with the choices every
// front end makes the same way.
#include <cmath>

#include <fmt/format.h>

#include "luxel/error.h"
#include "luxel/lightmap.h"

namespace luxel {

AtlasOptions lightmapAtlasOptions(const Scene& scene, const LightmapRecipe& recipe) {
  if (!(recipe.texelsPerMetre >= 0.0f) || !std::isfinite(recipe.texelsPerMetre))
    throw Error(fmt::format("lightmap density {} must be finite and >= 0", recipe.texelsPerMetre));
  if (double(recipe.texelBudget) > kMaxLightmapTexels)
    throw Error(fmt::format("lightmap texel budget {} is over the limit of {:g}", recipe.texelBudget, kMaxLightmapTexels));
  if (recipe.pageSize < 0) throw Error(fmt::format("lightmap page size {} must be >= 0", recipe.pageSize));
  AtlasOptions ao;
  ao.pageSize = recipe.pageSize > 0 ? recipe.pageSize : kMaxDefaultPageSize;
  ao.sizePagesToContent = recipe.pageSize == 0;
  ao.givenUvPages = recipe.givenUvPages;
  ao.texelsPerMetre = recipe.texelsPerMetre > 0.0f ? recipe.texelsPerMetre
                      : recipe.texelBudget > 0     ? texelsPerMetreForBudget(scene, recipe.texelBudget)
                                                   : defaultTexelsPerMetre(scene);
  const double area = sceneFaceArea(scene);
  const double texels = area * double(ao.texelsPerMetre) * double(ao.texelsPerMetre);
  if (texels > kMaxLightmapTexels)
    throw Error(fmt::format("scene '{}': {:g} texels per metre over its {:.4g} m2 of faces would make about {:.3g} "
                            "lightmap texels, over the limit of {:g} (~{:.0f} GB to solve); choose at most {:.3g} texels "
                            "per metre",
                            scene.name, ao.texelsPerMetre, area, texels, kMaxLightmapTexels, kMaxLightmapTexels * 300 / 1e9,
                            std::sqrt(kMaxLightmapTexels / area)));
  return ao;
}

BakedLightmaps bakeLightmaps(const Scene& scene, const LightmapRecipe& recipe, const ProgressCallback& progress) {
  const AtlasOptions ao = lightmapAtlasOptions(scene, recipe);
  validateSolveOptions(recipe.solve);  // before the atlas, which can take a while
  BakedLightmaps out{buildLightmapAtlas(scene, ao), {}};
  LightmapBakeOptions lo;
  lo.solve = recipe.solve;
  lo.dilation = ao.gutter;
  lo.directional = recipe.directional;
  out.bake = bakeLightmaps(scene, out.atlas, lo, progress);
  // Shown with the solve's warnings, where every caller already looks.
  auto& warnings = out.bake.solution.stats.warnings;
  warnings.insert(warnings.begin(), out.atlas.warnings.begin(), out.atlas.warnings.end());
  if (recipe.texelsPerMetre <= 0.0f && recipe.texelBudget == 0)
    if (std::string why = defaultDensityWarning(scene); !why.empty()) warnings.insert(warnings.begin(), std::move(why));
  return out;
}

}  // namespace luxel
