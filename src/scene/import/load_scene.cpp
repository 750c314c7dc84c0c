// What `luxel render SCENE` accepts: a built-in scene name, a .json scene file, or a mesh file.
#include <algorithm>
#include <cctype>
#include <filesystem>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "luxel/error.h"
#include "luxel/import.h"

namespace luxel {

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
  return scene;
}

}  // namespace luxel
