// A PLY file's header against its size, before Assimp reads it: Assimp reserves memory for the
// counts a header declares, so 500 bytes claiming 10^9 vertices took 11.7 GB and never finished.
#pragma once

#include <cstddef>
#include <span>
#include <string>

namespace luxel {

// When `bytes` start as a PLY file ("ply" and a header up to "end_header"), throws Error naming
// `file` if the elements the header declares need more bytes than follow it: at least each scalar
// property's size (binary) or two characters a value (ASCII), and a list's count. Anything else
// (not PLY, a header Assimp will reject anyway) is left to Assimp.
void checkPlyCounts(std::span<const std::byte> bytes, const std::string& file);

}  // namespace luxel
