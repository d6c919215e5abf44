#!/usr/bin/env bash
# Runs every Google Benchmark program of the build (make bench). Figures go into BENCHMARKS.md
# by hand, with the machine they were taken on.
set -euo pipefail
build_dir=${1:-build}
found=0
for bench in "$build_dir"/bench/*/*_bench; do
  [ -x "$bench" ] || continue
  found=1
  echo "== $(basename "$bench")"
  "$bench" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true "${@:2}"
done
if [ "$found" -eq 0 ]; then
  echo "run-benchmarks: no benchmark programs under $build_dir/bench; run make build first" >&2
  exit 1
fi
