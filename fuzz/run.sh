#!/usr/bin/env bash
# Runs every libFuzzer harness of a LUXEL_FUZZ build for SECONDS each (default 60), from a corpus
# of fuzz/seeds plus the shared scenes' small files, and fails on the first crash, leak, hang or
# out-of-memory. Usage: fuzz/run.sh BUILD_DIR [SECONDS]. Corpora grow in BUILD_DIR/fuzz-corpus;
# crashing inputs are written to BUILD_DIR/fuzz-artifacts (docs/fuzzing.md says how to replay them).
set -euo pipefail
build=$1
seconds=${2:-60}
here=$(cd "$(dirname "$0")" && pwd)
scenes="$build/scenes"
corpus="$build/fuzz-corpus"
artifacts="$build/fuzz-artifacts"
mkdir -p "$artifacts"

seed() {  # seed HARNESS FILES...: copy small files (<= 64 KiB) into the harness's corpus
  local dir="$corpus/$1"
  shift
  mkdir -p "$dir"
  for f in "$@"; do
    [ -f "$f" ] && [ "$(stat -c %s "$f")" -le 65536 ] && cp "$f" "$dir/" || true
  done
}
seed fuzz-mesh-obj "$here"/seeds/obj/* "$scenes"/mcguire-cornell-box/*.obj
seed fuzz-mesh-gltf "$here"/seeds/gltf/*
seed fuzz-mesh-glb "$here"/seeds/glb/* "$build"/test-tmp/*.glb
seed fuzz-mesh-ply "$here"/seeds/ply/*
seed fuzz-mesh-dae "$here"/seeds/dae/*
seed fuzz-mesh-fbx "$build"/test-tmp/import/*/*.fbx
seed fuzz-scene-json "$here"/seeds/scene-json/*
seed fuzz-texture "$here"/seeds/texture/*
seed fuzz-cli "$here"/seeds/cli/*

status=0
for harness in fuzz-mesh-obj fuzz-mesh-gltf fuzz-mesh-glb fuzz-mesh-ply fuzz-mesh-dae fuzz-mesh-fbx fuzz-scene-json fuzz-texture fuzz-cli; do
  mkdir -p "$corpus/$harness"
  echo "fuzz: $harness for ${seconds}s"
  # A dictionary of the input's words, where one exists (fuzz/cli.dict: options and values).
  dict=()
  [ -f "$here/${harness#fuzz-}.dict" ] && dict=(-dict="$here/${harness#fuzz-}.dict")
  # -rss_limit_mb: a memory bomb is a finding. -timeout: so is an input that takes 10 s.
  if ! ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions="$here/lsan.supp" \
      UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
      "$build/$harness" "$corpus/$harness" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
      -max_len=65536 "${dict[@]}" -artifact_prefix="$artifacts/$harness-" -print_final_stats=1 2>"$build/$harness.log"; then
    echo "fuzz: $harness FAILED; see $build/$harness.log and $artifacts" >&2
    tail -30 "$build/$harness.log" >&2
    status=1
  fi
  grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$build/$harness.log" | sed "s/^/  /" || true
done
exit $status
