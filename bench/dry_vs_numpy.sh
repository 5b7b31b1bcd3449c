#!/usr/bin/env bash
# The dry smooth point against an independent numpy active-set solver, in one
# run (issue 30):
#
#   bench/dry_vs_numpy.sh [--rounds K] [--repeats R] [--grid N] [--points S] [BUILD_DIR...]
#
# Each BUILD_DIR (default build) holds bench/dry_point; several (an old and a
# new build) are timed in turn in every round. First `dry_point --dump`
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
# machine the wall time also counts other programs' turns). Needs
# /usr/bin/python3 with numpy (Debian's python3-numpy).
set -euo pipefail
ROUNDS=5 REPEATS=5 GRID=400 POINTS=13 BUILDS=()
while (($#)); do
  case $1 in
    --rounds) ROUNDS=$2; shift 2 ;;
    --repeats) REPEATS=$2; shift 2 ;;
    --grid) GRID=$2; shift 2 ;;
    --points) POINTS=$2; shift 2 ;;
    -h|--help) sed -n '2,29p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) BUILDS+=("$1"); shift ;;
  esac
done
((${#BUILDS[@]})) || BUILDS=(build)
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
PY=${PYTHON:-/usr/bin/python3}
export OPENBLAS_NUM_THREADS=1
tmp=$(mktemp -d)
trap 'rm -rf -- "$tmp"' EXIT

median() { sort -g | awk '{ v[NR] = $1 } END { if (NR) print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", a / b }'; }

echo "# $(date -u +%FT%TZ) $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg), $(git -C "$HERE" rev-parse --short HEAD 2>/dev/null || echo '?')"
nb=${#BUILDS[@]}
for ((i = 0; i < nb; i++)); do
  mkdir -p "$tmp/dump$i"
  "${BUILDS[$i]}/bench/dry_point" --grid "$GRID" --points "$POINTS" --repeats 1 --dump "$tmp/dump$i" >/dev/null
  echo "${BUILDS[$i]}: $("$PY" "$HERE/dry_active_set.py" "$tmp/dump$i" --repeats 1 | grep numpy_vs_viscolube)"
  : >"$tmp/vl$i"; : >"$tmp/vlc$i"
done
: >"$tmp/np"; : >"$tmp/npc"
for ((r = 1; r <= ROUNDS; r++)); do
  line="round $r:"
  for ((i = 0; i < nb; i++)); do
    "${BUILDS[$i]}/bench/dry_point" --grid "$GRID" --points "$POINTS" --repeats "$REPEATS" >"$tmp/vl$i.out"
    awk '/^viscolube_ms_per_point/ { print $2 }' "$tmp/vl$i.out" >>"$tmp/vl$i"
    sed -n 's/^viscolube_ms.*CPU time \([0-9.]*\).*/\1/p' "$tmp/vl$i.out" >>"$tmp/vlc$i"
    line+=" ${BUILDS[$i]} $(tail -1 "$tmp/vl$i") ms,"
  done
  "$PY" "$HERE/dry_active_set.py" "$tmp/dump0" --repeats "$REPEATS" >"$tmp/np.out"
  awk '/^numpy_ms_per_point/ { print $2 }' "$tmp/np.out" >>"$tmp/np"
  sed -n 's/^numpy_ms.*CPU time \([0-9.]*\).*/\1/p' "$tmp/np.out" >>"$tmp/npc"
  echo "$line numpy $(tail -1 "$tmp/np") ms per point"
done
np=$(median <"$tmp/np") npc=$(median <"$tmp/npc")
echo "numpy: $np ms per point (CPU time $npc ms); $(sed -n 's/.*; \([0-9]* LAPACK solves[^)]*\)).*/\1/p' "$tmp/np.out")"
for ((i = 0; i < nb; i++)); do
  echo "${BUILDS[$i]}, last round's cost split:"
  grep -v '^viscolube_ms' "$tmp/vl$i.out" | grep -v '^#'
  vl=$(median <"$tmp/vl$i") vlc=$(median <"$tmp/vlc$i")
  echo "${BUILDS[$i]}: viscolube $vl ms per point (with its error estimate; CPU time $vlc ms), numpy $np ms (CPU time $npc ms): viscolube/numpy $(ratio "$vl" "$np") (CPU time $(ratio "$vlc" "$npc"))"
done
echo "(medians of $ROUNDS rounds, each the median of $REPEATS repeats)"
