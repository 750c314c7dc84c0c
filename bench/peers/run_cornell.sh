#!/usr/bin/env bash
# luxel beside Blender Cycles on the Cornell box, in one run (`make bench-peer`): for luxel's
# built-in `cornell` and for McGuire's CornellBox-Original.obj (unzipped at build time into
# build/scenes), renders the converged Cycles reference once (4 x 4096 spp, kept in out/peers/ and
# out/peers/mcguire/ and reused), then luxel and Cycles at several settings, and writes the
# matched-error tables to out/peers/table.md and out/peers/mcguire/table.md.
# Needs `blender` and `python3-numpy` (Debian packages); see bench/peers/README.md.
set -euo pipefail
cd "$(dirname "$0")/../.."
if ! command -v blender >/dev/null; then
  echo "bench-peer: blender is not installed (apt-get install blender python3-numpy)" >&2
  exit 1
fi
threads=${THREADS:-2}
mcguire=build/scenes/mcguire-cornell-box/CornellBox-Original.obj

# compare OUTDIR [--obj FILE]
compare() {
  local out=$1
  shift
  mkdir -p "$out"
  local refs=()
  for seed in 1 2 3 4; do
    local ref="$out/ref_seed$seed.exr"
    if [ ! -s "$ref" ]; then
      blender -b --factory-startup --python bench/peers/cycles_cornell.py -- \
        --spp 4096 --seed "$seed" --out "$ref" --json "$out/ref_seed$seed.json" \
        --threads "$threads" --size 256 "$@"
    fi
    refs+=("$ref")
  done
  # Cycles renders are reused when their EXR and timing are there (--reuse); luxel's are always redone.
  rm -f "$out"/luxel_*
  blender -b --factory-startup --python bench/peers/compare_cornell.py -- \
    --reference "${refs[@]}" --threads "$threads" --outdir "$out" "$@" \
    --cycles-spp 16,64,256,1024,4096 --luxel-modes hq,radiosity \
    --luxel-elements 2500,10000,40000 --luxel-spp 4,16,64 \
    --reuse --images --markdown "$out/table.md"
  echo "bench-peer: wrote $out/table.md"
}

compare out/peers
if [ -s "$mcguire" ]; then
  compare out/peers/mcguire --obj "$mcguire"
else
  echo "bench-peer: $mcguire is missing (build first: CMake unzips ../shared/scenes); McGuire's box skipped" >&2
fi
