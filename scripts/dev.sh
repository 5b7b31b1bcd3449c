#!/usr/bin/env bash
# The two set-up commands of the README.
#   scripts/dev.sh run    install what is missing, build, run the main job
#   scripts/dev.sh test   install what is missing, build, run all tests, then
#                         rebuild and rerun them under ASan + UBSan, then
#                         fuzz every reader (scripts/fuzz.sh, 20 s a target);
#                         first of all, the format check (scripts/format.sh --check)
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
scripts/install-deps.sh

configure() { # dir, extra cmake args...
  local dir=$1; shift
  cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVL_WERROR=ON "$@" >/dev/null
}

build() { # dir, extra cmake args...: everything (library, program, tests, benchmarks)
  configure "$@"
  cmake --build "$1" -j "$jobs"
}

case "${1:-}" in
  run)
    # the program alone: the tests, fuzz targets and benchmarks wait for `test`
    configure build
    cmake --build build -j "$jobs" --target viscolube_cli
    # the Python package (python/, target vl_python_core), built for the
    # interpreter CMake found with NumPy (/usr/bin/python3 first: the python3
    # on PATH may lack NumPy), and checked to import with that interpreter
    py=$(sed -n 's/^VL_PYTHON_INTERPRETER:INTERNAL=//p' build/CMakeCache.txt)
    if [ -n "$py" ]; then
      cmake --build build -j "$jobs" --target vl_python_core
      PYTHONPATH=build/python "$py" -c 'import viscolube' ||
        { echo "dev.sh: 'import viscolube' failed with $py (PYTHONPATH=build/python)" >&2; exit 1; }
      echo "Python package: PYTHONPATH=$PWD/build/python $py -c 'import viscolube'"
    else
      echo "Python package not built: no Python 3 with headers and NumPy (see cmake's message)" >&2
    fi
    # The main job on the embedded default database (created on first use):
    # filled against unfilled rubber in water (the seed's Figs. 15-17), with
    # the Stribeck curves side by side and figures in out/compare/.
    build/viscolube compound list
    exec build/viscolube compare --compounds sbr-unfilled,sbr-filled --surface paper-0.5um \
      --fluid water --from 1e-12 --to 0.1 --points 45 --plot \
      --out out/compare
    ;;
  test)
    # ctest runs tests in parallel on the cores: one BLAS thread per test
    export OPENBLAS_NUM_THREADS=1
    # the sources in the style of .clang-format (scripts/format.sh reformats)
    scripts/format.sh --check
    build build
    ctest --test-dir build --output-on-failure -j "$jobs"
    build build-asan -DVL_SANITIZE=ON
    # under the sanitizers every label but `hard`: the hard-case matrix is the
    # same solver code as the validation and unit tests, run for minutes of
    # Newton iterations (780 of the sanitizer run's 1550 CPU-seconds); it
    # runs in the normal build above
    ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
      ctest --test-dir build-asan --output-on-failure -j "$jobs" -LE hard
    # libFuzzer on every reader (tests/fuzz, clang, build-fuzz): each target
    # for VL_FUZZ_SECONDS (default 20) over its corpus; see scripts/fuzz.sh.
    scripts/fuzz.sh "${VL_FUZZ_SECONDS:-20}"
    ;;
  *)
    echo "usage: scripts/dev.sh run|test" >&2
    exit 2
    ;;
esac
