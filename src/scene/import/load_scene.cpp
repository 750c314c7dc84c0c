// What `luxel render SCENE` accepts: a built-in scene name, a .json scene file, or a mesh file.
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "luxel/error.h"
#include "luxel/import.h"

namespace luxel {
namespace {

// One warning naming the glass that meshes of the scene use (Material::transmittance): luxel lets
// only the lights' direct light through it. Given here, once the whole scene is known, so that a
// scene file that leaves the glass out (/materials/NAME/omit) hears nothing of it.
void warnAboutGlass(Scene& scene) {
  std::vector<uint8_t> used(scene.materials.size(), 0);
  for (const Mesh& m : scene.meshes)
    if (m.material < used.size()) used[m.material] = 1;
  std::vector<std::string> names;
  for (size_t i = 0; i < scene.materials.size(); ++i)
    if (used[i] && scene.materials[i].transmits() &&
        std::find(names.begin(), names.end(), scene.materials[i].name) == names.end())
      names.push_back(scene.materials[i].name);
  if (names.empty()) return;
  const bool many = names.size() > 1;
  scene.warnings.push_back(fmt::format(
      "scene '{}': material{} '{}' let{} light through (glass: OBJ Tf or d, glTF transmission or blending): the "
      "lights' direct light (lamps, suns, skies) passes {}, filtered by {} transmittance, but light from surfaces "
      "(emitting or reflecting) does not, so a room closed by glass gets no light bounced in from outside. Leave such "
      "glass out where all light should pass (a scene file's /materials/NAME/omit)",
      scene.name, many ? "s" : "", fmt::join(names, "', '"), many ? "" : "s", many ? "them" : "it",
      many ? "their" : "its"));
}

}  // namespace

Scene loadScene(std::string_view spec) {
  Scene scene;
  std::filesystem::path path{std::string(spec)};
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  // A built-in name wins over a file of the same name in the working directory: names have no
  // extension, and files to import always do.
  if (isBuiltinScene(spec)) {
    scene = builtinScene(spec);
  } else if (ext == ".json") {
    scene = loadSceneFile(path);
  } else if (ext.empty() && !std::filesystem::exists(path)) {
    // No extension and no such file: most likely a mistyped built-in name.
    throw Error(fmt::format("'{}' is neither a built-in scene ({}) nor a file", spec,
                            fmt::join(builtinSceneNames(), ", ")));
  } else {
    scene = importMeshFile(path);
  }
  scene.validate();
  warnAboutGlass(scene);
  return scene;
}

}  // namespace luxel
