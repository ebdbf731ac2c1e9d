#!/usr/bin/env bash
# Runs every benchmark binary in the build folder, printing JSON per program.
set -euo pipefail
build=${1:-build}
for b in "$build"/bench/bench_*; do
  [ -x "$b" ] || continue
  echo "== $(basename "$b")" >&2
  "$b" --benchmark_format=json
done
