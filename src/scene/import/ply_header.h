// A PLY file's header against its size, before Assimp reads it: Assimp reserves memory for the
// counts a header declares, so 500 bytes claiming 10^9 vertices took 11.7 GB and never finished.
#pragma once

#include <cstddef>
#include <span>
#include <string>

namespace luxel {

// When `bytes` start as a PLY file ("ply" on its own line), throws Error naming `file` if the
// header is malformed (no end_header, no format, an unknown keyword, format or type) or the
// elements it declares need more bytes than follow it: at least each scalar property's size
// (binary) or two characters a value (ASCII), and a list's count. Anything not PLY is left alone.
void checkPlyCounts(std::span<const std::byte> bytes, const std::string& file);

}  // namespace luxel
