#!/usr/bin/env bash
# The two set-up commands of the README.
#   scripts/dev.sh run    install what is missing, build, run the main job
#   scripts/dev.sh test   install what is missing, build, run all tests, then
#                         rebuild and rerun them under ASan + UBSan, then
#                         fuzz every reader (scripts/fuzz.sh, 20 s a target)
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
scripts/install-deps.sh

build() { # dir, extra cmake args...
  local dir=$1; shift
  cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVL_WERROR=ON "$@" >/dev/null
  cmake --build "$dir" -j "$jobs"
}

case "${1:-}" in
  run)
    build build
    # The main job on the embedded default database (created on first use):
    # the wet Stribeck curve of the seed's Fig. 5, written to out/fig05/.
    build/viscolube compound list
    exec build/viscolube run cases/fig05.ini --out out/fig05
    ;;
  test)
    # ctest runs tests in parallel on the cores: one BLAS thread per test
    export OPENBLAS_NUM_THREADS=1
    build build
    ctest --test-dir build --output-on-failure -j "$jobs"
    build build-asan -DVL_SANITIZE=ON
    ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
      ctest --test-dir build-asan --output-on-failure -j "$jobs"
    # libFuzzer on every reader (tests/fuzz, clang, build-fuzz): each target
    # for VL_FUZZ_SECONDS (default 20) over its corpus; see scripts/fuzz.sh.
    scripts/fuzz.sh "${VL_FUZZ_SECONDS:-20}"
    ;;
  *)
    echo "usage: scripts/dev.sh run|test" >&2
    exit 2
    ;;
esac
