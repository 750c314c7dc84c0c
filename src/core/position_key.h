// A point's exact bits as a hash key, for welding corners that lie at exactly the same place
// (faces that share a mesh vertex carry bit-identical copies of it). -0 and +0 are one place.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>

#include "luxel/scene.h"

namespace luxel {

struct PositionKey {
  uint32_t x = 0, y = 0, z = 0;
  bool operator==(const PositionKey&) const = default;
};

inline PositionKey positionKey(Vec3 p) {
  p += Vec3(0.0f);  // -0 + 0 = +0
  return {std::bit_cast<uint32_t>(p.x), std::bit_cast<uint32_t>(p.y), std::bit_cast<uint32_t>(p.z)};
}

struct PositionKeyHash {
  size_t operator()(const PositionKey& k) const {
    return (size_t(k.x) * 0x9E3779B97F4A7C15ull) ^ (size_t(k.y) * 0xC2B2AE3D27D4EB4Full) ^ (size_t(k.z) * 0x165667B19E3779F9ull);
  }
};

}  // namespace luxel
