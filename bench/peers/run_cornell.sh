#!/usr/bin/env bash
# luxel beside Blender Cycles on the Cornell box, in one run (`make bench-peer`): renders the
# converged Cycles reference once (4 x 4096 spp, kept in out/peers/ and reused), then luxel and
# Cycles at several settings, and writes the matched-error table to out/peers/table.md.
# Needs `blender` and `python3-numpy` (Debian packages); see bench/peers/README.md.
set -euo pipefail
cd "$(dirname "$0")/../.."
if ! command -v blender >/dev/null; then
  echo "bench-peer: blender is not installed (apt-get install blender python3-numpy)" >&2
  exit 1
fi
out=out/peers
mkdir -p "$out"
threads=${THREADS:-2}
refs=()
for seed in 1 2 3 4; do
  ref="$out/ref_seed$seed.exr"
  if [ ! -s "$ref" ]; then
    blender -b --factory-startup --python bench/peers/cycles_cornell.py -- \
      --spp 4096 --seed "$seed" --out "$ref" --json "$out/ref_seed$seed.json" \
      --threads "$threads" --size 256
  fi
  refs+=("$ref")
done
# Cycles renders are reused when their EXR and timing are there (--reuse); luxel's are always redone.
rm -f "$out"/luxel_*
blender -b --factory-startup --python bench/peers/compare_cornell.py -- \
  --reference "${refs[@]}" --threads "$threads" \
  --cycles-spp 16,64,256,1024,4096 --luxel-modes hq,radiosity \
  --luxel-elements 2500,10000,40000 --luxel-spp 4,16,64 \
  --reuse --images --markdown "$out/table.md"
echo "bench-peer: wrote $out/table.md"
