// `luxel bake SCENE -o OUT.glb [--vertex-colors]`: solves a scene as `luxel render` does and
// writes its meshes and materials as glTF 2.0 binary, with the solution baked in (docs/baking.md).
#pragma once

#include <cstddef>
#include <string>

namespace luxel::cli {

struct BakeArgs {
  std::string scene;
  std::string output;
  bool vertexColors = false;
  std::string solver = "progressive";
  size_t elements = 0;
  float elementSize = 0.0f;
  double unshot = 1e-3;
  size_t refine = 0;
  int threads = 0;
  bool quiet = false;
};

int runBake(const BakeArgs& args);

}  // namespace luxel::cli
