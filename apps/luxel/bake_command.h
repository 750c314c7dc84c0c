// `luxel bake SCENE -o OUT.glb [--vertex-colors | --lightmaps [--vertex-colors-for PATTERNS]] [--html]`:
// solves a scene as `luxel render` does and writes its meshes and materials as glTF 2.0 binary,
// with the solution baked in (docs/baking.md), and with --html a page that shows it in a browser.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

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
  float texelsPerMetre = 0.0f;  // 0: --elements texels when given, else luxel::defaultTexelsPerMetre
  int lightmapSize = 0;         // 0: pages sized to their content, up to 1024
  // --directional MODE (with --lightmaps): also where each texel's light comes from, as the
  // LUXEL_lightmap_directional extension (luxel/directional_lightmap.h, docs/baking.md).
  std::string directional = "none";
  // --transfer BANDS (with --lightmaps): SH transfer lightmaps (luxel/transfer_lightmap.h); 0: off.
  int transferBands = 0;
  // --vertex-colors-for PATTERN[,PATTERN...] (with --lightmaps): meshes whose names match a glob
  // get COLOR_0 (irradiance from their texels) instead of a lightmap. Each must match a mesh.
  std::vector<std::string> vertexColorsFor;
  SolveArgs solve;
  int threads = 0;
  bool quiet = false;
  std::string tracePath;  // --progress-trace FILE
  // --html: also OUT.html beside the glb, a self-contained page that shows the bake in a browser
  // (html_page.h). Needs a .glb output and baked light (--lightmaps or --vertex-colors).
  bool html = false;
};

// Everything about the arguments that can be checked without a file: throws Error.
void checkBakeArgs(const BakeArgs& args);
int runBake(const BakeArgs& args);
// Registers --lightmaps, --texels-per-metre, --lightmap-size and --vertex-colors-for on the bake
// subcommand (main.cpp).
void addLightmapOptions(CLI::App& bake, BakeArgs& args);

}  // namespace luxel::cli
