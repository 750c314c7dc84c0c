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
// The text of shader `name` as it is (DIR/name, or the built-in one).
std::string shaderFile(const std::string& name, const std::filesystem::path& overrides);

// The source of shader `name`: DIR/name when `overrides` names a folder holding it, else the
// built-in one, with `defines` ("#define VIEW 0\n") put after its #version line. Throws
// luxel::Error for an unknown name or an unreadable file.
std::string shaderSource(const std::string& name, const std::filesystem::path& overrides, const std::string& defines = {});

}  // namespace luxel::viewer
