#!/usr/bin/env bash
# The accuracy-vs-cost benchmark (issue 7) with one command.
#   scripts/bench.sh [OUT_DIR [bench_accuracy options...]]
# Builds bench/bench_accuracy in build-bench (Release flags of the project,
# RelWithDebInfo) and runs it on one core (OPENBLAS_NUM_THREADS=1): prints
# the tables (hunter, fig05, fig10, rubber, linsol, defaults, targets) and
# writes OUT_DIR/accuracy.csv, cost_vs_n.csv, prony_fits.csv, defaults.csv,
# reference-<scene>.csv and pareto-{fig05,fig10,rubber}.svg (default OUT_DIR:
# bench-out). About 6 minutes on a 2-core Xeon; "--quick" checks the program
# in ~40 s, "--only targets" runs the issue's speed targets (61-point fig05
# curves at the shipped defaults, uniform N 512 and the old uniform N 768).
# See bench/README.md.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-bench-out}
[ $# -gt 0 ] && shift
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVL_BENCH=ON >/dev/null
cmake --build build-bench -j "$jobs" --target bench_accuracy
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
exec build-bench/bench/bench_accuracy --out "$out" "$@"
