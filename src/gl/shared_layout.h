// Constants shared by the C++ side and the GLSL side, defined once: the shaders get them as
// #defines from glslPreamble(), so a vertex attribute or binding cannot drift between the two.
#pragma once

#include <string>

#include <fmt/format.h>

namespace luxel::gl {

constexpr int kPositionLocation = 0;  // vec3 world position
constexpr int kItemLocation = 1;      // uint item id (polygon index + 1; 0 is "nothing")

inline std::string glslPreamble() {
  return fmt::format(
      "#version 450 core\n"
      "#define POSITION_LOCATION {}\n"
      "#define ITEM_LOCATION {}\n",
      kPositionLocation, kItemLocation);
}

}  // namespace luxel::gl
