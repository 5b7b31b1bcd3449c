#!/usr/bin/env bash
# The dry smooth point against an independent numpy active-set solver, in one
# run (issue 30):
#
#   bench/dry_vs_numpy.sh [--rounds K] [--repeats R] [--grid N] [--points S] [BUILD_DIR]
#
# BUILD_DIR (default build) holds bench/dry_point. First `dry_point --dump`
# writes the discrete problem of each of the S speeds (default 13, the sweep of
# cases/fig03-smooth.ini at N 400) and viscolube's solution; the numpy script
# bench/dry_active_set.py solves the same problems and prints how far its
# pressure and mu_Rc are from viscolube's. Then K rounds (default 5), each
# timing `dry_point --repeats R` (default 5) and the numpy script (R repeats)
# one after the other, one BLAS thread for both. Each prints its median time
# per point over its R repeats; the summary is the median over the rounds and
# the ratio viscolube/numpy.
#
# What is timed: viscolube, one vl_simulation_run over the S speeds (contact
# creation, the influence matrix at every speed, KINSOL's solve, the point's
# report and its error estimate, a second solve on cells three times as wide);
# numpy, the S active-set solves in sequence with the matrices already in
# memory (neither the interpreter's start-up, numpy's import nor the matrices'
# construction or loading). Both also report their CPU time (on a loaded
# machine the wall time also counts other programs' turns). Needs /usr/bin/python3 with numpy (Debian's
# python3-numpy).
set -euo pipefail
ROUNDS=5 REPEATS=5 GRID=400 POINTS=13 BUILD=build
while (($#)); do
  case $1 in
    --rounds) ROUNDS=$2; shift 2 ;;
    --repeats) REPEATS=$2; shift 2 ;;
    --grid) GRID=$2; shift 2 ;;
    --points) POINTS=$2; shift 2 ;;
    -h|--help) sed -n '2,24p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) BUILD=$1; shift ;;
  esac
done
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
BIN=$BUILD/bench/dry_point
PY=${PYTHON:-/usr/bin/python3}
export OPENBLAS_NUM_THREADS=1
tmp=$(mktemp -d)
trap 'rm -rf -- "$tmp"' EXIT

median() { sort -g | awk '{ v[NR] = $1 } END { if (NR) print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }

echo "# $(date -u +%FT%TZ) $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg), $(git -C "$HERE" rev-parse --short HEAD 2>/dev/null || echo '?')"
"$BIN" --grid "$GRID" --points "$POINTS" --repeats 1 --dump "$tmp" >/dev/null
"$PY" "$HERE/dry_active_set.py" "$tmp" --repeats 1 | grep numpy_vs_viscolube
: >"$tmp/vl"; : >"$tmp/np"; : >"$tmp/vlc"; : >"$tmp/npc"
for ((r = 1; r <= ROUNDS; r++)); do
  "$BIN" --grid "$GRID" --points "$POINTS" --repeats "$REPEATS" >"$tmp/vl.out"
  awk '/^viscolube_ms_per_point/ { print $2 }' "$tmp/vl.out" >>"$tmp/vl"
  sed -n 's/^viscolube_ms.*CPU time \([0-9.]*\).*/\1/p' "$tmp/vl.out" >>"$tmp/vlc"
  "$PY" "$HERE/dry_active_set.py" "$tmp" --repeats "$REPEATS" >"$tmp/np.out"
  awk '/^numpy_ms_per_point/ { print $2 }' "$tmp/np.out" >>"$tmp/np"
  sed -n 's/^numpy_ms.*CPU time \([0-9.]*\).*/\1/p' "$tmp/np.out" >>"$tmp/npc"
  echo "round $r: viscolube $(tail -1 "$tmp/vl") ms, numpy $(tail -1 "$tmp/np") ms per point"
done
grep -v '^viscolube_ms' "$tmp/vl.out"
grep '^numpy_ms' "$tmp/np.out" | sed 's/^/last numpy round: /'
vl=$(median <"$tmp/vl") np=$(median <"$tmp/np")
vlc=$(median <"$tmp/vlc") npc=$(median <"$tmp/npc")
echo "CPU time per point, medians: viscolube $vlc ms, numpy $npc ms, viscolube/numpy $(awk -v a="$vlc" -v b="$npc" 'BEGIN { printf "%.3f", a / b }')"
echo "per point, median of $ROUNDS rounds (each the median of $REPEATS): viscolube $vl ms (with its error estimate), numpy $np ms, viscolube/numpy $(awk -v a="$vl" -v b="$np" 'BEGIN { printf "%.3f", a / b }')"
