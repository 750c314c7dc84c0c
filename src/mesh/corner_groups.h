// Which elements meet at each element corner, on the same smooth surface: same material and normals
// within a crease angle. Vertex interpolation averages over these groups, and adaptive refinement
// compares neighbours through them, so neither bleeds across creases or material boundaries.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "luxel/surface.h"

namespace luxel {

class CornerGroups {
 public:
  // `creaseCosine`: elements whose normals' dot product is below this are on different surfaces.
  CornerGroups(const SurfaceSet& surfaces, float creaseCosine);

  // The elements sharing corner `corner` of element `element` (the element itself included).
  std::span<const uint32_t> at(uint32_t element, int corner) const {
    size_t slot = size_t(element) * 4 + size_t(corner);
    return {members_.data() + offsets_[slot], members_.data() + offsets_[slot + 1]};
  }

 private:
  std::vector<uint32_t> offsets_;  // 4 slots per element, CSR into members_
  std::vector<uint32_t> members_;
};

// Default crease: 30 degrees.
constexpr float kDefaultCreaseCosine = 0.8660254f;

}  // namespace luxel
