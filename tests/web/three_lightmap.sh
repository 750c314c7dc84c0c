#!/bin/sh
# CTest Web.ThreeLightmap: three.js shows the lightmaps `luxel bake --lightmaps` writes as
# `luxel render --mode lightmap` does, with the recipe of docs/baking.md (tools/three-check/check.mjs).
# Usage: three_lightmap.sh LUXEL THREE_CHECK_DIR OUT_DIR
# Exit status 77 (CTest's SKIP_RETURN_CODE) when Node.js, Chromium or the npm packages are missing.
luxel=$1 check=$2 out=$3
if ! command -v node >/dev/null 2>&1; then
  echo "three-check: SKIP: node not found (scripts/install-deps.sh installs it)"
  exit 77
fi
exec node "$check/check.mjs" --luxel "$luxel" --out "$out"
