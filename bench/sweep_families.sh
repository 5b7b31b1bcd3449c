#!/usr/bin/env bash
# sweep_families.sh - convergence per family of sweeps and wall-clock timings of
# one or more viscolube binaries, measured in one run on the same machine.
#
# Usage:
#   bench/sweep_families.sh [--repeats K] [--out DIR] [--cases DIR] [--timeout S] BIN [BIN ...]
#
#   --repeats K   timing repeats, medians reported (default 3)
#   --out DIR     where everything is written (default: a new mktemp -d directory,
#                 printed at the start); DIR/<label>.csv per BIN, DIR/<label>/ holds the
#                 derived scenes, every run's output folder and its stdout/stderr logs
#   --cases DIR   the scene files (default: cases/ next to this script's bench/)
#   --timeout S   wall-clock limit of any one command (default 120 s; a run killed
#                 there writes nothing and counts as exit 124, all points failed)
#
# The label of a BIN is its path as given; the CSV name is that path sanitised
# (/tmp/old/viscolube -> tmp_old_viscolube.csv). With two or more BINs the first is the
# baseline: the comparison's ratios are BIN_k / BIN_1 (give the old binary first).
# About 3 min per binary with --repeats 3 (2 min of it the 30 nm surface, which
# does not finish within the default --timeout). Example:
#   bench/sweep_families.sh --repeats 1 --out /tmp/sf-check /tmp/oldbuild/viscolube build/viscolube
#
# What it measures, for each BIN (everything with OPENBLAS_NUM_THREADS=1: one core):
#  A. Convergence: converged/total points, counted from the `converged` column of every
#     curve.csv a run wrote (a run that exits non-zero but wrote curve.csv is counted
#     from it; a run that wrote nothing counts all its expected points as failed and
#     its exit status is shown). Families:
#     1. fine surfaces: cases/fig05.ini on paper-0.1um and on self-affine surfaces
#        H = 0.8, h_rms = 30 nm and 100 nm with the paper surfaces' q0, q1 (read from
#        `surface show paper-0.1um`), registered with `surface add --self-affine`; a
#        binary without that option gets a tabulated PSD file instead (q_per_m,C_m4;
#        the program's convention for the isotropic 2-D spectrum, docs/FORMATS.md
#        section 4 and `surface add --help`: h_rms^2 = 2 pi \int q C(q) dq, so for
#        C = C0 q^(-2(1+H)) on [q0, q1]: C0 = H h_rms^2 / (pi (q0^-2H - q1^-2H))).
#     2. start anywhere: fig05 and fig15 swept from v0 = 1e-6, 1e-3, 0.1 m/s to the
#        case's `to`, 20 points, fields_at dropped. The sweep quantity is v0_eta (Pa m),
#        so from = v0 * eta with eta read by `fluid show` (fig05: model-1e-4, 1e-4 Pa s;
#        fig15: water, 1e-3 Pa s). Descending sweeps (from > to): the scene format
#        requires to > from (docs/FORMATS.md section 1, [sweep]; "the sweep runs in
#        increasing speed"), so they are only probed: a refusal (exit 2, nothing
#        written) is reported as "skipped" and left out of the totals.
#     3. issue cases: `compare --compounds sbr-unfilled,sbr-filled --surface paper-0.5um
#        --fluid water --from 1e-6 --to 1e-3 --points 4` (counted over DIR/<compound>/
#        curve.csv) and a "seal" scene (sbr-filled on paper-0.5um in water, R = 1 mm,
#        117 N/m, sigma_s 1e6, persson-emt, quantity v0 from 1e-4 to 1 m/s, 9 points;
#        modelled on cases/fig15.ini).
#     4. shipped cases: every cases/*.ini as is (a multi-fluid scene counts every curve).
#  B. Timing: wall-clock of the whole process (date +%s.%N), medians over K repeats of
#     the runs that completed (exit 0 or 7); repeats are interleaved across the BINs so
#     that drifting load on the machine hits all of them alike; run after family A, so
#     every binary's database already holds its Persson and flow-factor tables:
#     - fig05.ini and fig15.ini with points = 60: s per curve, ms per point (wall time /
#       rows of curve.csv, fields_at points included), ratio fig15/fig05;
#     - fig15 with points = 60 and fields_at dropped: exactly a 60-point curve (the run
#       above also solves the case's 3 fields_at speeds and writes their field files);
#     - fig05 with fig15's flow factors (persson-emt), points = 60, and the ratio
#       fig15/that: the cost of the 28-term compound without that of the flow factors;
#     - `friction --compound sbr-unfilled --surface paper-0.5um --fluid water --speed V
#       --quiet` at V = 1e-6, 1e-4, 1e-2, 1 m/s: s per query;
#     - the dry smooth point: fig03-smooth.ini with grid = 400: the "ms per point" of
#       the summary line and the whole process's seconds.
#
# Isolation: each BIN is copied to a private mktemp -d directory (a rebuild of the
# binary during the run cannot change what is measured) together with a fresh database
# (--db; the binary creates it with its embedded materials on first use; XDG_DATA_HOME
# also points there). Commands run with that directory as working directory; it is
# removed at exit (trap). Nothing else is written outside DIR. No command's failure
# aborts the script: each is reported (exit status, first line of stderr).
set -euo pipefail

REPEATS=3
OUT=""
TIMEOUT=120
SCRIPT_DIR=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
CASES="$SCRIPT_DIR/../cases"

usage() { sed -n '2,13p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; }

BINS=()
while (($#)); do
  case $1 in
    --repeats) REPEATS=${2:?--repeats needs a value}; shift 2 ;;
    --repeats=*) REPEATS=${1#*=}; shift ;;
    --out) OUT=${2:?--out needs a value}; shift 2 ;;
    --out=*) OUT=${1#*=}; shift ;;
    --cases) CASES=${2:?--cases needs a value}; shift 2 ;;
    --cases=*) CASES=${1#*=}; shift ;;
    --timeout) TIMEOUT=${2:?--timeout needs a value}; shift 2 ;;
    --timeout=*) TIMEOUT=${1#*=}; shift ;;
    -h|--help) usage; exit 0 ;;
    --) shift; BINS+=("$@"); break ;;
    -*) echo "sweep_families.sh: unknown option $1" >&2; usage >&2; exit 2 ;;
    *) BINS+=("$1"); shift ;;
  esac
done
if ((${#BINS[@]} == 0)); then usage >&2; exit 2; fi
if ! [[ $REPEATS =~ ^[1-9][0-9]*$ ]]; then echo "sweep_families.sh: --repeats must be a positive integer" >&2; exit 2; fi
if ! [[ $TIMEOUT =~ ^[1-9][0-9]*$ ]]; then echo "sweep_families.sh: --timeout must be a positive integer (s)" >&2; exit 2; fi
CASES=$(cd "$CASES" 2>/dev/null && pwd) || { echo "sweep_families.sh: no cases folder ($CASES)" >&2; exit 2; }
for f in fig05.ini fig15.ini fig03-smooth.ini; do
  [[ -r $CASES/$f ]] || { echo "sweep_families.sh: $CASES/$f missing" >&2; exit 2; }
done

if [[ -z $OUT ]]; then
  OUT=$(mktemp -d "${TMPDIR:-/tmp}/sweep_families.XXXXXX")
fi
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
echo "sweep_families: output in $OUT"

export OPENBLAS_NUM_THREADS=1

WORKDIRS=()
cleanup() {
  local w
  for w in "${WORKDIRS[@]}"; do
    [[ -n $w && -d $w ]] && rm -rf -- "$w"
  done
  return 0
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

log() { echo "sweep_families: $*" >&2; }

# ---------------------------------------------------------------- helpers

# CSV-safe text: no commas, quotes or newlines
csvsafe() { printf '%s' "$*" | tr ',\n\r"' ';  '"'"; }

# first non-blank line of a file (an error message), shortened
# (without the "viscolube CMD: FILE:LINE: " prefix of a scene error)
first_line() {
  { grep -m1 -v '^[[:space:]]*$' "$1" 2>/dev/null || true; } |
    sed -e 's|^viscolube [a-z-]*: [^ ]*:[0-9][0-9]*: ||' | cut -c1-160
}
# ": first line of stderr", or nothing when stderr is empty
err_suffix() { local l; l=$(first_line "$1"); [[ -z $l ]] || printf ': %s' "$l"; }

# scene_get FILE SECTION KEY: the value (empty if absent)
scene_get() {
  awk -v sec="$2" -v key="$3" '
    { sub(/\r$/, "") }
    /^[[:space:]]*\[/ { s = $0; gsub(/[][[:space:]]/, "", s); cur = s; next }
    cur == sec {
      line = $0; k = line; sub(/=.*/, "", k); gsub(/[[:space:]]/, "", k)
      if (k == key && index(line, "=") > 0) { v = line; sub(/^[^=]*=[[:space:]]*/, "", v); sub(/[[:space:]]+$/, "", v); print v; exit }
    }' "$1"
}

# scene_edit (bench/scene_edit.sh): a scene with keys replaced or deleted
source "$SCRIPT_DIR/scene_edit.sh"

# expected_points SCENE: points of the sweep plus the fields_at values that are not
# sweep points (merged within 1e-9 relative), times the number of fluids
expected_points() {
  local pts from to fa fl
  pts=$(scene_get "$1" sweep points); from=$(scene_get "$1" sweep from); to=$(scene_get "$1" sweep to)
  fa=$(scene_get "$1" sweep fields_at); fl=$(scene_get "$1" materials fluid)
  awk -v p="$pts" -v a="$from" -v b="$to" -v fa="$fa" -v fl="$fl" 'BEGIN {
    p += 0; a += 0; b += 0; if (p < 1) { print 0; exit }
    n = p; nf = split(fa, f, ",")
    for (i = 1; i <= nf; i++) { x = f[i] + 0; if (x <= 0) continue; hit = 0
      for (k = 0; k < p; k++) { s = (p > 1) ? exp(log(a) + k * (log(b) - log(a)) / (p - 1)) : a
        d = x - s; if (d < 0) d = -d; if (d <= 1e-9 * s) { hit = 1; break } }
      if (!hit) n++ }
    nfl = (fl == "") ? 1 : split(fl, g, ",")
    print n * nfl }'
}

# count_curves DIR: "converged total files" over every curve.csv in DIR and its
# sub-folders (not fields/); columns found by name in the header row
count_curves() {
  local files=()
  if [[ -d $1 ]]; then
    mapfile -t files < <(find "$1" -name curve.csv -not -path '*/fields/*' -type f 2>/dev/null | sort)
  fi
  if ((${#files[@]} == 0)); then echo "0 0 0"; return 0; fi
  awk '
    function csvsplit(line, f,    n, i, c, inq, cur, L) {
      if (index(line, "\"") == 0) return split(line, f, ",")
      n = 0; cur = ""; inq = 0; L = length(line)
      for (i = 1; i <= L; i++) { c = substr(line, i, 1)
        if (inq) { if (c == "\"") { if (substr(line, i + 1, 1) == "\"") { cur = cur "\""; i++ } else inq = 0 } else cur = cur c }
        else if (c == "\"") inq = 1
        else if (c == ",") { f[++n] = cur; cur = "" }
        else cur = cur c }
      f[++n] = cur; return n }
    FNR == 1 { hdr = 0; col = 0; nfiles++ }
    { sub(/\r$/, "") }
    /^#/ || /^[[:space:]]*$/ { next }
    !hdr { hdr = 1; n = csvsplit($0, h); for (i = 1; i <= n; i++) if (h[i] == "converged") col = i; next }
    { tot++; if (col) { csvsplit($0, r); if (r[col] + 0 == 1) conv++ } }
    END { printf "%d %d %d\n", conv, tot, nfiles }' "${files[@]}"
}

# median of numbers on stdin (empty if none)
median() { sort -g | awk '{ a[NR] = $1 } END { if (NR == 0) exit; if (NR % 2) print a[(NR + 1) / 2]; else printf "%.6g\n", (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }

fmt() { # fmt FORMAT VALUE: printf of a number, "-" when empty
  if [[ -z ${2:-} ]]; then printf '%s' "-"; else awk -v f="$1" -v v="$2" 'BEGIN { printf f, v }'; fi
}

sanitise() {
  local s
  s=$(printf '%s' "$1" | sed -e 's/[^A-Za-z0-9._-]/_/g' -e 's/^[_.]*//' -e 's/_\{2,\}/_/g')
  [[ -n $s ]] || s=bin
  printf '%s' "$s"
}

# run_vl LOGBASE ARGS...: the current binary with the current database, in its work
# directory, under the time limit; stdout/stderr to LOGBASE.out/.err. Sets RC and SECS.
run_vl() {
  local logbase=$1; shift
  local t0 t1
  RC=0
  t0=$(date +%s.%N)
  ( cd "$VL_WORK" && exec timeout --kill-after=10 "$TIMEOUT" "$VL_BIN" --db "$VL_DB" "$@" ) \
    >"$logbase.out" 2>"$logbase.err" || RC=$?
  t1=$(date +%s.%N)
  SECS=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.4f", b - a }')
}

status_text() { # a short reading of an exit status
  case $1 in
    0) echo ok ;; 2) echo "bad input" ;; 3) echo "unknown material" ;; 5) echo "db error" ;;
    6) echo "file error" ;; 7) echo "not converged" ;; 70) echo "internal error" ;;
    124|137) echo "timed out (${TIMEOUT} s)" ;; 126|127) echo "cannot execute" ;;
    *) echo "exit $1" ;;
  esac
}

# per-binary state (arrays indexed by binary number)
LABELS=(); SNAP=(); WORK=(); DBS=(); BDIR=(); CSVF=()

select_bin() { # select_bin I: point the run_vl globals at binary I
  VL_BIN=${SNAP[$1]}; VL_DB=${DBS[$1]}; VL_WORK=${WORK[$1]}
  export XDG_DATA_HOME="$VL_WORK/xdg"
}

CSV_HEADER="section,family,item,converged,total,exit_status,seconds,ms_per_point,summary_ms_per_point,runs_ok,runs,value,note"
csv_row() { # csv_row I section family item converged total exit seconds ms sms ok runs value note
  local i=$1; shift
  printf '%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n' "$(csvsafe "$1")" "$(csvsafe "$2")" "$(csvsafe "$3")" \
    "$4" "$5" "$6" "$7" "$8" "$9" "${10}" "${11}" "${12}" "$(csvsafe "${13}")" >>"${CSVF[$i]}"
}

# record_curve I FAMILY ITEM RUNDIR LOGBASE EXPECTED: count a finished run into the CSV
record_curve() {
  local i=$1 fam=$2 item=$3 dir=$4 lb=$5 exp=$6
  local c t nf note=""
  read -r c t nf < <(count_curves "$dir")
  if ((nf == 0)); then
    c=0; t=${exp:-0}
    note="wrote no curve.csv ($(status_text "$RC"))$(err_suffix "$lb.err")"
  elif ((RC != 0)); then
    note="$(status_text "$RC")"
    ((RC == 7)) || note+="$(err_suffix "$lb.err")"
  fi
  csv_row "$i" A "$fam" "$item" "$c" "$t" "$RC" "$SECS" "" "" "" "" "" "$note"
  log "  [$fam] $item: $c/$t (exit $RC, ${SECS} s)"
}

# ---------------------------------------------------------------- setup per binary

nb=${#BINS[@]}
declare -A SEEN=()
for ((i = 0; i < nb; i++)); do
  b=${BINS[$i]}
  LABELS[i]=$b
  s=$(sanitise "$b")
  if [[ -n ${SEEN[$s]:-} ]]; then s="$s-$((i + 1))"; fi
  SEEN[$s]=1
  BDIR[i]="$OUT/$s"
  CSVF[i]="$OUT/$s.csv"
  rm -rf -- "${BDIR[$i]}"
  mkdir -p "${BDIR[$i]}/scenes" "${BDIR[$i]}/runs" "${BDIR[$i]}/logs"
  echo "$CSV_HEADER" >"${CSVF[$i]}"
  w=$(mktemp -d "${TMPDIR:-/tmp}/sweep_families_db.XXXXXX")
  WORKDIRS+=("$w")
  WORK[i]=$w
  mkdir -p "$w/xdg"
  DBS[i]="$w/materials.db"
  SNAP[i]="$w/viscolube"
  if ! cp -- "$b" "${SNAP[$i]}" 2>"${BDIR[$i]}/logs/copy.err" || ! [[ -x ${SNAP[$i]} ]]; then
    log "cannot copy or execute $b: $(first_line "${BDIR[$i]}/logs/copy.err")"
    SNAP[i]=$b   # runs will fail and be reported as such
  fi
done

# ---------------------------------------------------------------- A. convergence

Q0=2e5; Q1=7.8e9; HURST=0.8

# write_psd FILE HRMS: a tabulated self-affine spectrum (fallback for binaries
# without `surface add --self-affine`); 61 log-spaced points from q0 to q1
write_psd() {
  awk -v q0="$Q0" -v q1="$Q1" -v H="$HURST" -v h="$2" 'BEGIN {
    pi = atan2(0, -1)
    c0 = H * h * h / (pi * (q0 ^ (-2 * H) - q1 ^ (-2 * H)))
    print "# self-affine C(q) = C0 q^(-2(1+H)), H = " H ", h_rms = " h " m, q0 = " q0 ", q1 = " q1 " 1/m"
    print "# isotropic 2-D spectrum, h_rms^2 = 2 pi int q C(q) dq"
    print "q_per_m,C_m4"
    n = 61
    for (k = 0; k < n; k++) { q = exp(log(q0) + k * (log(q1) - log(q0)) / (n - 1)); printf "%.10g,%.10g\n", q, c0 * q ^ (-2 * (1 + H)) }
  }' >"$1"
}

# run_scene I FAMILY ITEM SCENE NAME: run a scene and record its counts
run_scene() {
  local i=$1 fam=$2 item=$3 scene=$4 name=$5
  local dir="${BDIR[$i]}/runs/$name" lb="${BDIR[$i]}/logs/$name"
  rm -rf -- "$dir"
  run_vl "$lb" run "$scene" --out "$dir" --quiet
  record_curve "$i" "$fam" "$item" "$dir" "$lb" "$(expected_points "$scene")"
}

# bad_scene I FAMILY ITEM: a scene that could not be derived (counted as n/a)
bad_scene() {
  csv_row "$1" A "$2" "$3" "" "" "" "" "" "" "" "" "" "skipped: could not derive the scene ($4)"
  log "  [$2] $3: could not derive the scene ($4)"
}

fluid_eta() { # fluid_eta I NAME LOGBASE: viscosity (Pa s) from `fluid show`, empty if not found
  run_vl "$3" fluid show "$2"
  if ((RC == 0)); then awk '$1 == "viscosity" { print $2; exit }' "$3.out"; fi
}

for ((i = 0; i < nb; i++)); do
  select_bin "$i"
  sd="${BDIR[$i]}/scenes"; lg="${BDIR[$i]}/logs"
  log "binary $((i + 1))/$nb: ${LABELS[$i]}"

  # the database: created on first use with the embedded materials
  run_vl "$lg/version" --version
  VERSION=$(head -1 "$lg/version.out" 2>/dev/null || true)
  run_vl "$lg/db-init" surface show paper-0.1um
  if ((RC != 0)); then
    log "  database setup failed (exit $RC): $(first_line "$lg/db-init.err")"
    csv_row "$i" setup db "create database" "" "" "$RC" "" "" "" "" "" "" "surface show paper-0.1um: $(first_line "$lg/db-init.err")"
  else
    v=$(awk '$1 == "q0" { print $2; exit }' "$lg/db-init.out"); [[ $v =~ ^[0-9.eE+-]+$ ]] && Q0=$v
    v=$(awk '$1 == "q1" { print $2; exit }' "$lg/db-init.out"); [[ $v =~ ^[0-9.eE+-]+$ ]] && Q1=$v
  fi
  csv_row "$i" setup binary "${LABELS[$i]}" "" "" "" "" "" "" "" "" "" "version: $VERSION; sha256 $(sha256sum "${SNAP[$i]}" 2>/dev/null | cut -c1-16)"

  # 1. fine surfaces
  fam="fine surfaces"
  surfs=(paper-0.1um)
  for h in 30 100; do
    name="sf-sa-h${HURST}-${h}nm"
    hrms=$(awk -v h="$h" 'BEGIN { printf "%g", h * 1e-9 }')
    run_vl "$lg/surface-add-$h" surface add "$name" --self-affine --hurst "$HURST" --q0 "$Q0" --q1 "$Q1" --hrms "$hrms" \
      --description "sweep_families.sh: self-affine H $HURST, h_rms $h nm"
    how="--self-affine"
    if ((RC != 0)); then
      log "  surface add --self-affine failed (exit $RC: $(first_line "$lg/surface-add-$h.err")); trying a PSD file"
      write_psd "$sd/$name.csv" "$hrms"
      run_vl "$lg/surface-add-psd-$h" surface add "$name" --psd "$sd/$name.csv"
      how="--psd"
    fi
    if ((RC == 0)); then
      surfs+=("$name")
      csv_row "$i" setup surface "$name" "" "" 0 "" "" "" "" "" "" "registered with $how"
    else
      csv_row "$i" setup surface "$name" "" "" "$RC" "" "" "" "" "" "" "not registered: $(first_line "$lg/surface-add-psd-$h.err")"
      surfs+=("!$name")
    fi
  done
  for s in "${surfs[@]}"; do
    if [[ $s == '!'* ]]; then
      bad_scene "$i" "$fam" "fig05 on ${s#!}" "surface not registered"; continue
    fi
    sc="$sd/fig05-$s.ini"
    if scene_edit "$CASES/fig05.ini" "$sc" materials surface "$s" 2>"$lg/edit.err"; then
      run_scene "$i" "$fam" "fig05 on $s" "$sc" "fine-fig05-$s"
    else bad_scene "$i" "$fam" "fig05 on $s" "$(first_line "$lg/edit.err")"; fi
  done

  # 2. start anywhere
  fam="start anywhere"
  for c in fig05 fig15; do
    fl=$(scene_get "$CASES/$c.ini" materials fluid)
    eta=$(fluid_eta "$i" "$fl" "$lg/fluid-$fl")
    enote=""
    if ! [[ $eta =~ ^[0-9.eE+-]+$ ]]; then
      case $c in fig05) eta=1e-4 ;; *) eta=1e-3 ;; esac
      enote=" (eta of $fl not read: assumed $eta Pa s)"
      log "  could not read the viscosity of $fl; assuming $eta Pa s"
    fi
    to=$(scene_get "$CASES/$c.ini" sweep to); from0=$(scene_get "$CASES/$c.ini" sweep from)
    for v in 1e-6 1e-3 0.1; do
      from=$(awk -v v="$v" -v e="$eta" 'BEGIN { printf "%.6g", v * e }')
      sc="$sd/$c-from-v$v.ini"
      if scene_edit "$CASES/$c.ini" "$sc" sweep from "$from" sweep points 20 sweep fields_at --delete 2>"$lg/edit.err"; then
        run_scene "$i" "$fam" "$c from v0=$v m/s$enote" "$sc" "start-$c-v$v"
      else bad_scene "$i" "$fam" "$c from v0=$v" "$(first_line "$lg/edit.err")"; fi
    done
    # descending: probed; refused by the scene format (to > from)
    sc="$sd/$c-descending.ini"
    item="$c descending ($to -> $from0, 20 pts)"
    if scene_edit "$CASES/$c.ini" "$sc" sweep from "$to" sweep to "$from0" sweep points 20 sweep fields_at --delete 2>"$lg/edit.err"; then
      dir="${BDIR[$i]}/runs/start-$c-descending"; lb="$lg/start-$c-descending"
      rm -rf -- "$dir"
      run_vl "$lb" run "$sc" --out "$dir" --quiet
      read -r _ _ nf < <(count_curves "$dir")
      if ((nf == 0 && RC == 2)); then
        csv_row "$i" A "$fam" "$item" "" "" "$RC" "$SECS" "" "" "" "" "" "skipped: the scene format refuses from > to: $(first_line "$lb.err")"
        log "  [$fam] $item: skipped, refused (exit 2)"
      else
        record_curve "$i" "$fam" "$item" "$dir" "$lb" 20
      fi
    else bad_scene "$i" "$fam" "$item" "$(first_line "$lg/edit.err")"; fi
  done

  # 3. issue cases
  fam="issue cases"
  dir="${BDIR[$i]}/runs/issue-compare"; rm -rf -- "$dir"
  run_vl "$lg/issue-compare" compare --compounds sbr-unfilled,sbr-filled --surface paper-0.5um --fluid water \
    --from 1e-6 --to 1e-3 --points 4 --out "$dir" --quiet
  record_curve "$i" "$fam" "compare sbr-unfilled+filled 1e-6..1e-3 x4" "$dir" "$lg/issue-compare" 8
  sc="$sd/seal.ini"
  cat >"$sc" <<'EOF'
; sweep_families.sh "seal": modelled on cases/fig15.ini with the filled compound and a
; speed sweep of 1e-4 .. 1 m/s
[scene]
title = seal: sbr-filled on paper-0.5um in water, 1e-4 .. 1 m/s

[materials]
compound = sbr-filled
surface = paper-0.5um
fluid = water

[contact]
radius_m = 0.001
load_n_per_m = 117
sigma_s_pa = 1e6

[sweep]
quantity = v0
from = 1e-4
to = 1
points = 9

[effects]
viscoelastic = on
roughness = on
fluid = on
solid_shear = on
flow_factors = persson-emt
viscous_flattening = off
temperature = off

[numerics]
EOF
  run_scene "$i" "$fam" "seal sbr-filled 1e-4..1 m/s x9" "$sc" "issue-seal"

  # 4. shipped cases
  fam="shipped cases"
  shopt -s nullglob
  cases=("$CASES"/*.ini)
  shopt -u nullglob
  for sc in "${cases[@]}"; do
    n=$(basename "$sc" .ini)
    run_scene "$i" "$fam" "$n" "$sc" "case-$n"
  done
done

# ---------------------------------------------------------------- B. timing

for ((i = 0; i < nb; i++)); do
  sd="${BDIR[$i]}/scenes"
  scene_edit "$CASES/fig05.ini" "$sd/time-fig05-60.ini" sweep points 60 2>/dev/null || true
  scene_edit "$CASES/fig15.ini" "$sd/time-fig15-60.ini" sweep points 60 2>/dev/null || true
  # the same curve with exactly its 60 points: no fields_at speeds added, no field files
  scene_edit "$sd/time-fig15-60.ini" "$sd/time-fig15only-60.ini" sweep fields_at --delete 2>/dev/null || true
  # fig05 with fig15's flow factors: the ratio to fig15 without the flow-factor model's cost
  scene_edit "$sd/time-fig05-60.ini" "$sd/time-fig05emt-60.ini" effects flow_factors persson-emt 2>/dev/null || true
  scene_edit "$CASES/fig03-smooth.ini" "$sd/time-fig03-smooth-400.ini" numerics grid 400 2>/dev/null || true
  : >"${BDIR[$i]}/timing.raw"
done

SPEEDS=(1e-6 1e-4 1e-2 1)
# raw rows: item rep exit seconds rows summary_ms
for ((r = 1; r <= REPEATS; r++)); do
  for ((i = 0; i < nb; i++)); do
    select_bin "$i"
    sd="${BDIR[$i]}/scenes"; lg="${BDIR[$i]}/logs"; raw="${BDIR[$i]}/timing.raw"
    log "timing repeat $r/$REPEATS, binary $((i + 1))/$nb"
    for t in fig05-60 fig05emt-60 fig15-60 fig15only-60 fig03-smooth-400; do
      sc="$sd/time-$t.ini"; dir="${BDIR[$i]}/runs/time-$t"; lb="$lg/time-$t-r$r"
      if [[ ! -s $sc ]]; then echo "$t $r derive NA 0 NA" >>"$raw"; continue; fi
      rm -rf -- "$dir"
      run_vl "$lb" run "$sc" --out "$dir" --quiet
      read -r _ tt _ < <(count_curves "$dir")
      sms=$(sed -n 's/.*(\([0-9.eE+-]*\) ms per point).*/\1/p' "$lb.out" | tail -1)
      echo "$t $r $RC $SECS $tt ${sms:-NA}" >>"$raw"
    done
    for v in "${SPEEDS[@]}"; do
      lb="$lg/time-friction-$v-r$r"
      run_vl "$lb" friction --compound sbr-unfilled --surface paper-0.5um --fluid water --speed "$v" --quiet
      echo "friction-$v $r $RC $SECS 1 NA" >>"$raw"
    done
  done
done

# summarise the raw timings into the CSV; T_<i>_<key> hold the values for the tables
declare -A T=()
for ((i = 0; i < nb; i++)); do
  raw="${BDIR[$i]}/timing.raw"
  for t in fig05-60 fig05emt-60 fig15-60 fig15only-60 fig03-smooth-400 "${SPEEDS[@]/#/friction-}"; do
    ok=$(awk -v t="$t" '$1 == t && ($3 == 0 || $3 == 7)' "$raw" | wc -l)
    runs=$(awk -v t="$t" '$1 == t' "$raw" | wc -l)
    med=$(awk -v t="$t" '$1 == t && ($3 == 0 || $3 == 7) { print $4 }' "$raw" | median)
    rows=$(awk -v t="$t" '$1 == t && ($3 == 0 || $3 == 7) && $5 > 0 { print $5 }' "$raw" | median)
    sms=$(awk -v t="$t" '$1 == t && ($3 == 0 || $3 == 7) && $6 != "NA" { print $6 }' "$raw" | median)
    stat=$(awk -v t="$t" '$1 == t { printf "%s%s", (n++ ? " " : ""), $3 }' "$raw")
    mspp=""
    [[ -n $med && -n $rows ]] && mspp=$(awk -v s="$med" -v n="$rows" 'BEGIN { if (n > 0) printf "%.4g", 1000 * s / n }')
    note="exit statuses: $stat"
    [[ $t == fig* && -n $rows ]] && note+="; $rows points per curve"
    case $t in
      fig05-60) item="fig05 points=60" ;; fig05emt-60) item="fig05 persson-emt points=60" ;; fig15-60) item="fig15 points=60" ;;
      fig15only-60) item="fig15 points=60 no fields_at" ;;
      fig03-smooth-400) item="fig03-smooth grid=400" ;; friction-*) item="friction v=${t#friction-} m/s" ;;
    esac
    csv_row "$i" B timing "$item" "" "" "" "$med" "$mspp" "$sms" "$ok" "$runs" "" "$note"
    T[$i,$t,s]=$med; T[$i,$t,ms]=$mspp; T[$i,$t,sms]=$sms; T[$i,$t,ok]=$ok; T[$i,$t,runs]=$runs; T[$i,$t,stat]=$stat
  done
  ratio=""
  if [[ -n ${T[$i,fig05-60,s]} && -n ${T[$i,fig15-60,s]} ]]; then
    ratio=$(awk -v a="${T[$i,fig15-60,s]}" -v b="${T[$i,fig05-60,s]}" 'BEGIN { if (b > 0) printf "%.3g", a / b }')
  fi
  T[$i,ratio]=$ratio
  csv_row "$i" B timing "ratio fig15/fig05 (s per curve)" "" "" "" "" "" "" "" "" "$ratio" ""
  ratio=""
  if [[ -n ${T[$i,fig05emt-60,s]} && -n ${T[$i,fig15-60,s]} ]]; then
    ratio=$(awk -v a="${T[$i,fig15-60,s]}" -v b="${T[$i,fig05emt-60,s]}" 'BEGIN { if (b > 0) printf "%.3g", a / b }')
  fi
  T[$i,ratio_emt]=$ratio
  csv_row "$i" B timing "ratio fig15/fig05 persson-emt (s per curve)" "" "" "" "" "" "" "" "" "$ratio" ""
done

# ---------------------------------------------------------------- tables

FAMS=("fine surfaces" "start anywhere" "issue cases" "shipped cases")
declare -A FC=() FT=()

print_table() {
  local i=$1 csv=${CSVF[$1]}
  local fam
  echo
  echo "=== BIN$((i + 1)): ${LABELS[$i]}"
  awk -F, '$1 == "setup" && $2 == "binary" { print "    " $13 }' "$csv"
  awk -F, '$1 == "setup" && $2 != "binary" { printf "    setup %s %s: exit %s; %s\n", $2, $3, $6, $13 }' "$csv"
  printf '%-16s %-44s %9s %5s %8s  %s\n' "A. family" "run" "conv/tot" "exit" "wall s" "note"
  for fam in "${FAMS[@]}"; do
    awk -F, -v fam="$fam" '
      $1 == "A" && $2 == fam {
        ct = ($4 == "" ? "n/a" : $4 "/" $5)
        printf "%-16s %-44s %9s %5s %8s  %s\n", (shown++ ? "" : fam), substr($3, 1, 44), ct, $6, ($7 == "" ? "" : sprintf("%.2f", $7)), substr($13, 1, 90)
        if ($4 != "") { c += $4; t += $5 }
      }
      END { if (shown) printf "%-16s %-44s %9s\n", "", "-- total", c "/" t }' "$csv"
    local fc ft
    read -r fc ft < <(awk -F, -v fam="$fam" '$1 == "A" && $2 == fam && $4 != "" { c += $4; t += $5 } END { print c + 0, t + 0 }' "$csv")
    FC["$i,$fam"]=$fc; FT["$i,$fam"]=$ft
  done
  echo
  printf '%-28s %10s %10s %14s %7s  %s\n' "B. timing (median of $REPEATS)" "s/run" "ms/point" "summary ms/pt" "ok" "exit statuses"
  local t label
  for t in fig05-60 fig05emt-60 fig15-60 fig15only-60 "${SPEEDS[@]/#/friction-}" fig03-smooth-400; do
    case $t in
      fig05-60) label="fig05 points=60" ;; fig05emt-60) label="fig05 persson-emt pts=60" ;; fig15-60) label="fig15 points=60" ;;
      fig15only-60) label="fig15 60, no fields_at" ;;
      fig03-smooth-400) label="fig03-smooth grid=400" ;; friction-*) label="friction v=${t#friction-}" ;;
    esac
    printf '%-28s %10s %10s %14s %7s  %s\n' "$label" "$(fmt '%.3f' "${T[$i,$t,s]}")" "$(fmt '%.2f' "${T[$i,$t,ms]}")" \
      "$(fmt '%.2f' "${T[$i,$t,sms]}")" "${T[$i,$t,ok]}/${T[$i,$t,runs]}" "${T[$i,$t,stat]}"
    [[ $t == fig15-60 ]] && printf '%-28s %10s\n' "ratio fig15/fig05" "$(fmt '%.2f' "${T[$i,ratio]}")" \
      "ratio fig15/fig05 persson-emt" "$(fmt '%.2f' "${T[$i,ratio_emt]}")"
  done
  echo "(fig05/fig15 ms/point = wall time / rows of curve.csv; friction: s per query; fig03-smooth: summary line's ms per point and whole process s)"
}

for ((i = 0; i < nb; i++)); do print_table "$i"; done

if ((nb >= 2)); then
  echo
  echo "=== comparison (ratios: BINk / BIN1, the first BIN is the baseline)"
  for ((i = 0; i < nb; i++)); do echo "    BIN$((i + 1)) = ${LABELS[$i]}"; done
  hdr=$(printf '%-30s' "family (converged/total)")
  for ((i = 0; i < nb; i++)); do hdr+=$(printf ' %12s' "BIN$((i + 1))"); done
  echo "$hdr"
  for fam in "${FAMS[@]}"; do
    line=$(printf '%-30s' "$fam")
    for ((i = 0; i < nb; i++)); do line+=$(printf ' %12s' "${FC["$i,$fam"]}/${FT["$i,$fam"]}"); done
    echo "$line"
  done
  # runs whose counts differ between the binaries
  diffs=$(for ((i = 0; i < nb; i++)); do
            awk -F, -v b="$i" '$1 == "A" { print $2 "|" $3 "|" b "|" ($4 == "" ? "n/a" : $4 "/" $5) }' "${CSVF[$i]}"
          done | awk -F'|' -v nb="$nb" '
            { k = $1 "|" $2; if (!(k in seen)) { seen[k] = 1; order[++n] = k } v[k, $3] = $4 }
            END { for (j = 1; j <= n; j++) { k = order[j]; d = 0; s = ""
                    for (b = 0; b < nb; b++) { x = ((k, b) in v) ? v[k, b] : "-"; if (b && x != v[k, 0]) d = 1; s = s sprintf(" %12s", x) }
                    if (d) { split(k, p, "|"); printf "  %-28s%s\n", substr(p[2], 1, 28), s } } }')
  if [[ -n $diffs ]]; then echo "runs that differ:"; echo "$diffs"; else echo "(every run has the same counts on every BIN)"; fi
  echo
  hdr=$(printf '%-30s' "timing (median)")
  for ((i = 0; i < nb; i++)); do hdr+=$(printf ' %12s' "BIN$((i + 1))"); done
  for ((i = 1; i < nb; i++)); do hdr+=$(printf ' %9s' "BIN$((i + 1))/1"); done
  echo "$hdr"
  cmp_line() { # cmp_line LABEL KEY FORMAT
    local line i a b
    line=$(printf '%-30s' "$1")
    for ((i = 0; i < nb; i++)); do line+=$(printf ' %12s' "$(fmt "$3" "${T[$i,$2]:-}")"); done
    for ((i = 1; i < nb; i++)); do
      a=${T[$i,$2]:-}; b=${T[0,$2]:-}
      if [[ -n $a && -n $b ]]; then line+=$(printf ' %9s' "$(awk -v a="$a" -v b="$b" 'BEGIN { if (b > 0) printf "%.2f", a / b; else printf "-" }')")
      else line+=$(printf ' %9s' "-"); fi
    done
    echo "$line"
  }
  cmp_line "fig05 60 pts, s/curve" "fig05-60,s" '%.3f'
  cmp_line "fig05 60 pts, ms/point" "fig05-60,ms" '%.2f'
  cmp_line "fig15 60 pts, s/curve" "fig15-60,s" '%.3f'
  cmp_line "fig15 60 pts, ms/point" "fig15-60,ms" '%.2f'
  cmp_line "fig15 60 pts no fields_at, s" "fig15only-60,s" '%.3f'
  cmp_line "ratio fig15/fig05" "ratio" '%.2f'
  cmp_line "fig05 persson-emt 60 pts, s/curve" "fig05emt-60,s" '%.3f'
  cmp_line "ratio fig15/fig05 persson-emt" "ratio_emt" '%.2f'
  for v in "${SPEEDS[@]}"; do cmp_line "friction v=$v, s/query" "friction-$v,s" '%.3f'; done
  cmp_line "fig03-smooth g400, ms/pt (sum.)" "fig03-smooth-400,sms" '%.2f'
  cmp_line "fig03-smooth g400, s/process" "fig03-smooth-400,s" '%.3f'
fi

echo
for ((i = 0; i < nb; i++)); do echo "wrote ${CSVF[$i]}"; done
