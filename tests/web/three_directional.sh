#!/bin/sh
# CTest Web.ThreeDirectionalLightmap: three.js shows directional lightmaps (`luxel bake --lightmaps
# --directional MODE`) as `luxel render --mode lightmap --directional MODE` does, with the
# directional recipe of docs/baking.md, for each mode (tools/three-check/directional_check.mjs).
# Usage: three_directional.sh LUXEL THREE_CHECK_DIR OUT_DIR
# Exit status 77 (CTest's SKIP_RETURN_CODE) when Node.js, Chromium or the npm packages are missing.
luxel=$1 check=$2 out=$3
if ! command -v node >/dev/null 2>&1; then
  echo "directional-check: SKIP: node not found (scripts/install-deps.sh installs it)"
  exit 77
fi
for mode in sh-l1 dominant sh-l2; do
  node "$check/directional_check.mjs" --luxel "$luxel" --out "$out/$mode" --mode "$mode" || exit $?
done
