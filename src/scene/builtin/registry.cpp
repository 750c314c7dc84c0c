// Built-in scenes by name, for `luxel render NAME`.
#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "luxel/error.h"
#include "luxel/import.h"
#include "scene/builtin/builtin_scenes.h"

namespace luxel {

std::vector<std::string> builtinSceneNames() { return {"cornell", "furnace", "cie-5.8"}; }

bool isBuiltinScene(std::string_view name) {
  auto names = builtinSceneNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

Scene builtinScene(std::string_view name) {
  if (name == "cornell") return builtin::cornellBox();
  if (name == "furnace") return builtin::furnace();
  if (name == "cie-5.8") return builtin::cieCube();
  throw Error(fmt::format("unknown built-in scene '{}' (known: {})", name,
                          fmt::join(builtinSceneNames(), ", ")));
}

}  // namespace luxel
