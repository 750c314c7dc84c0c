#!/bin/sh
# CTest Web.ThreeTransferLightmap: three.js relights transfer lightmaps (`luxel bake --lightmaps
# --transfer N`) as `luxel render --mode lightmap --transfer N --sun-direction D` does, with the
# transfer recipe of docs/baking.md, for 2 and 4 bands (tools/three-check/transfer_check.mjs).
# Usage: three_transfer.sh LUXEL THREE_CHECK_DIR OUT_DIR
# Exit status 77 (CTest's SKIP_RETURN_CODE) when Node.js, Chromium or the npm packages are missing.
luxel=$1 check=$2 out=$3
if ! command -v node >/dev/null 2>&1; then
  echo "transfer-check: SKIP: node not found (scripts/install-deps.sh installs it)"
  exit 77
fi
for bands in 2 4; do
  node "$check/transfer_check.mjs" --luxel "$luxel" --out "$out/$bands" --bands "$bands" || exit $?
done
