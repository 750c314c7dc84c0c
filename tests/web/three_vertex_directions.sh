#!/bin/sh
# CTest Web.ThreeVertexDirections: three.js shows directions per vertex (`luxel bake --vertex-colors
# --directional MODE`, LUXEL_vertex_directional) under a normal map as `luxel render --mode
# lightmap --directional MODE` shows the same light, with docs/baking.md's vertex recipe, for each
# mode (tools/three-check/directional_check.mjs --vertex 1), and the same for irradiance vertex colours
# beside lightmaps (`--lightmaps --vertex-colors-for`, --vertex 2).
# Usage: three_vertex_directions.sh LUXEL THREE_CHECK_DIR OUT_DIR
# Exit status 77 (CTest's SKIP_RETURN_CODE) when Node.js, Chromium or the npm packages are missing.
luxel=$1 check=$2 out=$3
if ! command -v node >/dev/null 2>&1; then
  echo "directional-check: SKIP: node not found (scripts/install-deps.sh installs it)"
  exit 77
fi
for mode in sh-l1 dominant sh-l2; do
  node "$check/directional_check.mjs" --luxel "$luxel" --out "$out/$mode" --mode "$mode" --vertex 1 || exit $?
  # Irradiance vertex colours beside lightmaps (--vertex-colors-for) with their directions.
  node "$check/directional_check.mjs" --luxel "$luxel" --out "$out/for-$mode" --mode "$mode" --vertex 2 || exit $?
done
