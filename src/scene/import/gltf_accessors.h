// What Assimp 5.2 silently repairs in a glTF 2.0 file's accessors, checked before it reads them:
// it drops faces whose indices are out of range (a log line, exit 0, geometry gone), and reads
// POSITION data of a non-float type, or through an illegal byteStride, as floats (garbage
// vertices). Specification: https://registry.khronos.org/glTF/specs/2.0/glTF-2.0.html, 3.6.
#pragma once

#include <cstddef>
#include <span>
#include <string>

#include "luxel/resources.h"

namespace luxel {

// When `bytes` are glTF 2.0 (JSON, or a GLB's JSON chunk), throws Error naming `file` and the
// mesh, primitive, accessor or bufferView when:
//  - a bufferView's byteStride is outside 4..252, not a multiple of 4, or below the size of an
//    element of an accessor that reads through it;
//  - a POSITION accessor is not FLOAT (5126) without KHR_mesh_quantization in extensionsRequired;
//  - an index is not below the count of the primitive's POSITION accessor.
// Index data is read from data: URIs, the GLB's binary chunk, or `resources`; a buffer that
// cannot be found is left to Assimp, which names it. Anything not glTF 2.0 JSON is left alone.
void checkGltfAccessors(std::span<const std::byte> bytes, const ResourceReader& resources,
                        const std::string& file);

}  // namespace luxel
