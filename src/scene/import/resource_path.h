// How the loaders spell the paths they ask a ResourceReader for (see luxel/resources.h).
#pragma once

#include <string>
#include <string_view>

namespace luxel {

// '/' separators (models authored on Windows write '\'), lexically normal, no trailing '/'.
// "" and "." both mean the main file's folder and come back as "".
std::string normalizeResourcePath(std::string_view path);

// The folder part of a normalised path: "a/b.png" -> "a", "b.png" -> "".
std::string resourceFolder(std::string_view path);

}  // namespace luxel
