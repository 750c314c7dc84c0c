// `luxel bake SCENE -o OUT.glb [--vertex-colors]`: solves a scene as `luxel render` does and
// writes its meshes and materials as glTF 2.0 binary, with the solution baked in (docs/baking.md).
#pragma once

#include <cstddef>
#include <string>

#include "solve_args.h"

namespace luxel::cli {

struct BakeArgs {
  std::string scene;
  std::string output;
  bool vertexColors = false;
  SolveArgs solve;
  int threads = 0;
  bool quiet = false;
};

int runBake(const BakeArgs& args);

}  // namespace luxel::cli
