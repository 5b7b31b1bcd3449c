#!/usr/bin/env bash
# Estimate against true error on rough wet films (issue 31; docs/NUMERICS.md
# section 11, "Rough films: measured"). Runs each scene of bench/rough/ with the
# automatic numerics and again as a reference: the same sweep refined until its
# own estimate is below REF_TARGET (default 0.1 %: cells refined until mu moves
# under 0.2 %), with up to 8 refinements and REF_CELLS cells (default 3000, twice the automatic
# sweep's 1500, so that the reference has a level the automatic sweep never
# reaches), and prints a markdown table: per scene the points, the true error of
# mu (max, median), how many estimates are at least the true error and at least
# a third of it, the points whose reference is not fine enough (its estimate above
# 2 REF_TARGET: left out of the figures), and the CPU time per curve.
#   bench/rough_estimate.sh PROGRAM [OUT_DIR]      e.g. build/viscolube /tmp/rough
# The scenes need the wiper's EPDM (a shear DMA export, EPDM_CSV), the glass and
# steel surfaces and the O-ring's oil; they are added to a fresh database in OUT_DIR.
# One core; the reference runs take minutes each. The scenes: the wiper, a smaller
# lip, an O-ring, sbr on glass (issue 31's first family) and a syringe plunger, a lip
# seal, a soft gel lens and a tread block (the second).
set -euo pipefail
prog=$(realpath "$1"); out=${2:-/tmp/rough-estimate}
here=$(cd "$(dirname "$0")" && pwd)
epdm=${EPDM_CSV:-$here/../../shared/data/real/marcusni96_epdm_70_tf_015p.csv}
ref_target=${REF_TARGET:-0.001}; ref_cells=${REF_CELLS:-3000}
mkdir -p "$out"
export VISCOLUBE_DB="$out/materials.db" OPENBLAS_NUM_THREADS=1
if [ ! -f "$VISCOLUBE_DB" ]; then
  "$prog" compound add epdm --measured "$epdm" --moduli shear --nu 0.5 >/dev/null
  "$prog" surface add glass --self-affine --hurst 0.8 --q0 1e6 --q1 1e9 --hrms 10e-9 >/dev/null
  "$prog" surface add steel02 --self-affine --hurst 0.8 --q0 1e5 --q1 1e9 --hrms 0.2e-6 >/dev/null
  "$prog" fluid add oil046 --viscosity 0.046 --description "O-ring oil (issue 31)" >/dev/null
  # the soft gel of soft-lens.ini: one retardation time, E0 = Einf/5 = 0.2 MPa
  printf 'A,tau_s\n4,1e-3\n' > "$out/gel.csv"
  "$prog" compound add gel --prony "$out/gel.csv" --e-inf 1e6 --nu 0.5 \
    --description "soft gel (issue 31)" >/dev/null
fi
# SCENES: a subset (paths), e.g. SCENES="bench/rough/wiper.ini"
for scene in ${SCENES:-"$here"/rough/*.ini "$here"/../cases/fig15.ini}; do
  name=$(basename "$scene" .ini)
  # CPU seconds (user + system) of the automatic sweep
  TIMEFORMAT='%U %S'
  { time "$prog" run "$scene" --out "$out/$name" --quiet >/dev/null 2>&1 || true; } 2> "$out/$name.time"
  awk '{print $1 + $2}' "$out/$name.time" > "$out/$name.seconds"
  if [ ! -f "$out/$name-ref/curve.csv" ]; then
    if grep -q '^\[numerics\]' "$scene"; then
      sed "/^\[numerics\]/a target_error = $ref_target" "$scene" > "$out/$name-ref.ini"
    else
      { cat "$scene"; printf '[numerics]\ntarget_error = %s\n' "$ref_target"; } > "$out/$name-ref.ini"
    fi
    VISCOLUBE_AUTO_MAX_CELLS=$ref_cells VISCOLUBE_AUTO_MAX_REFINEMENTS=8 "$prog" run "$out/$name-ref.ini" --out "$out/$name-ref" \
      --quiet >/dev/null || true
  fi
done
python3 - "$out" "$ref_target" <<'PY'
import csv, statistics, sys, os
out, ref_target = sys.argv[1], float(sys.argv[2])
def rows(p):
    return list(csv.DictReader(l for l in open(p) if not l.startswith('#')))
print("| scene | points | true error max / median | estimate >= true | estimate >= true/3 "
      "| marked | > 1 % unmarked | reference not fine (v0) | s per curve |")
print("|---|---|---|---|---|---|---|---|---|")
for name in sorted(n for n in os.listdir(out) if os.path.isdir(os.path.join(out, n)) and not n.endswith('-ref')):
    try:
        a, r = rows(f"{out}/{name}/curve.csv"), rows(f"{out}/{name}-ref/curve.csv")
    except FileNotFoundError:
        continue
    errs, ge, ge3, n, marked, bad, coarse = [], 0, 0, 0, 0, 0, []
    for x, y in zip(a, r):
        marked += x['converged'] == '1' and x['accuracy'] != 'met'
        ye = float(y['error_estimate']) if y['error_estimate'] else float('nan')
        if x['converged'] != '1' or y['converged'] != '1' or not ye <= 2 * ref_target:
            coarse.append(f"{float(x['v0_m_s']):.2g}")
            continue
        t = abs(float(x['mu']) - float(y['mu'])) / abs(float(y['mu']))
        e = float(x['error_estimate']) if x['error_estimate'] else float('nan')
        errs.append(t); n += 1
        ge += e >= t; ge3 += e >= t / 3
        bad += t > 0.01 and x['accuracy'] == 'met'
    sec = open(f"{out}/{name}.seconds").read().strip()
    if errs:
        print(f"| {name} | {n} | {100*max(errs):.2g} / {100*statistics.median(errs):.2g} % "
              f"| {ge} of {n} | {ge3} of {n} | {marked} | {bad} | {', '.join(coarse) or '-'} "
              f"| {float(sec):.2f} |")
PY
