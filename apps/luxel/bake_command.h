// `luxel bake SCENE -o OUT.glb [--vertex-colors]`: solves a scene as `luxel render` does and
// writes its meshes and materials as glTF 2.0 binary, with the solution baked in (docs/baking.md).
#pragma once

#include <cstddef>
#include <string>

#include <CLI/CLI.hpp>

#include "solve_args.h"

namespace luxel::cli {

struct BakeArgs {
  std::string scene;
  std::string output;
  bool vertexColors = false;
  // --lightmaps: bake texels as elements (docs/lightmaps.md) and write TEXCOORD_1, the pages as RGBM
  // PNGs in the glb and as float EXR files beside it (OUT.lightmapN.exr).
  bool lightmaps = false;
  float texelsPerMetre = 0.0f;  // 0: about as many texels as the element budget
  int lightmapSize = 1024;
  SolveArgs solve;
  int threads = 0;
  bool quiet = false;
};

int runBake(const BakeArgs& args);
// Registers --lightmaps, --texels-per-metre and --lightmap-size on the bake subcommand (main.cpp).
void addLightmapOptions(CLI::App& bake, BakeArgs& args);

}  // namespace luxel::cli
