#!/usr/bin/env bash
# Runs every Google Benchmark binary of the package (bench_*), one after the other on one core.
# Usage: run_benchmarks.sh WORKSPACE   (through `make bench`)
set -eo pipefail
ws=$1
found=0
for bench in "$ws"/devel/lib/acc_identification/bench_*; do
  [ -x "$bench" ] || continue
  found=1
  echo "== $(basename "$bench") on $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
  taskset -c 0 "$bench" --benchmark_min_time=0.5
done
[ "$found" -eq 1 ] || { echo "no benchmark built"; exit 1; }
