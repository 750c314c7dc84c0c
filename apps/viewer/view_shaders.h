// The viewer's shaders by name; a folder given with `luxel view --shaders DIR` replaces any of them
// with a file of the same name (scene.frag, tone.frag, ...), read again by `shaders.reload`.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace luxel::viewer {

struct ShaderSource {
  const char* name;
  const char* text;
};

const std::vector<ShaderSource>& builtinShaders();

// The source of shader `name`: DIR/name when `overrides` names a folder holding it, else the
// built-in one. Throws luxel::Error for an unknown name or an unreadable file.
std::string shaderSource(const std::string& name, const std::filesystem::path& overrides);

}  // namespace luxel::viewer
