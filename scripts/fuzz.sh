#!/usr/bin/env bash
# Fuzzes every reader with libFuzzer (clang, ASan + UBSan + leak checks).
#   scripts/fuzz.sh [SECONDS [TARGET...]]
# Builds the targets of tests/fuzz in build-fuzz (cmake -DVL_FUZZ=ON) and runs
# each for SECONDS (default $VL_FUZZ_SECONDS, else 60) over its seed corpus
# tests/fuzz/corpus/<target> (read only; new inputs go to
# build-fuzz/fuzz-corpus/<target>). Fails on any crash, sanitizer report,
# leak, hang (-timeout) or memory blow-up (-rss_limit_mb); the input is saved
# in build-fuzz/fuzz-artifacts/ (replay: build-fuzz/tests/fuzz/TARGET FILE).
# Prints the executions per target.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
seconds=${1:-${VL_FUZZ_SECONDS:-60}}
[ $# -gt 0 ] && shift
jobs=$(nproc 2>/dev/null || echo 2)
build=$root/build-fuzz

cmake -S . -B "$build" -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVL_FUZZ=ON \
  -DBUILD_TESTING=OFF -DVL_WERROR=OFF >/dev/null
cmake --build "$build" -j "$jobs" --target vl_fuzz_targets >/dev/null

targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for src in tests/fuzz/fuzz_*.c; do targets+=("$(basename "$src" .c)"); done
fi

mkdir -p "$build/fuzz-artifacts"
failed=0
for t in "${targets[@]}"; do
  seeds=$root/tests/fuzz/corpus/$t
  work=$build/fuzz-corpus/$t
  log=$build/fuzz-artifacts/$t.log
  mkdir -p "$work"
  args=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024
        -detect_leaks=1 -print_final_stats=1 -artifact_prefix="$build/fuzz-artifacts/$t-")
  [ -f "tests/fuzz/$t.dict" ] && args+=(-dict="$root/tests/fuzz/$t.dict")
  # the command-line target prints like the program: keep its output away
  [ "$t" = fuzz_cli ] && args+=(-close_fd_mask=3)
  if ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 \
     UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
     OPENBLAS_NUM_THREADS=1 "$build/tests/fuzz/$t" "${args[@]}" "$work" "$seeds" >"$log" 2>&1; then
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
    cov=$(grep -a -o 'cov: [0-9]*' "$log" | tail -1 || true)
    echo "fuzz $t: ok, ${execs:-?} executions in ${seconds} s, ${cov:-cov: ?}"
  else
    failed=1
    echo "fuzz $t: FAILED (log: $log)" >&2
    grep -a -E -A30 'ERROR|FUZZ CHECK|deadly signal|timeout|leak' "$log" | head -60 >&2 ||
      tail -40 "$log" >&2
  fi
done
exit $failed
