#!/bin/bash
# luxel against Blender Cycles on seed 002's room at 1.5M faces (issue 14): luxel bakes the scene
# to a glb that Cycles renders (its geometry, camera and materials), two converged Cycles renders
# are the reference, and compare_glb.py times both renderers to the same error against it.
# About 25 minutes on 2 cores the first time (the reference: 2 x 2048 spp of about 9 minutes each);
# the reference and the glb are kept in out/peers/room and reused.
set -euo pipefail
cd "$(dirname "$0")/../.."
if ! command -v blender >/dev/null; then
  echo "bench-peer-room: blender is not installed (apt-get install blender python3-numpy)" >&2
  exit 1
fi
threads=${THREADS:-2}
scene=${SCENE:-room-1.5m}
out=out/peers/room
mkdir -p "$out"
glb="$out/$scene.glb"
[ -s "$glb" ] || ./build/luxel bake "$scene" -o "$glb" -q
refs=()
for seed in 1 2; do
  ref="$out/ref_seed$seed.exr"
  if [ ! -s "$ref" ]; then
    blender -b --factory-startup --python bench/peers/cycles_cornell.py -- --glb "$glb" \
      --spp 2048 --seed "$seed" --out "$ref" --json "$out/ref_seed$seed.json" --threads "$threads" --size 256
  fi
  refs+=("$ref")
done
blender -b --factory-startup --python bench/peers/compare_glb.py -- --scene "$scene" --glb "$glb" \
  --reference "${refs[@]}" --threads "$threads" --outdir "$out" --cycles-spp 4,16,64,256 \
  --luxel-spp 16 --luxel-extra "${LUXEL_EXTRA:-}" --reuse --markdown "$out/table.md"
echo "bench-peer-room: wrote $out/table.md"
