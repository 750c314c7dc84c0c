// Constants shared by the C++ side and the GLSL side, defined once: the shaders get them as
// #defines from glslPreamble(), so a vertex attribute or binding cannot drift between the two.
#pragma once

#include <string>

#include <fmt/format.h>

namespace luxel::gl {

constexpr int kPositionLocation = 0;  // vec3 world position
constexpr int kItemLocation = 1;      // uint item id (polygon index + 1; 0 is "nothing")

// The hemicube integration pass (hemicube.cpp): shader storage bindings, the texture unit of the
// five-layer item texture, and the work-group edge.
constexpr int kDeltaBinding = 0;    // uint[]: fixed-point delta form factors, top then side table
constexpr int kItemSumBinding = 1;  // uint[]: per item, the fixed-point sum of its pixels' deltas
constexpr int kItemTextureUnit = 0;
constexpr int kIntegrateGroup = 8;  // 8 x 8 = 64 pixel rows per work group
// Fixed point of the sums: one unit is 2^-31. A hemicube's deltas sum to 1 = 2^31 units, so no
// item's sum can overflow a uint; each pixel's delta is rounded once, on the CPU (at most 2^-32
// off), so a sum over N pixels is within N 2^-32 of the float sum (2.9e-6 for all 12,288 pixels
// of a 64-pixel hemicube, 4.6e-5 at 256), and in practice far closer since the roundings cancel.
constexpr double kFixedPointScale = 2147483648.0;

inline std::string glslPreamble() {
  return fmt::format(
      "#version 450 core\n"
      "#define POSITION_LOCATION {}\n"
      "#define ITEM_LOCATION {}\n"
      "#define DELTA_BINDING {}\n"
      "#define ITEM_SUM_BINDING {}\n"
      "#define ITEM_TEXTURE_UNIT {}\n"
      "#define INTEGRATE_GROUP {}\n",
      kPositionLocation, kItemLocation, kDeltaBinding, kItemSumBinding, kItemTextureUnit, kIntegrateGroup);
}

}  // namespace luxel::gl
