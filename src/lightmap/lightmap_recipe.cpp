// bakeLightmaps(scene, recipe) (luxel/lightmap.h): the atlas and the bake, with the choices every
// front end makes the same way.
#include <fmt/format.h>

#include "luxel/error.h"
#include "luxel/lightmap.h"

namespace luxel {

BakedLightmaps bakeLightmaps(const Scene& scene, const LightmapRecipe& recipe, const ProgressCallback& progress) {
  if (!(recipe.texelsPerMetre >= 0.0f)) throw Error(fmt::format("lightmap density {} must be >= 0", recipe.texelsPerMetre));
  validateSolveOptions(recipe.solve);  // before the atlas, which can take a while
  AtlasOptions ao;
  ao.pageSize = recipe.pageSize;
  ao.texelsPerMetre = recipe.texelsPerMetre > 0.0f ? recipe.texelsPerMetre
                                                   : texelsPerMetreForBudget(scene, recipe.texelBudget > 0 ? recipe.texelBudget : 10000);
  BakedLightmaps out{buildLightmapAtlas(scene, ao), {}};
  LightmapBakeOptions lo;
  lo.solve = recipe.solve;
  lo.dilation = ao.gutter;
  out.bake = bakeLightmaps(scene, out.atlas, lo, progress);
  return out;
}

}  // namespace luxel
