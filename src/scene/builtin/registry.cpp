// Built-in scenes by name, for `luxel render NAME`.
#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "luxel/error.h"
#include "luxel/import.h"
#include "scene/builtin/builtin_scenes.h"

namespace luxel {

std::vector<std::string> builtinSceneNames() {
  std::vector<std::string> names = {"cornell",          "furnace",          "cie-5.8",
                                    "cornell-large",    "cornell-small",    "cornell-low",
                                    "indirect-light",   "shader-box-774",   "shader-box-2734",
                                    "shader-box-10254", "shader-box-15814", "shader-sphere-torus"};
  for (const builtin::RoomRung& r : builtin::kRoomLadder) names.push_back(r.name);
  return names;
}

bool isBuiltinScene(std::string_view name) {
  auto names = builtinSceneNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

Scene builtinScene(std::string_view name) {
  if (name == "cornell") return builtin::cornellBox();
  if (name == "furnace") return builtin::furnace();
  if (name == "cie-5.8") return builtin::cieCube();
  // The seed papers' test scenes (docs/seed-scenes.md).
  if (name == "cornell-large") return builtin::cornellLarge();
  if (name == "cornell-small") return builtin::cornellSmall();
  if (name == "cornell-low") return builtin::cornellLow();
  if (name == "indirect-light") return builtin::indirectLight();
  if (name == "shader-box-774") return builtin::shaderBox(10);
  if (name == "shader-box-2734") return builtin::shaderBox(20);
  if (name == "shader-box-10254") return builtin::shaderBox(40);
  if (name == "shader-box-15814") return builtin::shaderBox(50);
  if (name == "shader-sphere-torus") return builtin::shaderSphereTorus();
  // Seed 002's room, a ladder of face counts.
  for (const builtin::RoomRung& r : builtin::kRoomLadder)
    if (name == r.name) return builtin::faceClusterRoom(r.faces);
  throw Error(fmt::format("unknown built-in scene '{}' (known: {})", name,
                          fmt::join(builtinSceneNames(), ", ")));
}

}  // namespace luxel
