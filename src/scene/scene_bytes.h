// A Scene as bytes and back, field for field: how an import run in a child process hands its
// scene to the parent (scene/import/child_process_import.h). Not a file format: both ends are the
// same build of luxel, so nothing is versioned.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "luxel/scene.h"

namespace luxel {

std::vector<std::byte> sceneBytes(const Scene& scene);
// Throws Error when the bytes end early or run on (they did not come from sceneBytes).
Scene sceneFromBytes(std::span<const std::byte> bytes);

}  // namespace luxel
