#!/usr/bin/env bash
# performance.sh - the key timings of one viscolube binary, written into the tables
# of docs/PERFORMANCE.md (between its <!-- bench:NAME begin --> / end markers).
#
# Usage:
#   bench/performance.sh [--repeats K] [--bin PATH] [--doc FILE] [--out DIR]
#                        [--no-study] [--timeout S] [--print]
#
#   --repeats K   timing repeats, medians reported (default 3)
#   --bin PATH    the program (default build/viscolube; built with
#                 `cmake --build build --target viscolube_cli` when missing)
#   --doc FILE    the file whose tables are rewritten (default docs/PERFORMANCE.md)
#   --out DIR     keep the runs, logs and raw timings there (default: a temporary
#                 folder, removed at the end)
#   --no-study    leave out the study (studies/example.ini serially and --jobs 2,
#                 about 20 s a repeat on an idle 2-core machine)
#   --timeout S   wall-clock limit of any one command (default 300 s)
#   --print       print the tables, do not rewrite the file
#
# Everything runs with OPENBLAS_NUM_THREADS=1 on a fresh temporary database (created
# by the binary from its embedded materials), after one warm-up run of every scene
# that fills the database's Persson and flow-factor caches, so the timings are of
# the solves, not of the tables. Repeats are interleaved (every item once, then
# again), so drifting load hits all items alike. Times are wall clock of the whole
# process (date +%s.%N); on a shared machine they scatter by 10-30 %: the Newton
# iterations and the converged counts are the noise-free figures.
# About 75 s in all with 3 repeats (20 s a round with the study, the warm-up included)
# on 2 cores at load average 6-8; --no-study about halves it.
set -euo pipefail

REPEATS=3
BIN=""
DOC=""
OUT=""
STUDY=1
TIMEOUT=300
PRINT=0
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

usage() { sed -n '5,17p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; }

while (($#)); do
  case $1 in
    --repeats) REPEATS=${2:?--repeats needs a value}; shift 2 ;;
    --bin) BIN=${2:?--bin needs a value}; shift 2 ;;
    --doc) DOC=${2:?--doc needs a value}; shift 2 ;;
    --out) OUT=${2:?--out needs a value}; shift 2 ;;
    --no-study) STUDY=0; shift ;;
    --timeout) TIMEOUT=${2:?--timeout needs a value}; shift 2 ;;
    --print) PRINT=1; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "performance.sh: unknown argument $1" >&2; usage >&2; exit 2 ;;
  esac
done
[[ $REPEATS =~ ^[1-9][0-9]*$ ]] || { echo "performance.sh: --repeats must be a positive integer" >&2; exit 2; }
[[ $TIMEOUT =~ ^[1-9][0-9]*$ ]] || { echo "performance.sh: --timeout must be a positive integer" >&2; exit 2; }
DOC=${DOC:-$ROOT/docs/PERFORMANCE.md}
if ((!PRINT)) && [[ ! -w $DOC ]]; then echo "performance.sh: cannot write $DOC" >&2; exit 2; fi

if [[ -z $BIN ]]; then
  BIN=$ROOT/build/viscolube
  if [[ ! -x $BIN ]]; then
    echo "performance.sh: building $BIN" >&2
    cmake -S "$ROOT" -B "$ROOT/build" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
    cmake --build "$ROOT/build" -j "$(nproc 2>/dev/null || echo 2)" --target viscolube_cli >&2
  fi
fi
[[ -x $BIN ]] || { echo "performance.sh: $BIN is not an executable" >&2; exit 2; }

T_START=$(date +%s)
WORK=$(mktemp -d "${TMPDIR:-/tmp}/vl-performance.XXXXXX")
KEEP=0
if [[ -n $OUT ]]; then mkdir -p "$OUT"; OUT=$(cd "$OUT" && pwd); KEEP=1; else OUT=$WORK/out; mkdir -p "$OUT"; fi
cleanup() { rm -rf -- "$WORK"; }
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

cp -- "$BIN" "$WORK/viscolube"         # a rebuild during the run changes nothing here
VL=$WORK/viscolube
DB=$WORK/materials.db
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 XDG_DATA_HOME=$WORK/xdg
mkdir -p "$XDG_DATA_HOME" "$OUT/scenes" "$OUT/runs" "$OUT/logs"
RAW=$OUT/timing.raw
: >"$RAW"
log() { echo "performance: $*" >&2; }
log "binary $BIN, $REPEATS repeats, output in $OUT$( ((KEEP)) || echo ' (temporary)')"

# scene_edit (bench/scene_edit.sh): a scene with keys replaced or deleted
source "$ROOT/bench/scene_edit.sh"

# curve_stats DIR: "converged total iterations" over every curve.csv under DIR (a study:
# its results.csv, which has the same columns after the factors)
curve_stats() {
  local files=()
  mapfile -t files < <(find "$1" -name curve.csv -not -path '*/fields/*' -type f 2>/dev/null | sort)
  if ((${#files[@]} == 0)) && [[ -f $1/results.csv ]]; then files=("$1/results.csv"); fi
  if ((${#files[@]} == 0)); then echo "0 0 0"; return 0; fi
  awk -F, '
    FNR == 1 { hdr = 0 }
    { sub(/\r$/, "") }
    /^#/ || /^[[:space:]]*$/ { next }
    !hdr { hdr = 1; cc = ci = 0; for (i = 1; i <= NF; i++) { if ($i == "converged") cc = i; if ($i == "iterations") ci = i }; next }
    { tot++; if (cc && $cc + 0 == 1) conv++; if (ci) it += $ci }
    END { printf "%d %d %d\n", conv, tot, it }' "${files[@]}"
}

# run_item NAME ARGS...: one timed run of the binary; appends "NAME rep exit s conv tot iters"
run_item() {
  local name=$1; shift
  local dir=$OUT/runs/$name lb=$OUT/logs/$name-r$REP t0 t1 rc=0 s c t it
  rm -rf -- "$dir"
  t0=$(date +%s.%N)
  ( cd "$WORK" && exec timeout --kill-after=10 "$TIMEOUT" "$VL" --db "$DB" "$@" ) >"$lb.out" 2>"$lb.err" || rc=$?
  t1=$(date +%s.%N)
  s=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.4f", b - a }')
  read -r c t it < <(curve_stats "$dir")
  # the solver's own time per point, from the summary line of `run` ("(17.4 ms per point)")
  sms=$(sed -n 's/.*(\([0-9.eE+-]*\) ms per point).*/\1/p' "$lb.out" | tail -1)
  echo "$name $REP $rc $s $c $t $it ${sms:-NA}" >>"$RAW"
}

# ------------------------------------------------------------------ the items
C=$ROOT/cases
S=$OUT/scenes
scene_edit "$C/fig05.ini" "$S/fig05-60.ini" sweep points 60 sweep fields_at --delete
scene_edit "$S/fig05-60.ini" "$S/fig05emt-60.ini" effects flow_factors persson-emt
scene_edit "$C/fig15.ini" "$S/fig15-60.ini" sweep points 60 sweep fields_at --delete
scene_edit "$C/fig03-smooth.ini" "$S/fig03-smooth-400.ini" numerics grid 400 sweep fields_at --delete
SPEEDS=(1e-6 1e-4 1e-2 1)

one_round() {
  local v
  run_item fig05-60 run "$S/fig05-60.ini" --out "$OUT/runs/fig05-60" --quiet
  run_item fig05emt-60 run "$S/fig05emt-60.ini" --out "$OUT/runs/fig05emt-60" --quiet
  run_item fig15-60 run "$S/fig15-60.ini" --out "$OUT/runs/fig15-60" --quiet
  run_item fig03-smooth-400 run "$S/fig03-smooth-400.ini" --out "$OUT/runs/fig03-smooth-400" --quiet
  # the main job of scripts/dev.sh run, figures included
  run_item compare compare --compounds sbr-unfilled,sbr-filled --surface paper-0.5um \
    --fluid water --from 1e-12 --to 0.1 --points 45 --plot --out "$OUT/runs/compare" --quiet
  for v in "${SPEEDS[@]}"; do
    run_item "friction-$v" friction --compound sbr-unfilled --surface paper-0.5um --fluid water --speed "$v" --json --quiet
    cp -- "$OUT/logs/friction-$v-r$REP.out" "$OUT/runs/friction-$v.json" 2>/dev/null || true
  done
  if ((STUDY)); then
    run_item study-serial study "$ROOT/studies/example.ini" --out "$OUT/runs/study-serial" --quiet
    run_item study-jobs2 study "$ROOT/studies/example.ini" --out "$OUT/runs/study-jobs2" --jobs 2 --quiet
  fi
}

LOAD0=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo "?")
log "warm-up (fills the database's caches; not timed)"
REP=0
one_round
: >"$RAW"
for ((REP = 1; REP <= REPEATS; REP++)); do
  log "repeat $REP/$REPEATS"
  one_round
done
LOAD1=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo "?")
T_END=$(date +%s)

# ------------------------------------------------------------------ summaries
median() { sort -g | awk '{ a[NR] = $1 } END { if (NR == 0) exit; if (NR % 2) print a[(NR + 1) / 2]; else printf "%.6g\n", (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
# item_stat NAME: "median min max ok runs conv tot iters summary_ms" (seconds over runs
# with exit 0 or 7; summary_ms: median of the summary lines' ms per point, NA if none)
item_stat() {
  local med mn mx sms
  med=$(awk -v n="$1" '$1 == n && ($3 == 0 || $3 == 7) { print $4 }' "$RAW" | median)
  mn=$(awk -v n="$1" '$1 == n && ($3 == 0 || $3 == 7) { print $4 }' "$RAW" | sort -g | head -1)
  mx=$(awk -v n="$1" '$1 == n && ($3 == 0 || $3 == 7) { print $4 }' "$RAW" | sort -g | tail -1)
  sms=$(awk -v n="$1" '$1 == n && ($3 == 0 || $3 == 7) && $8 != "NA" { print $8 }' "$RAW" | median)
  awk -v n="$1" -v med="${med:-NA}" -v mn="${mn:-NA}" -v mx="${mx:-NA}" -v sms="${sms:-NA}" '
    $1 == n { runs++; if ($3 == 0 || $3 == 7) ok++; conv = $5; tot = $6; it = $7 }
    END { printf "%s %s %s %d %d %s %s %s %s\n", med, mn, mx, ok, runs, conv, tot, it, sms }' "$RAW"
}
f3() { awk -v v="$1" 'BEGIN { if (v == "NA" || v == "") printf "-"; else printf "%.3f", v }'; }
f2() { awk -v v="$1" 'BEGIN { if (v == "NA" || v == "") printf "-"; else printf "%.2f", v }'; }

# the commit; "+ local changes" only when what is measured (sources, build, materials,
# scenes) differs from it: edits to documentation do not change a timing
COMMIT=$(git -C "$ROOT" describe --always 2>/dev/null || echo unknown)
if [[ -n $(git -C "$ROOT" status --porcelain -- src include cmake CMakeLists.txt materials cases studies 2>/dev/null) ]]; then
  COMMIT+=" + local changes to the sources"
fi
VERSION=$("$VL" --version 2>/dev/null | head -1 || echo "?")
CPU=$(awk -F': ' '/^model name/ { print $2; exit }' /proc/cpuinfo 2>/dev/null || echo "?")
NCPU=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo "?")   # not nproc: it honours OMP_NUM_THREADS

TAB=$WORK/tables
mkdir -p "$TAB"
{
  echo "| | |"
  echo "|---|---|"
  echo "| measured | $(date -u '+%Y-%m-%d %H:%M UTC') by \`bench/performance.sh --repeats $REPEATS$( ((STUDY)) || echo ' --no-study')\` ($((T_END - T_START)) s in all) |"
  echo "| source | commit \`$COMMIT\`; \`viscolube --version\`: $VERSION |"
  echo "| machine | $CPU, $NCPU online cores; load average $LOAD0 before, $LOAD1 after (1, 5, 15 min) |"
  echo "| settings | one BLAS thread (\`OPENBLAS_NUM_THREADS=1\`), a fresh database with its caches filled by a warm-up round, wall clock of the whole process, medians of $REPEATS interleaved repeats |"
} >"$TAB/machine"

{
  echo "| run | points converged | Newton iterations | s per run (median) | min ... max | ms per point, whole run | ms per point, solver (summary line) |"
  echo "|---|---|---|---|---|---|---|"
  for n in fig05-60 fig05emt-60 fig15-60 fig03-smooth-400 compare; do
    read -r med mn mx ok runs conv tot it sms < <(item_stat "$n")
    case $n in
      fig05-60) label="\`cases/fig05.ini\`, 60 points (model rubber, patir-cheng)" ;;
      fig05emt-60) label="the same with \`flow_factors = persson-emt\`" ;;
      fig15-60) label="\`cases/fig15.ini\`, 60 points (28-term \`sbr-unfilled\`, persson-emt)" ;;
      fig03-smooth-400) label="\`cases/fig03-smooth.ini\`, grid 400 (dry smooth, 61 points)" ;;
      compare) label="the main job: \`compare\` of \`scripts/dev.sh run\` (2 x 45 points, figures)" ;;
    esac
    mspp=$(awk -v s="$med" -v t="$tot" 'BEGIN { if (s == "NA" || t + 0 == 0) printf "-"; else printf "%.2f", 1000 * s / t }')
    note=""; ((ok == runs)) || note=" ($ok of $runs runs completed)"
    echo "| $label | $conv of $tot | $it | $(f3 "$med")$note | $(f3 "$mn") ... $(f3 "$mx") | $mspp | $(f2 "$sms") |"
  done
  r05=$(item_stat fig05-60 | cut -d' ' -f1); r05e=$(item_stat fig05emt-60 | cut -d' ' -f1); r15=$(item_stat fig15-60 | cut -d' ' -f1)
  echo "| ratio fig15 / fig05; fig15 / fig05 with persson-emt | | | $(awk -v a="$r15" -v b="$r05" 'BEGIN { if (b + 0 > 0) printf "%.2f", a / b; else printf "-" }'); $(awk -v a="$r15" -v b="$r05e" 'BEGIN { if (b + 0 > 0) printf "%.2f", a / b; else printf "-" }') | | | |"
} >"$TAB/sweeps"

{
  echo "| speed (m/s) | mu | regime | Newton iterations | s per query (median) | min ... max |"
  echo "|---|---|---|---|---|---|"
  for v in "${SPEEDS[@]}"; do
    read -r med mn mx ok runs _ _ _ _ < <(item_stat "friction-$v")
    js=$OUT/runs/friction-$v.json
    mu=$(grep -o '"mu": *[-0-9.eE+]*' "$js" 2>/dev/null | head -1 | sed 's/.*: *//'); mu=${mu:+$(awk -v m="$mu" 'BEGIN { printf "%.4g", m }')}
    rg=$(grep -o '"regime": *"[a-z]*"' "$js" 2>/dev/null | head -1 | sed 's/.*: *"//; s/"//')
    itn=$(grep -o '"iterations": *[0-9]*' "$js" 2>/dev/null | head -1 | sed 's/.*: *//')
    note=""; ((ok == runs)) || note=" ($ok of $runs runs completed)"
    echo "| $v | ${mu:--} | ${rg:--} | ${itn:--} | $(f3 "$med")$note | $(f3 "$mn") ... $(f3 "$mx") |"
  done
} >"$TAB/friction"

{
  if ((STUDY)); then
    echo "| \`studies/example.ini\` (12 curves of 12 points) | points converged | s (median) | min ... max | curves per second |"
    echo "|---|---|---|---|---|"
    for n in study-serial study-jobs2; do
      read -r med mn mx ok runs conv tot _ _ < <(item_stat "$n")
      [[ $n == study-serial ]] && label="serial" || label="\`--jobs 2\`"
      tps=$(awk -v s="$med" 'BEGIN { if (s == "NA" || s + 0 == 0) printf "-"; else printf "%.2f", 12 / s }')
      echo "| $label | $conv of $tot | $(f2 "$med") | $(f2 "$mn") ... $(f2 "$mx") | $tps |"
    done
    if cmp -s "$OUT/runs/study-serial/results.csv" "$OUT/runs/study-jobs2/results.csv"; then
      echo "| the two \`results.csv\` | identical byte for byte | | | |"
    else
      echo "| the two \`results.csv\` | **differ** | | | |"
    fi
  else
    echo "(not measured in the last run: \`--no-study\`)"
  fi
} >"$TAB/study"

if ((PRINT)); then
  for t in machine sweeps friction study; do echo "## $t"; cat "$TAB/$t"; echo; done
  exit 0
fi

# rewrite the blocks between <!-- bench:NAME begin --> and <!-- bench:NAME end -->
tmp=$DOC.tmp.$$
awk -v dir="$TAB" '
  match($0, /<!-- bench:[a-z]+ begin -->/) {
    print; name = substr($0, RSTART + 11); sub(/ begin -->.*/, "", name)
    f = dir "/" name
    if ((getline line < f) > 0) { print line; while ((getline line < f) > 0) print line; close(f); skip = 1; seen[name] = 1 }
    else { print "performance.sh: no table named " name > "/dev/stderr"; skip = 0 }
    next
  }
  /<!-- bench:[a-z]+ end -->/ { skip = 0; print; next }
  !skip { print }
  END { for (n in seen) k++; if (k == 0) { print "performance.sh: no bench markers in the file" > "/dev/stderr"; exit 1 } }
' "$DOC" >"$tmp" && mv -- "$tmp" "$DOC" || { rm -f -- "$tmp"; exit 1; }
log "rewrote the tables of $DOC in $((T_END - T_START)) s"
