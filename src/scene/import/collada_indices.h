// A COLLADA <p> (the index list of <triangles>, <polylist>, <polygons>) with a negative index:
// Assimp 5.2 reads it as a huge unsigned number and wraps it to some other vertex, so the face
// is imported in the wrong place with exit 0. Checked on the text before Assimp reads it.
#pragma once

#include <cstddef>
#include <span>
#include <string>

namespace luxel {

// Throws Error naming `file`, the line and the value when a <p> element holds a negative or
// non-numeric index. Anything without <p> elements is left alone.
void checkColladaIndices(std::span<const std::byte> bytes, const std::string& file);

}  // namespace luxel
