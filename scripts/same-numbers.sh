#!/usr/bin/env bash
# Runs every shipped scene, `friction --json` at four speeds, a `compare` and the
# example study with one program and leaves the outputs in DIR, so that two builds
# can be compared number for number (a refactoring must not change them):
#   scripts/same-numbers.sh PROGRAM DIR        e.g. build/viscolube /tmp/new
#   diff -r /tmp/old /tmp/new                  (run.json and timings excluded)
# The database is a fresh one in DIR, made from the program's embedded materials.
set -euo pipefail
prog=$(realpath "$1"); out=$2
cd "$(dirname "$0")/.."
rm -rf "$out"; mkdir -p "$out"
export VISCOLUBE_DB="$out/materials.db" OPENBLAS_NUM_THREADS=1
for scene in cases/*.ini; do
  name=$(basename "$scene" .ini)
  "$prog" run "$scene" --out "$out/run-$name" --json --quiet > "$out/run-$name.json" || echo "exit $? $name" >> "$out/status"
done
for v in 1e-6 1e-4 1e-2 1; do
  "$prog" friction --compound sbr-unfilled --surface paper-0.5um --fluid water --speed $v --json \
    > "$out/friction-$v.json" || echo "exit $? friction $v" >> "$out/status"
done
"$prog" compare --compounds sbr-unfilled,sbr-filled --surface paper-0.5um --fluid water \
  --from 1e-12 --to 0.1 --points 45 --out "$out/compare" --quiet > "$out/compare.txt" || echo "exit $? compare" >> "$out/status"
"$prog" study studies/example.ini --out "$out/study" --quiet > "$out/study.txt" || echo "exit $? study" >> "$out/status"
# what differs from run to run: the manifests, times and the database file
find "$out" \( -name run.json -o -name materials.db -o -name 'tasks.csv' \) -delete
find "$out" -type f \( -name '*.json' -o -name '*.csv' -o -name '*.txt' \) -print0 |
  xargs -0 sed -i -E -e "s|$out|OUT|g" -e 's/seconds [0-9.e+-]+/seconds X/g' -e 's/[0-9.]+ s for ([0-9]+) tasks: [0-9.]+ tasks.s/X s for \1 tasks/' \
    -e 's/"(seconds|elapsed_s|time_s|started|ended|[a-z_]*seconds)": *[^,}]*/"\1": X/g'
