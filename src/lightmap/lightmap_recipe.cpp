// bakeLightmaps(scene, recipe) (luxel/lightmap.h): the atlas and the bake, with the choices every
// front end makes the same way.
#include <fmt/format.h>

#include "luxel/error.h"
#include "luxel/lightmap.h"

namespace luxel {

AtlasOptions lightmapAtlasOptions(const Scene& scene, const LightmapRecipe& recipe) {
  if (!(recipe.texelsPerMetre >= 0.0f)) throw Error(fmt::format("lightmap density {} must be >= 0", recipe.texelsPerMetre));
  if (recipe.pageSize < 0) throw Error(fmt::format("lightmap page size {} must be >= 0", recipe.pageSize));
  AtlasOptions ao;
  ao.pageSize = recipe.pageSize > 0 ? recipe.pageSize : kMaxDefaultPageSize;
  ao.sizePagesToContent = recipe.pageSize == 0;
  ao.texelsPerMetre = recipe.texelsPerMetre > 0.0f ? recipe.texelsPerMetre
                      : recipe.texelBudget > 0     ? texelsPerMetreForBudget(scene, recipe.texelBudget)
                                                   : defaultTexelsPerMetre(scene);
  return ao;
}

BakedLightmaps bakeLightmaps(const Scene& scene, const LightmapRecipe& recipe, const ProgressCallback& progress) {
  const AtlasOptions ao = lightmapAtlasOptions(scene, recipe);
  validateSolveOptions(recipe.solve);  // before the atlas, which can take a while
  BakedLightmaps out{buildLightmapAtlas(scene, ao), {}};
  LightmapBakeOptions lo;
  lo.solve = recipe.solve;
  lo.dilation = ao.gutter;
  out.bake = bakeLightmaps(scene, out.atlas, lo, progress);
  return out;
}

}  // namespace luxel
