// Saves a scene edited in the viewer as a scene file (docs/scene-format.md) that loads to the same
// scene: the scene it was loaded from as "base", the moved objects' transforms, the lights (all of
// them, replacing the base's), changed materials, and the viewer's camera.
#pragma once

#include <filesystem>
#include <string>

#include "luxel/scene.h"

namespace luxel::viewer {

// The JSON text. `loaded` is the scene as `baseSpec` (a built-in name or an absolute path) loads
// it; `edited` is that scene after the viewer's edits. Throws luxel::Error when an edit cannot be
// written: a moved object whose name is shared by another object (scene files address objects by
// name).
std::string sceneJson(const Scene& edited, const Scene& loaded, const std::string& baseSpec, const Camera& camera);

// Writes sceneJson to `path` atomically (no half-written file on failure).
void writeSceneJson(const std::filesystem::path& path, const Scene& edited, const Scene& loaded,
                    const std::string& baseSpec, const Camera& camera);

}  // namespace luxel::viewer
