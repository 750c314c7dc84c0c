#!/usr/bin/env bash
# A short, seeded run of the harnesses over luxel's own parsers (scene JSON, textures, the command
# line) for CI: it keeps the fuzzing build compiling and catches a parser that now crashes on its
# seeds or their first mutations. The mesh harnesses are left out: they find defects of Debian's
# Assimp within seconds (docs/hostile-inputs.md), which luxel contains by importing in a child
# process but which would turn CI red on a third party's code. Usage: fuzz/smoke.sh BUILD_DIR.
set -euo pipefail
build=$1
here=$(cd "$(dirname "$0")" && pwd)
status=0
for pair in fuzz-scene-json:scene-json fuzz-texture:texture fuzz-cli:cli; do
  harness=${pair%%:*} seeds=${pair#*:}
  corpus=$(mktemp -d)
  cp "$here/seeds/$seeds"/* "$corpus/"
  dict=()
  [ -f "$here/$seeds.dict" ] && dict=(-dict="$here/$seeds.dict")
  echo "fuzz-smoke: $harness"
  # A fixed seed and run count: the same inputs on every machine, unless the time cap ends it early.
  if ! ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions="$here/lsan.supp" \
      UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
      "$build/$harness" "$corpus" "${dict[@]}" -seed=1 -runs=20000 -max_total_time=60 -timeout=30 \
      -rss_limit_mb=2048 -max_len=16384 -artifact_prefix="$build/smoke-$harness-" 2>"$build/smoke-$harness.log"; then
    echo "fuzz-smoke: $harness FAILED" >&2
    tail -40 "$build/smoke-$harness.log" >&2
    status=1
  fi
  grep -E "^Done [0-9]+ runs|stat::number_of_executed_units" "$build/smoke-$harness.log" | sed "s/^/  /" || true
  rm -rf "$corpus"
done
exit $status
