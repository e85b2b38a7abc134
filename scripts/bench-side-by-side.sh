#!/usr/bin/env bash
# Runs the benchmarks of two builds alternately, so that their figures come from one run on
# the same machine state (for "no slowdown" claims: quote the ratios).
#
#   scripts/bench-side-by-side.sh BEFORE_DIR AFTER_DIR [REPS]
#
# Each DIR holds bench_grid, bench_volume and bench_multigrid binaries (e.g. copies of
# target/release/examples/ from two revisions). Prints each benchmark's key lines per build
# and repetition: bench_grid at 513² and 1025² (multigrid + nested, no plain Picard),
# bench_volume at 65³ (3D multigrid and Bi-CGSTAB), bench_multigrid --quick.
set -euo pipefail
before="${1:?usage: bench-side-by-side.sh BEFORE_DIR AFTER_DIR [REPS]}"
after="${2:?usage: bench-side-by-side.sh BEFORE_DIR AFTER_DIR [REPS]}"
reps="${3:-2}"
cd "$(dirname "$0")/.."
for r in $(seq 1 "$reps"); do
  for side in before after; do
    dir="$before"
    [ "$side" = after ] && dir="$after"
    echo "== $side, repetition $r"
    "$dir/bench_grid" --sizes 513,1025 --no-plain | grep "mg+nested"
    "$dir/bench_volume" 65 | grep "grid_volume"
    "$dir/bench_multigrid" --quick | grep -E "^poisson9|^boundary" | grep -E "V\(1,1\) |F\(1,1\) " || true
  done
done
