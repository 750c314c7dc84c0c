// What Assimp 5.2 silently repairs in an OBJ file, checked before it reads it: a face corner whose
// texture coordinate or normal index is past the end is imported with whatever lies there, a
// missing mtllib or an undefined usemtl leaves faces grey and dark with only a log line. A scene
// whose light went that way renders black with exit 0.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "luxel/resources.h"

namespace luxel {

// When `bytes` are an OBJ file, throws Error naming `file` and the line when a face refers to a
// vertex, texture coordinate or normal that is 0 or not defined before it (OBJ indices count from
// 1; negative ones count back from the last defined). Returns warnings, each naming `file`, for an
// mtllib that `resources` does not have and for a usemtl naming a material no mtllib defines.
std::vector<std::string> checkObjReferences(std::span<const std::byte> bytes,
                                            const ResourceReader& resources, const std::string& file);

}  // namespace luxel
